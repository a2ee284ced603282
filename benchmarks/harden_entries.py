"""The entry points of the hardening campaign (`harden.py`) and the checks of every point.

One `Task` draws a buildable design and an operating point for its case, runs the case's
entry point at several torques, and records each point as ``ok``, ``flagged``, ``silent``
(with the check that failed) or ``bug``. Only public names of ballcvt are used.
"""

from __future__ import annotations

import json
import math
import os
import re
import traceback
from dataclasses import dataclass, field

import numpy as np

from ballcvt import (
    BUILTIN_DRIVES,
    ConvergenceError,
    InputError,
    SolveSettings,
    TractionLimitError,
    Variator,
    load_builtin,
)
from ballcvt.api import with_oil_temperature
from ballcvt.errors import NoEquilibriumError
from ballcvt.registry import CLAMP_LAWS, OPERATING_MODES, TRACTION_LAWS
from ballcvt.solvers.options import SolverOptions
from ballcvt.solvers.planetary import ratio_tolerance
from ballcvt.solvers.refusal import CREEP_RTOL

#: The entry points, in the order they are reported.
ENTRIES = ("solve", "sweep", "limit", "map", "table", "cycle step", "study evaluation")
#: Entry points the public API offers in a planetary mode (and which clamping they take).
MODE_ENTRIES = {"solve": "any", "limit": "any", "map": "any", "cycle step": "any"}
FLAGS = (TractionLimitError, NoEquilibriumError, InputError, ConvergenceError)
ETA_TOL = 1e-6  # sweep/map/table/cycle/study against solve
#: A creep is within the limit up to the solvers' own admissibility tolerance: `solve`
#: refuses only above ``creep_limit (1 + CREEP_RTOL)`` (the optimal clamp holds the
#: creep at the limit to that tolerance).
CREEP_SLACK = CREEP_RTOL
LIMIT_TOL = 1e-3  # limit searches against each other; 1.001 x the limit is "above"
ETA_SLACK = 1e-12  # round-off allowed outside [0, 1]
#: ``HARDEN_OIL=drive`` runs every task's drive with the oil model its file names (the
#: hub's heat balance: every path then solves each point at its own oil temperature,
#: docs/model.md §15, some 20 times the cost of a point); by default the fluid at its own
#: temperature. Not yet a case of the default campaign: 600 s at seed 4242 with every
#: task so (session 16, after its fixes): 681 points, 0 bug, 5 silent, all cycle steps
#: under the oil's transient up to 8e-6 off `solve` at their oil temperature (the
#: transient then took the chord of runs 1 K apart; the cubic through four since session
#: 17, within 4e-8 on the hub: tests/test_oil_temperature.py). Session 17, 900 s at seed
#: 4242 on one process of a machine 10-20 times slower than usual: 96 points, 0 silent, 1
#: task past the 600 s timeout (4242:13, a limit under the optimal clamp). Session 18:
#: 4242:13 completes, ok, in 9 min 51 s (near the timeout still); 150 s at seed 2718:
#: 154 points, 0 bug, 0 silent.


class Unsupported(Exception):
    """The public API refuses the case on purpose (e.g. the cam law in a planetary mode)."""


def supported(case: dict) -> bool:
    """Whether the public API has a call for ``case`` (the cam law in a planetary solve is
    found out by trying)."""
    if OPERATING_MODES.get(case["mode"]).is_default:
        return True
    need = MODE_ENTRIES.get(case["entry"])
    return need == "any" or (need == "fixed" and CLAMP_LAWS.get(case["clamp"]).fixed_force)


def heavy(case: dict) -> bool:
    """Whether a case costs seconds a point: a traction law with more than one equilibrium
    (every solve a continuation from zero torque, every limit the fold of a branch)."""
    return TRACTION_LAWS.get(case["law"]).multiple_equilibria


def points_per_call(case: dict) -> int:
    """Torques a task evaluates per grid row: 4 on a `heavy` case, 16 on the others
    (each point is still checked, and against `Variator.solve`, one by one)."""
    return 4 if heavy(case) else 16


