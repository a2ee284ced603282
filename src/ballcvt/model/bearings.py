"""Bearing friction torque: load-independent (Eq. 15) plus load-dependent (Eq. 16) parts.

The empirical formulas take the kinematic viscosity in mm^2/s, the speed in rpm, the
diameters in mm, and give N m; the functions here take and return SI units and convert.
"""

from __future__ import annotations

import numpy as np

from ..params.models import BearingModel
from ..units import rad_s_to_rpm

__all__ = [
    "speed_dependent_torque",
    "load_dependent_torque",
    "speed_torque_constants",
    "load_torque_constants",
]


def speed_torque_constants(diameter, kinematic_viscosity, model: BearingModel) -> tuple:
    """The constants of `speed_dependent_torque`: ``(1e-10 f_0 d^3`` [N m] (``d`` in mm),
    ``nu`` [mm^2/s] times the rpm of 1 rad/s [rpm/(rad/s)], ``c_low``, the exponent
    ``e)`` (Eq. 15), for ``T_B0 = scale max(c_low, (nu_rpm |speed|)^e)``."""
    scale = 1e-10 * model.f0 * (diameter * 1e3) ** 3
    return (
        scale,
        rad_s_to_rpm(kinematic_viscosity * 1e6),
        model.low_speed_factor,
        model.speed_exponent,
    )


def load_torque_constants(diameter, model: BearingModel) -> tuple:
    """The constants of `load_dependent_torque`: ``(1e-3 f_1 d^b`` [N m / N^a] (``d`` in
    mm), ``a)`` (Eq. 16), for ``T_B1 = coef |P|^a``."""
    return 1e-3 * model.f1 * (diameter * 1e3) ** model.diameter_exponent, model.load_exponent


def speed_dependent_torque(speed, diameter, kinematic_viscosity, model: BearingModel):
    """Load-independent friction torque ``T_B0`` of one bearing (Eq. 15, made continuous).

    ``T_B0 = 1e-10 f_0 d^3 max(c_low, (nu N)^e)`` (``nu`` in mm^2/s, ``N`` in rpm, ``d`` in
    mm, ``T`` in N m). Printed Eq. 15 switches from ``c_low = 160`` to ``(nu N)^0.69`` at
    ``nu N = 2000``, where it jumps by 18 % (``2000^0.69 = 189``), and an equilibrium that
    falls on the jump has no solution. The maximum equals Eq. 15 for ``nu N >= 2000`` and
    is continuous below (it differs from Eq. 15 only for ``1570 < nu N < 2000``).

    Parameters
    ----------
    speed : array_like
        Bearing speed [rad/s] (its sign is ignored).
    diameter : float
        Bearing mean diameter ``d`` [m].
    kinematic_viscosity : float
        Lubricant kinematic viscosity [m^2/s].
    model : BearingModel
        Coefficients ``f_0``, ``c_low`` and the exponent ``e``.

    Returns
    -------
    ndarray
        Friction torque magnitude [N m].
    """
    # the scalar factors first: two array operations fewer (this runs at every iteration)
    # nu [mm^2/s] times n [rpm] (Eq. 15): the speed's conversion applied to nu, first
    scale, nu_rpm, low, exponent = speed_torque_constants(diameter, kinematic_viscosity, model)
    nu_n = nu_rpm * np.abs(np.asarray(speed, dtype=float))
    return scale * np.maximum(low, nu_n**exponent)


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
    coef, exponent = load_torque_constants(diameter, model)
    return coef * np.abs(np.asarray(load, dtype=float)) ** exponent
