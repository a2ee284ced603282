"""Bearing friction torque: load-independent (Eq. 15) plus load-dependent (Eq. 16) parts.

The empirical formulas take the kinematic viscosity in mm^2/s, the speed in rpm, the
diameters in mm, and give N m; the functions here take and return SI units and convert.
"""

from __future__ import annotations

import numpy as np

from ..params.models import BearingModel

__all__ = ["speed_dependent_torque", "load_dependent_torque"]


def speed_dependent_torque(speed, diameter, kinematic_viscosity, model: BearingModel):
    """Load-independent friction torque ``T_B0`` of one bearing (Eq. 15).

    ``T_B0 = 1e-10 (nu N)^e f_0 d^3`` for ``nu N`` above the threshold, else
    ``160e-10 f_0 d^3`` (``nu`` in mm^2/s, ``N`` in rpm, ``d`` in mm, ``T`` in N m).

    Parameters
    ----------
    speed : array_like
        Bearing speed [rad/s] (its sign is ignored).
    diameter : float
        Bearing mean diameter ``d`` [m].
    kinematic_viscosity : float
        Lubricant kinematic viscosity [m^2/s].
    model : BearingModel
        Coefficients ``f_0``, the exponent ``e`` and the threshold.

    Returns
    -------
    ndarray
        Friction torque magnitude [N m].
    """
    nu_n = kinematic_viscosity * 1e6 * np.abs(np.asarray(speed, dtype=float)) * 30.0 / np.pi
    d3 = (diameter * 1e3) ** 3
    fast = 1e-10 * nu_n**model.speed_exponent * model.f0 * d3
    return np.where(nu_n < model.speed_threshold, 160e-10 * model.f0 * d3, fast)


def load_dependent_torque(load, diameter, model: BearingModel):
    """Load-dependent friction torque ``T_B1 = 1e-3 f_1 P^a d^b`` of one bearing (Eq. 16).

    Parameters
    ----------
    load : array_like
        Bearing load ``P`` [N] (its sign is ignored).
    diameter : float
        Bearing mean diameter [m].
    model : BearingModel
        Coefficients ``f_1``, ``a``, ``b``.

    Returns
    -------
    ndarray
        Friction torque magnitude [N m].
    """
    p = np.abs(np.asarray(load, dtype=float))
    return 1e-3 * model.f1 * p**model.load_exponent * (diameter * 1e3) ** model.diameter_exponent
