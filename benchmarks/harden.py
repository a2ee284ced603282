"""Hardening campaign: random designs and operating points over every case, every point checked.

Run: ``python benchmarks/harden.py --seed 1 --budget 600 [--json] [--failures out.jsonl]``
(``--workers N`` processes, ``--points N`` to stop early; ``--task SEED:INDEX`` re-runs one
task and prints its points, e.g. one named in a failures file).

The cases are the product of the registries (never a list written here): every traction
law (`ballcvt.registry.TRACTION_LAWS`) x clamping law (`CLAMP_LAWS`) x architecture
(`ARCHITECTURES`) x operating mode (`OPERATING_MODES`) x entry point: ``solve``
(`Variator.solve`), ``sweep`` (`Variator.sweep`), ``limit`` (`Variator.limit_torque`, or
`Variator.planetary_capacity` in a planetary mode, checked against ``limit_torque(mode=)``),
``map`` (`Variator.efficiency_map`, or `Variator.planetary_map`), ``table``
(`Variator.lookup_table`), ``cycle step`` (`Variator.run_cycle` on a short duty cycle, with
``mode=`` in a planetary mode; under the optimal clamp padded to 256 steps, copies of the
checked ones, so that its first pass's seeds are exercised) and ``study evaluation`` (one design through
`ballcvt.analysis.studies.evaluate_chunk`). Only public names are used.

Each task takes the next case (the cases in a seeded order, round after round), draws a
buildable design around a built-in drive (``table1`` or ``hub``; sizes x 0.3-3, angles,
ball counts, grooves, now and then over the validators' whole ranges; a random loading cam
for the cam law) and an operating point (ratio over the usable range, input speed and
clamping force scaled to the ball size), and evaluates the entry point at torques from 0
to 1.5 x the limiting torque. Every point ends as exactly one of:

* ``ok``: converged and every check holds;
* ``flagged``: `TractionLimitError`, `NoEquilibriumError`, `InputError` or
  `ConvergenceError`, with a one-line message (or a grid status other than converged);
* ``silent``: a check violated without a flag: a NaN or inf; eta outside [0, 1] by the
  direction the power flows (planetary: power out over power in, whichever member is the
  input); a negative loss; Eq. 38 and Eq. 39 apart beyond the residual bound; ``|creep|``
  above the creep limit; the solve converging above the reported limiting torque, or not
  at it, or failing without `TractionLimitError` just above it (1.001 x); a sweep, map,
  table, cycle step or study evaluation disagreeing with `Variator.solve` at the same point
  (status, or eta by more than 1e-6: a different branch);
* ``bug``: any other exception, a flag whose message is several lines or says
  "internal error", or a point that hangs past ``--timeout``;
* ``unsupported`` (not a point): an entry point the public API does not offer for the case
  (a sweep, table or study in a planetary mode), or refuses on purpose in one line saying
  what to use instead (the cam and optimal laws, or parasitic losses, in a planetary mode:
  the mode-aware call is made and its refusal recorded), counted so the coverage gaps show.

The target is 0 silent failures and 0 bugs.
"""

from __future__ import annotations

import argparse
import collections
import itertools
import json
import os
import signal
import sys
import time
import traceback
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass, field

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harden_entries as entries  # noqa: E402  (the entry points and their checks)

from ballcvt import __version__  # noqa: E402
from ballcvt.registry import ARCHITECTURES, CLAMP_LAWS, OPERATING_MODES, TRACTION_LAWS  # noqa: E402

OUTCOMES = ("ok", "flagged", "silent", "bug", "unsupported")
CASE_KEYS = ("law", "clamp", "arch", "mode", "entry")


def all_cases() -> list[dict]:
    """Every case: the registries' names x the entry points."""
    names = (
        TRACTION_LAWS.names(),
        CLAMP_LAWS.names(),
        ARCHITECTURES.names(),
        OPERATING_MODES.names(),
        entries.ENTRIES,
    )
    return [dict(zip(CASE_KEYS, c)) for c in itertools.product(*names)]


