"""The hardening campaign (benchmarks/harden.py) runs within its budget and reports every
case of the registries, in the JSON shape the lead's tools read."""

from __future__ import annotations

import json
import subprocess
import sys
import time
from pathlib import Path

import ballcvt
from ballcvt.registry import ARCHITECTURES, CLAMP_LAWS, OPERATING_MODES, TRACTION_LAWS

ROOT = Path(__file__).resolve().parents[1]
ENTRIES = ("solve", "sweep", "limit", "map", "table", "cycle step", "study evaluation")
OUTCOMES = ("ok", "flagged", "silent", "bug", "unsupported")
BUDGET = 120  # the short run in CI: about 2 minutes


def test_campaign_json(tmp_path):
    failures = tmp_path / "failures.jsonl"
    start = time.perf_counter()
    got = subprocess.run(
        [
            sys.executable,
            str(ROOT / "benchmarks" / "harden.py"),
            "--json",
            "--budget",
            str(BUDGET),
            "--seed",
            "0",
            "--failures",
            str(failures),
        ],
        capture_output=True,
        text=True,
        timeout=4 * BUDGET,
        cwd=ROOT,
    )
    elapsed = time.perf_counter() - start
    assert got.returncode in (0, 1), got.stderr[-2000:]  # 1: silent failures or bugs found
    s = json.loads(got.stdout)
    for key in (
        "points",
        "ok",
        "flagged",
        "silent",
        "bug",
        "unsupported",
        "by_case",
        "seconds",
        "version",
        "seed",
    ):
        assert key in s, key
    assert s["seed"] == 0 and s["version"] == ballcvt.__version__
    assert s["points"] > 0
    assert s["seconds"] <= 1.1 * BUDGET + 5 and elapsed <= 1.1 * BUDGET + 30  # + start-up
    names = {
        "law": TRACTION_LAWS.names(),
        "clamp": CLAMP_LAWS.names(),
        "arch": ARCHITECTURES.names(),
        "mode": OPERATING_MODES.names(),
        "entry": ENTRIES,
    }
    for key, expected in names.items():
        assert set(s["by_case"][key]) == set(expected), key
        for counts in s["by_case"][key].values():
            assert set(counts) >= set(OUTCOMES)
        total = sum(sum(c[o] for o in OUTCOMES[:4]) for c in s["by_case"][key].values())
        assert total == s["points"], key
    records = [json.loads(line) for line in failures.read_text().splitlines()]
    assert len(records) == s["silent"] + s["bug"]
    for r in records:
        assert r["outcome"] in ("silent", "bug") and r["check"] and r["message"]
        assert {"law", "clamp", "arch", "mode", "entry"} <= set(r["case"])
    # the campaign's target (issue 23): no silent wrong answer, no internal error (seed 0
    # gave 247 points, 0 and 0, in 120 s on one loaded core at commit 77e861a)
    assert s["silent"] == 0 and s["bug"] == 0, (s["by_check"], [r["message"] for r in records])


def test_cam_refusal_below_its_interval_is_a_flag_not_silent():
    """harden task 2:663 (of the first schedule): a cam with a small preload admits 0.x to 935 N m only, so its
    refusal at zero torque is a flag (the capacity's intervals, not the largest torque,
    say which torques a solve must accept)."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    import harden

    case = {  # task 2:663's case before heavy cases were drawn less often
        "law": "isothermal",
        "clamp": "cam",
        "arch": "single",
        "mode": "carrier_held",
        "entry": "solve",
    }
    got = harden.run_task(2, 663, time.time() + 300, 300, case)
    outcomes = [p["outcome"] for p in got["points"]]
    assert "silent" not in outcomes and "bug" not in outcomes, got["points"]
    assert "flagged" in outcomes


def test_the_timer_inside_a_compiled_call_is_the_timer_not_a_bug():
    """A signal handler that raises while a compiled (numba) function runs surfaces as
    ``SystemError: ... returned a result with an exception set``, caused by the handler's
    exception: the campaign's per-task timer firing there at its budget's end was
    recorded as bugs (task 0:324 of a loaded CI-like run, session 28). The timer's
    exception is raised again instead."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    import numpy as np
    import harden
    import harden_entries

    task = harden_entries.Task({"entry": "study evaluation"}, np.random.default_rng(0), [],
                               {"seed": 0, "task": 0})
    try:
        raise harden._Alarm
    except harden._Alarm as alarm:
        try:
            raise SystemError("CPUDispatcher(f) returned a result with an exception set") from alarm
        except SystemError as caught:
            wrapped = caught
    assert harden_entries.interrupt(wrapped) is wrapped.__cause__
    try:
        task.exception(wrapped, {})
    except harden._Alarm:
        pass
    else:
        raise AssertionError("the timer's exception was recorded, not raised")
    assert task.points == []
    task.exception(ValueError("an ordinary failure"), {})  # still a bug
    assert [p["outcome"] for p in task.points] == ["bug"]


