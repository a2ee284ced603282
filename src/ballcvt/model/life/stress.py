"""The subsurface stress the life models use: Lundberg and Palmgren's orthogonal shear.

Pure functions, SI units, NumPy broadcasting (docs/life.md §2).
"""

from __future__ import annotations

import numpy as np

__all__ = ["orthogonal_shear", "peak_pressure"]

_NEWTON_STEPS = 60


def peak_pressure(load, semi_major, semi_minor):
    """Peak Hertz pressure of an elliptical contact, ``p0 = 3 Q / (2 pi a b)``.

    Parameters
    ----------
    load : array_like
        Normal load ``Q`` [N].
    semi_major, semi_minor : array_like
        Semi-axes ``a`` (transverse to rolling) and ``b`` (along rolling) [m].

    Returns
    -------
    ndarray
        ``p0`` [Pa] (Hertz 1881; Johnson, Contact Mechanics, Eq. 3.62).
    """
    load = np.asarray(load, dtype=float)
    return 1.5 * load / (np.pi * np.asarray(semi_major, float) * np.asarray(semi_minor, float))


def _auxiliary(ratio):
    """Lundberg and Palmgren's auxiliary parameter ``t`` of ``(b/a)^2 = (t^2-1)(2t-1)``.

    Newton's method from ``t = 1 + min(k/2, (k/2)^(1/3))`` (``k = (b/a)^2``), which lies
    at or above the root; the cubic is increasing and convex for ``t >= 1``, so the
    iterates decrease monotonically onto it.
    """
    k = np.asarray(ratio, dtype=float) ** 2
    t = 1.0 + np.minimum(0.5 * k, np.cbrt(0.5 * k))
    for _ in range(_NEWTON_STEPS):
        f = (t * t - 1.0) * (2.0 * t - 1.0) - k
        step = f / (6.0 * t * t - 2.0 * t - 2.0)
        t = t - step
        if np.all(np.abs(step) <= 1e-15 * t):
            break
    return t


def orthogonal_shear(semi_major, semi_minor, p_max):
    """Amplitude and depth of the maximum orthogonal shear stress under a rolling ellipse.

    Lundberg and Palmgren (1947), Acta Polytechnica, Mech. Eng. Series 1(3), Eqs. 8-10
    (also Harris and Kotzalas, Rolling Bearing Analysis, 5th ed., Eqs. 23.8-23.10):
    ``(b/a)^2 = (t^2 - 1)(2t - 1)``, ``tau0 / p0 = sqrt(2t - 1) / (2t (t + 1))`` and
    ``z0 / b = 1 / ((t + 1) sqrt(2t - 1))``. ``tau0`` is the amplitude of the shear
    stress on planes parallel to the surface, in the direction of rolling; it reverses
    sign as the ellipse passes. A line contact (``b/a -> 0``) gives ``tau0 = p0/4`` at
    ``z0 = b/2``, a circular one ``tau0 = 0.214 p0`` at ``z0 = 0.35 b``.

    Parameters
    ----------
    semi_major : array_like
        Semi-axis ``a`` transverse to the rolling direction [m] (LP's ``a``; usually,
        not necessarily, the major one: any ``b/a > 0`` is valid).
    semi_minor : array_like
        Semi-axis ``b`` along the rolling direction [m].
    p_max : array_like
        Peak Hertz pressure ``p0`` [Pa].

    Returns
    -------
    tau0 : ndarray
        Amplitude of the orthogonal shear stress [Pa].
    z0 : ndarray
        Its depth below the surface [m].
    """
    b = np.asarray(semi_minor, dtype=float)
    t = _auxiliary(b / np.asarray(semi_major, dtype=float))
    root = np.sqrt(2.0 * t - 1.0)
    tau0 = np.asarray(p_max, dtype=float) * root / (2.0 * t * (t + 1.0))
    z0 = b / ((t + 1.0) * root)
    return tau0, z0
