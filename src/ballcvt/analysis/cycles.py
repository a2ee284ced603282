"""Run a drive over a duty cycle: pick the ratio, solve every step batched, add up energy.

Strategies (``strategy=``; which options each uses: `ballcvt.analysis.cycle_request`):

* ``target-input-speed``: hold the input at a target speed (a cyclist's cadence, a
  motor's best speed): ``tau_ID = omega_2 / (omega_target eta_speed)``, found in two
  batched passes (the second corrects for the creep of the first). Steps whose ratio falls
  outside the allowed range (``ratio_range``, the usable range by default) run at the
  range's end and are flagged ``ratio_limited``.
* ``max-efficiency``: at each step, the most efficient of ``candidates`` ratios spread
  geometrically over the allowed range, refined by a parabola through the best and its
  neighbours; the input speed follows from the output speed. The default without a
  target input speed.

The ratio search and the creep correction use the solver's coarse predictor rule; every
reported value comes from a final solve on the full quadrature.

Input-side cycles (test rigs) give the input speed and power; with a ``ratio`` column the
ratio is commanded, else ``max-efficiency`` picks it. Their output torque is found by a
batched secant iteration on ``P_in = T_0 omega_0``.

Steps with no speed or no power are idle (zero energy, not flagged); negative torque
(braking) is outside the model and flagged ``negative_torque``; an input power below the
drive's own losses at zero output torque is flagged ``power_below_drag``; steps beyond the
traction
capacity (status 1) or not converged (status 2) are flagged and carry no energy, which the
summary reports as the energy the drive could not deliver (docs/cycles.md).
"""

from __future__ import annotations

import time as _time
from concurrent.futures import ProcessPoolExecutor
from contextlib import nullcontext
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np

from .._display import html_summary, text_summary
from .._version import __version__
from ..files import write_json
from ..model.clamping import clamp_law as resolve_law
from ..params.drive import Drive
from ..performance.efficiency import LOSS_KINDS
from ..results.losses import LossBreakdown
from ..solvers.options import SolverOptions, coarse_options
from ..status import Status
from ..units import rad_s_to_rpm, rpm_to_rad_s
from .cycle_files import STRATEGIES, Cycle
from .cycle_request import COMMANDED, CycleRequest, allowed_ratios
from .sweeps.curves import OperatingRows
from .sweeps.export import write_table
from .sweeps.points import evaluate_points

__all__ = ["CycleResult", "CycleRequest", "run_cycle", "STRATEGIES", "FLAGS"]

#: Step flags (``flag`` column): ``ok`` and ``idle`` are not counted as flagged.
FLAGS = (
    "ok",
    "idle",
    "ratio_limited",
    "negative_torque",
    "power_below_drag",
    "beyond_capacity",
    "not_converged",
)
#: Secant passes for the output torque of an input-side cycle.
POWER_PASSES = 12
#: Relative tolerance of its input torque [-].
POWER_RTOL = 1e-9


