"""Greenwood-Tripp's asperity integrals and the root of the load share (docs/model.md §16).

The mixed lubrication model (`ballcvt.model.lubrication`) shares a contact's load between
the film and the asperities (Johnson, Greenwood and Poon, Wear 19 (1972) 91-108) with the
asperity pressure of Greenwood and Tripp (Proc. Instn Mech. Engrs 185 (1970-71) 625-633):
``F_n(t)`` tabulated for cubic Hermite interpolation, and ``f = g(lambda_s (1 - f)^-e)``
solved per contact by safeguarded Newton. The root runs compiled (`solve_share`: one
contact at a time, scalar arithmetic in the NumPy path's order, without fast-math, so the
same bits as `solve_share_numpy`, tested); the NumPy path ran some 30 small-array
operations per Newton step and took a third of a hub uncertainty run (issue 26).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.special import gamma, pbdv

from .traction.kernels import AVAILABLE, njit, scalar_powers

__all__ = [
    "LAMBDA_CUTOFF",
    "FILM_SHARE_EXPONENT",
    "asperity_integral",
    "film_factor",
    "solve_share",
    "solve_share_numpy",
]

#: Film parameter ``h / sigma`` above which no asperity touches (``f_a = 0`` exactly) [-].
LAMBDA_CUTOFF = 4.0
#: ``h = h_s (1 - f_a)^-e``: ``e = 0.67 - 0.53`` from the speed and material exponents of
#: Eq. 56 under the scaling of Johnson, Greenwood and Poon (1972) [-].
FILM_SHARE_EXPONENT = 0.14


def _gt(t, n: float):
    """Greenwood-Tripp's ``F_n(t)`` through the parabolic cylinder function:
    ``F_n(t) = Gamma(n + 1) (2 pi)^-1/2 exp(-t^2/4) D_-(n+1)(t)`` [-]."""
    t = np.asarray(t, dtype=float)
    return gamma(n + 1.0) / np.sqrt(2.0 * np.pi) * np.exp(-0.25 * t * t) * pbdv(-n - 1.0, t)[0]


#: Intervals of the tables of ``F_5/2``, ``F_3/2``, ``F_1/2`` on ``[0, LAMBDA_CUTOFF]``:
#: cubic Hermite interpolation with the exact slopes ``dF_n/dt = -n F_(n-1)`` is then
#: within 1e-13 of `_gt` (tested), at a hundredth of its cost.
_INTERVALS = 2000
_STEP_T = LAMBDA_CUTOFF / _INTERVALS
_GRID = np.linspace(0.0, LAMBDA_CUTOFF, _INTERVALS + 1)
_TABLE = {n: _gt(_GRID, n) for n in (2.5, 1.5, 0.5)}
#: The slopes ``dF_n/dt = -n F_(n-1)`` times the step, of ``F_5/2`` and ``F_3/2``.
_SLOPE = {n: -n * _TABLE[n - 1.0] * _STEP_T for n in (2.5, 1.5)}
#: Largest ``t / step`` interpolated: inside the last interval.
_TOP = _INTERVALS - 1e-9


def _hermite(t: np.ndarray, n: float) -> np.ndarray:
    """``F_n(t)`` for ``0 <= t <= LAMBDA_CUTOFF`` from the table (``n`` 2.5 or 1.5)."""
    x = np.clip(t / _STEP_T, 0.0, _TOP)
    i = x.astype(np.intp)
    s = x - i
    s2, s3 = s * s, s * s * s
    v, d = _TABLE[n], _SLOPE[n]
    return (
        (2 * s3 - 3 * s2 + 1) * v[i]
        + (s3 - 2 * s2 + s) * d[i]
        + (3 * s2 - 2 * s3) * v[i + 1]
        + (s3 - s2) * d[i + 1]
    )


_F52_CUT, _F32_CUT = float(_TABLE[2.5][-1]), float(_TABLE[1.5][-1])


def asperity_integral(lam):
    """Greenwood-Tripp's ``F_5/2(lambda)`` joined C1 to zero at `LAMBDA_CUTOFF`, and its
    derivative (``dF_5/2 / dt = -5/2 F_3/2``).

    Parameters
    ----------
    lam : array_like
        Film parameter ``h / sigma`` >= 0 [-].

    Returns
    -------
    value, slope : ndarray
        ``F_5/2(l) - F_5/2(l_c) + 5/2 F_3/2(l_c) (l - l_c)`` for ``l < l_c``, else 0, and
        its derivative [-].
    """
    lam = np.asarray(lam, dtype=float)
    below = lam < LAMBDA_CUTOFF
    t = np.where(below, lam, LAMBDA_CUTOFF)
    value = _hermite(t, 2.5) - _F52_CUT + 2.5 * _F32_CUT * (t - LAMBDA_CUTOFF)
    slope = -2.5 * (_hermite(t, 1.5) - _F32_CUT)
    return np.where(below, value, 0.0), np.where(below, slope, 0.0)


def film_factor(keep) -> np.ndarray:
    """``keep^-e`` (``keep = 1 - f_a``), element by element with the C library's ``pow``
    (`ballcvt.model.traction.kernels.scalar_powers`): the same bits whatever the batch
    (NumPy's vectorised power rounds by an element's position), so that a point's result
    does not depend on the points solved with it."""
    keep = np.asarray(keep, dtype=float)
    out = np.ones(keep.shape)
    scalar_powers(np.ascontiguousarray(keep.reshape(-1)), -FILM_SHARE_EXPONENT, out.reshape(-1))
    return out


def solve_share_numpy(lam_s: np.ndarray, scale: np.ndarray) -> np.ndarray:
    """The root ``f`` of ``f - scale F_5/2(lam_s (1 - f)^-e) = 0`` in ``[0, 1)``.

    Each contact iterates until its own step is below 1e-15 and then stops, so that its
    root does not depend on the other contacts of the batch."""
    e = FILM_SHARE_EXPONENT
    lo, hi = np.zeros(lam_s.shape), np.full(lam_s.shape, 1.0 - 1e-12)  # f < 1: some film
    f = np.zeros(lam_s.shape)
    on = np.arange(lam_s.size)
    for _ in range(100):
        x, ls, sc = f[on], lam_s[on], scale[on]
        lam = ls * film_factor(1.0 - x)
        value, slope = asperity_integral(lam)
        phi = x - sc * value
        lo[on] = np.where(phi <= 0.0, x, lo[on])
        hi[on] = np.where(phi >= 0.0, x, hi[on])
        new = x - phi / (1.0 - sc * slope * e * lam / (1.0 - x))
        new = np.where((new > lo[on]) & (new < hi[on]), new, 0.5 * (lo[on] + hi[on]))
        f[on] = new
        on = on[np.abs(new - x) > 1e-15]
        if on.size == 0:
            break
    return f


def _hermite_scalar(t, v, d):
    """`_hermite` of one ``t`` on the table ``v`` with slopes ``d`` (times the step)."""
    x = t / _STEP_T
    x = min(max(x, 0.0), _TOP)
    i = int(x)
    s = x - i
    s2, s3 = s * s, s * s * s
    return (
        (2 * s3 - 3 * s2 + 1) * v[i]
        + (s3 - 2 * s2 + s) * d[i]
        + (3 * s2 - 2 * s3) * v[i + 1]
        + (s3 - s2) * d[i + 1]
    )


def _share_python(lam_s, scale, tables, out):
    """`solve_share_numpy`'s iteration, one contact ``k`` at a time, into ``out[k]``;
    ``tables``: ``F_5/2``, its slope times the step, ``F_3/2``, its slope times the step."""
    v25, d25, v15, d15 = tables
    e, cutoff = FILM_SHARE_EXPONENT, LAMBDA_CUTOFF
    for k in range(lam_s.shape[0]):
        ls, sc = lam_s[k], scale[k]
        lo, hi, f = 0.0, 1.0 - 1e-12, 0.0
        for _ in range(100):
            x = f
            keep = 1.0 - x
            lam = ls * (math.pow(keep, -e) if keep < 1.0 else 1.0)
            value, slope = 0.0, 0.0
            if lam < cutoff:
                value = _hermite_scalar(lam, v25, d25) - _F52_CUT
                value = value + 2.5 * _F32_CUT * (lam - cutoff)
                slope = -2.5 * (_hermite_scalar(lam, v15, d15) - _F32_CUT)
            phi = x - sc * value
            if phi <= 0.0:
                lo = x
            if phi >= 0.0:
                hi = x
            new = x - phi / (1.0 - sc * slope * e * lam / (1.0 - x))
            if not (new > lo and new < hi):
                new = 0.5 * (lo + hi)
            f = new
            if not (abs(new - x) > 1e-15):
                break
        out[k] = f


_TABLES = (_TABLE[2.5], _SLOPE[2.5], _TABLE[1.5], _SLOPE[1.5])
if AVAILABLE:
    _hermite_scalar = njit(cache=True, inline="always")(_hermite_scalar)
    _share_compiled = njit(cache=True)(_share_python)


def solve_share(lam_s, scale) -> np.ndarray:
    """`solve_share_numpy`, compiled (the same bits; the NumPy path without numba).

    Parameters
    ----------
    lam_s : ndarray
        Smooth film parameter ``h_s / sigma`` of each contact, 1-D [-].
    scale : ndarray
        ``K E' / p_mean`` of each contact, 1-D [-].

    Returns
    -------
    ndarray
        The asperity load fraction ``f_a`` of each contact [-].
    """
    if not AVAILABLE:  # pragma: no cover - numba is a declared dependency
        return solve_share_numpy(lam_s, scale)
    out = np.empty(np.shape(lam_s)[0])
    _share_compiled(
        np.ascontiguousarray(lam_s, dtype=float),
        np.ascontiguousarray(scale, dtype=float),
        _TABLES,
        out,
    )
    return out
