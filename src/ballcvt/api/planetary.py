"""The variator as a planetary (docs/model.md §13): one point, batched maps, the
capacity and the efficiency map of a mode, for `Variator.solve`, `Variator.limit_torque`,
`Variator.efficiency_map`, `Variator.planetary_map` and `Variator.planetary_capacity`
given a mode."""

from __future__ import annotations

import numpy as np

from ..analysis.planetary import mode_map
from ..analysis.planetary_cycles import ModeCycle, mode_cycle
from ..errors import ConvergenceError, InputError, NoEquilibriumError, TractionLimitError
from ..model.architectures import CONTACT_NAMES
from ..model.modes import OperatingMode
from ..params.drive import Drive
from ..results.planetary import PlanetaryResult, make_planetary_result
from ..results.point import make_result
from ..solvers.planetary import ModePoint, ModeSolution, solve_mode
from ..solvers.planetary_batch import ModeBatch, limit_load_batch, solve_mode_batch
from ..units import rad_s_to_rpm

__all__ = [
    "solve_in_mode",
    "planetary_map",
    "planetary_capacity",
    "limit_in_mode",
    "map_in_mode",
    "cycle_in_mode",
]


def _constant_force(variator, clamp_force, clamp_law) -> float:
    """``F_N0`` [N]: only the constant law is defined with the carrier turning."""
    law = variator.clamp_law(clamp_law, clamp_force)
    if not law.fixed_force:
        raise InputError(
            "clamp_law",
            law.name,
            "constant in a planetary mode (the cam "
            "and optimal laws are not yet defined with the carrier turning): give "
            "clamp_force instead, or use the default mode (carrier held)",
        )
    return law.force


def solve_in_mode(
    variator, mode: OperatingMode, ratio, load_torque, clamp: dict, driver_speed, check_capacity
) -> PlanetaryResult:
    """`Variator.solve` in a planetary mode; ``clamp`` holds ``clamp_force`` and
    ``clamp_law``, ``driver_speed`` is in [rad/s]."""
    v = variator
    force = _constant_force(v, clamp.get("clamp_force"), clamp.get("clamp_law"))
    drive, point = (
        Drive(v.design, v.fluid, v.architecture),
        ModePoint(float(ratio), float(load_torque), driver_speed, force),
    )
    try:
        got = solve_mode(drive, mode, point, v.options)
    except ConvergenceError:
        if not check_capacity:
            raise
        _refuse_overload(v, mode, point, None)
        raise
    if check_capacity and _largest_creep(v, got)[1] > v.design.creep_limit:
        _refuse_overload(v, mode, point, got)
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


def _largest_creep(variator, got: ModeSolution) -> tuple[str, float]:
    """The contact with the largest ``|C|`` of a solved point, and that creep [-]."""
    creep = [abs(float(c)) for c in got.solution.state.creep]
    i = max(range(len(creep)), key=creep.__getitem__)
    return CONTACT_NAMES[variator.architecture][i], creep[i]


def _refuse_overload(variator, mode: OperatingMode, point: ModePoint, got) -> None:
    """Raise `TractionLimitError` for a load beyond the mode's capacity (one line, naming
    the contact at its creep limit and its creep), or `NoEquilibriumError` where even zero
    load is not admissible; return where the load is within the capacity (the caller
    then reports its own failure)."""
    v, load = variator, float(point.load_torque)
    drive = Drive(v.design, v.fluid, v.architecture)
    limit = float(limit_load_batch(drive, mode, point, v.options)[0])
    where = (
        f" ({mode.label}, ratio {float(point.ratio):g}, clamp {point.clamp_force:g} N, "
        f"driver {rad_s_to_rpm(float(point.driver_speed)):g} rpm"
    )
    if limit != limit:  # NaN: not even zero load
        raise NoEquilibriumError(
            f"no admissible equilibrium even at zero load{where}): the traction of "
            f"clamp_force {point.clamp_force:g} N does not carry the drive's own drag "
            f"within creep_limit {v.design.creep_limit:g}; raise the clamping force"
        )
    if abs(load) <= limit:
        return
    if got is None:  # no equilibrium at this load: name the contact at the capacity
        sign = 1.0 if load > 0 else -1.0
        got = solve_mode(
            drive,
            mode,
            ModePoint(point.ratio, sign * limit, point.driver_speed, point.clamp_force),
            v.options,
        )
        contact, creep = _largest_creep(v, got)
        why = f"at the capacity the {contact} contact's creep reaches {creep:.3g}"
    else:
        contact, creep = _largest_creep(v, got)
        why = f"the {contact} contact's creep {creep:.3g} exceeds creep_limit"
    # each direction of the load has its own capacity (`limit_load_batch`): name the range
    allowed = f"{-limit:.4g} to 0 N m" if load < 0 else ""
    raise TractionLimitError(
        load, limit, f"{where}; {why}, creep_limit {v.design.creep_limit:g})", allowed
    )


