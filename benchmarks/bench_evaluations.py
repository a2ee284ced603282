"""Where a sweep's time goes: residual evaluations per point and what one costs.

Run: ``python benchmarks/bench_evaluations.py`` (about a minute; ``--n 10`` for small grids;
``--json`` for the rows; the table it prints by default is the README's, and
``--write-readme`` puts it there between ``<!-- bench-evaluations-start -->`` and its end).
Prints figures, asserts nothing.

For each sweep row of ``bench_table.py`` (Table I, ratio 0.5-2 x output torque 5-70 N m,
``n x n`` points, 2000 rpm; every traction law under a constant force of 2 kN, the cam
and the optimal clamp) it prints the CPU time per point, the residual evaluations per
point (every point of every batched evaluation of the equilibrium's residual, with its
Jacobian or without, counted where each passes: the compiled kernels'
`ballcvt.equilibrium.compiled.evaluate_rows`; the NumPy path, which these 1-D batches do
not take, is counted apart and printed where it ran), the CPU
time of one such evaluation [us] (the traction law's integrals are most of it) and the
share of the row's time spent in them, and the evaluations by phase: each curve's limit
search (`ballcvt.analysis.sweeps.curves.limit_search_curves`; under the cam its capacity
scan, `ballcvt.solvers.capacity.interval_search`: 49 torques per curve from zero to the
force's pressure bound, and the bisections of its changes, each counted apart) and the
sweep's own solves, each with the CPU time it took per point (its own, without the phases
inside it). The optimal clamp's search runs inside its sweep's solves. Last, the
evaluations by quadrature rule: the solver's full rule (32 x 24 nodes) and its predictor's
coarse one (12 x 8), each with its cost; an evaluation's cost depends on its rule as much
as on its law, so the cost per evaluation of two rows compares their mix of rules too.

What the figures bound. Evaluations times their cost is most of each row's time, so a row
whose target is ``2 x`` the baseline's cost per point has to do with ``2 x`` the
baseline's evaluations per point, scaled by the ratio of the two laws' cost per
evaluation. Issue 26's two rows that miss (the thermal law under the cam and under the
optimal clamp) read here how far their evaluation counts lie from that budget; the
README's performance section quotes them.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from contextlib import contextmanager
from dataclasses import asdict, dataclass, field

import numpy as np

from ballcvt import Variator
from ballcvt.analysis.sweeps import curves
from ballcvt.equilibrium import compiled, residual
from ballcvt.solvers import capacity

sys.path.insert(0, os.path.dirname(__file__))

from bench_table import CLAMPS, OP, write_readme  # noqa: E402 - the table's own rows

#: Where the table goes in README.md (``--write-readme``).
MARKERS = ("<!-- bench-evaluations-start -->", "<!-- bench-evaluations-end -->")
LAWS = ("isothermal", "viscoelastic", "thermal")


@dataclass
class Counted:
    """One sweep row: CPU time per point [ms], residual evaluations per point, CPU time per
    evaluation [us], share of the time in evaluations, evaluations per phase, the NumPy
    path's calls, the capacity scan's torques (and those not converged), CPU time per
    phase [ms/point] and, per quadrature rule, ``(evaluations/point, us/evaluation)``."""

    law: str
    clamp: str
    ms_per_point: float
    evaluations_per_point: float
    us_per_evaluation: float
    share_in_evaluations: float
    phases: dict
    numpy_calls: int = 0
    scan: tuple = (0, 0)
    phase_ms: dict = field(default_factory=dict)
    rules: dict = field(default_factory=dict)


class _Counter:
    """Evaluated points and their CPU seconds, by the phase named last (`phase`)."""

    def __init__(self):
        self.points, self.seconds, self.by_phase = 0, 0.0, {}
        self.phase, self.numpy_calls = "sweep", 0
        self.scan = [0, 0]  # the capacity scan's torques, and those that did not converge
        self.phase_seconds, self._inner = {}, 0.0  # each phase's own CPU time
        self.by_rule = {}  # (radial, angular nodes) -> [points, seconds]

    def wrap(self, fn, points_of, rule_of):
        def counted(*args, **kwargs):
            t = time.process_time()
            out = fn(*args, **kwargs)
            n, spent = points_of(*args), time.process_time() - t
            self.points += n
            self.seconds += spent
            self.by_phase[self.phase] = self.by_phase.get(self.phase, 0) + n
            tally = self.by_rule.setdefault(rule_of(*args), [0, 0.0])
            tally[0], tally[1] = tally[0] + n, tally[1] + spent
            return out

        return counted

    def in_phase(self, name, fn):
        def phased(*args, **kwargs):
            outer, self.phase = self.phase, name
            inner, self._inner = self._inner, 0.0
            t = time.process_time()
            try:
                return fn(*args, **kwargs)
            finally:
                spent = time.process_time() - t
                own = spent - self._inner  # without the phases inside it
                self.phase_seconds[name] = self.phase_seconds.get(name, 0.0) + own
                self._inner, self.phase = inner + spent, outer

        return phased


@contextmanager
def counting():
    """Count every residual evaluation (and the capacity search's phases) while inside."""
    c = _Counter()
    saved = [(compiled, "evaluate_rows"), (residual, "_contact_inputs"),
             (curves, "limit_search_curves"), (capacity, "_scan"),
             (capacity, "_confirmed_bisection"), (capacity, "_bisect")]
    old = [getattr(m, name) for m, name in saved]
    compiled.evaluate_rows = c.wrap(old[0], lambda problem, creep, *a: creep.shape[0],
                                    lambda problem, creep, h, q, *a: (q.n_radial, q.n_angular))

    def numpy_path(*args):
        c.numpy_calls += 1
        return old[1](*args)

    residual._contact_inputs = numpy_path
    curves.limit_search_curves = c.in_phase("limit search", old[2])
    scan = c.in_phase("capacity scan", old[3])

    def scanned(points, *args):
        ok, converged, creep = scan(points, *args)
        c.scan[0] += points.size
        c.scan[1] += int(np.sum(~np.asarray(converged, dtype=bool)))
        return ok, converged, creep

    capacity._scan = scanned
    capacity._confirmed_bisection = c.in_phase("capacity bisections", old[4])
    capacity._bisect = c.in_phase("capacity bisections", old[5])
    try:
        yield c
    finally:
        for (m, name), fn in zip(saved, old):
            setattr(m, name, fn)


def measure(law, clamp, n, repeat=3):
    """The `Counted` figures of one sweep row: the median CPU time of ``repeat`` sweeps after
    one more (the first of a process ran 20 % slower than the next), each counted (the
    counts are the same in each)."""
    v, kw = Variator(traction_law=law), CLAMPS[clamp]
    grid = {"ratio": np.linspace(0.5, 2.0, n), "output_torque": np.linspace(5.0, 70.0, n)}
    v.sweep(**grid, **kw, **OP, progress=False)
    runs = []
    for _ in range(repeat):
        with counting() as c:
            t = time.process_time()
            v.sweep(**grid, **kw, **OP, progress=False)
            runs.append((time.process_time() - t, c))
    total, c = sorted(runs, key=lambda r: r[0])[repeat // 2]
    points = n * n
    phase_ms = {k: s / points * 1e3 for k, s in c.phase_seconds.items()}
    phase_ms = {"sweep": total / points * 1e3 - sum(phase_ms.values()), **phase_ms}
    finest = sorted(c.by_rule.items(), key=lambda kv: -kv[0][0] * kv[0][1])  # full rule first
    rules = {f"{a} x {b}": (p / points, s / max(p, 1) * 1e6) for (a, b), (p, s) in finest}
    return Counted(law, clamp, total / points * 1e3, c.points / points,
                   c.seconds / max(c.points, 1) * 1e6, c.seconds / total,
                   {k: e / points for k, e in c.by_phase.items()}, c.numpy_calls,
                   tuple(c.scan), phase_ms, rules)


def table(rows, n):
    """The rows as a Markdown table, each against the first (the baseline)."""
    base = rows[0]
    lines = [f"{n} x {n} sweeps of Table I at {OP['input_speed_rpm']:g} rpm, CPU time, warm; generated by "
             "`python benchmarks/bench_evaluations.py --write-readme`.", "",
             "| law, clamp | ms/point (x baseline) | evaluations/point (x baseline) | "
             "us/evaluation (x baseline) | time in evaluations | by phase: evaluations/point "
             "(ms/point) | capacity scan: torques (not converged) | by rule: evaluations/point "
             "(us each) |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        shown = [k for k in dict.fromkeys([*r.phases, *r.phase_ms])  # evaluations or time
                 if r.phases.get(k, 0) or r.phase_ms.get(k, 0) >= 0.01 * r.ms_per_point]
        phases = ", ".join(
            f"{k} {r.phases.get(k, 0.0):.1f}"
            + (f" ({r.phase_ms[k]:.3f})" if k in r.phase_ms else "") for k in shown)
        phases += f" (and {r.numpy_calls} calls on the NumPy path)" if r.numpy_calls else ""
        rules = "; ".join(f"{k}: {p:.1f} ({us:.1f})" for k, (p, us) in r.rules.items())
        lines.append(
            f"| {r.law}, {r.clamp} | {r.ms_per_point:.3f} "
            f"({r.ms_per_point / base.ms_per_point:.2f}) | {r.evaluations_per_point:.1f} "
            f"({r.evaluations_per_point / base.evaluations_per_point:.2f}) | "
            f"{r.us_per_evaluation:.1f} ({r.us_per_evaluation / base.us_per_evaluation:.2f}) | "
            f"{r.share_in_evaluations:.0%} | {phases} | "
            + (f"{r.scan[0]:,} ({r.scan[1]:,}) |" if r.scan[0] else "- |")
            + f" {rules or '-'} |")
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=30, help="grid points per axis (default 30)")
    ap.add_argument("--json", action="store_true", help="print the rows as JSON")
    ap.add_argument("--write-readme", action="store_true", help="put the table in README.md")
    args = ap.parse_args(argv)
    rows = [measure(law, clamp, args.n) for law in LAWS for clamp in CLAMPS]
    text = table(rows, args.n)
    print(json.dumps([asdict(r) for r in rows], indent=1) if args.json else text)
    if args.write_readme:
        write_readme(text, markers=MARKERS)


if __name__ == "__main__":
    main()
