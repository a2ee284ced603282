"""ISO 281:2007 bearing ratings: basic rating life, life modification factor ``a_ISO``
and the basic dynamic load rating of a radial ball bearing (docs/life.md §5).

Pure functions; SI units at the interface (the standard's own mm and N inside).
"""

from __future__ import annotations

import numpy as np

from ...errors import InputError

__all__ = ["bearing_l10", "a_iso", "deep_groove_rating"]

#: ISO 281:2007 Table 2, single-row radial contact groove ball bearings: ``f_c``
#: against ``gamma = D_w cos(alpha) / D_pw`` (linear interpolation allowed, §6.1.1).
_FC_GAMMA = (
    0.01, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07, 0.08, 0.09, 0.10, 0.12, 0.14, 0.16,
    0.18, 0.20, 0.22, 0.24, 0.26, 0.28, 0.30, 0.32, 0.34, 0.36, 0.38, 0.40,
)  # fmt: skip
_FC_VALUE = (
    29.1, 35.8, 40.3, 43.8, 46.7, 49.1, 51.1, 52.8, 54.3, 55.5, 57.5, 58.8, 59.6,
    59.9, 59.9, 59.6, 59.0, 58.2, 57.1, 56.0, 54.6, 53.2, 51.7, 50.0, 48.4,
)  # fmt: skip
#: ISO 281:2007 Table 1: b_m of radial ball bearings (other than filling-slot ones).
_B_M = 1.3
#: ISO 281:2007 §9.3.2, Eqs. for radial ball bearings: (kappa upper bound, c, exponent).
_A_ISO_BRANCHES = ((0.4, 2.2649, 0.054381), (1.0, 1.9987, 0.19087), (np.inf, 1.9987, 0.071739))
_A_ISO_MAX = 50.0


def bearing_l10(dynamic_rating, equivalent_load, exponent=3.0):
    """Basic rating life ``L10 = (C / P)^p`` (ISO 281:2007 Eq. 5; ``p = 3`` ball bearings).

    Parameters
    ----------
    dynamic_rating : array_like
        Basic dynamic load rating ``C`` [N].
    equivalent_load : array_like
        Dynamic equivalent load ``P`` [N] (``0``: infinite life).
    exponent : float
        Life exponent ``p`` [-] (3 for ball, 10/3 for roller bearings).

    Returns
    -------
    ndarray
        ``L10`` [10^6 revolutions].
    """
    with np.errstate(divide="ignore"):
        ratio = np.asarray(dynamic_rating, dtype=float) / np.asarray(equivalent_load, float)
    return ratio**exponent


def a_iso(fatigue_load_limit_ratio, kappa):
    """Life modification factor ``a_ISO`` of a radial ball bearing (ISO 281:2007 §9.3.2).

    ``a_ISO = 0.1 [1 - (2.5671 - c / kappa^m)^0.83 (e_C C_u / P)^(1/3)]^-9.3`` with
    ``(c, m) = (2.2649, 0.054381)`` for ``0.1 <= kappa < 0.4``, ``(1.9987, 0.19087)``
    for ``0.4 <= kappa < 1`` and ``(1.9987, 0.071739)`` for ``1 <= kappa <= 4``;
    ``kappa > 4`` counts as 4 and ``a_ISO`` is capped at 50.

    Parameters
    ----------
    fatigue_load_limit_ratio : array_like
        ``e_C C_u / P``: contamination factor times fatigue load limit over the
        equivalent load [-].
    kappa : array_like
        Viscosity ratio ``kappa = nu / nu_1`` [-] (>= 0.1: the standard does not
        cover thinner films).

    Returns
    -------
    ndarray
        ``a_ISO`` [-] in (0, 50].
    """
    kappa = np.minimum(np.asarray(kappa, dtype=float), 4.0)
    if np.any(~(kappa >= 0.1)):
        raise InputError("kappa", float(np.min(kappa)), ">= 0.1 (ISO 281 §9.3.2)")
    x = np.asarray(fatigue_load_limit_ratio, dtype=float)
    if np.any(~(x >= 0.0)):
        raise InputError("fatigue_load_limit_ratio", float(np.min(x)), ">= 0")
    c = np.select([kappa < b[0] for b in _A_ISO_BRANCHES], [b[1] for b in _A_ISO_BRANCHES])
    m = np.select([kappa < b[0] for b in _A_ISO_BRANCHES], [b[2] for b in _A_ISO_BRANCHES])
    bracket = 1.0 - (2.5671 - c / kappa**m) ** 0.83 * np.cbrt(x)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        factor = np.where(bracket > 0.0, 0.1 * np.maximum(bracket, 1e-300) ** -9.3, np.inf)
    return np.minimum(factor, _A_ISO_MAX)


def deep_groove_rating(ball_diameter, n_balls, pitch_diameter, contact_angle=0.0):
    """Basic dynamic radial load rating of a single-row radial ball bearing.

    ISO 281:2007 Eq. 2: ``C_r = b_m f_c (i cos alpha)^0.7 Z^(2/3) D_w^1.8`` (N, mm) for
    ``D_w <= 25.4 mm``, ``C_r = 3.647 b_m f_c (i cos alpha)^0.7 Z^(2/3) D_w^1.4``
    above, with ``i = 1`` row, ``b_m = 1.3`` (Table 1) and ``f_c`` from Table 2
    (linearly interpolated in ``gamma = D_w cos(alpha) / D_pw``, 0.01 to 0.4).

    Parameters
    ----------
    ball_diameter : array_like
        Ball diameter ``D_w`` [m].
    n_balls : array_like
        Number of balls ``Z`` [-].
    pitch_diameter : array_like
        Pitch diameter of the ball set ``D_pw`` [m].
    contact_angle : array_like
        Nominal contact angle ``alpha`` [rad].

    Returns
    -------
    ndarray
        ``C_r`` [N].
    """
    d_w = np.asarray(ball_diameter, dtype=float) * 1e3  # the standard's mm
    cos_a = np.cos(np.asarray(contact_angle, dtype=float))
    gamma = d_w * cos_a / (np.asarray(pitch_diameter, dtype=float) * 1e3)
    if np.any(~((gamma >= _FC_GAMMA[0]) & (gamma <= _FC_GAMMA[-1]))):
        raise InputError("D_w cos(alpha) / D_pw", float(np.max(gamma)), "0.01 to 0.4 (ISO 281)")
    f_c = np.interp(gamma, _FC_GAMMA, _FC_VALUE)
    common = _B_M * f_c * cos_a**0.7 * np.asarray(n_balls, dtype=float) ** (2.0 / 3.0)
    return np.where(d_w <= 25.4, common * d_w**1.8, 3.647 * common * d_w**1.4)
