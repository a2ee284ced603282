"""Design-study throughput on Dask: 1,000 designs x 100 operating points (issues 11, 26).

Run: ``python benchmarks/bench_study.py`` (about 5 minutes on an idle 2-core machine;
``--designs 200`` for a quick look; prints figures, asserts nothing).

The same study (Sobol designs over ball radius, aspect ratio, contact angles and the number
of balls, near Table I; a 10 x 10 grid of ratios 0.6-1.6 and torques 5-45 N m at 2 kN and
2000 rpm; capacity at ratio 1) is run four ways:

* **the in-process loop**: `evaluate_chunk` over every design in this process, nothing
  stored (each design's 100 points in one batch through the fast solver, its limit in one
  `limit_search`): the work itself;
* `run_study` in process, without Dask (the same plus the Zarr appends and the tables);
* `run_study` on a local Dask cluster of 1 worker process, then of 2 (``--workers``).

**Overhead** (issue 26: under 10 % at 10,000 designs) is Dask's on *one* worker against
the in-process loop, one process computing in both: ``t_dask1 / t_loop - 1``, the cluster's
start-up left out (printed apart, and with it). It holds everything a Dask study adds:
scheduling, sending the tasks and results, the workers' imports and kernel loading, the
appends and the tables. With 2 workers the script prints the speed-up over the loop and the
overhead per worker, ``2 t_dask2 / t_loop - 1`` (which on a 2-core machine also counts the
cores the scheduler and this process take from the workers).

It imports the studies' internals on purpose (`evaluate_chunk`, `local_client`,
`parse_study`): it times the Dask machinery against the in-process loop.
"""

from __future__ import annotations

import argparse
import os
import platform
import tempfile
import time

import numpy as np

from ballcvt import __version__
from ballcvt.analysis.studies.evaluate import evaluate_chunk, make_context
from ballcvt.analysis.studies.run import design_vectors, local_client, run_study, task_size
from ballcvt.analysis.studies.spec import parse_study

STUDY = """
[study]
name = "benchmark"
method = "sobol"
samples = {designs}
seed = 7
chunk = {chunk}
capacity_ratios = [1.0]

[parameters]
roller_radius = {{ min = 0.027, max = 0.033 }}
aspect_ratio = {{ min = 1.6, max = 1.8 }}
theta0_deg = {{ min = 42.0, max = 48.0 }}
theta2_deg = {{ min = 42.0, max = 48.0 }}
n_rollers = {{ values = [7, 8] }}

[operating]
ratio = [0.6, 0.71, 0.82, 0.93, 1.04, 1.16, 1.27, 1.38, 1.49, 1.6]
output_torque = [5.0, 9.4, 13.9, 18.3, 22.8, 27.2, 31.7, 36.1, 40.6, 45.0]
input_speed_rpm = [2000.0]
clamp_force = 2000.0

[objectives]
eta_mean = "max"
capacity = "max"
"""


def loop_time(spec) -> tuple[float, dict]:
    """Seconds of the in-process loop over the study's designs (nothing stored), and its
    result (`evaluate_chunk`'s arrays)."""
    ctx = make_context(spec)
    x = design_vectors(spec)
    t = time.perf_counter()
    result = evaluate_chunk(ctx, np.arange(len(x)), x)
    return time.perf_counter() - t, result


def dask_time(spec, out, workers: int) -> tuple[float, float]:
    """(cluster start-up, study run) seconds of ``spec`` on a new local cluster."""
    t = time.perf_counter()
    client = local_client(workers)
    t_start = time.perf_counter() - t
    t = time.perf_counter()
    run_study(spec, out, client=client, progress=False)
    t_run = time.perf_counter() - t
    cluster = client.cluster
    client.close()
    cluster.close()
    return t_start, t_run


def in_process_and_dask(designs, chunk, workers=(1, 2), out=print):
    """The in-process loop, then the study on local Dask clusters of ``workers``
    processes; returns ``{"points", "designs", "plain": loop s, workers: (start-up s, run
    s)}`` and prints (``out``) as it goes (`benchmarks/bench_table.py`'s study row)."""
    spec = parse_study(STUDY.format(designs=designs, chunk=chunk))
    with tempfile.TemporaryDirectory() as tmp:
        run_study(parse_study(STUDY.format(designs=2, chunk=1)), f"{tmp}/warm",
                  in_process=True, progress=False)  # warm the JIT cache
        t_loop, res = loop_time(spec)
        points = int((res["point_status"] >= 0).sum())
        times = {"points": points, "designs": len(res["design"]), "plain": t_loop}
        out(f"  in-process loop: {t_loop:7.1f} s = {points / t_loop:7,.0f} points/s")
        for w in workers:
            times[w] = dask_time(spec, f"{tmp}/dask{w}", w)
            out(f"  Dask, {w} worker(s): {times[w][1]:7.1f} s "
                f"(cluster start-up {times[w][0]:.1f} s more)")
    return times


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=1000)
    parser.add_argument("--chunk", type=int, default=10,
                        help="the study's chunk: the fewest designs per task (run.task_size)")
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2],
                        help="local cluster sizes to time (default: 1 2)")
    parser.add_argument("--no-in-process-study", action="store_true",
                        help="skip run_study in process (time the loop and Dask only)")
    args = parser.parse_args()
    print(f"ballcvt {__version__}, Python {platform.python_version()}, {platform.machine()}, "
          f"{os.cpu_count()} cores")
    spec = parse_study(STUDY.format(designs=args.designs, chunk=args.chunk))
    with tempfile.TemporaryDirectory() as tmp:
        # warm the JIT cache (the workers load it from disk)
        run_study(parse_study(STUDY.format(designs=2, chunk=1)), f"{tmp}/warm",
                  in_process=True, progress=False)
        t_loop, res = loop_time(spec)
        points = int((res["point_status"] >= 0).sum())
        designs = len(res["design"])
        print(f"{designs} designs x {res['eta'].shape[1]} operating points: "
              f"{int((res['status'] == 0).sum())} feasible, {points} points solved; tasks of "
              f"{task_size(designs, args.chunk, 1)} designs on 1 worker")
        print(f"  in-process loop (nothing stored): {t_loop:7.1f} s = "
              f"{points / t_loop:7,.0f} points/s = {designs / t_loop:6.1f} designs/s")
        if not args.no_in_process_study:
            t = time.perf_counter()
            run_study(spec, f"{tmp}/plain", in_process=True, progress=False)
            t_plain = time.perf_counter() - t
            print(f"  run_study in process (no Dask): {t_plain:7.1f} s "
                  f"({(t_plain / t_loop - 1) * 100:+.1f} % against the loop)")
        for workers in args.workers:
            s, r = dask_time(spec, f"{tmp}/dask{workers}", workers)
            print(f"  Dask, {workers} worker(s): {r:7.1f} s = {points / r:7,.0f} points/s "
                  f"(cluster start-up {s:.1f} s more); speed-up over the loop "
                  f"{t_loop / r:.2f}x; overhead per worker {(workers * r / t_loop - 1) * 100:+.1f} %"
                  f" ({(workers * (r + s) / t_loop - 1) * 100:+.1f} % with the start-up)")
        print("  overhead = Dask on 1 worker / in-process loop - 1 (issue 26 target: "
              "under 10 % at 10,000 designs)")


if __name__ == "__main__":
    main()
