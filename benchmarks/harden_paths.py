"""The hardening campaign's entry points in the paper's mode (carrier held, disc 0 drives):
solve, sweep, limit, map, table, cycle step and study evaluation (`harden.py`)."""

from __future__ import annotations

import math

import numpy as np
from harden_entries import (
    ETA_TOL,
    LIMIT_TOL,
    agree,
    close,
    grid_point_checks,
    points_per_call,
    reference,
    result_checks,
)

from ballcvt import (
    CycleSettings,
    InputError,
    MapGrid,
    SweepSettings,
    TableGrid,
    TractionLimitError,
    cycle_from_arrays,
)
from ballcvt.errors import NoEquilibriumError
from ballcvt.model.traction.base import has_multiple_equilibria
from ballcvt.solvers.optimal_batch import SEED_MIN
from ballcvt.units import rpm_to_rad_s

KEEP = ("output_torque", "loss", "contact")


def limit_of(task, v, cond):
    """``(limiting torque or None, exception or None)`` of the task's point (once)."""
    if "limit" not in task.cache:
        try:
            got = v.limit_torque(cond["ratio"], **cond["kw"], input_speed_rpm=cond["rpm"])
            task.cache["limit"] = (float(got), None)
        except Exception as exc:  # noqa: BLE001 - the limit entry records it
            task.cache["limit"] = (None, exc)
    return task.cache["limit"]


def torques(task, v, cond, fractions) -> list[float]:
    """Torques at ``fractions`` of the limit (of a guess where there is none) [N m]."""
    lim, _ = limit_of(task, v, cond)
    top = lim if lim is not None and math.isfinite(lim) and lim > 0 else cond["guess"]
    return [float(f * top) for f in fractions]


def _fractions(task) -> list[float]:
    """Shares of the limit: 0, 0.95, one above it and the rest at random below it."""
    rng, k = task.rng, points_per_call(task.case)
    below = sorted(float(x) for x in rng.uniform(0.05, 0.9, k - 3))
    return [0.0, *below, 0.95, float(rng.uniform(1.0, 1.5))]


def capacity_of(task, v, cond):
    """`Variator.capacity` of the task's point (once; None where it raises): under a
    loading cam with a small preload the admissible torques need not start at zero."""
    if "capacity" not in task.cache:
        try:
            task.cache["capacity"] = v.capacity(
                cond["ratio"], **cond["kw"], input_speed_rpm=cond["rpm"]
            )
        except Exception:  # noqa: BLE001 - the limit entry records why
            task.cache["capacity"] = None
    return task.cache["capacity"]


def _refused_below(task, v, cond, exc, t: float) -> bool:
    """A torque the reported capacity admits, refused as beyond it or as bad input."""
    refused = isinstance(exc, TractionLimitError) or (
        isinstance(exc, InputError) and exc.quantity == "output_torque"
    )
    lim, _ = limit_of(task, v, cond)
    if not (refused and lim is not None and math.isfinite(lim) and t < lim * (1 - LIMIT_TOL)):
        return False
    cap = capacity_of(task, v, cond)
    if cap is None:
        return True
    return any(lo * (1 + LIMIT_TOL) <= t <= hi * (1 - LIMIT_TOL) for lo, hi in cap.intervals)


def run_solve(task, v, cond):
    lim, _ = limit_of(task, v, cond)
    for t in torques(task, v, cond, _fractions(task)):
        inputs = task.inputs(output_torque=t)
        kind, got = reference(task, v, cond, t)
        if kind != "ok":
            if _refused_below(task, v, cond, got, t):
                msg = (
                    f"{type(got).__name__} at {t:.6g} N m, below the reported limit {lim:.6g} N m"
                )
                task.judge([("refused below the limit", f"{msg}: {str(got)[:160]}")], inputs)
            else:
                task.exception(got, inputs)
            continue
        task.judge(beyond_limit(task, v, cond, t) + result_checks(v, got), inputs)


