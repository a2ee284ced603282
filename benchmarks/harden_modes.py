"""The hardening campaign's entry points in the planetary modes (a held member and a
driver, docs/model.md §13): solve, limit (`Variator.planetary_capacity`) and map
(`Variator.planetary_map`) (`harden.py`)."""

from __future__ import annotations

import math

import numpy as np
from harden_entries import (
    CREEP_SLACK,
    ETA_SLACK,
    LIMIT_TOL,
    agree,
    close,
    planetary_checks,
    reference,
)

from ballcvt import CycleSettings, InputError, MapGrid, TractionLimitError, cycle_from_arrays
from ballcvt.registry import OPERATING_MODES
from ballcvt.units import rpm_to_rad_s

MEMBERS = ("disc0", "disc2", "carrier")  # ballcvt.model.modes.MEMBERS, the speeds' rows


def _mode_kw(cond) -> dict:
    return {"driver_speed_rpm": cond["rpm"], "clamp_force": cond["force"]}


def capacity_of(task, v, cond):
    """``(|L| or None, braking sign, exception or None)`` of the task's point (once)."""
    if "capacity" not in task.cache:
        mode = task.case["mode"]
        try:
            zero = v.planetary_map(mode, cond["ratio"], 0.0, **_mode_kw(cond))
            sign = float(zero.braking_direction(OPERATING_MODES.get(mode))[0])
            cap = float(v.planetary_capacity(mode, [cond["ratio"]], **_mode_kw(cond))[0])
            task.cache["capacity"] = (cap, sign, None)
        except Exception as exc:  # noqa: BLE001 - the limit entry records it
            task.cache["capacity"] = (None, 1.0, exc)
    return task.cache["capacity"]


def loads(task, v, cond, fractions) -> list[float]:
    """Load torques of the driven member at ``fractions`` of its capacity [N m], signed to
    brake it (a guess where there is no capacity)."""
    cap, sign, _ = capacity_of(task, v, cond)
    top = cap if cap is not None and math.isfinite(cap) and cap > 0 else cond["guess"]
    return [float(sign * f * top) for f in fractions]


def _unsupported(task, exc, inputs) -> bool:
    """The cam and optimal laws, and parasitic losses, are refused in a planetary mode on
    purpose (coverage gaps, not defects)."""
    if isinstance(exc, InputError) and exc.quantity in ("clamp_law", "design.parasitic"):
        task.record("unsupported", "api", str(exc).splitlines()[0], inputs)
        return True
    return False


def run_solve(task, v, cond):
    fixed = "clamp_force" in cond["kw"]
    cap = capacity_of(task, v, cond)[0] if fixed else None
    fractions = [0.0, float(task.rng.uniform(0.05, 0.9)), 0.95, float(task.rng.uniform(1.0, 1.5))]
    for t in loads(task, v, cond, fractions) if fixed else [cond["guess"] * 0.3]:
        inputs = task.inputs(output_torque=t)
        kind, got = reference(task, v, cond, t)
        if kind != "ok":
            if not _unsupported(task, got, inputs):
                task.exception(got, inputs)
            continue
        bad = planetary_checks(v, got)
        if cap is not None and math.isfinite(cap) and abs(t) > cap * (1 + LIMIT_TOL):
            bad.append(
                (
                    "converged beyond the limit",
                    f"solve converged at load {t:.6g} N m "
                    f"= {abs(t) / cap:.4g} x the capacity {cap:.6g} N m, unflagged",
                )
            )
        task.judge(bad, inputs)