@dataclass(frozen=True)
class CycleResult:
    """A duty cycle run: every step and the totals.

    Attributes
    ----------
    steps : pandas.DataFrame
        One row per step (SI units; ``input_speed_rpm``/``output_speed_rpm`` in rpm),
        with the highest Hertz peak pressure ``max_pressure`` [Pa] and the lowest film
        thickness ratio ``min_lambda`` [-] over the contacts, ``flag`` (`FLAGS`) and
        ``status``.
    summary : dict
        ``energy_in_J``, ``energy_out_J``, ``efficiency`` (energy out over energy in),
        ``losses_J`` (by component, and ``total``, their sum: `_loss_energies`),
        ``loss_subtotals_J`` (``bearing``, ``parasitic``), ``steps``, ``steps_flagged``, ``flags`` (steps and seconds
        per flag), the inputs (design, strategy, clamping law) and the run time.
    """

    steps: Any  # pandas.DataFrame
    summary: dict = field(default_factory=dict)

    def _summary(self) -> tuple[str, list]:
        s = self.summary
        eff = s.get("efficiency")
        rows = [
            ("steps", s.get("steps", len(self.steps)), ""),
            ("duration", s.get("duration_s", float("nan")), "s"),
            ("energy in", s.get("energy_in_J", float("nan")) / 3.6e3, "Wh"),
            ("energy out", s.get("energy_out_J", float("nan")) / 3.6e3, "Wh"),
            ("efficiency", "n/a" if eff is None else eff, "-"),
            ("steps flagged", s.get("steps_flagged", 0), ""),
            ("strategy", s.get("strategy", ""), ""),
        ]
        return "CycleResult", rows

    def __repr__(self) -> str:
        return text_summary(*self._summary())

    def _repr_html_(self) -> str:
        return html_summary(*self._summary())

    def to_dataframe(self):
        """The steps, one row each (`steps`)."""
        return self.steps

    def save(self, out) -> list[Path]:
        """Write ``steps.csv`` and ``summary.json`` into the folder ``out``."""
        out = Path(out)
        units = {
            "time": "s",
            "duration": "s",
            "input_speed_rpm": "rpm",
            "output_speed_rpm": "rpm",
            "input_power": "W",
            "output_power": "W",
            "max_pressure": "Pa",
            **{f"loss_{k}": "W" for k in LOSS_KINDS},
        }
        files = [
            write_table(self.steps, out / "steps.csv", units),
            write_json(out / "summary.json", self.summary),
        ]
        return files


@dataclass(frozen=True)
class _Plan:
    """What the ratio strategies share within one run: the batched solve, the allowed
    ratios (`allowed_ratios`), the step flags and the steps that run."""

    solve: Any
    allowed: tuple[float, float]
    candidates: int
    flag: np.ndarray
    run: np.ndarray

    def limit(self, ratio):
        """``ratio`` within the allowed range; the clipped steps flagged ``ratio_limited``."""
        clipped = np.clip(ratio, *self.allowed)
        changed = clipped != ratio
        self.flag[self.run[changed]] = "ratio_limited"
        return clipped, changed


def run_cycle(drive, cycle: Cycle, settings: CycleRequest | None = None, **keywords):
    """Evaluate a drive over a duty cycle, all steps batched.

    Parameters
    ----------
    drive : Drive or Variator
        The drive (design, fluid, architecture and, if it has them, solver ``options``).
    cycle : Cycle
        From `ballcvt.analysis.cycle_files.read_cycle` or `cycle_from_arrays`.
    settings : CycleRequest, optional
        How the cycle is run; or give its fields as keywords (``strategy=...``).

    Returns
    -------
    CycleResult
    """
    import pandas as pd

    start = _time.perf_counter()
    s = replace(settings or CycleRequest(), **keywords).resolve(cycle)
    assert s.candidates is not None
    design = drive.design
    law = resolve_law(s.clamp_law, design, s.clamp_force)
    commanded = s.strategy == COMMANDED
    allowed = allowed_ratios(design, s)
    flag = _step_flags(cycle)
    run = np.flatnonzero(flag == "ok")
    passes = s.candidates + 2 if s.strategy == "max-efficiency" else 2
    if cycle.kind == "input":
        passes = POWER_PASSES * (1 if commanded else s.candidates + 1)
    # the ratio search and the creep correction run on the solver's coarse rule (the
    # predictor) to the predictor's tolerance (`_coarse`); every reported value comes
    # from a final solve on the full rule
    fine = getattr(drive, "options", None) or SolverOptions()
    coarse = _coarse(fine, law.optimises)
    pool = ProcessPoolExecutor(max_workers=s.workers) if s.workers > 1 else None
    with _bar(s, passes * run.size, cycle.size) as bar, pool or nullcontext():
        here = Drive(design, drive.fluid, drive.architecture)

        def solve(ratio, t2, w0, rough=False, near=None):
            # ``near``: a pass's result at nearby conditions, whose creeps start the solves
            # (and whose forces the optimal law's search)
            guess = None if near is None or not law.optimises else near["clamp_force"]
            points = OperatingRows.of(
                here,
                ratio,
                w0,
                clamp_force=law.force if law.fixed_force else guess,
                law=None if law.fixed_force else law,
                options=coarse if rough else fine,
            )
            start = None if near is None else near["creep"]
            return evaluate_points(points, t2, callback=bar.update, executor=pool, start=start)

        plan = _Plan(solve, allowed, s.candidates, flag, run)
        if cycle.kind == "output":
            assert cycle.output_speed is not None and cycle.output_torque is not None
            t2 = cycle.output_torque[run]
            ratio, w0, res = _output_side(plan, s, cycle.output_speed[run], t2)
        else:
            assert cycle.input_speed is not None and cycle.input_power is not None
            fixed = cycle.ratio[run] if commanded and cycle.ratio is not None else None
            ratio, w0, t2, res = _input_side(
                plan, cycle.input_speed[run], cycle.input_power[run], fixed
            )
    status = res["status"]
    flag[run[status == Status.BEYOND_LIMIT]] = "beyond_capacity"
    flag[run[status == Status.NOT_CONVERGED]] = "not_converged"
    if "below_drag" in res:
        flag[run[res["below_drag"]]] = "power_below_drag"
    steps = _table(cycle, run, (ratio, w0, t2), res, flag)
    summary = _summary(
        drive, cycle, steps, s.strategy, law, s.target_input_speed, _time.perf_counter() - start
    )
    summary["workers"] = int(s.workers)
    return CycleResult(steps=pd.DataFrame(steps), summary=summary)