def beyond_limit(task, v, cond, t: float) -> list:
    """A solve that converged (unflagged) at ``t`` [N m] above the reported limit, or where
    the limit search finds no admissible torque at all."""
    lim, exc = limit_of(task, v, cond)
    if lim is not None and math.isfinite(lim) and t > lim * (1 + LIMIT_TOL):
        return [
            (
                "converged beyond the limit",
                f"solve converged at {t:.6g} N m = {t / lim:.4g} x the reported limit "
                f"{lim:.6g} N m, unflagged",
            )
        ]
    if isinstance(exc, NoEquilibriumError) and t > 0:
        return [
            (
                "converged beyond the limit",
                f"solve converged at {t:.6g} N m where limit_torque finds no admissible "
                f"torque ({str(exc)[:120]})",
            )
        ]
    return []


#: Share of the limit [-] below it at which `_branch_below` solves again.
BRANCH_STEP = 1e-4


def _disc_creep(result) -> float:
    """The larger disc contact's ``|creep|`` of a solve's result [-]."""
    return max(abs(result.contacts[name].creep) for name in ("input", "output"))


def _branch_below(task, v, cond, at) -> list:
    """Under a law with more than one equilibrium and a force that does not optimise: the
    solve `BRANCH_STEP` below the limit lies on the branch below it, its larger disc
    creep no larger than the limit's (``at`` = ``(limit, result there)``). Along the
    branch from zero torque the disc creeps grow with the torque up to its fold; a solve
    past the fold has more creep at less torque (session 29: Table I's thermal cam sweep
    at ratio 1.83 reported such an equilibrium's efficiency at its limit)."""
    lim, got = at
    if not (has_multiple_equilibria(v.fluid) and lim > 0) or task.case["clamp"] == "optimal":
        return []
    kind, below = reference(task, v, cond, lim * (1 - BRANCH_STEP))
    if kind != "ok":
        return []
    creep_below, creep_at = _disc_creep(below), _disc_creep(got)
    if creep_below <= creep_at * (1 + 1e-9):
        return []
    return [("branch below the limit", f"solve at {1 - BRANCH_STEP:g} x the limit "
             f"{lim:.6g} N m has a disc creep {creep_below:.6g}, beyond the limit's "
             f"{creep_at:.6g}: past the fold")]  # fmt: skip


def run_limit(task, v, cond):
    lim, exc = limit_of(task, v, cond)
    inputs = task.inputs(output_torque=None)
    if exc is not None:
        task.exception(exc, inputs)
        return
    bad = []
    if not (math.isfinite(lim) and lim >= 0):
        bad.append(("limit value", f"limit_torque = {lim!r}"))
    else:
        kind, got = reference(task, v, cond, lim)
        if kind != "ok":
            bad.append(
                (
                    "solve at the limit",
                    f"solve refuses the reported limit {lim:.6g} N m: "
                    f"{type(got).__name__}: {str(got)[:200]}",
                )
            )
        else:
            bad += [(f"at the limit: {c}", m) for c, m in result_checks(v, got)]
            bad += _branch_below(task, v, cond, (lim, got))
        if lim > 0:
            kind, got = reference(task, v, cond, lim * (1 + LIMIT_TOL))
            if kind == "ok":
                creep = max(abs(c.creep) for c in got.contacts.values())
                bad.append(
                    (
                        "solve above the limit",
                        f"solve converges at 1.001 x the limit "
                        f"{lim:.6g} N m (|creep| {creep:.4g}), unflagged",
                    )
                )
            elif not isinstance(got, TractionLimitError) and not _runaway(got):
                bad.append(
                    (
                        "flag above the limit",
                        f"{type(got).__name__} (not "
                        f"TractionLimitError) at 1.001 x the limit: {str(got)[:200]}",
                    )
                )
        curve = v.limit_curve(
            [cond["ratio"]], input_speed_rpm=cond["rpm"], **cond["kw"], progress=False
        ).torque[0]
        if not close(float(curve), lim):
            bad.append(
                (
                    "limit_curve = limit_torque",
                    f"limit_curve {curve:.8g} vs limit_torque {lim:.8g} N m",
                )
            )
    task.judge(bad, inputs)


