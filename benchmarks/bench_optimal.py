"""The efficiency-optimal clamp's speed and agreement (issue 26):
``python benchmarks/bench_optimal.py [--n 30] [--steps 10000] [--compare 40] [--old]``.

Prints the milliseconds of one ``Variator.solve(..., clamp_law="optimal")`` (median of
repeated calls), the points per second of an ``n x n`` sweep (ratio 0.5-2, torque
0-70 N m, Table I drive at 2000 rpm), the seconds of an ``--steps`` duty cycle (the
e-bike commute repeated, ``hub`` drive, target input speed), and the largest efficiency
difference between the batched search (`ballcvt.solvers.optimal_batch.optimal_forces`)
and the one-point search (`ballcvt.solvers.optimal_search.search_optimum`) over
``--compare`` points of the sweep. ``--old``: time the sweep and the cycle with the
one-point search as well (slow).
"""

import argparse
import time
from pathlib import Path
from unittest import mock

import numpy as np

from ballcvt import Variator, load_builtin
from ballcvt.analysis.cycle_files import cycle_from_arrays, read_cycle
from ballcvt.analysis.cycles import run_cycle
from ballcvt.analysis.sweeps import curves
from ballcvt.equilibrium.problem import build_problem
from ballcvt.model.clamping import OptimalClamp
from ballcvt.performance.efficiency import efficiency
from ballcvt.solvers.clamped import with_clamp
from ballcvt.solvers.newton import solve_batch
from ballcvt.solvers.optimal_batch import optimal_forces
from ballcvt.solvers.optimal_search import ClampCase, search_optimum

ROOT = Path(__file__).resolve().parents[1]
RPM = 2000.0


def one_by_one(pb, law, options):
    """The former `at_optimal_forces`: the one-point search, point by point."""
    forces = np.array(pb.clamp_force, dtype=float)
    for j in range(pb.size):
        case = ClampCase(pb.design, pb.fluid, pb.layout.architecture, float(pb.ratio[j]),
                         float(pb.output_torque[j]), float(pb.input_speed[j]))
        try:
            forces[j] = search_optimum(case, law, options).clamp_force
        except Exception:  # noqa: BLE001 - a refused point keeps its force
            pass
    return with_clamp(pb, forces)


def single(v, repeats=15):
    v.solve(1.0, 20.0, clamp_law="optimal", input_speed_rpm=RPM)
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        v.solve(1.0, 20.0, clamp_law="optimal", input_speed_rpm=RPM)
        times.append(time.perf_counter() - t)
    return 1e3 * float(np.median(times))


def sweep(v, n):
    t = time.perf_counter()
    ds = v.sweep(ratio=np.linspace(0.5, 2.0, n), output_torque=np.linspace(0.0, 70.0, n),
                 clamp_law="optimal", input_speed_rpm=RPM, progress=False)
    dt = time.perf_counter() - t
    return n * n / dt, int((ds.status.values == 0).sum())


def cycle(steps):
    base = read_cycle(ROOT / "examples" / "cycles" / "ebike_commute.csv")
    reps = int(np.ceil(steps / base.size))
    t = np.concatenate([base.time + k * (base.time[-1] + 1.0) for k in range(reps)])
    cyc = cycle_from_arrays(time=t[:steps], output_speed=np.tile(base.output_speed, reps)[:steps],
                            output_torque=np.tile(base.output_torque, reps)[:steps])
    v = Variator(*load_builtin("hub"))
    start = time.perf_counter()
    res = run_cycle(v, cyc, strategy="target-input-speed", target_input_speed=180 * np.pi / 30,
                    clamp_law="optimal", progress=False)
    return time.perf_counter() - start, res.summary["steps_flagged"]


def compare(v, n, count, seed=1):
    """Largest |eta(batched) - eta(one-point search)| over ``count`` sweep points."""
    rng = np.random.default_rng(seed)
    ratio = rng.choice(np.linspace(0.5, 2.0, n), count)
    torque = rng.choice(np.linspace(0.0, 70.0, n), count)
    w = RPM * np.pi / 30
    pb = build_problem(v.design, v.fluid, v.architecture, ratio, torque, 1000.0, w)
    got = optimal_forces(pb, OptimalClamp(), v.options)
    at = with_clamp(pb, got.force)
    eta = efficiency(at, solve_batch(at, v.options).state).overall
    old = np.array([search_optimum(ClampCase(v.design, v.fluid, v.architecture, r, t, w),
                                  OptimalClamp(), v.options).eta
                    for r, t in zip(ratio, torque)])
    return float(np.max(np.abs(eta - old))), float(np.min(eta - old)), int(got.fast.sum())


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--n", type=int, default=30)
    ap.add_argument("--steps", type=int, default=10_000)
    ap.add_argument("--compare", type=int, default=40)
    ap.add_argument("--old", action="store_true")
    args = ap.parse_args()
    v = Variator()
    print(f"single solve: {single(v):.1f} ms (median)")
    rate, ok = sweep(v, args.n)
    print(f"{args.n} x {args.n} sweep: {rate:.0f} points/s ({ok} converged)")
    dt, flagged = cycle(args.steps)
    print(f"{args.steps}-step cycle (hub, optimal clamp): {dt:.1f} s ({flagged} flagged)")
    worst, low, fast = compare(v, args.n, args.compare)
    print(f"max |d eta| vs the one-point search over {args.compare} points: {worst:.2e} "
          f"(min new - old {low:.2e}; {fast} found by the batched search)")
    if args.old:
        with mock.patch.object(curves, "at_optimal_forces", one_by_one), \
                mock.patch("ballcvt.analysis.sweeps.points.at_optimal_forces", one_by_one):
            rate, _ = sweep(v, args.n)
            print(f"one-point search: {args.n} x {args.n} sweep {rate:.0f} points/s")
            dt, _ = cycle(args.steps)
            print(f"one-point search: {args.steps}-step cycle {dt:.1f} s")


if __name__ == "__main__":
    main()
