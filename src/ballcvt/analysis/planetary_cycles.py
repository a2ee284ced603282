"""A duty cycle in a planetary mode (docs/model.md §13), every step batched.

The cycle's output side is the driven member: its speed [rad/s] and load torque [N m] per
step (a braking load: positive power demanded). The driver turns at a target speed (the
``target-input-speed`` strategy of `ballcvt.analysis.cycles.run_cycle`), so the ideal
ratio relative to the carrier follows from Willis' relation; batched passes then correct
it for the creep (up to `CORRECTIONS` of them, to `RATIO_RTOL`). Steps whose ratio falls
outside the usable range run at the range's end (``ratio_limited``); steps beyond the
capacity, not converged or with speeds out of range are flagged and carry no energy.
"""

from __future__ import annotations

import time as _time
from dataclasses import dataclass

import numpy as np

from .._version import __version__
from ..errors import InputError
from ..model.kinematics import ratio_range
from ..model.modes import MEMBERS, OperatingMode
from ..params.drive import Drive
from ..performance.efficiency import LOSS_KINDS
from ..solvers.options import SolverOptions
from ..solvers.planetary import ModePoint
from ..solvers.planetary_batch import ModeBatch, limit_load_batch, solve_mode_batch
from ..status import Status
from ..units import rad_s_to_rpm
from .cycle_files import Cycle
from .cycles import CycleResult

__all__ = ["ModeCycle", "mode_cycle", "ratio_for_speed", "CORRECTIONS", "RATIO_RTOL"]

#: Most creep corrections of the ratio (batched solves after the first).
CORRECTIONS = 4
#: Relative tolerance of the actual ratio on the one the driven speed needs [-].
RATIO_RTOL = 1e-7


@dataclass(frozen=True)
class ModeCycle:
    """How a cycle is run in a planetary mode.

    Attributes
    ----------
    mode : OperatingMode
        Held, driving and driven members.
    driver_speed : float
        Speed the driver is held at [rad/s] (signed).
    clamp_force : float
        ``F_N0`` [N] (constant clamping, the only law defined with the carrier turning).
    """

    mode: OperatingMode
    driver_speed: float
    clamp_force: float


def ratio_for_speed(mode: OperatingMode, driver_speed, driven_speed):
    """Ratio relative to the carrier that gives the driven member ``driven_speed``.

    Willis' relation ``omega_2 - omega_c = tau (omega_0 - omega_c)`` solved for ``tau``
    with the held member at ``mode.held_speed`` and the driver at ``driver_speed``.

    Parameters
    ----------
    mode : OperatingMode
        Held and driving members.
    driver_speed, driven_speed : array_like
        Speeds of the driver and of the driven member [rad/s].

    Returns
    -------
    ndarray
        ``tau`` [-] (``inf`` or NaN where disc 0 and the carrier would turn together).
    """
    w = {
        mode.held: np.asarray(mode.held_speed, dtype=float),
        mode.driver: np.asarray(driver_speed, dtype=float),
        mode.driven: np.asarray(driven_speed, dtype=float),
    }
    with np.errstate(divide="ignore", invalid="ignore"):
        return (w["carrier"] - w["disc2"]) / (w["carrier"] - w["disc0"])


def mode_cycle(drive, cycle: Cycle, how: ModeCycle) -> CycleResult:
    """Run an output-side duty cycle in a planetary mode (module docstring).

    Parameters
    ----------
    drive : Drive or Variator
        Design, fluid, idler architecture and (optionally) solver ``options``.
    cycle : Cycle
        An output-side cycle: the driven member's speed [rad/s] and load torque [N m].
    how : ModeCycle
        Mode, driver speed [rad/s] and clamping force [N].

    Returns
    -------
    CycleResult
        Steps with ``ratio``, member speeds [rpm], ``load_torque`` [N m], ``input_power``
        and ``output_power`` (the drive's, by the way the power flows) [W], ``eta`` [-],
        ``input_speed_rpm``, ``output_speed_rpm`` (driver, driven), ``loss_<kind>`` [W],
        ``max_creep`` [-], ``status`` and ``flag``; the summary as
        `run_cycle`'s (energy in and out [J], efficiency, flags) with the mode.
    """
    if cycle.kind != "output" or cycle.output_speed is None or cycle.output_torque is None:
        raise InputError("cycle", cycle.kind, "an output-side cycle in a planetary mode")
    start = _time.perf_counter()
    mode = how.mode
    here = Drive(drive.design, drive.fluid, drive.architecture)
    opts = getattr(drive, "options", None) or SolverOptions()
    w_out, load = cycle.output_speed, cycle.output_torque
    flag = np.full(cycle.size, "ok", dtype=object)
    flag[(w_out == 0) & (load == 0)] = "idle"
    flag[w_out * load < 0] = "negative_torque"
    run = np.flatnonzero(flag == "ok")
    target = ratio_for_speed(mode, how.driver_speed, w_out[run])
    lo, hi = ratio_range(drive.design)
    tau = np.clip(np.nan_to_num(target, nan=hi, posinf=hi, neginf=lo), lo, hi)
    flag[run[tau != target]] = "ratio_limited"

    def solve(ratio):
        point = ModePoint(ratio, load[run], how.driver_speed, how.clamp_force)
        return solve_mode_batch(here, mode, point, opts)

    got = solve(tau)
    for _ in range(CORRECTIONS):  # scale tau_ID by the target over the actual ratio
        with np.errstate(divide="ignore", invalid="ignore"):
            actual = ratio_for_speed(mode, how.driver_speed, _driven(got, mode))
            fixed = np.clip(tau * target / actual, lo, hi)
        redo = (got.status == Status.CONVERGED) & (flag[run] == "ok") & np.isfinite(fixed)
        redo &= ~(np.abs(actual - target) <= RATIO_RTOL * np.abs(target))
        if not redo.any():
            break
        tau = np.where(redo, fixed, tau)
        got = solve(tau)
    _beyond(here, how, (run, tau, load), got, opts)
    flag[run[got.status == Status.BEYOND_LIMIT]] = "beyond_capacity"
    flag[run[got.status == Status.NOT_CONVERGED]] = "not_converged"
    flag[run[got.status == Status.OUT_OF_RANGE]] = "speed_out_of_range"
    steps = _steps(cycle, mode, (run, tau), got, flag)
    return CycleResult(steps, _summary(drive, cycle, steps, how, _time.perf_counter() - start))