def _rows(ds, **isel) -> dict:
    """The variables of a grid along its torques (every other dimension picked)."""
    sub = ds.isel(**isel) if isel else ds
    sub = sub.isel({d: 0 for d in sub.dims if d not in KEEP})
    out = {"torque": sub.output_torque.values, "limit": float(sub.limit_torque.values)}
    for name in ("status", "eta", "eta_loss"):
        out[name] = sub[name].transpose("output_torque").values
    out["losses"] = sub.losses.transpose("output_torque", "loss").values
    out["creep"] = sub.creep.transpose("output_torque", "contact").values
    return out


def judge_grid(task, v, cond, entry, rows, at=None):
    """Each torque of a grid's rows: checked, and against solve at the same point."""
    lim, _ = limit_of(task, v, cond)
    at = at or {}
    for j, t in enumerate(rows["torque"]):
        inputs = task.inputs(output_torque=float(t), **at)
        ref = reference(task, v, cond, float(t), **at)
        status, eta = int(rows["status"][j]), float(rows["eta"][j])
        bad = agree(entry, status, eta, ref)
        drawn = at.get("rpm", cond["rpm"]) == cond["rpm"] and at.get("ratio") in (
            None,
            cond["ratio"],
        )
        if ref[0] == "ok" and drawn:
            bad = beyond_limit(task, v, cond, float(t)) + bad
        if status == 0:
            values = {k: rows[k][j] for k in ("eta", "eta_loss", "losses", "creep")}
            bad += grid_point_checks(v, values)
            if ref[0] == "ok" and abs(eta - rows["eta_loss"][j]) > max(
                ETA_TOL, 10 * abs(ref[1].eta - ref[1].eta_loss)
            ):
                bad.append(
                    ("Eq. 38 = Eq. 39", f"eta {eta:.8g} vs eta_loss {rows['eta_loss'][j]:.8g}")
                )
        if j == 0 and drawn and lim is not None and not close(rows["limit"], lim):
            bad.append(
                (
                    f"{entry} limit = limit_torque",
                    f"{entry} limit {rows['limit']:.8g} vs limit_torque {lim:.8g} N m",
                )
            )
        if bad or status == 0:
            task.judge(bad, inputs)
        else:
            task.record("flagged", None, f"{entry} status {status}", inputs)


def _grid_call(task, entry, points, call):
    """Run a grid call; a raise makes every one of its ``points`` torques that outcome."""
    try:
        return call()
    except Exception as exc:  # noqa: BLE001
        for t in points:
            task.exception(exc, task.inputs(output_torque=float(t)))
        return None


def run_sweep(task, v, cond):
    ts = sorted(set(torques(task, v, cond, _fractions(task))))
    ds = _grid_call(
        task,
        "sweep",
        ts,
        lambda: v.sweep(
            ratio=cond["ratio"],
            output_torque=ts,
            **cond["kw"],
            input_speed_rpm=cond["rpm"],
            settings=SweepSettings(progress=False),
        ),
    )
    if ds is not None:
        judge_grid(task, v, cond, "sweep", _rows(ds))


def _ratio_pair(v, r: float) -> tuple[tuple[float, float], int]:
    """A two-ratio range with ``r`` exactly at one end, inside the usable range."""
    lo, hi = v.ratio_range
    return ((r, r * 1.001), 0) if r * 1.001 <= hi else ((r / 1.001, r), 1)


def run_map(task, v, cond):
    top = torques(task, v, cond, [1.5])[0]
    span, i = _ratio_pair(v, cond["ratio"])
    n = points_per_call(task.case)
    grid = MapGrid(ratio_range=span, n_ratio=2, torque_max=top, n_torque=n)
    ds = _grid_call(
        task,
        "map",
        [top * j / n for j in range(1, n + 1)] * 2,  # the points the map would have given
        lambda: v.efficiency_map(grid, input_speed_rpm=cond["rpm"], **cond["kw"], progress=False),
    )
    if ds is not None:
        for k in (i, 1 - i):  # the drawn ratio first (its limit is known), then the other
            judge_grid(task, v, cond, "map", _rows(ds, ratio=k), {"ratio": float(ds.ratio[k])})


