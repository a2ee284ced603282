"""Single operating point: time to solve and efficiency error against a converged reference.

Run: ``python benchmarks/bench_point.py`` (prints figures; nothing is asserted).
The reference is the same model with the high-order pole-centred rule (96 x 64 nodes,
docs/model.md §3).
"""

import platform
import time

import numpy as np

from ballcvt import REFERENCE, Variator, __version__

OP = {"clamp_force": 2000.0, "input_speed_rpm": 2000.0}


def timed(fn, repeat):
    fn()  # warm
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return np.median(times), np.min(times)


def main():
    print(f"ballcvt {__version__}, Python {platform.python_version()}, {platform.machine()}, "
          f"{platform.processor() or 'cpu'}")
    for arch in ("double", "single"):
        v = Variator(architecture=arch)
        ref = v.with_quadrature(REFERENCE)
        med, best = timed(lambda: v.solve(ratio=1.0, output_torque=40.0, **OP), 20)
        print(f"\n[{arch} idler] quadrature {v.options.quadrature}")
        print(f"  one point (ratio 1, 40 N m): median {med * 1e3:.2f} ms, best {best * 1e3:.2f} ms")
        errors, creep_err, times = [], [], []
        for ratio in np.linspace(0.5, 2.0, 7):
            limit = v.limit_torque(ratio=ratio, **OP)
            for torque in np.linspace(5.0, 0.9 * limit, 6):
                t = time.perf_counter()
                r = v.solve(ratio=ratio, output_torque=torque, **OP)
                times.append(time.perf_counter() - t)
                rr = ref.solve(ratio=ratio, output_torque=torque, **OP)
                errors.append(abs(r.eta - rr.eta))
                c, cr = (np.array([x.creep for x in y.contacts.values()]) for y in (r, rr))
                big = np.abs(cr) > 1e-6
                creep_err.append(np.max(np.abs(c[big] / cr[big] - 1)))
        print("  42 points ratio 0.5-2 x torque 5 N m-90 % of limit:")
        print(f"    solve time median {np.median(times) * 1e3:.2f} ms, max {np.max(times) * 1e3:.1f} ms")
        print(f"    |eta - eta_ref| max {np.max(errors):.2e}, mean {np.mean(errors):.2e}")
        print(f"    relative creep error (|C| > 1e-6) max {np.max(creep_err):.2e}")


if __name__ == "__main__":
    main()