def weight(case: dict) -> int:
    """How many times a case is drawn per round: `entries.heavy` cases (seconds a point)
    once, the others `LIGHT_WEIGHT` times, so that a campaign's points are not spent
    mostly waiting on a few slow cases while every case is still drawn every round."""
    return 1 if entries.heavy(case) else LIGHT_WEIGHT


#: Draws per round of a case that is not `entries.heavy`.
LIGHT_WEIGHT = 9


def schedule(seed: int) -> list[dict]:
    """One round of cases in the seed's order, each `weight` times (task ``i`` takes
    ``schedule[i % len]``)."""
    cases = [c for c in all_cases() for _ in range(weight(c))]
    order = np.random.default_rng([seed, 99991]).permutation(len(cases))
    return [cases[i] for i in order]


class _Alarm(BaseException):
    """Raised by the per-task timer (a BaseException: no ``except Exception`` swallows it)."""


def _timed_out(task, out: dict, at: int, deadline: float, timeout: float) -> None:
    """The task's timer fired when ``at`` points were recorded. Drop the points recorded
    after it: the alarm can surface inside a compiled call as that call's ``SystemError``
    (`harden_entries.interrupt`), or inside numba's compiler or a library's handler as
    another exception, caught by the entry's own checks or by `run_task`. Then record
    the task's end: the budget's cut, or a timeout (a bug) if the task's own limit came
    first."""
    del out["points"][at:]
    if time.time() >= deadline - 0.05:  # the budget ran out: drop the partial point
        out["cut"] = True
    else:
        task.record("bug", "timeout", f"no answer within {timeout:g} s", task.last_inputs or {})


def run_task(seed: int, index: int, deadline: float, timeout: float, case=None) -> dict:
    """Task ``index``: its case's points, each classified (run in a worker process).

    ``case`` (a dict of `CASE_KEYS`) overrides the schedule's case of the task; the
    draws depend on ``seed`` and ``index`` only (a regression test keeps a task so)."""
    case = case or (cases := schedule(seed))[index % len(cases)]
    out = {"points": [], "seconds": 0.0, "cpu": 0.0, "cut": False, "entry": case["entry"]}
    if not entries.supported(case):
        out["points"].append(
            {
                "case": case,
                "outcome": "unsupported",
                "check": "api",
                "message": "no public entry point for this case",
            }
        )
        return out
    rng = np.random.default_rng([seed, index])
    stop = min(time.time() + timeout, deadline)
    t0, c0 = time.perf_counter(), time.process_time()
    task = entries.Task(case, rng, out["points"], {"seed": seed, "task": index})
    fired: dict = {}

    def on_alarm(signum, frame):
        fired["at"] = len(out["points"])  # the points recorded from here on are the timer's
        raise _Alarm

    signal.signal(signal.SIGALRM, on_alarm)
    try:  # the timer starts inside: a short one must not fire before the handler's scope
        signal.setitimer(signal.ITIMER_REAL, max(0.01, stop - time.time()))
        entries.run_case(task)
    except _Alarm:
        pass
    except Exception as exc:  # noqa: BLE001 - the harness itself must never stop
        if "at" not in fired:
            task.record(
                "bug",
                "harness",
                f"{type(exc).__name__}: {exc}\n" + traceback.format_exc(limit=-3),
                task.last_inputs or {},
            )
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
    if "at" in fired:  # the timer fired: what follows is its, whatever it surfaced as
        _timed_out(task, out, fired["at"], deadline, timeout)
    out["seconds"] = time.perf_counter() - t0
    out["cpu"] = time.process_time() - c0
    return out