def run_table(task, v, cond):
    top = torques(task, v, cond, [1.5])[0]
    span, i = _ratio_pair(v, cond["ratio"])
    grid = TableGrid(
        ratio_range=span,
        n_ratio=2,
        torque_max=top,
        n_torque=points_per_call(task.case) - 1,
        speed_range_rpm=(cond["rpm"], cond["rpm"] * 1.05),
        n_speed=2,
    )
    ds = _grid_call(
        task,
        "table",
        list(np.linspace(0.0, top, points_per_call(task.case) - 1)) * 4,
        lambda: v.lookup_table(grid, **cond["kw"], progress=False),
    )
    if ds is not None:
        for k, m in ((i, 0), (i, 1), (1 - i, 0), (1 - i, 1)):  # the drawn point first
            at = {"ratio": float(ds.ratio[k]), "rpm": float(ds.input_speed_rpm[m])}
            judge_grid(task, v, cond, "table", _rows(ds, ratio=k, input_speed_rpm=m), at)


def run_cycle(task, v, cond):
    """Steps of an output-side cycle near the drawn ratio (the drawn one first), at a
    target input speed: torques at random shares of the limit, 0.9 and 1.3 of it."""
    lo, hi = v.ratio_range
    k = points_per_call(task.case) - 1
    near = task.rng.uniform(0.97, 1.03, k - 1)
    ratios = np.clip(cond["ratio"] * np.concatenate([[1.0], near]), lo, hi)
    ts = torques(task, v, cond, [*task.rng.uniform(0.05, 0.6, k - 2), 0.9, 1.3])
    w_in = rpm_to_rad_s(cond["rpm"])
    speeds, loads = w_in * ratios, np.asarray(ts, dtype=float)
    if task.case["clamp"] == "optimal":  # the first pass's seeds: SEED_MIN steps at least,
        # the checked ones first, then copies of them within a few per cent (session 34)
        pick = task.rng.integers(0, k, max(0, SEED_MIN - k))
        speeds = np.concatenate([speeds, speeds[pick] * task.rng.uniform(0.98, 1.02, pick.size)])
        loads = np.concatenate([loads, loads[pick] * task.rng.uniform(0.95, 1.05, pick.size)])
    cycle = cycle_from_arrays(
        time=np.arange(speeds.size, dtype=float),
        output_speed=speeds,
        output_torque=loads,
        name="harden",
    )
    got = _grid_call(
        task,
        "cycle step",
        ts,
        lambda: v.run_cycle(
            cycle,
            **cond["kw"],
            settings=CycleSettings(target_input_speed_rpm=cond["rpm"], progress=False),
        ),
    )
    if got is None:
        return
    loss_cols = [c for c in got.steps.columns if c.startswith("loss_")]
    eff = got.summary.get("efficiency")
    for j, row in enumerate(got.steps.to_dict("records")[:k]):
        at = {"ratio": float(row["ratio"]), "rpm": float(row["input_speed_rpm"])}
        t = float(row["output_torque"])
        inputs = task.inputs(
            output_torque=t,
            step=j,
            cycle_output_speed=list(speeds),
            cycle_output_torque=list(loads),
            **at,
        )
        # under the oil's transient a step runs at its own oil temperature, not the balance
        oil = row.get("oil_temperature_C")
        oil = float(oil) + 273.15 if oil is not None and math.isfinite(oil) else None
        ref = reference(task, v, cond, t, **at, oil=oil)
        status, eta = int(row["status"]), float(row["eta"])
        bad = agree("cycle step", status, eta, ref)
        if status == 0:
            bad += grid_point_checks(v, {"eta": eta, "losses": [row[c] for c in loss_cols]})
        if j == 0 and eff is not None and not 0.0 <= float(eff) <= 1.0:
            bad.append(("cycle efficiency", f"summary efficiency {eff!r} outside [0, 1]"))
        if bad or status == 0:
            task.judge(bad, inputs)
        else:
            task.record("flagged", None, f"cycle step status {status} ({row['flag']})", inputs)