def log_uniform(rng, lo, hi) -> float:
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


def _flag_key(exc: BaseException) -> str:
    """The message of a flag with its numbers replaced, for counting kinds of flags."""
    text = str(exc).strip().splitlines()[0] if str(exc).strip() else ""
    return f"{type(exc).__name__}: " + re.sub(r"[-+]?\d[\d.]*(e[-+]?\d+)?", "#", text)[:90]


def interrupt(exc: BaseException, depth: int = 8):
    """The exception behind ``exc`` that is not an ``Exception`` (the campaign's per-task
    timer, `harden._Alarm`, or a keyboard interrupt), else None. A signal handler that
    raises while a compiled (numba) function runs surfaces as ``SystemError: ...
    returned a result with an exception set``, caused by the handler's exception: task
    0:324 of the CI run recorded the budget's end that way as three bugs
    (``exception (study evaluation)``) in a loaded test run (session 28)."""
    seen: BaseException | None = exc
    for _ in range(depth):
        if seen is None:
            return None
        if not isinstance(seen, Exception):
            return seen
        seen = seen.__cause__ or seen.__context__
    return None


@dataclass
class Task:
    """One task: its case, random numbers, the points recorded, and the inputs so far."""

    case: dict
    rng: np.random.Generator
    points: list
    where: dict
    last_inputs: dict | None = None
    base: dict = field(default_factory=dict)
    cache: dict = field(default_factory=dict)

    def inputs(self, **point) -> dict:
        self.last_inputs = {**self.where, **self.base, **point}
        return self.last_inputs

    def record(self, outcome: str, check: str | None, message: str, inputs: dict) -> None:
        p = {"case": self.case, "outcome": outcome, "check": check, "message": message}
        if outcome in ("silent", "bug"):
            p["inputs"] = inputs
            p["rerun"] = (
                f"python benchmarks/harden.py --task {self.where['seed']}:{self.where['task']}"
            )
            p["python"] = python_snippet(inputs)  # the point through solve (or limit_torque)
        self.points.append(p)

    def exception(self, exc: BaseException, inputs: dict) -> None:
        """Record a point that raised: a flag (one clean line) or a bug. An exception
        caused by the campaign's own timer is the timer's: it is raised again
        (`interrupt`)."""
        stop = interrupt(exc)
        if stop is not None:
            raise stop
        text = str(exc).strip()
        if isinstance(exc, FLAGS):
            if "\n" in text or "internal error" in text.lower():
                self.record("bug", "flag message", f"{type(exc).__name__}: {text}", inputs)
            else:
                self.record("flagged", None, _flag_key(exc), inputs)
            return
        frames = traceback.extract_tb(exc.__traceback__)
        at = (
            f" (at {frames[-1].filename.split('/src/')[-1]}:{frames[-1].lineno} in "
            f"{frames[-1].name})"
            if frames
            else ""
        )
        self.record("bug", "exception", f"{type(exc).__name__}: {text}{at}", inputs)

    def judge(self, failed: list, inputs: dict) -> None:
        """Record a computed point: silent if a check failed, else ok."""
        if failed:
            self.record("silent", failed[0][0], "; ".join(f"{c}: {m}" for c, m in failed), inputs)
        else:
            self.record("ok", None, "", inputs)


def python_snippet(inputs: dict) -> str:
    """Python that rebuilds the drive and calls the entry point of a recorded point."""
    if "fields" not in inputs:
        return ""
    head = (
        f"import json; from ballcvt import *; from ballcvt.api import with_oil_temperature; "
        f"d, f = load_builtin({inputs['base']!r}); "
        f"d = d.replace(name='random', **json.loads({json.dumps(inputs['fields'])!r})); "
        f"v = Variator(d, f, {inputs['architecture']!r}, "
        f"traction_law={inputs['traction_law']!r}); "
        + ("" if inputs.get("oil") == "drive" else "v = with_oil_temperature(v, 'fixed'); ")
    )
    clamp = (
        f"clamp_force={inputs['clamp_force']!r}"
        if inputs.get("clamp_law") == "constant"
        else f"clamp_law={inputs.get('clamp_law')!r}"
    )
    mode = (
        ""
        if inputs.get("mode") in (None, "carrier_held")
        else f", settings=SolveSettings(mode={inputs['mode']!r})"
    )
    call = (
        f"v.limit_torque({inputs.get('ratio')!r}, {clamp}, "
        f"input_speed_rpm={inputs.get('input_speed_rpm')!r})"
        if inputs.get("output_torque") is None
        else f"v.solve({inputs.get('ratio')!r}, {inputs.get('output_torque')!r}, {clamp}, "
        f"input_speed_rpm={inputs.get('input_speed_rpm')!r}{mode})"
    )
    return head + "print(" + call + ")"


