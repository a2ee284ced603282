"""Fast batched solver on a 30 x 30 map: throughput, accuracy and the speed-up on baselines.

Run: ``python benchmarks/bench_batch.py`` (about 8 minutes, 30 s with ``--skip-adaptive``;
prints figures, asserts nothing).

Map: ratio 0.5-2 x output torque 5 N m to 90 % of the limiting torque, F_N0 = 2 kN,
2000 rpm, for each architecture. Printed:

* first-call latency (fresh interpreter: import + first point, JIT included);
* points per second of the default solver on one core and on both cores (processes);
* the same on one core under the thermal and the visco-elastic traction laws (docs/model.md
  §14), each on its own map (torques to 90 % of that law's limiting torques), next to the
  isothermal figure (issue 10's target: >= 1,000 points/s/core with the thermal law);
* max and mean |eta - eta_ref| and relative creep error (creeps above 1e-6) against the
  high-order reference (pole-centred rule, 64 x 64 nodes, 128 in the centred part);
* speed-up against (a) the package's straightforward path: SciPy ``root`` (hybr) with a
  finite-difference Jacobian on the fixed centred 32 x 32 grid, the integrals in NumPy (no
  compiled kernels), point by point; and (b) a
  plain SciPy implementation with nested adaptive ``quad`` for the traction integrals and
  ``root`` on the equilibrium, on one point, as a user without ballcvt would write it.

It imports internals below the public API on purpose (the equilibrium, the kernels and the
solvers): it times them one by one.
"""

from __future__ import annotations

import argparse
import os
import platform
import subprocess
import sys
import tempfile
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np
from scipy.optimize import root

from ballcvt import Quadrature, SolverOptions, __version__, load_builtin
from ballcvt.equilibrium.problem import build_problem
from ballcvt.equilibrium.residual import _balances, _contact_inputs
from ballcvt.model.kinematics import creep_term
from ballcvt.model.traction.contact import ContactState
from ballcvt.model.traction.reference import adaptive_coefficients
from ballcvt.performance.efficiency import efficiency
from ballcvt.solvers.limit import limit_torque_batch
from ballcvt.solvers.newton import initial_creep, solve_batch
from ballcvt.solvers.point import solve_point

SPEED = 2000.0 * np.pi / 30.0
REFERENCE = SolverOptions(quadrature=Quadrature("pole", 64, 64, 128))
#: Baseline (a), the straightforward implementation: the NumPy integrals (no compiled
#: kernels) on the fixed centred 32 x 32 grid, SciPy's hybrid method, point by point.
BASELINE_A = SolverOptions(quadrature=Quadrature("centred", 32, 32, engine="numpy"),
                           method="hybr", predictor=None)
FIRST_CALL = ("import time; t = time.perf_counter(); from ballcvt import Variator; "
              "Variator().solve(ratio=1.0, output_torque=40.0, clamp_force=2000.0, "
              "input_speed_rpm=2000); print(time.perf_counter() - t)")


def the_map(arch, n=30, law="isothermal"):
    design, fluid = load_builtin()
    fluid = fluid.with_traction_law(law)
    ratio = np.linspace(0.5, 2.0, n)
    base = build_problem(design, fluid, arch, ratio, 0.0, 2000.0, SPEED)
    t = time.perf_counter()
    limit = limit_torque_batch(base, design.creep_limit, SolverOptions())
    t_limit = time.perf_counter() - t
    torque = 5.0 + np.linspace(0.0, 1.0, n)[None, :] * (0.9 * limit[:, None] - 5.0)
    return design, fluid, ratio, torque, t_limit


def solve_rows(args):
    design, fluid, arch, ratio, torque = args
    pb = build_problem(design, fluid, arch, ratio[:, None], torque, 2000.0, SPEED)
    sol = solve_batch(pb)
    return sol.state.creep, sol.converged


