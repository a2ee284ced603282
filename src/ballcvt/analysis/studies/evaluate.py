"""Evaluate designs of a study: build, check, solve the duty, score (docs/studies.md).

`evaluate_chunk` is what a Dask task runs: a chunk of designs, each with all its operating
points batched through the fast solver (`ballcvt.analysis.sweeps.points.evaluate_points`) and its
limits in one `limit_search`. It is a pure function of its arguments, so a design gives the
same numbers in any process.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...errors import BallCVTError, InputError
from ...model.architectures import contact_layout
from ...model.clamping import clamp_law
from ...model.clamping.base import names_fixed_force
from ...model.kinematics import ratio_range
from ...model.oil import fluid_at
from ...params.drive import PAPER_POINT, Drive
from ...params.drive_models import with_oil_model
from ...params.io import resolve_drive
from ...params.models import Design, Fluid
from ...status import Status
from ...units import rpm_to_rad_s
from ..oil_sweep import at_own_oil, limits_at_own_oil, oil_balance_of
from ..sweeps.curves import OperatingRows
from ..sweeps.points import evaluate_points
from .spec import OBJECTIVES, StudySpec

__all__ = [
    "Context",
    "make_context",
    "evaluate_chunk",
    "DESIGN_CODES",
    "METRICS",
    "envelope_diameter",
]

#: The status codes of a design (`ballcvt.status.Status`), with their words.
DESIGN_CODES = {
    Status.CONVERGED: "evaluated",
    Status.CANNOT_BE_BUILT: "cannot be built",
    Status.CONSTRAINT_VIOLATED: "constraint violated",
    Status.NOT_CONVERGED: "not solved",
}
#: Figures recorded for every design (the objectives are among them).
METRICS = tuple(OBJECTIVES)


@dataclass(frozen=True)
class Context:
    """Everything a task needs besides the designs' parameter vectors (picklable)."""

    spec: StudySpec
    base: dict
    fluid: Fluid
    ratio: np.ndarray
    torque: np.ndarray
    speed: np.ndarray
    weights: np.ndarray
    capacity_ratios: np.ndarray

    @property
    def n_points(self) -> int:
        return int(self.ratio.size)


def make_context(spec: StudySpec) -> Context:
    """Resolve the study's drive, fluid and operating points."""
    design, fluid = _oil_model(*resolve_drive(spec.study.drive), spec.study.oil_temperature)
    fluid = fluid.with_traction_law(spec.study.traction_law)
    op = spec.operating
    if op.cycle is None:
        r, t, w = np.meshgrid(
            np.asarray(op.ratio),
            np.asarray(op.output_torque),
            rpm_to_rad_s(np.asarray(op.input_speed_rpm)),
            indexing="ij",
        )
        ratio, torque, speed = r.ravel(), t.ravel(), w.ravel()
        weights = (
            np.ones(ratio.size) if op.weights is None else np.asarray(op.weights, dtype=float)
        )
    else:
        ratio = torque = speed = weights = np.zeros(0)
    cap = spec.study.capacity_ratios
    if cap is None:
        cap = sorted(set(op.ratio)) if op.ratio else [1.0]
    cap = sorted(set(cap) | {c.ratio for c in spec.constraints.min_capacity})
    return Context(
        spec,
        design.model_dump(),
        fluid,
        ratio,
        torque,
        speed,
        weights / weights.sum() if weights.size else weights,
        np.asarray(cap, dtype=float),
    )


def _oil_model(design: Design, fluid: Fluid, choice) -> tuple[Design, Fluid]:
    """The drive with the study's oil model ``choice`` (`StudySettings.oil_temperature`):
    None keeps the drive file's; a temperature [K] sets the fluid there, at a fixed oil."""
    if choice is None:
        return design, fluid
    if choice == "balance" and design.thermal is None:
        raise InputError("study.oil_temperature", choice, "a drive with a [design.thermal]")
    if not isinstance(choice, str):
        return with_oil_model(design, "fixed"), fluid_at(fluid, float(choice))
    return with_oil_model(design, choice), fluid


def envelope_diameter(design: Design) -> float:
    """Diameter of the balls' envelope ``2 (k + 2) r_S`` [m]: the balls' centres lie at
    ``(1 + k) r_S`` from the axis (docs/model.md §1)."""
    return 2.0 * (design.aspect_ratio + 2.0) * design.roller_radius


def evaluate_chunk(ctx: Context, index: np.ndarray, x: np.ndarray) -> dict:
    """Evaluate designs ``x`` (rows of parameter values, `StudySpec.names` order).

    Returns a dict of arrays with a leading axis of length ``len(index)``: ``design``
    (the indices), ``status`` (`DESIGN_CODES`), ``reason``, every metric of `METRICS`, ``eta``
    and ``point_status`` ``(n, n_points)``.
    """
    n = len(index)
    out: dict[str, Any] = {
        "design": np.asarray(index, dtype=np.int64),
        "status": np.zeros(n, np.int8),
        "reason": np.full(n, "", dtype="<U200"),
    }
    out.update({m: np.full(n, np.nan) for m in METRICS})
    out["eta"] = np.full((n, ctx.n_points), np.nan)
    out["point_status"] = np.full((n, ctx.n_points), -1, np.int8)
    for row in range(n):
        try:
            status, reason, metrics, eta, pst = _evaluate(ctx, dict(zip(ctx.spec.names, x[row])))
        except BallCVTError as exc:  # a solve that failed: said, not raised
            status, reason, metrics, eta, pst = Status.NOT_CONVERGED, str(exc), {}, None, None
        out["status"][row], out["reason"][row] = status, reason[:200]
        for m, v in metrics.items():
            out[m][row] = v
        if eta is not None:
            out["eta"][row], out["point_status"][row] = eta, pst
    return out