@dataclass
class Tally:
    """Counts of a campaign."""

    by_case: dict = field(default_factory=dict)
    by_combo: collections.Counter = field(default_factory=collections.Counter)
    checks: collections.Counter = field(default_factory=collections.Counter)
    flags: collections.Counter = field(default_factory=collections.Counter)
    entry_seconds: collections.Counter = field(default_factory=collections.Counter)
    entry_cpu: collections.Counter = field(default_factory=collections.Counter)
    entry_points: collections.Counter = field(default_factory=collections.Counter)
    failures: list = field(default_factory=list)
    tasks: int = 0

    def __post_init__(self):
        names = {
            "law": TRACTION_LAWS.names(),
            "clamp": CLAMP_LAWS.names(),
            "arch": ARCHITECTURES.names(),
            "mode": OPERATING_MODES.names(),
            "entry": entries.ENTRIES,
        }
        self.by_case = {k: {n: dict.fromkeys(OUTCOMES, 0) for n in names[k]} for k in CASE_KEYS}

    def add(self, result: dict) -> None:
        self.tasks += 1
        self.entry_seconds[result["entry"]] += result["seconds"]
        self.entry_cpu[result["entry"]] += result.get("cpu", 0.0)
        for p in result["points"]:
            case, outcome = p["case"], p["outcome"]
            for k in CASE_KEYS:
                self.by_case[k][case[k]][outcome] += 1
            self.by_combo["/".join(case[k] for k in CASE_KEYS) + ":" + outcome] += 1
            if outcome != "unsupported":
                self.entry_points[case["entry"]] += 1
            if outcome in ("silent", "bug"):
                self.checks[f"{outcome}: {p['check']} ({case['entry']})"] += 1
                self.failures.append(p)
            elif outcome == "flagged":
                self.flags[p["message"]] += 1

    def totals(self) -> dict:
        t = dict.fromkeys(OUTCOMES, 0)
        for counts in self.by_case["entry"].values():
            for k, n in counts.items():
                t[k] += n
        return t


def _kill(pool: ProcessPoolExecutor) -> None:
    """End this pool's own worker processes (by their ids) when they overrun the budget."""
    for proc in list(getattr(pool, "_processes", {}).values()):
        if proc.is_alive():
            proc.kill()
    pool.shutdown(wait=False, cancel_futures=True)


def campaign(args) -> Tally:
    """Run tasks on a process pool until the budget or the point count is reached."""
    tally, start = Tally(), time.time()
    deadline = start + args.budget
    index, in_flight, cases = 0, {}, schedule(args.seed)
    pool = ProcessPoolExecutor(max_workers=args.workers)
    try:
        while True:
            done_points = sum(tally.totals()[k] for k in OUTCOMES[:4])
            while (
                len(in_flight) < 2 * args.workers
                and time.time() < deadline - 0.5
                and (args.points is None or done_points < args.points)
            ):
                case = cases[index % len(cases)]
                if entries.supported(case):
                    fut = pool.submit(run_task, args.seed, index, deadline, args.timeout)
                    in_flight[fut] = index
                else:  # no call to make: counted here, not sent to a worker
                    tally.add(run_task(args.seed, index, deadline, args.timeout))
                index += 1
            if not in_flight:
                break
            done, _ = wait(in_flight, timeout=1.0, return_when=FIRST_COMPLETED)
            for fut in done:
                i = in_flight.pop(fut)
                try:
                    tally.add(fut.result())
                except BrokenProcessPool as exc:  # a worker died (e.g. a segfault)
                    tally.add(_crashed(args.seed, i, exc))
                    pool = _restart(pool, args.workers, in_flight, args, tally)
                    break
            if time.time() > deadline + max(2.0, 0.05 * args.budget):
                _kill(pool)  # a point overran: stop within the budget
                in_flight.clear()
                break
    finally:
        pool.shutdown(wait=False, cancel_futures=True)
    return tally


def _crashed(seed: int, index: int, exc: BaseException) -> dict:
    case = (cases := schedule(seed))[index % len(cases)]
    return {
        "points": [
            {
                "case": case,
                "outcome": "bug",
                "check": "worker crashed",
                "message": f"{type(exc).__name__}: {exc}",
                "inputs": {"seed": seed, "task": index},
            }
        ],
        "seconds": 0.0,
        "cut": False,
        "entry": case["entry"],
    }


def _restart(pool, workers, in_flight, args, tally):
    """A new pool after a crash; the tasks that were running on the old one count as bugs
    (any of them may have crashed it) unless they finished."""
    for fut, i in list(in_flight.items()):
        try:
            tally.add(fut.result(timeout=0))
        except Exception as exc:  # noqa: BLE001
            tally.add(_crashed(args.seed, i, exc))
    in_flight.clear()
    pool.shutdown(wait=False, cancel_futures=True)
    return ProcessPoolExecutor(max_workers=workers)


