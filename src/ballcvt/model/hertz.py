"""Hertzian dry contact of the ball with each body (Eqs. 41-50, Hamrock-Brewe).

Pure functions, SI units, NumPy broadcasting.
"""

from __future__ import annotations

import numpy as np

__all__ = ["rolling_curvature_ratio", "transverse_curvature_ratio", "hertz_contact"]

_HALF_PI_M1 = np.pi / 2.0 - 1.0


def rolling_curvature_ratio(radius, aspect_ratio):
    """Equivalent radius in the rolling direction over ``r_S`` (Eqs. 41-44).

    ``rho~_x = r~_c / (1 + k)`` for every contact: the concave disc tracks and the convex
    idlers both give this form (docs/model.md §3).

    Parameters
    ----------
    radius : array_like
        ``r~_c = r_c / r_S`` [-].
    aspect_ratio : float
        ``k`` [-].

    Returns
    -------
    ndarray
        ``rho~_x`` [-].
    """
    return np.asarray(radius, dtype=float) / (1.0 + aspect_ratio)


def transverse_curvature_ratio(groove_ratio):
    """Equivalent radius in the transverse direction over ``r_S`` (Eqs. 41-44).

    Ball of radius ``r_S`` in a concave groove of meridian radius ``r_j2``:
    ``rho~_y = r~_j2 / (r~_j2 - 1)`` (the printed ``(r~_j2 - 1)/r~_j2`` is its inverse,
    docs/model.md §3); a straight generatrix (``r~_j2 = inf``) gives 1.

    Parameters
    ----------
    groove_ratio : array_like
        ``r~_j2 = r_j2 / r_S`` > 1, ``inf`` allowed [-].

    Returns
    -------
    ndarray
        ``rho~_y`` [-].
    """
    g = np.asarray(groove_ratio, dtype=float)
    with np.errstate(invalid="ignore"):
        return np.where(np.isinf(g), 1.0, g / (g - 1.0))


def hertz_contact(load, rx, ry, reduced_modulus):
    """Semi-axes, peak pressure and approach of an elliptical Hertz contact.

    Hamrock-Brewe approximations (Eqs. 45-49) with the combined radius
    ``R = (1/R_x + 1/R_y)^-1`` (docs/model.md §3). Eq. 49 as printed is the branch
    ``xi = R_y / R_x >= 1`` (major axis along ``y``); for ``xi < 1`` the axes swap roles.

    Parameters
    ----------
    load : array_like
        Normal load ``F_N`` [N].
    rx, ry : array_like
        Equivalent radii in the rolling (x) and transverse (y) directions [m].
    reduced_modulus : float
        ``E' = E / (1 - nu^2)`` [Pa].

    Returns
    -------
    ax, ay : ndarray
        Semi-axes along x and y [m].
    p_max : ndarray
        Peak pressure ``3 F_N / (2 pi a_x a_y)`` (Eq. 50) [Pa].
    approach : ndarray
        Mutual approach of distant points ``delta`` [m].
    """
    load = np.asarray(load, dtype=float)
    rx = np.asarray(rx, dtype=float)
    ry = np.asarray(ry, dtype=float)
    r = 1.0 / (1.0 / rx + 1.0 / ry)
    xi = ry / rx
    major_y = xi >= 1.0
    xi_m = np.where(major_y, xi, 1.0 / xi)  # >= 1: major over minor radius
    ell = xi_m ** (2.0 / np.pi)  # Eq. 45, ellipticity >= 1
    e2 = 1.0 + _HALF_PI_M1 / xi_m  # Eq. 47, second-kind integral
    e1 = np.pi / 2.0 + _HALF_PI_M1 * np.log(xi_m)  # Eq. 46, first-kind integral
    base = 6.0 * load * r / (np.pi * reduced_modulus)  # Lambda^3 * rho~ of Eqs. 48-49
    a_major = np.cbrt(ell**2 * e2 * base)
    a_minor = np.cbrt(e2 * base / ell)
    ax = np.where(major_y, a_minor, a_major)
    ay = np.where(major_y, a_major, a_minor)
    p_max = 3.0 * load / (2.0 * np.pi * ax * ay)
    approach = e1 * np.cbrt(9.0 / (2.0 * e2 * r) * (load / (np.pi * ell * reduced_modulus)) ** 2)
    return ax, ay, p_max, approach