# --------------------------------------------------------------------------- drawing


def draw_fields(rng, d, wide: bool) -> dict:
    """Design fields around the base design ``d`` (or over the validators' whole ranges)."""
    if wide:
        groove = lambda: math.inf if rng.random() < 0.2 else 1.0 + log_uniform(rng, 1e-2, 100)  # noqa: E731
        rs = log_uniform(rng, 1e-3, 1.0)
        return dict(
            aspect_ratio=log_uniform(rng, 0.05, 100.0),
            roller_radius=rs,
            theta0_deg=rng.uniform(0.5, 89.5),
            theta2_deg=rng.uniform(0.5, 89.5),
            alpha_deg=rng.uniform(0.0, 89.5),
            n_rollers=int(rng.integers(3, 65)),
            roller_bearing_diameter=rs * log_uniform(rng, 0.05, 2.0),
            idler_bearing_diameter=rs * log_uniform(rng, 0.05, 2.0),
            disc_groove_ratio=groove(),
            idler_groove_ratio=groove(),
            single_idler_groove_ratio=groove(),
            tilt_safety_factor=rng.uniform(0.05, 1.0),
            creep_limit=log_uniform(rng, 1e-2, 0.5),
            min_roller_gap=rs * log_uniform(rng, 1e-4, 0.5),
        )
    f = lambda: log_uniform(rng, 0.3, 3.0)  # noqa: E731
    rs = d.roller_radius * f()
    return dict(
        aspect_ratio=d.aspect_ratio * f(),
        roller_radius=rs,
        theta0_deg=d.theta0_deg + rng.uniform(-20, 20),
        theta2_deg=d.theta2_deg + rng.uniform(-20, 20),
        alpha_deg=float(np.clip(d.alpha_deg + rng.uniform(-8, 20), 0.0, 89.0)),
        n_rollers=int(rng.integers(3, 17)),
        roller_bearing_diameter=rs / 3 * f(),
        idler_bearing_diameter=rs / 3 * f(),
        disc_groove_ratio=1.0 + 1.4548 * f(),
        idler_groove_ratio=1.0 + 1.4548 * f(),
        single_idler_groove_ratio=math.inf if rng.random() < 0.5 else 1.0 + 10 * f(),
        tilt_safety_factor=rng.uniform(0.5, 0.95),
        creep_limit=rng.uniform(0.05, 0.2),
        min_roller_gap=d.min_roller_gap * f(),
    )


def draw_cam(rng, rs: float) -> dict:
    """A loading cam scaled to the ball radius ``rs`` [m] (used by the cam law only)."""
    scale = rs / 0.03
    return {
        "disc": "output" if rng.random() < 0.7 else "input",
        "preload": 1000.0 * scale**2 * log_uniform(rng, 0.05, 10.0),
        "ramp_angle_deg": rng.uniform(2.0, 20.0),
        "mean_radius": 0.05 * scale * log_uniform(rng, 0.5, 2.0),
        "friction": rng.uniform(0.0, 0.05),
    }


def own_oil(task: Task) -> bool:
    """Whether the task's drive keeps the oil model its file names (``HARDEN_OIL``)."""
    return os.environ.get("HARDEN_OIL") == "drive"


