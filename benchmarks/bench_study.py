"""Design-study throughput on Dask: 1,000 designs x 100 operating points (issue 11).

Run: ``python benchmarks/bench_study.py`` (about 5 minutes; ``--designs 200`` for a quick
look; prints figures, asserts nothing).

The same study (Sobol designs over ball radius, aspect ratio, contact angles and the number
of balls, near Table I; a 10 x 10 grid of ratios 0.6-1.6 and torques 5-45 N m at 2 kN and
2000 rpm; capacity at ratio 1) is run three ways:

* in process, without Dask: the plain batched solve of the same work (each design's 100
  points in one batch through the fast solver, its limit in one `limit_search`);
* on a local Dask cluster of 1 worker process, then of 2;

and printed: designs and points per second, the scaling from 1 to 2 workers, and Dask's
overhead on 1 worker against the plain batched solve (target: under 15 %), with and without
the cluster's start-up.

It imports the studies' internals on purpose (`local_client`, `parse_study`): it times the
Dask machinery against the in-process loop.
"""

from __future__ import annotations

import argparse
import os
import platform
import tempfile
import time

from ballcvt import __version__
from ballcvt.analysis.studies.run import local_client, run_study
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


def in_process_and_dask(designs, chunk, workers=(1, 2), out=print):
    """Run the benchmark study in process, then on local Dask clusters of ``workers``
    processes; returns ``{"points", "designs", "plain": s, workers: (start-up s, run s)}``
    and prints (``out``) as it goes."""
    spec = parse_study(STUDY.format(designs=designs, chunk=chunk))
    with tempfile.TemporaryDirectory() as tmp:
        # warm the JIT cache (the workers load it from disk)
        run_study(parse_study(STUDY.format(designs=2, chunk=1)), f"{tmp}/warm",
                  in_process=True, progress=False)
        t = time.perf_counter()
        plain = run_study(spec, f"{tmp}/plain", in_process=True, progress=False)
        t_plain = time.perf_counter() - t
        points = int((plain.dataset["point_status"].values >= 0).sum())
        n = plain.dataset.sizes["design"]
        out(f"{n} designs x {plain.dataset.sizes['point']} operating points: "
            f"{int((plain.dataset['status'].values == 0).sum())} feasible, {points} points "
            "solved")
        out(f"  in process (plain batched solve): {t_plain:7.1f} s = "
            f"{points / t_plain:7,.0f} points/s = {n / t_plain:6.1f} designs/s")
        times = {"points": points, "designs": n, "plain": t_plain}
        for w in workers:
            t = time.perf_counter()
            client = local_client(w)
            t_start = time.perf_counter() - t
            t = time.perf_counter()
            run_study(spec, f"{tmp}/dask{w}", client=client, progress=False)
            t_run = time.perf_counter() - t
            cluster = client.cluster
            client.close()
            cluster.close()
            times[w] = (t_start, t_run)
            out(f"  Dask, {w} worker(s): {t_run:7.1f} s = {points / t_run:7,.0f} "
                f"points/s (cluster start-up {t_start:.1f} s more)")
    return times


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--designs", type=int, default=1000)
    parser.add_argument("--chunk", type=int, default=10,
                        help="designs per task (each finished chunk is one append to the "
                        "Zarr store, about 80 ms: --chunk 50 runs faster, README)")
    args = parser.parse_args()
    print(f"ballcvt {__version__}, Python {platform.python_version()}, {platform.machine()}, "
          f"{os.cpu_count()} cores")
    times = in_process_and_dask(args.designs, args.chunk)
    t_plain = times["plain"]
    (s1, r1), (_, r2) = times[1], times[2]
    print(f"  scaling 1 -> 2 workers: {r1 / r2:.2f}x")
    print(f"  Dask overhead on 1 worker against the plain batched solve: "
          f"{(r1 / t_plain - 1) * 100:+.1f} % ({(r1 + s1) / t_plain * 100 - 100:+.1f} % "
          "with the cluster's start-up); target under 15 %")


if __name__ == "__main__":
    main()