def _law_refused(task, v, cond) -> bool:
    """Under the cam or optimal law, the mode-aware public call of the entry (`limit_torque`,
    `efficiency_map` or `run_cycle` with ``mode=``) must refuse in one line, saying why and
    what to use: recorded as ``unsupported`` with its message (any other outcome is judged)."""
    if "clamp_force" in cond["kw"]:
        return False
    mode, inputs = task.case["mode"], task.inputs(output_torque=None)
    calls = {
        "limit": lambda: v.limit_torque(
            cond["ratio"], **cond["kw"], input_speed_rpm=cond["rpm"], mode=mode
        ),
        "map": lambda: v.efficiency_map(
            MapGrid((0.9 * cond["ratio"], 1.1 * cond["ratio"]), n_ratio=2, n_torque=2),
            **cond["kw"],
            input_speed_rpm=cond["rpm"],
            mode=mode,
        ),
        "cycle step": lambda: v.run_cycle(
            _cycle(v, cond, mode, [0.1 * cond["guess"]] * 3),
            **cond["kw"],
            settings=CycleSettings(target_input_speed_rpm=cond["rpm"], progress=False),
            mode=mode,
        ),
    }
    try:
        calls[task.case["entry"]]()
    except InputError as exc:
        if len(str(exc).splitlines()) == 1 and "instead" in str(exc):
            task.record("unsupported", "api", str(exc), inputs)
        else:
            task.exception(exc, inputs)
    except Exception as exc:  # noqa: BLE001 - judged as any other exception
        task.exception(exc, inputs)
    else:
        task.judge([("refusal", f"{task.case['clamp']} law accepted in a planetary mode")], inputs)
    return True


def _cycle(v, cond, name: str, loads):
    """Three steps of the driven member of mode ``name`` at about the drawn ratio's speed,
    braked by ``loads`` [N m] (signed to brake it)."""
    zero = v.planetary_map(name, cond["ratio"], 0.0, **_mode_kw(cond))
    mode = OPERATING_MODES.get(name)
    w = float(np.atleast_1d(zero.speeds[MEMBERS.index(mode.driven)])[0])
    w = w if math.isfinite(w) and w != 0 else rpm_to_rad_s(cond["rpm"])
    return cycle_from_arrays(
        time=[0.0, 1.0, 2.0],
        output_speed=list(w * np.array([1.0, 0.97, 1.03])),
        output_torque=[float(np.sign(w) * abs(x)) for x in loads],
        name="harden",
    )


def run_cycle(task, v, cond):
    """Three steps of a duty cycle in the mode (`Variator.run_cycle` with ``mode=``): every
    converged step checked (eta by power flow, losses, creep limit), others flagged."""
    if _law_refused(task, v, cond):
        return
    cap = capacity_of(task, v, cond)[0]
    top = cap if cap is not None and math.isfinite(cap) and cap > 0 else cond["guess"]
    loads = [float(task.rng.uniform(0.05, 0.6)) * top, 0.9 * top, 1.3 * top]
    settings = CycleSettings(target_input_speed_rpm=cond["rpm"], progress=False)
    try:
        cyc = _cycle(v, cond, task.case["mode"], loads)
        got = v.run_cycle(cyc, **cond["kw"], settings=settings, mode=task.case["mode"])
    except Exception as exc:  # noqa: BLE001
        for t in loads:
            task.exception(exc, task.inputs(output_torque=t))
        return
    loss_cols = [c for c in got.steps.columns if c.startswith("loss_")]
    for row in got.steps.to_dict("records"):
        inputs = task.inputs(output_torque=float(row["load_torque"]))
        if int(row["status"]) != 0:
            task.record("flagged", None, f"planetary cycle step {row['flag']}", inputs)
            continue
        bad = []
        e = float(row["eta"])
        if row["input_power"] > 0 and not -ETA_SLACK <= e <= 1.0 + ETA_SLACK:
            bad.append(("eta range", f"cycle step eta {e:.6g} outside [0, 1]"))
        if any(not row[c] >= 0 for c in loss_cols):
            bad.append(("negative loss", f"cycle step losses {[row[c] for c in loss_cols]}"))
        if row["max_creep"] > v.design.creep_limit * (1 + CREEP_SLACK):
            bad.append(("creep limit", f"cycle step max creep {row['max_creep']:.4g}"))
        task.judge(bad, inputs)