def draw_drive(task: Task) -> Variator:
    """A buildable variator for the task's case; sets ``task.base`` (its inputs)."""
    rng, case = task.rng, task.case
    bases = tuple(BUILTIN_DRIVES)
    for _ in range(500):
        base = bases[int(rng.integers(len(bases)))]
        design, fluid = load_builtin(base)
        fields = draw_fields(rng, design, wide=rng.random() < 0.15)
        if rng.random() < 0.5:  # bias half the draws towards ball counts that fit
            k, rs, g = fields["aspect_ratio"], fields["roller_radius"], fields["min_roller_gap"]
            s = min(0.999, (1 + g / (2 * rs)) / (1 + k))
            fields["n_rollers"] = int(rng.integers(3, max(4, int(math.pi / math.asin(s)) + 1)))
        fields["cam"] = draw_cam(rng, fields["roller_radius"])
        if not OPERATING_MODES.get(case["mode"]).is_default and rng.random() < 0.7:
            fields["parasitic"] = None  # parasitic losses are refused with the carrier turning
        try:
            d = design.replace(name="random", **fields)
            v = Variator(d, fluid, case["arch"], traction_law=case["law"])
            oil = "drive" if own_oil(task) else "fixed"
            v = v if oil == "drive" else with_oil_temperature(v, "fixed")
        except InputError:
            continue
        task.base = {
            "base": base,
            "fields": fields,
            "fluid": base,
            "architecture": case["arch"],
            "traction_law": case["law"],
            "clamp_law": case["clamp"],
            "mode": case["mode"],
            "entry": case["entry"],
            "oil": oil,
        }
        return v
    raise RuntimeError("no buildable design in 500 draws")


def draw_condition(task: Task, v: Variator) -> dict:
    """Ratio [-], input (driver) speed [rpm] and clamping force [N] (or the law's)."""
    rng = task.rng
    lo, hi = v.ratio_range
    ratio = log_uniform(rng, lo, hi) if rng.random() < 0.85 else (lo if rng.random() < 0.5 else hi)
    scale = v.design.roller_radius / 0.03  # relative to the Table I ball
    wide = rng.random() < 0.15
    force = (
        2000.0 * scale**2 * (log_uniform(rng, 1e-2, 1e2) if wide else log_uniform(rng, 0.1, 10))
    )
    rpm = 2000.0 / scale * (log_uniform(rng, 1e-2, 30) if wide else log_uniform(rng, 0.02, 3))
    fixed = CLAMP_LAWS.get(task.case["clamp"]).fixed_force
    kw = {"clamp_force": force} if fixed else {"clamp_law": task.case["clamp"]}
    task.base.update(ratio=ratio, input_speed_rpm=rpm, clamp_force=force if fixed else None)
    guess = 0.05 * force * v.design.roller_radius if fixed else 20.0 * scale**3
    return {"ratio": ratio, "rpm": rpm, "kw": kw, "force": force, "guess": guess}


# --------------------------------------------------------------------------- checks


def _bound(v, rel, input_power: float) -> float:
    """How far Eq. 38 and Eq. 39 may differ: the power of the equilibrium residual."""
    speeds = abs(rel.roller_speed) + sum(abs(c.body_speed) for c in rel.contacts.values())
    slack = v.design.n_rollers * rel.clamp_force * v.design.roller_radius * rel.residual_norm
    return 1e-12 + 2.0 * slack * speeds / input_power if input_power > 0 else 1e-9


def _ratio_bound(v, p) -> float:
    """How far a planetary point's Eq. 38 and Eq. 39 may differ through its fixed point on
    the actual ratio (docs/model.md §13): the carrier frame's powers move with the ratio,
    which settles to `ratio_tolerance` (the thermal law's residual floor raises it)."""
    rel = p.relative
    tol = ratio_tolerance(SolverOptions(), v.fluid)
    return 2.0 * tol * (abs(rel.input_power) + abs(rel.output_power)) / p.input_power


def _creep_flagged(r) -> bool:
    return any("creep" in w.lower() for w in r.warnings)


