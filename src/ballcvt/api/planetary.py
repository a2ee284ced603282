"""The variator as a planetary (docs/model.md §13): one point, batched maps and the
capacity of a mode, for `Variator.solve`, `Variator.planetary_map` and
`Variator.planetary_capacity`."""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..model.modes import OperatingMode
from ..params.drive import Drive
from ..results.planetary import PlanetaryResult, make_planetary_result
from ..results.point import make_result
from ..solvers.planetary import ModePoint, solve_mode
from ..solvers.planetary_batch import ModeBatch, limit_load_batch, solve_mode_batch

__all__ = ["solve_in_mode", "planetary_map", "planetary_capacity"]


def _constant_force(variator, clamp_force, clamp_law) -> float:
    """``F_N0`` [N]: only the constant law is defined with the carrier turning."""
    law = variator.clamp_law(clamp_law, clamp_force)
    if not law.fixed_force:
        raise InputError(
            "clamp_law",
            law.name,
            "constant in a planetary mode (the cam "
            "and optimal laws are not yet defined with the carrier turning)",
        )
    return law.force


def solve_in_mode(
    variator, mode: OperatingMode, ratio, load_torque, clamp: dict, driver_speed, check_capacity
) -> PlanetaryResult:
    """`Variator.solve` in a planetary mode; ``clamp`` holds ``clamp_force`` and
    ``clamp_law``, ``driver_speed`` is in [rad/s]."""
    v = variator
    force = _constant_force(v, clamp.get("clamp_force"), clamp.get("clamp_law"))
    got = solve_mode(
        Drive(v.design, v.fluid, v.architecture),
        mode,
        ModePoint(float(ratio), float(load_torque), driver_speed, force),
        v.options,
    )
    creep = max(abs(c) for c in got.solution.state.creep)
    if check_capacity and creep > v.design.creep_limit:
        raise InputError(
            "output_torque",
            float(load_torque),
            f"within the traction capacity: the largest creep {creep:.3g} "
            f"exceeds creep_limit {v.design.creep_limit:g} ({mode.label})",
        )
    rel = make_result(got.problem, got.solution, v.options.quadrature)
    return make_planetary_result(
        mode, rel, got.sign, got.speeds, float(load_torque), driver_speed, got.passes
    )


def planetary_map(variator, mode, ratio, load_torque, driver_speed, clamp_force) -> ModeBatch:
    """`Variator.planetary_map`: ``ratio``, ``load_torque`` [N m] and ``driver_speed``
    [rad/s] broadcast to one batch, at ``clamp_force`` [N]."""
    v = variator
    force = _constant_force(v, clamp_force, None)
    return solve_mode_batch(
        Drive(v.design, v.fluid, v.architecture),
        mode,
        ModePoint(ratio, load_torque, driver_speed, force),
        v.options,
    )


def planetary_capacity(variator, mode, ratio, driver_speed, clamp_force) -> np.ndarray:
    """`Variator.planetary_capacity`: largest load torque ``|L|`` [N m] at each ratio."""
    v = variator
    force = _constant_force(v, clamp_force, None)
    return limit_load_batch(
        Drive(v.design, v.fluid, v.architecture),
        mode,
        ModePoint(ratio, np.nan, driver_speed, force),
        v.options,
    )