def run_limit(task, v, cond):
    if _law_refused(task, v, cond):
        return
    cap, sign, exc = capacity_of(task, v, cond)
    inputs = task.inputs(output_torque=None)
    if exc is not None:
        if not _unsupported(task, exc, inputs):
            task.exception(exc, inputs)
        return
    bad = []
    if math.isnan(cap):  # "even zero load is not admissible": solve must agree
        kind, got = reference(task, v, cond, 0.0)
        if kind == "ok":
            bad.append(
                (
                    "solve at the limit",
                    "planetary_capacity is NaN (no admissible "
                    "load) but solve converges at zero load",
                )
            )
        else:
            task.record("flagged", None, "planetary_capacity NaN (no admissible load)", inputs)
            return
    elif not cap >= 0:
        bad.append(("limit value", f"planetary_capacity = {cap!r}"))
    else:
        got_limit = v.limit_torque(
            cond["ratio"], **cond["kw"], input_speed_rpm=cond["rpm"], mode=task.case["mode"]
        )
        if not close(got_limit, cap):
            bad.append(
                ("limit_torque = capacity", f"limit_torque(mode=) {got_limit:.8g} vs {cap:.8g}")
            )
        kind, got = reference(task, v, cond, sign * cap)
        if kind != "ok":
            bad.append(
                (
                    "solve at the limit",
                    f"solve refuses the capacity {sign * cap:.6g} "
                    f"N m: {type(got).__name__}: {str(got)[:200]}",
                )
            )
        else:
            bad += [(f"at the limit: {c}", m) for c, m in planetary_checks(v, got)]
        kind, got = reference(task, v, cond, sign * cap * (1 + LIMIT_TOL))
        if kind == "ok":
            bad.append(
                (
                    "solve above the limit",
                    f"solve converges at 1.001 x the capacity {cap:.6g} N m, unflagged",
                )
            )
        elif not isinstance(got, TractionLimitError):
            bad.append(
                (
                    "flag above the limit",
                    f"{type(got).__name__} (not TractionLimitError) "
                    f"at 1.001 x the capacity: {str(got)[:160]}",
                )
            )
    task.judge(bad, inputs)


def run_map(task, v, cond):
    if _law_refused(task, v, cond):
        return
    ls = loads(task, v, cond, [0.0, float(task.rng.uniform(0.05, 0.9)), 0.95, 1.3])
    try:
        batch = v.planetary_map(task.case["mode"], cond["ratio"], np.array(ls), **_mode_kw(cond))
    except Exception as exc:  # noqa: BLE001
        for t in ls:
            if not _unsupported(task, exc, task.inputs(output_torque=t)):
                task.exception(exc, task.inputs(output_torque=t))
        return
    eta, status = np.atleast_1d(batch.eta), np.atleast_1d(batch.status)
    loss, creep = np.atleast_1d(batch.loss), np.atleast_1d(batch.max_creep)
    p_in = np.atleast_1d(batch.input_power)
    for j, t in enumerate(ls):
        inputs = task.inputs(output_torque=t)
        ref = reference(task, v, cond, t)
        st = int(status[j])
        e = float(eta[j])
        both_nan = ref[0] == "ok" and st == 0 and math.isnan(e) and math.isnan(ref[1].eta)
        bad = [] if both_nan else agree("map", st, e, ref)
        if st == 0:
            if p_in[j] > 0 and not -ETA_SLACK <= e <= 1.0 + ETA_SLACK:
                bad.append(("eta range", f"map eta {e:.6g} outside [0, 1]"))
            if not loss[j] >= 0:
                bad.append(("negative loss", f"map loss {loss[j]:.4g} W"))
            if creep[j] > v.design.creep_limit * (1 + CREEP_SLACK):
                bad.append(("creep limit", f"map max creep {creep[j]:.4g} at status 0"))
            if ref[0] == "ok" and not close(float(loss[j]), ref[1].loss, 1e-6):
                bad.append(("map = solve", f"map loss {loss[j]:.8g} vs solve {ref[1].loss:.8g} W"))
        if bad or st == 0:
            task.judge(bad, inputs)
        else:
            task.record("flagged", None, f"planetary map status {st}", inputs)


PLANETARY_RUNNERS = {
    "solve": run_solve,
    "limit": run_limit,
    "map": run_map,
    "cycle step": run_cycle,
}