def _bar(settings: CycleRequest, total: int, n: int):
    import sys

    from tqdm.auto import tqdm

    show = sys.stderr.isatty() if settings.progress is None else settings.progress
    return tqdm(total=total, desc=f"duty cycle, {n} steps", unit="point", disable=not show)


def _step_flags(cycle: Cycle) -> np.ndarray:
    """``ok``, ``idle`` or ``negative_torque`` per step, from the cycle's own columns."""
    flag = np.full(cycle.size, "ok", dtype=object)
    if cycle.kind == "output":
        speed, load = cycle.output_speed, cycle.output_torque
    else:
        speed, load = cycle.input_speed, cycle.input_power
    assert speed is not None and load is not None  # read_cycle guarantees them
    flag[load < 0] = "negative_torque"
    flag[(speed <= 0) | (load == 0)] = "idle"
    return flag


def _coarse(fine: SolverOptions, search: bool = False) -> SolverOptions:
    """The options of the ratio search and the creep correction: the coarse rule (the
    predictor; ``search``, under the optimal clamp: the options' smooth ``search_rule``),
    solved to the predictor's tolerance (as a solve's predictor stage is,
    `coarse_options`).

    The coarse rule's creeps differ from the full rule's by far more than that tolerance,
    so a tighter one buys nothing; and on it the optimal clamp's efficiency is not smooth
    in the force below about 1e-6, where Newton at 1e-11 took up to 30 iterations at some
    forces (benchmarks/bench_table.py, cycle rows: the optimal clamp's first pass, 0.73 of
    its 1.1 s per 1,000 steps)."""
    return coarse_options(fine, search)


def _output_side(plan: _Plan, s: CycleRequest, w2, t2):
    solve = plan.solve
    if s.strategy == "target-input-speed":
        target = s.target_input_speed
        want = w2 / target
        ratio, limited = plan.limit(want)
        res = solve(ratio, t2, w2 / ratio, rough=True)
        # second pass: the creep's speed loss, so that the input turns at the target
        speed_eff = np.where(res["status"] == 0, res["eta_speed"], 1.0)
        ratio2 = np.where(limited, ratio, np.clip(want / speed_eff, *plan.allowed))
        w0 = np.where(limited, w2 / ratio, target)
        return ratio2, w0, solve(ratio2, t2, w0, near=res)
    ratio = _best_ratio(
        lambda r: solve(r, t2, w2 / r, rough=True), t2.size, *plan.allowed, plan.candidates
    )
    first = solve(ratio, t2, w2 / ratio, rough=True)
    speed_eff = np.where(first["status"] == 0, first["eta_speed"], 1.0)
    w0 = w2 / (ratio * speed_eff)  # the output turns at the cycle's speed
    return ratio, w0, solve(ratio, t2, w0, near=first)