def _beyond(drive: Drive, how: ModeCycle, steps, got: ModeBatch, options) -> None:
    """Mark the steps with no equilibrium whose load exceeds the capacity at their ratio
    as beyond it (``got.status``, in place), as in the maps."""
    run, tau, load = steps
    bad = np.flatnonzero(got.status == Status.NOT_CONVERGED)
    if bad.size:
        limit = limit_load_batch(
            drive,
            how.mode,
            ModePoint(tau[bad], load[run][bad], how.driver_speed, how.clamp_force),
            options,
        )
        got.status[bad[np.abs(load[run][bad]) > limit]] = Status.BEYOND_LIMIT


def _driven(got: ModeBatch, mode: OperatingMode):
    return got.speeds[MEMBERS.index(mode.driven)]


def _steps(cycle: Cycle, mode: OperatingMode, solved, got: ModeBatch, flag):
    """The steps' table (pandas.DataFrame); ``solved``: the steps run and their ratios."""
    import pandas as pd

    run, tau = solved
    n = cycle.size

    def put(values, idle=np.nan):
        out = np.full(n, np.nan)
        out[run] = values
        return np.where(flag == "idle", idle, out)

    col = {"time": cycle.time, "duration": cycle.durations, "ratio": put(tau)}
    for i, m in enumerate(MEMBERS):
        col[f"{m}_speed_rpm"] = put(rad_s_to_rpm(got.speeds[i]))
        col[f"{m}_torque"] = put(got.torques[i])
    col["load_torque"] = cycle.output_torque
    col["input_power"] = put(got.input_power, 0.0)
    col["output_power"] = put(np.sum(np.maximum(-got.powers, 0.0), axis=0), 0.0)
    # the carrier-held cycle's columns too: driver as input, driven member as output
    col["input_speed_rpm"] = col[f"{mode.driver}_speed_rpm"]
    col["output_speed_rpm"] = col[f"{mode.driven}_speed_rpm"]
    col["eta"] = put(got.eta)
    for row, kind in enumerate(LOSS_KINDS):
        col[f"loss_{kind}"] = put(got.losses[row], 0.0)
    col["max_creep"] = put(got.max_creep)
    status = np.full(n, -1)
    status[run] = got.status
    col["status"] = status
    col["flag"] = flag
    return pd.DataFrame(col)


def _summary(drive, cycle: Cycle, steps, how: ModeCycle, run_time: float) -> dict:
    dt = steps["duration"].to_numpy()
    counted = (steps["status"] == Status.CONVERGED).to_numpy()
    e_in = float(np.sum(np.where(counted, steps["input_power"] * dt, 0.0)))
    e_out = float(np.sum(np.where(counted, steps["output_power"] * dt, 0.0)))
    flags = {
        f: {"steps": int(m.sum()), "time_s": float(np.sum(dt[m]))}
        for f in dict.fromkeys(steps["flag"])
        for m in [(steps["flag"] == f).to_numpy()]
    }
    return {
        "cycle": cycle.name,
        "kind": cycle.kind,
        "mode": how.mode.label,
        "duration_s": float(np.sum(dt)),
        "energy_in_J": e_in,
        "energy_out_J": e_out,
        "efficiency": e_out / e_in if e_in > 0 else None,
        "losses_J": {
            k: float(np.sum(np.where(counted, steps[f"loss_{k}"] * dt, 0.0))) for k in LOSS_KINDS
        },
        "steps": int(len(dt)),
        "steps_flagged": int(sum(v["steps"] for k, v in flags.items() if k not in ("ok", "idle"))),
        "flags": flags,
        "strategy": f"target-input-speed, {how.mode.label}",
        "target_input_speed_rpm": rad_s_to_rpm(how.driver_speed),
        "clamp_law": "constant",
        "clamp_force": how.clamp_force,
        "architecture": drive.architecture,
        "design": drive.design.name,
        "version": __version__,
        "run_time_s": run_time,
    }