def limit_in_mode(variator, mode: OperatingMode, ratio, clamp: dict, driver_speed, creep_limit):
    """`Variator.limit_torque` in a planetary mode: the largest load torque ``|L|`` of the
    driven member [N m] with every ``|C| <= creep_limit``, to 1e-3 relative, braking the
    driven member (`limit_load_batch`). ``clamp`` holds ``clamp_force`` and ``clamp_law``,
    ``driver_speed`` is in [rad/s]. Where even zero load is not admissible: NaN at
    that ratio of an array, and for a single ratio the zero-load point's error (e.g. an
    `InputError` for a carrier too fast, `NoEquilibriumError`)."""
    v = variator
    force = _constant_force(v, clamp.get("clamp_force"), clamp.get("clamp_law"))
    design = v.design if creep_limit is None else v.design.replace(creep_limit=creep_limit)
    got = limit_load_batch(
        Drive(design, v.fluid, v.architecture),
        mode,
        ModePoint(np.atleast_1d(np.asarray(ratio, dtype=float)), np.nan, driver_speed, force),
        v.options,
    )
    if np.ndim(ratio) == 0 and np.isnan(got[0]):  # say why: the zero-load point's error
        solve_in_mode(v, mode, ratio, 0.0, clamp, driver_speed, True)
    return float(got[0]) if np.ndim(ratio) == 0 else got


def map_in_mode(variator, mode: OperatingMode, grid, driver_speed, clamp: dict):
    """`Variator.efficiency_map` in a planetary mode (`ballcvt.analysis.planetary.mode_map`
    on ``grid``, a `MapGrid`; ``clamp`` holds ``clamp_force`` and ``clamp_law``,
    ``driver_speed`` is in [rad/s])."""
    force = _constant_force(variator, clamp.get("clamp_force"), clamp.get("clamp_law"))
    loads = (
        grid.n_torque
        if grid.torque_max is None
        else np.linspace(grid.torque_max / grid.n_torque, grid.torque_max, grid.n_torque)
    )
    return mode_map(
        variator, mode, grid.ratios(), loads, driver_speed=driver_speed, clamp_force=force
    )


def cycle_in_mode(variator, mode: OperatingMode, cycle, how, clamp: dict):
    """`Variator.run_cycle` in a planetary mode (`ballcvt.analysis.planetary_cycles`):
    the driver held at the target input speed of ``how`` (a `CycleSettings`); ``clamp``
    holds ``clamp_force`` and ``clamp_law``."""
    if how.strategy not in (None, "target-input-speed"):
        raise InputError("strategy", how.strategy, "target-input-speed in a planetary mode")
    driver_speed = how.target()
    if driver_speed is None:
        raise InputError(
            "target_input_speed",
            None,
            "a speed for the driver in a planetary mode (--target-speed [rpm])",
        )
    force = _constant_force(variator, clamp.get("clamp_force"), clamp.get("clamp_law"))
    return mode_cycle(variator, cycle, ModeCycle(mode, float(driver_speed), force))