def adaptive_point(problem):
    """Baseline (b): SciPy root on the equilibrium with nested adaptive quad integrals."""
    def fun(x):
        ws, w, sg, u, h = _contact_inputs(problem, x)
        c = creep_term(x)
        mu, chi = np.zeros(x.size), np.zeros(x.size)
        for i in range(x.size):
            mu[i], chi[i] = adaptive_coefficients(ContactState(
                c[i], sg[i], problem.ax[i], problem.ay[i], problem.p_max[i], problem.load[i],
                problem.radius[i], u[i], h[i]), problem.fluid, epsrel=1e-8)
        return _balances(problem, x, ws, w, sg, u, h, mu, chi).residual

    return root(fun, initial_creep(problem), method="hybr", options={"xtol": 1e-12})


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=30, help="map size n x n (default 30)")
    parser.add_argument("--baseline-a-points", type=int, default=30)
    parser.add_argument("--skip-adaptive", action="store_true", help="skip baseline (b)")
    args = parser.parse_args()
    print(f"ballcvt {__version__}, Python {platform.python_version()}, {platform.machine()}, "
          f"{os.cpu_count()} cores, {platform.processor() or 'cpu'}")
    with tempfile.TemporaryDirectory() as cache:               # empty JIT cache: cold start
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        first = [float(subprocess.run([sys.executable, "-c", FIRST_CALL], capture_output=True,
                                      text=True, check=True, env=env).stdout)
                 for _ in range(2)]
    print(f"first call in a fresh interpreter (import + first point): {first[0]:.2f} s with "
          f"JIT compilation, {first[1]:.2f} s from the JIT cache")
    for arch in ("double", "single"):
        design, fluid, ratio, torque, t_limit = the_map(arch, args.n)
        n_pts = torque.size
        pb = build_problem(design, fluid, arch, ratio[:, None], torque, 2000.0, SPEED)
        solve_batch(pb)                                       # warm (JIT, caches)
        t = time.perf_counter()
        fast = solve_batch(pb)
        t1 = time.perf_counter() - t
        halves = np.array_split(np.arange(ratio.size), 2)
        jobs = [(design, fluid, arch, ratio[h], torque[h]) for h in halves]
        with ProcessPoolExecutor(max_workers=2) as pool:
            list(pool.map(solve_rows, jobs))                  # warm the workers
            t = time.perf_counter()
            parts = list(pool.map(solve_rows, jobs))
            t2 = time.perf_counter() - t
        assert np.allclose(np.concatenate([p[0] for p in parts]), fast.state.creep)
        t = time.perf_counter()
        ref = solve_batch(pb, REFERENCE, x0=fast.state.creep)
        t_ref = time.perf_counter() - t
        eta = efficiency(pb, fast.state).overall
        eta_ref = efficiency(pb, ref.state).overall
        err = np.abs(eta - eta_ref)
        c, cr = fast.state.creep, ref.state.creep
        big = np.abs(cr) > 1e-6
        rel = np.abs(c[big] / cr[big] - 1.0)
        # baseline (a): point by point, hybr + FD Jacobian on the fixed centred grid
        idx = np.linspace(0, n_pts - 1, args.baseline_a_points).astype(int)
        flat = pb.flat()
        t = time.perf_counter()
        for i in idx:
            solve_point(flat.take(int(i)), BASELINE_A)
        t_a = (time.perf_counter() - t) / idx.size
        print(f"\n[{arch} idler] {n_pts} points, quadrature {SolverOptions().quadrature}")
        print(f"  limiting torques of the {ratio.size} ratios (batched bisection): "
              f"{t_limit:.2f} s")
        print(f"  converged {int(fast.converged.sum())}/{n_pts}, mean iterations "
              f"{fast.iterations.mean():.1f} (coarse predictor + fine Newton)")
        print(f"  one core : {t1:.3f} s = {n_pts / t1:,.0f} points/s")
        print(f"  two cores: {t2:.3f} s = {n_pts / t2:,.0f} points/s (speed-up {t1 / t2:.2f}x)")
        for law, target in (("thermal", "target >= 1,000"), ("viscoelastic", "")):
            d_l, f_l, r_l, q_l, t_lim = the_map(arch, args.n, law)
            pb_l = build_problem(d_l, f_l, arch, r_l[:, None], q_l, 2000.0, SPEED)
            solve_batch(pb_l)                                 # warm
            t = time.perf_counter()
            sol_l = solve_batch(pb_l)
            t_l = time.perf_counter() - t
            print(f"  one core, {law} law: {t_l:.3f} s = {q_l.size / t_l:,.0f} points/s "
                  f"({target + ', ' if target else ''}isothermal {n_pts / t1:,.0f}; converged "
                  f"{int(sol_l.converged.sum())}/{q_l.size}; its {r_l.size} limits "
                  f"{t_lim:.2f} s)")
        print(f"  |eta - eta_ref| max {err.max():.2e}, mean {err.mean():.2e}; relative creep "
              f"error max {rel.max():.2e}, mean {rel.mean():.2e} (reference solved in "
              f"{t_ref:.1f} s)")
        print(f"  baseline (a) hybr + centred 32x32, point by point: {t_a * 1e3:.1f} ms/point "
              f"= {1 / t_a:,.0f} points/s -> fast solver {t_a * n_pts / t1:,.0f}x faster")
        if not args.skip_adaptive:
            point = flat.take(int(idx[len(idx) // 2]))
            t = time.perf_counter()
            sol = adaptive_point(point)
            t_b = time.perf_counter() - t
            print(f"  baseline (b) SciPy root + nested adaptive quad, one point: {t_b:.1f} s "
                  f"({'converged' if sol.success else 'not converged'}, {sol.nfev} residual "
                  f"evaluations) -> fast solver {t_b * n_pts / t1:,.0f}x faster")


if __name__ == "__main__":
    main()
