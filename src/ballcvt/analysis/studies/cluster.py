"""The local Dask cluster a study or a propagation starts when it is given no scheduler."""

from __future__ import annotations

__all__ = ["QUIET", "local_client"]

#: Dask settings of the clusters `local_client` starts: the scheduler's and the workers'
#: periodic callbacks run seldom (Dask's defaults in brackets): the event loops' tick
#: every 1 s (20 ms), the system monitor every 5 s (0.5 s), the workers' memory
#: monitor every 1 s (0.1 s), work stealing every 1 s (0.1 s), and the workers'
#: statistical profiler (a stack sample of the computing thread every 10 ms, for the
#: dashboard's profile page) off. Each wakes a thread that takes the GIL from the solves
#: or a core's caches from the process computing. With them, a 10,000-design study on one
#: worker took 7.6 % and 5.4 % longer than the in-process loop in two runs in a row
#: (benchmarks/bench_study.py; 11.4 % with Dask's defaults the same day, 10.3-13.6 % in
#: earlier sessions; session 24; those runs also set a nanny key Dask does not have).
#: Which of the five matters was not measured apart.
QUIET = {
    "distributed.admin.tick.interval": "1s",
    "distributed.admin.system-monitor.interval": "5s",
    "distributed.worker.memory.monitor-interval": "1s",
    "distributed.scheduler.work-stealing-interval": "1s",
    "distributed.worker.profile.enabled": False,
}


def local_client(workers: int):
    """A Dask client on a new ``LocalCluster`` of ``workers`` single-threaded processes,
    bound to 127.0.0.1, with the settings `QUIET` (its scheduler reads them as it starts,
    its nannies hand them to their workers; this process's own settings are restored)."""
    import dask
    from distributed import Client, LocalCluster

    with dask.config.set(QUIET):
        cluster = LocalCluster(
            n_workers=workers,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address="127.0.0.1:0",
        )
        return Client(cluster)