def _best_ratio(evaluate, n, r_lo, r_hi, candidates):
    """Most efficient ratio per point: the best of a geometric grid, refined by a parabola
    in log(ratio) through it and its neighbours (kept within them)."""
    grid = np.geomspace(r_lo, r_hi, candidates)
    eta = np.empty((n, candidates))
    for j, r in enumerate(grid):
        out = evaluate(np.full(n, r))
        eta[:, j] = np.where(out["status"] == 0, out["eta"], -np.inf)
    best = np.argmax(eta, axis=1)
    ratio = grid[best]
    x = np.log(grid)
    inner = (best > 0) & (best < candidates - 1) & np.isfinite(eta.max(axis=1))
    i = np.flatnonzero(inner)
    if i.size:
        b = best[i]
        y0, y1, y2 = eta[i, b - 1], eta[i, b], eta[i, b + 1]
        ok = np.isfinite(y0) & np.isfinite(y2)
        h = x[1] - x[0]
        with np.errstate(invalid="ignore"):
            denom = np.where(ok, y0 - 2 * y1 + y2, 0.0)
            shift = np.where(
                ok & (denom < 0),
                0.5 * h * np.where(ok, y0 - y2, 0.0) / np.where(denom < 0, denom, -1.0),
                0.0,
            )
        ratio[i] = np.exp(x[b] + np.clip(shift, -h, h))
    return ratio


def _input_side(plan: _Plan, w0, power, fixed):
    solve = plan.solve

    def at(ratio):
        """The output torque whose input torque is ``P / omega_0``: secant iterations on
        ``T_0(T_2)``, which is nearly affine (a drag plus ``tau_ID T_2 / eta_T``)."""
        t_in = power / w0
        t2, prev, out = t_in * ratio * 0.9, None, None
        for _ in range(POWER_PASSES):
            out = solve(ratio, t2, w0, near=out)
            ok = out["status"] == 0
            got = np.where(ok, out["input_torque"], np.nan)
            if np.all(~ok | (np.abs(got - t_in) <= POWER_RTOL * t_in)):
                break
            with np.errstate(divide="ignore", invalid="ignore"):
                slope = ratio if prev is None else (got - prev[1]) / (t2 - prev[0])
            slope = np.where(np.isfinite(slope) & (slope > 0), slope, ratio)
            prev = (t2, got)
            t2 = np.where(ok, np.maximum(t2 + (t_in - got) / slope, 0.0), t2)
        out = solve(ratio, t2, w0, near=out)
        missed = (out["status"] == 0) & (np.abs(out["input_torque"] - t_in) > 1e-6 * t_in)
        out["status"] = np.where(missed, Status.NOT_CONVERGED, out["status"])
        # the drive's own losses at zero output torque need more than the cycle's power
        out["below_drag"] = missed & (t2 == 0.0) & (out["input_torque"] > t_in)
        return t2, out

    if fixed is not None:
        ratio, _ = plan.limit(fixed)
    else:
        ratio = _best_ratio(lambda r: at(r)[1], w0.size, *plan.allowed, plan.candidates)
    t2, res = at(ratio)
    return ratio, w0, t2, res


