"""A hub's own bearings: the shell bearings under the wheel's load and the driver bearing
under the chain pull (docs/model.md §12).

Two built-in loss terms of kind ``hub_bearings``, read from the hub keys of
``[design.parasitic]`` (`ballcvt.params.hub_losses`) and off without them:

* ``shell_bearings``: the two bearings of the hub shell, turning with the output disc
  (the shell), each carrying half the wheel's radial load ``W``;
* ``driver_bearing``: the bearing of the driver (sprocket), turning with the input disc,
  carrying the chain pull ``F_c = T_0 / r_sp`` (``T_0`` the lossless input torque
  `DragInputs.input_torque`, ``r_sp`` the sprocket's pitch radius).

Each bearing's friction torque is Palmgren's (`palmgren_torque`).
"""

from __future__ import annotations

import numpy as np

from ...params.models import Design
from ...registry import LOSS_TERMS
from ...units import rad_s_to_rpm
from .base import DragInputs, LossTerm

__all__ = ["palmgren_torque", "SHELL_BEARINGS", "DRIVER_BEARING"]


def palmgren_torque(speed, load, mean_diameter, kinematic_viscosity, f0, f1):
    """Friction torque of one rolling bearing, ``M = M_0 + M_1`` [N m] (Palmgren).

    ``M_0 = 1e-7 f_0 max(160, (nu n)^(2/3)) d_m^3`` (load-independent, viscous) and
    ``M_1 = f_1 P d_m`` (load-dependent), with ``nu`` in mm^2/s, ``n`` in rpm, ``d_m`` in
    mm and ``M`` in N mm (Palmgren, Ball and Roller Bearing Engineering, 3rd ed., 1959;
    Harris and Kotzalas, Rolling Bearing Analysis, 5th ed., 2007, vol. 2, Ch. 4: ``f_0``
    = 0.7-2 for deep-groove ball bearings in grease, ``f_1 = 0.0007 (P_0/C_0)^0.5``). The
    floor 160 is Palmgren's below ``nu n = 2000``, taken as a floor as in Eq. 15 of the
    paper (`ballcvt.model.bearings.speed_dependent_torque`): continuous in the speed. At
    rest the load-independent part keeps its floor: a magnitude; its direction
    (`ballcvt.model.losses.base.coulomb_direction`) takes it to zero with the speed.

    Parameters
    ----------
    speed : array_like
        Bearing speed [rad/s] (sign ignored).
    load : array_like
        Equivalent load ``P`` on the bearing [N] (sign ignored).
    mean_diameter : float
        Pitch diameter ``d_m`` [m].
    kinematic_viscosity : float
        Of the bearing's lubricant (base oil of its grease) [m^2/s].
    f0, f1 : float
        Palmgren's coefficients [-].

    Returns
    -------
    ndarray
        Torque magnitude [N m], >= 0.
    """
    nu_n = rad_s_to_rpm(kinematic_viscosity * 1e6) * np.abs(np.asarray(speed, dtype=float))
    dm = mean_diameter * 1e3
    m0 = 1e-7 * f0 * np.maximum(160.0, nu_n ** (2.0 / 3.0)) * dm**3
    m1 = f1 * np.abs(np.asarray(load, dtype=float)) * dm
    return 1e-3 * (m0 + m1)


def has_hub_bearings(design: Design) -> bool:
    """Whether ``design`` gives the hub's bearings (``[design.parasitic]`` hub keys)."""
    return design.parasitic is not None and design.parasitic.has_hub_bearings


def _shell_bearings(at: DragInputs):
    """Both shell bearings, each under half the wheel load (`palmgren_torque`) [N m]."""
    par = at.design.parasitic
    assert par is not None and par.hub_bearing_diameter is not None and par.wheel_load is not None
    one = palmgren_torque(
        at.speed,
        0.5 * par.wheel_load,
        par.hub_bearing_diameter,
        par.hub_bearing_viscosity,
        par.hub_bearing_f0,
        par.hub_bearing_f1,
    )
    return 2.0 * one


def _driver_bearing(at: DragInputs):
    """The driver bearing under the chain pull ``T_0 / r_sp`` (`palmgren_torque`) [N m]."""
    par = at.design.parasitic
    assert par is not None and par.sprocket_radius is not None
    pull = np.asarray(at.input_torque, dtype=float) / par.sprocket_radius
    return palmgren_torque(
        at.speed,
        pull,
        par.driver_bearing_diameter,
        par.hub_bearing_viscosity,
        par.hub_bearing_f0,
        par.hub_bearing_f1,
    )


_SOURCE = (
    "design.parasitic: hub_bearing_diameter, driver_bearing_diameter, wheel_load, "
    "sprocket_radius, hub_bearing_f0, hub_bearing_f1, hub_bearing_viscosity"
)
SHELL_BEARINGS = LOSS_TERMS.register(
    LossTerm(
        "shell_bearings", "output", _shell_bearings, "hub_bearings", _SOURCE, has_hub_bearings
    )
)
DRIVER_BEARING = LOSS_TERMS.register(
    LossTerm("driver_bearing", "input", _driver_bearing, "hub_bearings", _SOURCE, has_hub_bearings)
)
