"""Duty-cycle throughput: ``python benchmarks/bench_cycle.py [--steps N]``.

Runs the example e-bike commute, repeated to N steps (default 10,000), on the built-in
``hub`` drive with its cam, by both strategies on 1 and 2 worker processes, and prints the
time and steps per second.

It calls the analysis layer's `run_cycle` directly (what `Variator.run_cycle` calls), to time
the cycle alone.
"""

import argparse
import time
from pathlib import Path

import numpy as np

from ballcvt import Variator, load_builtin
from ballcvt.analysis.cycle_files import cycle_from_arrays, read_cycle
from ballcvt.analysis.cycles import run_cycle

ROOT = Path(__file__).resolve().parents[1]


def commute(steps):
    """The example e-bike commute repeated to ``steps`` steps."""
    base = read_cycle(ROOT / "examples" / "cycles" / "ebike_commute.csv")
    reps = int(np.ceil(steps / base.size))
    t = np.concatenate([base.time + k * (base.time[-1] + 1.0) for k in range(reps)])
    return cycle_from_arrays(time=t[:steps],
                             output_speed=np.tile(base.output_speed, reps)[:steps],
                             output_torque=np.tile(base.output_torque, reps)[:steps],
                             name=f"commute x{reps}")


def jittered(steps, seed=1):
    """`commute` with every step's output speed and torque scaled by factors drawn in
    0.9-1.1: its steps all differ (the repeated commute has 132 distinct ones)."""
    c = commute(steps)
    rng = np.random.default_rng(seed)
    return cycle_from_arrays(time=c.time,
                             output_speed=c.output_speed * rng.uniform(0.9, 1.1, steps),
                             output_torque=c.output_torque * rng.uniform(0.9, 1.1, steps),
                             name=f"{c.name}, jittered")


def warm_up(v, **clamp):
    """One two-step cycle (loads the compiled kernels)."""
    run_cycle(v, cycle_from_arrays(time=[0.0, 1.0], output_speed=[20.0, 20.0],
                                   output_torque=[10.0, 10.0]),
              target_input_speed=19.0, progress=False, **clamp)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--steps", type=int, default=10_000)
    args = ap.parse_args()
    cycle = commute(args.steps)
    v = Variator(*load_builtin("hub"))
    warm_up(v, clamp_law="cam")
    print(f"ballcvt duty cycle, {cycle.size} steps ({cycle.name}), hub drive, cam clamping")
    for strategy, kw in (("target-input-speed", {"target_input_speed": 180 * np.pi / 30}),
                         ("max-efficiency", {"ratio_range": (0.5, 2.0)})):
        for workers in (1, 2):
            start = time.perf_counter()
            res = run_cycle(v, cycle, strategy=strategy, clamp_law="cam", progress=False,
                            workers=workers, **kw)
            dt = time.perf_counter() - start
            s = res.summary
            print(f"  {strategy:<20} {workers} worker(s) {dt:7.1f} s  {cycle.size / dt:7.0f} "
                  f"steps/s  efficiency {s['efficiency']:.6f}  flagged {s['steps_flagged']}"
                  f"  (target: 10,000 steps < 10 s)")


if __name__ == "__main__":
    main()
