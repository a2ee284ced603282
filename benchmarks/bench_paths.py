"""User-facing paths: what a user calls, its wall time, its target and a SciPy baseline.

Run: ``python benchmarks/bench_paths.py`` (about 2 minutes; prints figures, asserts
nothing). One process, warm JIT cache, the Table I drive at F_N0 = 2 kN and 2000 rpm.

Each row is the median of repeated calls of the public API, as a user would make them:

* ``sweep`` on 30 x 30, 10 x 10 and 1 x 1 grids (ratio 0.5-2 x output torque 5-70 N m,
  limit search and Dataset included);
* ``solve`` one point (capacity check included) and ``limit_torque`` one ratio;
* the 30 limits of a map (`limit_torque_batch`);
* the batched kernel on the prepared 900-point map of `bench_batch.py`, with its accuracy
  against the high-order reference (pole-centred rule, 64 x 64 nodes, 128 centred);
* first call in a fresh interpreter from the JIT cache (import + first point).

Baseline: the straightforward SciPy path (`bench_batch.py` baseline (a): ``root`` (hybr)
with a finite-difference Jacobian on the fixed centred 32 x 32 grid, point by point, and a
15-step bisection per limit). Its time per point is measured on a sample; a row's baseline
is the number of point solves it needs times that time (printed as such).
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import time

import numpy as np

from ballcvt import Variator, __version__, load_builtin
from ballcvt.equilibrium.problem import build_problem
from ballcvt.performance.efficiency import efficiency
from ballcvt.solver.batch import solve_batch
from ballcvt.solver.limit import bisection_steps, limit_torque_batch
from ballcvt.solver.point import solve_point

sys.path.insert(0, os.path.dirname(__file__))
from bench_batch import BASELINE_A, FIRST_CALL, REFERENCE, SPEED  # noqa: E402
from bench_point import timed  # noqa: E402

OP = {"clamp_force": 2000.0, "input_speed_rpm": 2000.0}


def median_time(fn, repeat):
    """Median wall time of ``repeat`` calls after a warm-up call [s]."""
    return float(timed(fn, repeat)[0])


def grid(n):
    return {"ratio": np.linspace(0.5, 2.0, n), "output_torque": np.linspace(5.0, 70.0, n)}


def baseline_point_time(design, fluid, samples):
    """Median time of one baseline (a) point solve over a sample of the map [s]."""
    times = []
    for ratio, torque in samples:
        pb = build_problem(design, fluid, "double", ratio, torque, 2000.0, SPEED)
        t = time.perf_counter()
        solve_point(pb, BASELINE_A)
        times.append(time.perf_counter() - t)
    return float(np.median(times))


def row(name, seconds, target, base_solves, t_a, points=None):
    rate = f" = {points / seconds:,.0f} points/s" if points else ""
    base = base_solves * t_a
    print(f"  {name:<34s} {seconds * 1e3:9.1f} ms{rate:<22s} target {target:<16s} "
          f"SciPy {base * 1e3:9.0f} ms ({base_solves} solves) -> {base / seconds:5.0f}x")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="calls per row (median)")
    parser.add_argument("--skip-reference", action="store_true",
                        help="skip the kernel accuracy against the reference (~20 s)")
    args = parser.parse_args()
    print(f"ballcvt {__version__}, Python {platform.python_version()}, {platform.machine()}, "
          f"{os.cpu_count()} cores, {platform.processor() or 'cpu'}; one process")
    v = Variator()
    design, fluid = load_builtin()
    steps = bisection_steps() - 1                       # trials after the zero-torque one
    t_a = baseline_point_time(design, fluid, [(r, t) for r in (0.6, 1.0, 1.8)
                                              for t in (10.0, 40.0)])
    print(f"SciPy baseline (a): {t_a * 1e3:.1f} ms per point (hybr + FD Jacobian, centred "
          f"32 x 32), {steps} solves per limit\n")
    print("  what the user calls                  wall time")
    for n in (30, 10, 1):
        t = median_time(lambda n=n: v.sweep(**grid(n), **OP),
                        max(1, args.repeat // (n // 10 + 1)))
        target = {30: ">= 2,000 pts/s", 10: "< 60 ms", 1: "< 10 ms"}[n]
        row(f"sweep {n} x {n} (limits, Dataset)", t, target, n * n + n * (steps + 1), t_a,
            n * n)
    t = median_time(lambda: v.solve(1.0, 40.0, **OP), 20 * args.repeat)
    row("solve one point (capacity check)", t, "< 1 ms", 1, t_a)
    t = median_time(lambda: v.limit_torque(1.0, **OP), 4 * args.repeat)
    row("limit_torque one ratio", t, "< 20 ms", steps + 1, t_a)
    base = build_problem(design, fluid, "double", np.linspace(0.5, 2.0, 30), 0.0, 2000.0,
                         SPEED)
    t = median_time(lambda: limit_torque_batch(base, design.creep_limit), args.repeat)
    row("30 limits of a map", t, "< 150 ms", 30 * (steps + 1), t_a)

    limit = limit_torque_batch(base, design.creep_limit)
    ratio = np.linspace(0.5, 2.0, 30)
    torque = 5.0 + np.linspace(0.0, 1.0, 30)[None, :] * (0.9 * limit[:, None] - 5.0)
    pb = build_problem(design, fluid, "double", ratio[:, None], torque, 2000.0, SPEED)
    t = median_time(lambda: solve_batch(pb), max(1, args.repeat // 2))
    row("batched kernel, prepared 30 x 30", t, ">= 6,000 pts/s", pb.size, t_a, pb.size)
    if not args.skip_reference:
        fast = solve_batch(pb)
        ref = solve_batch(pb, REFERENCE, x0=fast.state.creep)
        err = np.abs(efficiency(pb, fast.state).overall - efficiency(pb, ref.state).overall)
        c, cr = fast.state.creep, ref.state.creep
        big = np.abs(cr) > 1e-6
        print(f"  {'':34s} accuracy: max |eta - eta_ref| {err.max():.1e} (target <= 1e-4), "
              f"relative creep error max {np.max(np.abs(c[big] / cr[big] - 1)):.1e} "
              f"(target <= 1e-3)")
    first = [float(subprocess.run([sys.executable, "-c", FIRST_CALL], capture_output=True,
                                  text=True, check=True).stdout) for _ in range(3)]
    print(f"  {'first call, fresh interpreter':<34s} {min(first[1:]) * 1e3:9.0f} ms "
          f"(from the JIT cache; import + first point)   target < 1,500 ms")


if __name__ == "__main__":
    main()