def result_checks(v, r) -> list:
    """The checks of one `OperatingResult` (the paper's drive): ``[(check, message)]``."""
    bad = []
    numbers = [
        r.eta,
        r.eta_loss,
        r.eta_speed,
        r.eta_torque,
        r.input_torque,
        r.actual_ratio,
        r.tilt,
        r.clamp_force,
        *r.losses.values(),
    ]
    for c in r.contacts.values():
        numbers += [
            c.creep,
            c.spin,
            c.mu,
            c.chi,
            c.p_max,
            c.film_thickness,
            c.creep_loss,
            c.spin_loss,
            c.lambda_ratio,
        ]
    if not all(math.isfinite(x) for x in numbers):
        bad.append(("finite", "NaN or inf in the result"))
    if r.input_power <= 0 < r.output_power:
        bad.append(
            ("power direction", f"power in {r.input_power:.4g} W, out {r.output_power:.4g} W")
        )
    if not -ETA_SLACK <= r.eta <= 1.0 + ETA_SLACK:
        bad.append(("eta range", f"eta = {r.eta:.6g} outside [0, 1]"))
    neg = {k: x for k, x in r.losses.items() if x < 0}
    neg.update(
        {
            f"{n}.creep/spin": min(c.creep_loss, c.spin_loss)
            for n, c in r.contacts.items()
            if min(c.creep_loss, c.spin_loss) < 0
        }
    )
    if neg:
        bad.append(("negative loss", ", ".join(f"{k} {x:.4g} W" for k, x in neg.items())))
    bound = _bound(v, r, r.input_power)
    if abs(r.eta - r.eta_loss) > bound:
        bad.append(
            (
                "Eq. 38 = Eq. 39",
                f"eta {r.eta:.8g} vs eta_loss {r.eta_loss:.8g} (bound {bound:.3g})",
            )
        )
    creep = max(abs(c.creep) for c in r.contacts.values())
    if creep > v.design.creep_limit * (1 + CREEP_SLACK) and not _creep_flagged(r):
        bad.append(
            (
                "creep limit",
                f"|creep| {creep:.4g} > creep_limit {v.design.creep_limit:.4g} unflagged",
            )
        )
    if any(c.creep * c.mu < 0 for c in r.contacts.values()):
        bad.append(("creep sign", "creep and traction of opposite signs"))
    return bad


def planetary_checks(v, p) -> list:
    """The checks of one `PlanetaryResult`: efficiency by the way the power flows."""
    rel, bad = p.relative, []
    numbers = [*p.speeds.values(), *p.torques.values(), *rel.losses.values(), rel.tilt]
    numbers += [c.creep for c in rel.contacts.values()]
    if not all(math.isfinite(x) for x in numbers):
        bad.append(("finite", "NaN or inf in the result"))
    if p.input_power > 0:
        if not -ETA_SLACK <= p.eta <= 1.0 + ETA_SLACK:
            bad.append(("eta range", f"eta (power out / power in) = {p.eta:.6g} outside [0, 1]"))
        bound = _bound(v, rel, p.input_power) + _ratio_bound(v, p)
        if abs(p.eta - p.eta_loss) > bound:
            bad.append(
                (
                    "Eq. 38 = Eq. 39",
                    f"eta {p.eta:.8g} vs eta_loss {p.eta_loss:.8g} (bound {bound:.3g})",
                )
            )
    elif p.load_torque != 0:
        bad.append(("eta range", f"no power in at load {p.load_torque:.4g} N m"))
    neg = {k: x for k, x in rel.losses.items() if x < 0}
    if neg:
        bad.append(("negative loss", ", ".join(f"{k} {x:.4g} W" for k, x in neg.items())))
    creep = max(abs(c.creep) for c in rel.contacts.values())
    if creep > v.design.creep_limit * (1 + CREEP_SLACK) and not _creep_flagged(rel):
        bad.append(("creep limit", f"|creep| {creep:.4g} > {v.design.creep_limit:.4g}"))
    data = p.to_dict()
    for key in ("eta", "overall_eta"):
        x = data.get(key)
        if isinstance(x, float) and math.isfinite(x) and not -ETA_SLACK <= x <= 1.0 + ETA_SLACK:
            bad.append(("json eta", f"to_dict()[{key!r}] = {x:.4g} outside [0, 1]"))
    return bad


