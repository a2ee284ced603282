"""Evaluate drawn drives: build each (through the normal validators), solve its operating
points and search its capacity.

`evaluate_chunk` is what a Dask task runs: a pure function of its arguments (a sample gives
the same numbers in any process). Each drive's operating points are batched through the
fast solver (`ballcvt.analysis.sweeps.points.evaluate_points`) and its capacities in one
limit search (`ballcvt.analysis.sweeps.curves.limit_search_curves`), as a study does.
A drawn drive that cannot be built is counted with its reason, never dropped silently.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ...errors import BallCVTError
from ...model.architectures import contact_layout
from ...model.clamping import clamp_law
from ...params.drive import Drive
from ...params.models import Design, Fluid
from ...params.uncertainty import with_values
from ...solvers import SolverOptions
from ...status import Status
from ..oil_sweep import at_own_oil, limits_at_own_oil
from ..sweeps.curves import OperatingRows
from ..sweeps.points import evaluate_points

__all__ = ["Duty", "Context", "evaluate_chunk", "POWER_PASSES"]

#: Secant passes on the output torque that draws a given input power.
POWER_PASSES = 8
#: Relative tolerance on the input power [-].
POWER_RTOL = 1e-7


@dataclass(frozen=True)
class Duty:
    """The operating points of a propagation, one row each, and the capacity rows.

    Attributes
    ----------
    ratio, input_speed : ndarray
        Ideal ratio [-] and input speed [rad/s] of each point, ``(m,)``.
    load : ndarray
        Output torque [N m] (``power`` false) or input power [W] (``power`` true), ``(m,)``.
    power : bool
        Whether ``load`` is the input power (the output torque is then found by secant
        iterations on ``P = T_0 omega_0``).
    capacity_ratio, capacity_speed : ndarray
        Ratio [-] and input speed [rad/s] of each capacity (limiting torque) row, ``(c,)``.
    """

    ratio: np.ndarray
    input_speed: np.ndarray
    load: np.ndarray
    power: bool
    capacity_ratio: np.ndarray
    capacity_speed: np.ndarray


@dataclass(frozen=True)
class Context:
    """Everything a task needs besides the samples (picklable).

    Attributes
    ----------
    design, fluid : Design, Fluid
        The nominal drive.
    architecture : str
        Idler architecture.
    paths : tuple of str
        Dotted paths of the uncertain values, the columns of the samples.
    duty : Duty
        Operating points and capacity rows.
    clamp_law : str
        Name of the clamping law (re-resolved on every drawn design: a cam's preload is
        the design's).
    clamp_force : float or None
        ``F_N0`` [N] of a fixed-force law.
    options : SolverOptions
        Solver options.
    """

    design: Design
    fluid: Fluid
    architecture: str
    paths: tuple[str, ...]
    duty: Duty
    clamp_law: str
    clamp_force: float | None
    options: SolverOptions = SolverOptions()


def evaluate_chunk(ctx: Context, index: np.ndarray, x: np.ndarray) -> dict:
    """Evaluate the drives drawn as rows of ``x`` (`Context.paths` order).

    Returns
    -------
    dict of ndarray
        ``sample`` (the indices), ``built`` (bool), ``reason`` (why not built or not
        solved), ``eta``, ``status`` (`ballcvt.status.Status`) and ``output_torque`` [N m]
        ``(n, m)``, ``input_torque`` [N m] ``(n, m)``, ``capacity`` [N m] ``(n, c)``.
    """
    n, m, c = len(index), ctx.duty.ratio.size, ctx.duty.capacity_ratio.size
    out: dict[str, Any] = {
        "sample": np.asarray(index, dtype=np.int64),
        "built": np.zeros(n, bool),
        "reason": np.full(n, "", dtype="<U200"),
        "status": np.full((n, m), Status.CANNOT_BE_BUILT, np.int8),
        "capacity": np.full((n, c), np.nan),
    }
    for key in ("eta", "output_torque", "input_torque"):
        out[key] = np.full((n, m), np.nan)
    for row in range(n):
        try:
            design, fluid = with_values(ctx.design, ctx.fluid, dict(zip(ctx.paths, x[row])))
            contact_layout(design, ctx.architecture)
            law = clamp_law(ctx.clamp_law, design, ctx.clamp_force)
        except BallCVTError as exc:
            out["reason"][row] = str(exc)[:200]
            continue
        out["built"][row] = True
        try:
            _solve(ctx, Drive(design, fluid, ctx.architecture), law, out, row)
        except BallCVTError as exc:  # a solve that failed: said, not raised
            out["status"][row] = Status.NOT_CONVERGED
            out["reason"][row] = str(exc)[:200]
    return out


def _rows(ctx: Context, drive: Drive, law, ratio, speed) -> OperatingRows:
    fixed = getattr(law, "fixed_force", False)
    return OperatingRows.of(
        drive,
        ratio,
        speed,
        clamp_force=law.force if fixed else None,
        law=None if fixed else law,
        options=ctx.options,
    )


def _solve(ctx: Context, drive: Drive, law, out: dict, row: int) -> None:
    """Efficiency at the points and capacity at the capacity rows of one drive."""
    duty = ctx.duty
    points = _rows(ctx, drive, law, duty.ratio, duty.input_speed)
    caps = _rows(ctx, drive, law, duty.capacity_ratio, duty.capacity_speed)

    def solved(rows, idx):
        if duty.power:
            return _at_power(rows, duty.load[idx])
        return duty.load[idx], evaluate_points(rows, duty.load[idx])

    # each point and each limit at its own oil temperature where the drive names the
    # oil's balance (docs/model.md §15)
    t2, res = at_own_oil(points, solved)
    out["capacity"][row] = limits_at_own_oil(caps)
    out["status"][row] = res["status"]
    ok = res["status"] == Status.CONVERGED
    out["eta"][row] = np.where(ok, res["eta"], np.nan)
    out["output_torque"][row] = np.where(ok, t2, np.nan)
    out["input_torque"][row] = np.where(ok, res["input_torque"], np.nan)


def _at_power(points: OperatingRows, power: np.ndarray):
    """``(output torque, results)`` at which each point draws the input power ``power``
    [W]: secant iterations on ``T_0(T_2)``, nearly affine (a drag plus ``tau T_2 /
    eta``), as a duty cycle's input side is solved (`ballcvt.analysis.cycles`)."""
    ratio, t_in = points.ratio, power / points.input_speed
    t2, prev = t_in * ratio * 0.9, None
    res = evaluate_points(points, t2)
    for _ in range(POWER_PASSES):
        ok = res["status"] == Status.CONVERGED
        got = np.where(ok, res["input_torque"], np.nan)
        if np.all(~ok | (np.abs(got - t_in) <= POWER_RTOL * t_in)):
            break
        with np.errstate(divide="ignore", invalid="ignore"):
            slope = ratio if prev is None else (got - prev[1]) / (t2 - prev[0])
        slope = np.where(np.isfinite(slope) & (slope > 0), slope, ratio)
        prev = (t2, got)
        t2 = np.where(ok, np.maximum(t2 + (t_in - got) / slope, 0.0), t2)
        res = evaluate_points(points, t2)
    missed = (res["status"] == Status.CONVERGED) & (
        np.abs(res["input_torque"] - t_in) > 1e-5 * t_in
    )
    res["status"] = np.where(missed, Status.NOT_CONVERGED, res["status"]).astype(np.int8)
    return t2, res