def _design(ctx: Context, values: dict):
    fields = {k: v for k, v in values.items() if k != "clamp_force"}
    for key, value in fields.items():  # whole numbers for integer fields
        if Design.model_fields[key].annotation is int:
            fields[key] = int(round(value))
    data = {**ctx.base, **ctx.spec.fixed, **fields}
    data["name"] = f"{ctx.spec.study.name}: " + ", ".join(
        f"{k} = {v:.6g}" for k, v in values.items()
    )
    return Design(**data)


def _geometry_violation(ctx: Context, design, outer_diameter: float) -> str:
    """Why the design's ratio range or size breaks a constraint ("" if neither does)."""
    con = ctx.spec.constraints
    lo, hi = ratio_range(design)
    needed = [*ctx.ratio, *ctx.capacity_ratios] + (con.ratio_range or [])
    if needed and (min(needed) < lo or max(needed) > hi):
        return f"ratio range {lo:.3f}-{hi:.3f} does not cover {min(needed):g}-{max(needed):g}"
    if con.outer_diameter_max is not None and outer_diameter > con.outer_diameter_max:
        return f"outer_diameter {outer_diameter:.4g} m > {con.outer_diameter_max:g} m"
    return ""


def _wants_life(spec: StudySpec) -> bool:
    """Whether the study asks for the fatigue life (an objective or a constraint)."""
    return "l10_hours" in spec.objectives or spec.constraints.min_l10_hours is not None


def _points_life(ctx: Context, drive: Drive, res: dict) -> float:
    """Shortest system L10 over the operating points [h] (docs/life.md)."""
    from ..life.point import SolvedPoints, creep_life

    points = SolvedPoints(
        drive, ctx.ratio, ctx.torque, res["clamp_force"], ctx.speed, res["creep"]
    )
    return float(np.nanmin(creep_life(points)[0]))


def _cycle_life(ctx: Context, design, force, law) -> float:
    """System L10 over the study's duty cycle by Miner's rule [h] (docs/life.md)."""
    from ..life import cycle_life

    op = ctx.spec.operating
    drive = Drive(design, ctx.fluid, ctx.spec.study.architecture)
    target = None if op.target_input_speed_rpm is None else rpm_to_rad_s(op.target_input_speed_rpm)
    run = _run_cycle(ctx, drive, None if law else force, law, target)
    return float(cycle_life(drive, run).summary["life"]["l10_hours"])


def _evaluate(ctx: Context, values: dict):
    """(status, reason, metrics, eta per point, point status) of one design."""
    spec = ctx.spec
    try:
        design = _design(ctx, values)
        contact_layout(design, spec.study.architecture)
    except BallCVTError as exc:
        return Status.CANNOT_BE_BUILT, str(exc), {}, None, None
    metrics = {"outer_diameter": envelope_diameter(design)}
    violated = _geometry_violation(ctx, design, metrics["outer_diameter"])
    if violated:
        return Status.CONSTRAINT_VIOLATED, violated, metrics, None, None
    force = values.get("clamp_force", spec.operating.clamp_force)
    law = None if names_fixed_force(spec.operating.clamp_law) else spec.operating.clamp_law
    law_obj = None if law is None else clamp_law(law, design)
    eta = pst = None
    if spec.operating.cycle is None:
        drive = Drive(design, ctx.fluid, spec.study.architecture)
        points = OperatingRows.of(drive, ctx.ratio, ctx.speed, None if law else force, law_obj)
        torque = ctx.torque  # each point at its own oil temperature where the drive names it
        _, res = at_own_oil(points, lambda r, i: (torque[i], evaluate_points(r, torque[i])))
        pst, eta = res["status"].astype(np.int8), res["eta"]
        beyond = int(np.sum(pst != 0))
        metrics["max_pressure"] = float(np.nanmax(res["p_max"])) if beyond < pst.size else np.nan
        metrics["min_lambda"] = (
            float(np.nanmin(res["lambda_ratio"])) if beyond < pst.size else np.nan
        )
        if beyond:
            return (
                Status.CONSTRAINT_VIOLATED,
                (
                    f"{beyond} of {pst.size} operating points beyond the traction capacity "
                    "or not solved"
                ),
                metrics,
                eta,
                pst,
            )
        metrics["eta_mean"] = float(np.sum(ctx.weights * eta))
        metrics["eta_min"] = float(np.min(eta))
        if _wants_life(spec):
            metrics["l10_hours"] = _points_life(ctx, drive, res)
    else:
        cyc = _cycle(ctx, design, force, law)
        metrics.update({k: cyc[k] for k in ("cycle_efficiency", "max_pressure", "min_lambda")})
        beyond = cyc["beyond"]
        if beyond:
            return (
                Status.CONSTRAINT_VIOLATED,
                f"{beyond} cycle steps beyond the traction capacity",
                metrics,
                None,
                None,
            )
        if _wants_life(spec):
            metrics["l10_hours"] = _cycle_life(ctx, design, force, law)
    # capacity at the capacity ratios (constant force: the study's; laws: their own),
    # searched as a sweep searches its limits
    speed = float(np.median(ctx.speed)) if ctx.speed.size else _cycle_speed(ctx)
    rows = OperatingRows.of(
        Drive(design, ctx.fluid, spec.study.architecture),
        ctx.capacity_ratios,
        np.full(ctx.capacity_ratios.size, speed),
        None if law_obj is not None else force,
        law_obj,
    )
    limits = limits_at_own_oil(rows)
    metrics["capacity"] = float(np.min(limits))
    volume = math.pi * (metrics["outer_diameter"] / 2) ** 2 * 2 * design.roller_radius
    mass = design.n_rollers * design.material.density * 4 / 3 * math.pi * design.roller_radius**3
    metrics["torque_per_volume"] = metrics["capacity"] / volume
    metrics["torque_per_mass"] = metrics["capacity"] / mass
    return _constraints(ctx, metrics, limits) + (metrics, eta, pst)