#: A case every stubbed `run_case` below stands for.
STUB_CASE = {"law": "isothermal", "clamp": "constant", "arch": "double",
             "mode": "carrier_held", "entry": "solve"}  # fmt: skip


def _stubbed(monkeypatch, run_case):
    """`harden` with its entry points' `run_case` replaced by ``run_case``."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    import harden

    monkeypatch.setattr(harden.entries, "run_case", run_case)
    monkeypatch.setattr(harden.entries, "supported", lambda case: True)
    return harden


def test_points_recorded_after_the_timer_fired_are_dropped(monkeypatch):
    """Wherever the timer's exception is caught as another (a compiled call's
    SystemError, caught by an entry's ``except``), the points recorded from the moment
    it fired are dropped, and the task ends as the timer says: cut at the budget's end."""

    def run_case(task):
        task.record("ok", None, "", {})
        try:
            time.sleep(5.0)
        except BaseException as exc:  # a call that turns the timer's exception into its own
            task.record("bug", "exception", f"SystemError: {type(exc).__name__}", {})

    harden = _stubbed(monkeypatch, run_case)
    got = harden.run_task(0, 0, time.time() + 0.3, 600.0, STUB_CASE)
    assert got["cut"] and [p["outcome"] for p in got["points"]] == ["ok"]


def test_the_timer_surfacing_as_another_exception_is_the_timer_not_a_harness_bug(monkeypatch):
    """The timer's exception can be replaced by another one with no link to it (e.g.
    inside numba's compiler); the fresh-clone suite of session 35 once recorded such a
    point as ``bug: harness`` in `test_campaign_json`. An exception reaching `run_task`
    after the timer fired is the timer's: the task is cut at the budget's end, or ends in
    a timeout at the task's own limit; one raised before it is still a harness bug."""

    def run_case(task):
        task.record("ok", None, "", {})
        try:
            time.sleep(5.0)
        except BaseException:  # noqa: BLE001 - a call that loses the timer's exception
            raise RuntimeError("compilation failed") from None

    harden = _stubbed(monkeypatch, run_case)
    got = harden.run_task(0, 0, time.time() + 0.3, 600.0, STUB_CASE)
    assert got["cut"] and [p["outcome"] for p in got["points"]] == ["ok"]
    got = harden.run_task(0, 0, time.time() + 60.0, 0.3, STUB_CASE)  # the task's own limit
    assert not got["cut"] and [p["check"] for p in got["points"]] == [None, "timeout"]

    def broken(task):
        raise RuntimeError("a harness bug")

    harden = _stubbed(monkeypatch, broken)
    got = harden.run_task(0, 0, time.time() + 60.0, 600.0, STUB_CASE)
    assert [p["check"] for p in got["points"]] == ["harness"]


def test_the_branch_check_below_a_thermal_limit():
    """The limit entry's check `_branch_below` (session 29): a solve 1e-4 below the limit
    whose disc creep exceeds the limit's lies past the fold. Table I's thermal cam limit at
    ratio 1.83 passes; the same limit paired with a result of less creep (the solve at
    0.99 of it, standing in for the equilibrium there) is reported."""
    sys.path.insert(0, str(ROOT / "benchmarks"))
    import numpy as np
    import harden_entries
    import harden_paths

    v = ballcvt.Variator(traction_law="thermal")
    kw = {"clamp_law": "cam"}
    cond = {"ratio": 1.8333333333333333, "rpm": 2000.0, "kw": kw}
    case = {"law": "thermal", "clamp": "cam", "arch": "double", "mode": "carrier_held",
            "entry": "limit"}
    task = harden_entries.Task(case, np.random.default_rng(0), [], {"seed": 0, "task": 0})
    lim = v.limit_torque(cond["ratio"], **kw, input_speed_rpm=2000.0)
    at = v.solve(cond["ratio"], lim, **kw, input_speed_rpm=2000.0)
    assert harden_paths._branch_below(task, v, cond, (lim, at)) == []
    less = v.solve(cond["ratio"], 0.99 * lim, **kw, input_speed_rpm=2000.0)
    got = harden_paths._branch_below(task, v, cond, (lim, less))
    assert [c for c, _ in got] == ["branch below the limit"]
