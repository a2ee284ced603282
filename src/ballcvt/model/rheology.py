"""Traction-fluid rheology: Roelands viscosity, limiting shear stress, shear law.

Eqs. 51, 53 and 54 of the paper, as corrected in docs/model.md §3. Pure functions.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "roelands_viscosity",
    "roelands_pressure_limit",
    "limiting_shear_stress",
    "saturation_factor",
    "saturation_slope",
]

#: Largest ``log(eta / eta_0)`` kept: ``exp`` overflows double precision at 709.8.
LOG_VISCOSITY_MAX = 700.0


def roelands_viscosity(pressure, eta0, eta_inf, pole_pressure, index):
    """Roelands pressure-viscosity law (Eq. 51, with ``1 + p / c_p``, docs/model.md §3).

    ``log(eta / eta_0) = [(1 + p / c_p)^Z_1 - 1] log(eta_0 / eta_inf)``.

    Parameters
    ----------
    pressure : array_like
        Local pressure ``p`` >= 0 [Pa].
    eta0 : float
        Viscosity at atmospheric pressure [Pa s].
    eta_inf : float
        Pole viscosity [Pa s].
    pole_pressure : float
        Pole pressure ``c_p`` [Pa].
    index : float
        Viscosity-pressure index ``Z_1`` [-].

    Returns
    -------
    ndarray
        Viscosity [Pa s].
    """
    p = np.asarray(pressure, dtype=float)
    return eta0 * np.exp(np.log(eta0 / eta_inf) * np.expm1(index * np.log1p(p / pole_pressure)))


def roelands_pressure_limit(eta0, eta_inf, pole_pressure, index):
    """Pressure at which the Roelands viscosity (Eq. 51) leaves double precision [Pa].

    Solves ``[(1 + p / c_p)^Z_1 - 1] log(eta_0 / eta_inf) = 700`` for ``p``. Peak pressures
    above it (clamping forces of 10^8 N on the Table I drive, 87 GPa) have no finite
    viscosity; `ballcvt.equilibrium.build_problem` refuses them.

    Parameters
    ----------
    eta0, eta_inf, pole_pressure, index : float
        As in `roelands_viscosity` ([Pa s], [Pa s], [Pa], [-]).

    Returns
    -------
    float
        ``p_lim`` [Pa] (``inf`` when the viscosity does not grow with pressure).
    """
    growth = np.log(eta0 / eta_inf)
    if growth <= 0:
        return float("inf")
    return float(pole_pressure * np.expm1(np.log1p(LOG_VISCOSITY_MAX / growth) / index))


def limiting_shear_stress(pressure, tau_l0, slope):
    """``tau_L = tau_L0 + a p`` (Eq. 54).

    Parameters
    ----------
    pressure : array_like
        Local pressure [Pa].
    tau_l0 : float
        Limiting shear stress at atmospheric pressure [Pa].
    slope : float
        Pressure coefficient ``a`` [-].

    Returns
    -------
    ndarray
        Limiting shear stress [Pa].
    """
    return tau_l0 + slope * np.asarray(pressure, dtype=float)


def saturation_factor(x):
    """``(1 - exp(-x)) / x`` with its limit 1 at ``x = 0`` (the shear law of Eq. 53).

    The shear stress of Eq. 53 is ``tau = (eta / h) * saturation_factor(eta |V| / (h tau_L)) V``,
    which equals ``tau_L (1 - exp(-eta |V| / (h tau_L))) V / |V|`` and never divides 0 by 0.

    Parameters
    ----------
    x : array_like
        ``eta |V| / (h tau_L)`` >= 0 [-].

    Returns
    -------
    ndarray
        Factor in (0, 1] [-].
    """
    x = np.asarray(x, dtype=float)
    small = x < 1e-8
    safe = np.where(small, 1.0, x)
    return np.where(small, 1.0 - 0.5 * x, -np.expm1(-safe) / safe)


def saturation_slope(x, factor=None):
    """Derivative of `saturation_factor`: ``d/dx [(1 - exp(-x)) / x]`` [-].

    Equals ``((1 + x) exp(-x) - 1) / x^2 = (exp(-x) - S) / x`` (``S`` the factor),
    computed in the second form: the first form's ``(1 - S) - x S``, a difference of two
    terms near 1 for large ``x``, carries a rounding error of ``1e-16 x`` relative (noise
    in the derivatives at high pressure; docs/model.md §3). A three-term series below
    ``x = 1e-3`` avoids the cancellation there. Used for the analytic creep derivatives of
    the traction integrals.

    Parameters
    ----------
    x : array_like
        ``eta |V| / (h tau_L)`` >= 0 [-].
    factor : array_like, optional
        ``saturation_factor(x)`` if already computed (saves an exponential).

    Returns
    -------
    ndarray
        Slope in [-1/2, 0) [-].
    """
    x = np.asarray(x, dtype=float)
    s = saturation_factor(x) if factor is None else factor
    small = x < 1e-3
    safe = np.where(small, 1.0, x)
    # (1 + x) e^-x - 1 = x e^-x - x S (e^-x = 1 - x S): x (e^-x - S)
    return np.where(small, -0.5 + x / 3.0 - x * x / 8.0, (np.exp(-safe) - s) / safe)