def _constraints(ctx: Context, metrics: dict, limits) -> tuple[int, str]:
    con = ctx.spec.constraints
    checks = [
        ("max_pressure", con.max_pressure_max, "<="),
        ("min_lambda", con.min_lambda_min, ">="),
        ("eta_min", con.eta_min_min, ">="),
        ("l10_hours", con.min_l10_hours, ">="),
    ]
    for name, bound, sense in checks:
        value = metrics.get(name, np.nan)
        if bound is not None and not (value <= bound if sense == "<=" else value >= bound):
            return (
                Status.CONSTRAINT_VIOLATED,
                f"{name} {value:.4g} {'>' if sense == '<=' else '<'} {bound:g}",
            )
    if not np.all(np.isfinite(limits)):
        return Status.CONSTRAINT_VIOLATED, "no admissible equilibrium at a capacity ratio"
    for req in con.min_capacity:
        got = float(limits[int(np.argmin(np.abs(ctx.capacity_ratios - req.ratio)))])
        if got < req.torque:
            return (
                Status.CONSTRAINT_VIOLATED,
                f"capacity {got:.4g} N m < {req.torque:g} N m at ratio {req.ratio:g}",
            )
    return Status.CONVERGED, ""


def _cycle_speed(ctx: Context) -> float:
    return rpm_to_rad_s(ctx.spec.operating.target_input_speed_rpm or PAPER_POINT.input_speed_rpm)


def _cycle(ctx: Context, design, force, law) -> dict:
    """Efficiency, steps beyond capacity, highest peak pressure [Pa] and lowest film
    thickness ratio [-] (over the solved steps and their contacts; NaN if none solved) of
    the study's duty cycle (`_run_cycle`)."""
    op = ctx.spec.operating
    v = Drive(design, ctx.fluid, ctx.spec.study.architecture)
    # held by target-input-speed only (under max-efficiency: the capacity speed)
    target = (
        rpm_to_rad_s(op.target_input_speed_rpm) if op.strategy == "target-input-speed" else None
    )
    res = _run_cycle(ctx, v, None if law else force, law, target)
    s = res.summary
    beyond = int(s.get("flags", {}).get("beyond_capacity", {}).get("steps", 0))
    eff = s["efficiency"]
    solved = res.steps[res.steps["status"] == Status.CONVERGED]
    return {
        "cycle_efficiency": np.nan if eff is None else float(eff),
        "beyond": beyond,
        "max_pressure": float(solved["max_pressure"].max()) if len(solved) else np.nan,
        "min_lambda": float(solved["min_lambda"].min()) if len(solved) else np.nan,
    }


def _run_cycle(ctx: Context, drive: Drive, force, law, target):
    """The study's duty cycle on ``drive`` (``force`` [N] or ``law``, ``target`` input speed
    [rad/s] or None): under the oil's lumped transient where the drive file names the
    oil's heat balance and its housing a thermal mass, as `Variator.run_cycle` runs it
    (docs/model.md §15); else with the fluid as given."""
    from ..cycle_files import read_cycle
    from ..cycle_request import CycleRequest
    from ..cycles import run_cycle
    from ..oil_cycle import OilTransient, run_cycle_with_oil

    op = ctx.spec.operating
    assert op.cycle is not None
    request = CycleRequest(
        strategy=op.strategy,
        target_input_speed=target,
        clamp_force=force,
        clamp_law=law,
        progress=False,
    )
    thermal = oil_balance_of(drive.design)
    if thermal is not None and thermal.thermal_mass is not None:
        return run_cycle_with_oil(drive, read_cycle(op.cycle), request, OilTransient(thermal))
    return run_cycle(drive, read_cycle(op.cycle), request)