def run_study(task, v, cond):
    """One design through a study's evaluation, against solve and limit_torque."""
    from ballcvt.analysis.studies import StudySpec, evaluate_chunk, make_context

    k = points_per_call(task.case) - 1
    ts = torques(task, v, cond, [*task.rng.uniform(0.05, 0.6, k - 2), 0.9, 1.3])
    fields = dict(task.base["fields"])
    n = fields.pop("n_rollers")
    operating = {"ratio": [cond["ratio"]], "output_torque": ts, "input_speed_rpm": [cond["rpm"]]}
    operating.update(
        {"clamp_force": cond["force"]}
        if "clamp_force" in cond["kw"]
        else {"clamp_law": cond["kw"]["clamp_law"]}
    )
    spec = {
        "study": {
            "name": "harden",
            "drive": task.base["base"],
            "samples": 1,
            "architecture": task.case["arch"],
            "traction_law": task.case["law"],
            "capacity_ratios": [cond["ratio"]],
            # the oil model of the task's drive (a study runs its drive file's by default)
            **({} if task.base.get("oil") == "drive" else {"oil_temperature": "fixed"}),
        },
        "parameters": {"n_rollers": {"values": [n]}},
        "fixed": fields,
        "operating": operating,
        "objectives": {"eta_mean": "max", "capacity": "max"},
    }

    def evaluate():
        return evaluate_chunk(make_context(StudySpec(**spec)), np.array([0]), np.array([[n]]))

    out = _grid_call(task, "study evaluation", ts, evaluate)
    if out is None:
        return
    lim, _ = limit_of(task, v, cond)
    status, reason = int(out["status"][0]), str(out["reason"][0])
    for j, t in enumerate(ts):
        inputs = task.inputs(output_torque=t, study=spec)
        pst = int(out["point_status"][0][j])
        if pst < 0:  # the design was not evaluated at its points
            ref = reference(task, v, cond, t)
            bad = (
                [
                    (
                        "study = solve",
                        f"study did not evaluate a design Variator builds and "
                        f"solves (status {status}: {reason})",
                    )
                ]
                if ref[0] == "ok"
                else []
            )
            if bad:
                task.judge(bad, inputs)
            else:
                task.record("flagged", None, f"study status {status}: {reason[:60]}", inputs)
            continue
        rows = {"torque": np.array(ts), "status": out["point_status"][0], "eta": out["eta"][0]}
        bad = agree("study", pst, float(rows["eta"][j]), reference(task, v, cond, t))
        if pst == 0:
            bad += grid_point_checks(v, {"eta": rows["eta"][j]})
        cap = float(out["capacity"][0])
        if j == 0 and lim is not None and math.isfinite(cap) and not close(cap, lim):
            bad.append(
                (
                    "study capacity = limit_torque",
                    f"capacity {cap:.8g} vs limit_torque {lim:.8g} N m",
                )
            )
        if bad or pst == 0:
            task.judge(bad, inputs)
        else:
            task.record("flagged", None, f"study point status {pst}", inputs)


RUNNERS = {
    "solve": run_solve,
    "sweep": run_sweep,
    "limit": run_limit,
    "map": run_map,
    "table": run_table,
    "cycle step": run_cycle,
    "study evaluation": run_study,
}


def _runaway(exc) -> bool:
    """Whether ``exc`` refuses a point as a thermal runaway of the oil (no heat balance
    below 150 C): the flag above a limit the runaway bounds (docs/model.md §15)."""
    return isinstance(exc, InputError) and "no oil heat balance" in str(exc)