def summary(args, tally: Tally, seconds: float) -> dict:
    totals = tally.totals()
    rate = {
        e: {
            "points": tally.entry_points[e],
            "worker_seconds": round(tally.entry_seconds[e], 2),
            "points_per_second": round(tally.entry_points[e] / tally.entry_seconds[e], 2)
            if tally.entry_seconds[e] > 0
            else None,
            "worker_cpu_seconds": round(tally.entry_cpu[e], 2),
            "points_per_cpu_second": round(tally.entry_points[e] / tally.entry_cpu[e], 2)
            if tally.entry_cpu[e] > 0
            else None,
        }
        for e in entries.ENTRIES
    }
    return {
        "version": __version__,
        "seed": args.seed,
        "seconds": round(seconds, 2),
        "budget": args.budget,
        "workers": args.workers,
        "tasks": tally.tasks,
        "points": sum(totals[k] for k in OUTCOMES[:4]),
        **{k: totals[k] for k in OUTCOMES},
        "by_case": tally.by_case,
        "by_check": dict(tally.checks.most_common()),
        "flags": dict(tally.flags.most_common(30)),
        "rate": rate,
        "by_combo": dict(sorted(tally.by_combo.items())),
    }


def print_table(s: dict, tally: Tally) -> None:
    print(
        f"ballcvt {s['version']} hardening campaign, seed {s['seed']}: {s['points']} points "
        f"in {s['tasks']} tasks, {s['seconds']:.0f} s on {s['workers']} processes"
    )
    print("  ".join(f"{k} {s[k]}" for k in OUTCOMES))
    for key, rows in s["by_case"].items():
        print(f"\n{key:<26}" + "".join(f"{o:>12}" for o in OUTCOMES))
        for name, counts in rows.items():
            print(f"  {name:<24}" + "".join(f"{counts[o]:12d}" for o in OUTCOMES))
    print("\npoints per worker-second (wall, and CPU) by entry point:")
    for e, r in s["rate"].items():
        print(
            f"  {e:<18} {r['points']:7d} points  {r['points_per_second']}  "
            f"{r['points_per_cpu_second']}"
        )
    print("\nsilent failures and bugs by check:")
    for name, n in s["by_check"].items():
        print(f"  {n:6d}  {name}")
    print("\nflags:")
    for name, n in s["flags"].items():
        print(f"  {n:6d}  {name}")
    seen = set()
    for p in tally.failures:
        key = (p["check"], p["case"]["entry"], p["case"]["law"], p["case"]["clamp"])
        if key not in seen and len(seen) < 25:
            seen.add(key)
            print(
                f"\n{p['outcome'].upper()} {p['check']} {'/'.join(p['case'].values())}: "
                f"{p['message'][:300]}\n  rerun: python benchmarks/harden.py --task "
                f"{p['inputs'].get('seed')}:{p['inputs'].get('task')}"
            )


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--budget", type=float, default=300.0, help="seconds (wall clock)")
    parser.add_argument("--points", type=int, default=None, help="stop after N points")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--timeout", type=float, default=600.0, help="seconds per task")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.add_argument("--failures", default=None, help="JSONL file of silent/bug points")
    parser.add_argument("--task", default=None, help="SEED:INDEX: re-run one task, print it")
    args = parser.parse_args(argv)
    if args.task:
        seed, index = (int(x) for x in args.task.split(":"))
        # the deadline past the timeout: a task that hangs is reported as a timeout (at
        # the campaign's deadline a task is cut and its partial point dropped)
        got = run_task(seed, index, time.time() + args.timeout + 5.0, args.timeout)
        for p in got["points"]:
            print(json.dumps(p, default=str))
        return 0
    start = time.time()
    tally = campaign(args)
    s = summary(args, tally, time.time() - start)
    if args.failures:
        with open(args.failures, "w") as fh:
            for p in tally.failures:
                fh.write(json.dumps(p, default=str) + "\n")
    if args.json:
        print(json.dumps(s, default=str))
    else:
        print_table(s, tally)
    return 0 if s["silent"] == 0 and s["bug"] == 0 else 1


if __name__ == "__main__":
    raise SystemExit(main())