def _table(cycle: Cycle, run, solved, res, flag) -> dict:
    """The steps' columns; ``solved``: (ratio, input speed, output torque) of the run."""
    ratio, w0, t2 = solved
    n = cycle.size
    nan = np.full(n, np.nan)
    col = {}

    def put(values):
        v = nan.copy()
        v[run] = values
        return v

    col["time"] = cycle.time
    col["duration"] = cycle.durations
    col["ratio"] = put(ratio)
    col["input_speed_rpm"] = put(rad_s_to_rpm(w0))
    col["output_speed_rpm"] = put(rad_s_to_rpm(res["actual_ratio"] * w0))
    col["output_torque"] = put(t2)
    col["input_torque"] = put(res["input_torque"])
    # torque x rpm -> W (converted last, as always)
    col["input_power"] = rpm_to_rad_s(col["input_torque"] * col["input_speed_rpm"])
    col["output_power"] = rpm_to_rad_s(col["output_torque"] * col["output_speed_rpm"])
    col["clamp_force"] = put(res["clamp_force"])
    col["axial_force"] = put(res["axial_force"])
    col["eta"] = put(res["eta"])
    col["tilt_deg"] = put(res["tilt_deg"])
    col["max_pressure"] = put(np.max(res["p_max"], axis=-1))  # over the contacts
    col["min_lambda"] = put(np.min(res["lambda_ratio"], axis=-1))
    for j, kind in enumerate(LOSS_KINDS):
        col[f"loss_{kind}"] = put(res["losses"][:, j])
    col["warnings"] = put(res["warnings"]).astype(float)
    status = np.full(n, -1)
    status[run] = res["status"]
    col["status"] = status
    col["flag"] = flag
    idle = flag == "idle"
    for key in ("input_power", "output_power", *(f"loss_{k}" for k in LOSS_KINDS)):
        col[key] = np.where(idle, 0.0, col[key])
    return col


def _summary(variator, cycle, steps, strategy, law, target, run_time) -> dict:
    dt = steps["duration"]
    ok = steps["flag"] == "ok"
    counted = ok | (steps["flag"] == "ratio_limited") & (steps["status"] == 0)
    e_in = float(np.sum(np.where(counted, steps["input_power"] * dt, 0.0)))
    e_out = float(np.sum(np.where(counted, steps["output_power"] * dt, 0.0)))
    losses, subtotals = _loss_energies(steps, counted, dt)
    flags = {}
    for f in FLAGS:
        mask = steps["flag"] == f
        flags[f] = {"steps": int(mask.sum()), "time_s": float(np.sum(dt[mask]))}
    if cycle.kind == "output":
        demand = np.where(steps["flag"] != "idle", cycle.output_speed * cycle.output_torque, 0.0)
        missing = float(np.sum(np.where(counted, 0.0, np.maximum(demand, 0.0)) * dt))
    else:
        missing = float(
            np.sum(
                np.where(
                    counted | (steps["flag"] == "idle"), 0.0, np.maximum(cycle.input_power, 0.0)
                )
                * dt
            )
        )
    return {
        "cycle": cycle.name,
        "kind": cycle.kind,
        "duration_s": float(np.sum(dt)),
        "energy_in_J": e_in,
        "energy_out_J": e_out,
        "efficiency": e_out / e_in if e_in > 0 else None,
        "losses_J": losses,
        "loss_subtotals_J": subtotals,
        "energy_not_delivered_J": missing,
        "steps": int(len(dt)),
        "steps_flagged": int(sum(v["steps"] for k, v in flags.items() if k not in ("ok", "idle"))),
        "flags": flags,
        "strategy": strategy,
        "target_input_speed_rpm": None if target is None else rad_s_to_rpm(target),
        "clamp_law": law.name,
        "clamp_force": getattr(law, "force", None),
        "architecture": variator.architecture,
        "design": variator.design.name,
        "version": __version__,
        "run_time_s": run_time,
    }


def _loss_energies(steps, counted, dt) -> tuple[dict, dict]:
    """Energy lost over the counted steps [J]: by component with ``total`` their sum to
    round-off (`ballcvt.results.losses.LossBreakdown`: ``creep``, ``spin``, ``roller_bearings``,
    ``idler_bearings``, ``churning``, ``seals``, ``disc_bearings``, ``hub_bearings``, and ``user_terms``
    when user loss terms dissipate), and the subtotals ``bearing`` and ``parasitic``."""
    energy = {
        k: float(np.sum(np.where(counted, steps[f"loss_{k}"] * dt, 0.0))) for k in LOSS_KINDS
    }
    builtin = ("churning", "seals", "disc_bearings", "hub_bearings")
    user = energy["parasitic"] - sum(energy[k] for k in builtin)
    if abs(user) > 1e-12 * max(1.0, abs(energy["parasitic"])):
        energy["user_terms"] = user
    parts = LossBreakdown(energy)
    return dict(parts), {"bearing": parts.bearing, "parasitic": parts.parasitic}
