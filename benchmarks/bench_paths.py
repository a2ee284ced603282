"""User-facing paths: what a user calls, its wall time, its target and a SciPy baseline.

Run: ``python benchmarks/bench_paths.py`` (about 2 minutes; prints figures, asserts
nothing). One process, warm JIT cache, the Table I drive at F_N0 = 2 kN and 2000 rpm.

Each row is the median call of repeated calls of the public API, as a user would make them
(the quietest of `BATCHES` batches, and the median of all calls next to it):

* ``sweep`` on 30 x 30, 10 x 10 and 1 x 1 grids (ratio 0.5-2 x output torque 5-70 N m,
  limit search and Dataset included);
* ``solve`` one point (capacity check included) and ``limit_torque`` one ratio;
* the 30 limits of a map (`limit_torque_batch`);
* the batched kernel on the prepared 900-point map of `bench_batch.py`, with its accuracy
  against the high-order reference (pole-centred rule, 64 x 64 nodes, 128 centred);
* first call in a fresh interpreter from the JIT cache (import + first point).

Next to each row, the same work done by the straightforward SciPy implementation, run (not
estimated), once: `bench_batch.py` baseline (a), SciPy's ``root`` (hybr, finite-difference
Jacobian) point by point with the traction integrals in NumPy on the fixed centred 32 x 32
grid (no compiled kernels), each limit a 15-step bisection on the output torque from the
traction ceiling, each solve started from the last admissible one; a sweep's points below
their limit solved in torque order from the point below, into plain arrays.

Besides the public API it imports internals on purpose (the problem, the batched solver): the
SciPy baseline is built from them.
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
from ballcvt.solvers.limit import bisection_steps, limit_torque_batch, saturated_traction
from ballcvt.solvers.newton import solve_batch
from ballcvt.solvers.point import solve_point

sys.path.insert(0, os.path.dirname(__file__))
from bench_batch import BASELINE_A, FIRST_CALL, REFERENCE, SPEED  # noqa: E402

FORCE = 2000.0
OP = {"clamp_force": FORCE, "input_speed_rpm": 2000.0}
TARGETS = {  # row -> (target text, test on the measured seconds)
    "sweep 30 x 30": (">= 2,000 points/s", lambda s: 900 / s >= 2000),
    "sweep 10 x 10": ("< 60 ms", lambda s: s < 0.060),
    "sweep 1 x 1": ("< 10 ms", lambda s: s < 0.010),
    "solve one point": ("< 1 ms median", lambda s: s < 0.001),
    "limit_torque one ratio": ("< 20 ms", lambda s: s < 0.020),
    "30 limits of a map": ("< 150 ms", lambda s: s < 0.150),
    "kernel, prepared 30 x 30": (">= 6,000 points/s", lambda s: 900 / s >= 6000),
}


#: Batches of calls per row: this machine's speed drifts within seconds (a virtual machine
#: sharing its host), so each row reports the median call of its quietest batch, and the
#: median over all calls next to it.
BATCHES = 5


def median_time(fn, repeat):
    """Median wall time of a call [s]: of the quietest of `BATCHES` batches of ``repeat``
    calls each, after a warm-up call. Sets ``median_time.overall``: the median of all."""
    fn()
    batches = []
    for _ in range(BATCHES):
        times = []
        for _ in range(repeat):
            t = time.perf_counter()
            fn()
            times.append(time.perf_counter() - t)
        batches.append(times)
    median_time.overall = float(np.median(np.concatenate(batches)))
    return float(min(np.median(b) for b in batches))


def grid(n):
    return {"ratio": np.linspace(0.5, 2.0, n), "output_torque": np.linspace(5.0, 70.0, n)}


# --------------------------------------------------------------- the SciPy baseline


def scipy_point(design, fluid, ratio, torque, x0=None):
    """One point the straightforward way: ``root`` (hybr) on NumPy integrals."""
    pb = build_problem(design, fluid, "double", ratio, torque, FORCE, SPEED)
    return solve_point(pb, BASELINE_A, x0=x0)


def admissible(sol, creep_limit):
    return sol.converged and float(np.max(np.abs(sol.state.creep))) <= creep_limit


def scipy_limit(design, fluid, ratio):
    """Limiting torque by bisection (`bisection_steps` trials after T_2 = 0) between 0 and
    the traction ceiling of the disc contacts; returns the torque and the creeps there."""
    zero = scipy_point(design, fluid, ratio, 0.0)
    pb = build_problem(design, fluid, "double", ratio, 0.0, FORCE, SPEED)
    cap = design.n_rollers * pb.load * pb.radius * saturated_traction(pb)
    lo, hi, x = 0.0, float(min(cap[0] / ratio, cap[-1])), zero.state.creep
    for _ in range(bisection_steps() - 1):
        mid = 0.5 * (lo + hi)
        sol = scipy_point(design, fluid, ratio, mid, x)
        if admissible(sol, design.creep_limit):
            lo, x = mid, sol.state.creep
        else:
            hi = mid
    return lo, x


def scipy_sweep(design, fluid, ratio, torque):
    """Limits, then every point below its limit in torque order; efficiency arrays."""
    eta = np.full((ratio.size, torque.size), np.nan)
    for i, r in enumerate(ratio):
        limit, x = scipy_limit(design, fluid, float(r))
        x = None
        for j, t in enumerate(torque):
            if t > limit:
                break
            sol = scipy_point(design, fluid, float(r), float(t), x)
            if sol.converged:
                x = sol.state.creep
                pb = build_problem(design, fluid, "double", float(r), float(t), FORCE, SPEED)
                eta[i, j] = float(efficiency(pb, sol.state).overall)
    return eta


def once(fn):
    t = time.perf_counter()
    fn()
    return time.perf_counter() - t


# ---------------------------------------------------------------------------- main


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="calls per row (median)")
    parser.add_argument("--skip-reference", action="store_true",
                        help="skip the kernel accuracy against the reference (~5 s)")
    args = parser.parse_args()
    print(f"ballcvt {__version__}, Python {platform.python_version()}, {platform.machine()}, "
          f"{os.cpu_count()} cores; one process")
    v = Variator()
    design, fluid = load_builtin()
    base = build_problem(design, fluid, "double", np.linspace(0.5, 2.0, 30), 0.0, FORCE, SPEED)
    limit = limit_torque_batch(base, design.creep_limit)
    ratio = np.linspace(0.5, 2.0, 30)
    torque = 5.0 + np.linspace(0.0, 1.0, 30)[None, :] * (0.9 * limit[:, None] - 5.0)
    pb = build_problem(design, fluid, "double", ratio[:, None], torque, FORCE, SPEED)

    rows = []  # (name, ballcvt seconds, all-calls median, points, SciPy seconds)
    for n in (30, 10, 1):
        g = grid(n)
        t = median_time(lambda g=g: v.sweep(**g, **OP), max(1, args.repeat // (n // 10 + 1)))
        t_all = median_time.overall
        base_t = once(lambda g=g: scipy_sweep(design, fluid, g["ratio"], g["output_torque"]))
        rows.append((f"sweep {n} x {n}", t, t_all, n * n, base_t))
    t = median_time(lambda: v.solve(1.0, 40.0, **OP), 40 * args.repeat)
    t_all = median_time.overall
    rows.append(("solve one point", t, t_all, None, once(
        lambda: scipy_point(design, fluid, 1.0, 40.0))))
    t = median_time(lambda: v.limit_torque(1.0, **OP), 4 * args.repeat)
    t_all = median_time.overall
    rows.append(("limit_torque one ratio", t, t_all, None, once(
        lambda: scipy_limit(design, fluid, 1.0))))
    t = median_time(lambda: limit_torque_batch(base, design.creep_limit), args.repeat)
    t_all = median_time.overall
    rows.append(("30 limits of a map", t, t_all, None, once(
        lambda: [scipy_limit(design, fluid, float(r)) for r in ratio])))
    t = median_time(lambda: solve_batch(pb), max(1, args.repeat // 2))
    t_all = median_time.overall
    flat = pb.flat()
    rows.append(("kernel, prepared 30 x 30", t, t_all, pb.size, once(
        lambda: [solve_point(flat.take(i), BASELINE_A) for i in range(flat.size)])))

    print(f"\n  {'what the user calls':<26s} {'ballcvt':>10s}  {'':14s} {'(all calls)':>11s}  "
          f"{'target':<18s} {'met':<4s} {'SciPy baseline':>15s} {'speed-up':>9s}")
    for name, t, t_all, points, base_t in rows:
        target, test = TARGETS[name]
        rate = f"{points / t:,.0f} pts/s" if points and points > 1 else ""
        print(f"  {name:<26s} {t * 1e3:8.2f} ms  {rate:14s} {t_all * 1e3:8.2f} ms  "
              f"{target:<18s} {'yes' if test(t) else 'NO':<4s} {base_t * 1e3:12.0f} ms "
              f"{base_t / t:8.0f}x")
    if not args.skip_reference:
        fast = solve_batch(pb)
        ref = solve_batch(pb, REFERENCE, x0=fast.state.creep)
        err = np.abs(efficiency(pb, fast.state).overall - efficiency(pb, ref.state).overall)
        c, cr = fast.state.creep, ref.state.creep
        big = np.abs(cr) > 1e-6
        print(f"  {'':26s} kernel accuracy: max |eta - eta_ref| {err.max():.1e} (target "
              f"<= 1e-4), relative creep error max {np.max(np.abs(c[big] / cr[big] - 1)):.1e} "
              f"(target <= 1e-3)")
    first = [float(subprocess.run([sys.executable, "-c", FIRST_CALL], capture_output=True,
                                  text=True, check=True).stdout) for _ in range(3)]
    best = min(first[1:])
    print(f"  {'first call, fresh interp.':<26s} {best * 1e3:8.0f} ms  {'':14s} "
          f"{'< 1,500 ms':<18s} {'yes' if best < 1.5 else 'NO':<4s} (import + first point, "
          f"JIT cache)")


if __name__ == "__main__":
    main()