def reference(task: Task, v, cond: dict, torque: float, ratio=None, rpm=None, oil=None):
    """``Variator.solve`` at a point, once per task: ``("ok", result)`` or
    ``("flagged"|"bug", exception)``; ``oil``: with the oil at this temperature [K] (a
    cycle's step under the oil's transient)."""
    ratio = cond["ratio"] if ratio is None else float(ratio)
    rpm = cond["rpm"] if rpm is None else float(rpm)
    key = (ratio, float(torque), rpm, oil)
    if oil is not None:
        v = with_oil_temperature(v, oil)
    if key not in task.cache:
        mode = task.case["mode"]
        how = None if OPERATING_MODES.get(mode).is_default else SolveSettings(mode=mode)
        try:
            task.cache[key] = (
                "ok",
                v.solve(ratio, float(torque), **cond["kw"], input_speed_rpm=rpm, settings=how),
            )
        except FLAGS as exc:
            task.cache[key] = ("flagged", exc)
        except Exception as exc:  # noqa: BLE001
            task.cache[key] = ("bug", exc)
    return task.cache[key]


def agree(entry: str, status: int, eta: float, ref) -> list:
    """Whether a grid's point (status, eta) is the solve's answer (same flag, same branch)."""
    kind, got = ref
    if kind == "ok":
        if status != 0:
            return [
                (
                    f"{entry} = solve",
                    f"{entry} status {status}, solve converged (eta {got.eta:.8g})",
                )
            ]
        if not abs(eta - got.eta) <= ETA_TOL:
            return [(f"{entry} = solve", f"{entry} eta {eta:.8g} vs solve {got.eta:.8g}")]
    elif kind == "flagged" and status == 0:
        return [
            (
                f"{entry} = solve",
                f"{entry} converged (eta {eta:.6g}) where solve flagged {_flag_key(got)}",
            )
        ]
    return []


def grid_point_checks(v, values: dict) -> list:
    """The checks of a converged point of a grid (``values``: eta, eta_loss, losses,
    creep arrays)."""
    bad = []
    nums = np.concatenate([np.atleast_1d(np.asarray(x, float)) for x in values.values()])
    if not np.all(np.isfinite(nums)):
        bad.append(("finite", "NaN or inf at a converged point"))
    eta = float(values["eta"])
    if not -ETA_SLACK <= eta <= 1.0 + ETA_SLACK:
        bad.append(("eta range", f"eta = {eta:.6g} outside [0, 1]"))
    losses = np.asarray(values.get("losses", []), float)
    if losses.size and np.nanmin(losses) < 0:
        bad.append(("negative loss", f"a loss of {np.nanmin(losses):.4g} W"))
    creep = np.asarray(values.get("creep", []), float)
    if creep.size and np.nanmax(np.abs(creep)) > v.design.creep_limit * (1 + CREEP_SLACK):
        bad.append(
            (
                "creep limit",
                f"|creep| {np.nanmax(np.abs(creep)):.10g} > {v.design.creep_limit:.10g} "
                "at status 0",
            )
        )
    return bad


def close(a: float, b: float, tol: float = LIMIT_TOL) -> bool:
    if not (math.isfinite(a) and math.isfinite(b)):
        return math.isnan(a) == math.isnan(b) and (math.isnan(a) or a == b)
    return abs(a - b) <= tol * max(abs(a), abs(b), 1e-9)


# --------------------------------------------------------------------------- run


def run_case(task: Task) -> None:
    """Draw the drive and the point, then run the case's entry point."""
    from harden_modes import PLANETARY_RUNNERS
    from harden_paths import RUNNERS

    v = draw_drive(task)
    cond = draw_condition(task, v)
    default = OPERATING_MODES.get(task.case["mode"]).is_default
    (RUNNERS if default else PLANETARY_RUNNERS)[task.case["entry"]](task, v, cond)
