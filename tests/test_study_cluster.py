"""The local Dask cluster of a study runs its periodic callbacks seldom (session 24)."""

import dask
import distributed  # noqa: F401  (loads its configuration)

from ballcvt.analysis.studies.cluster import QUIET, local_client


def _callbacks(dask_worker=None, dask_scheduler=None):
    server = dask_worker or dask_scheduler
    return {name: pc.callback_time for name, pc in server.periodic_callbacks.items()}


def test_the_local_cluster_takes_the_quiet_settings_and_the_callbacks_follow():
    """The workers (through their nannies) keep `QUIET`; their profiler no longer samples,
    their event loops tick every second, not every 20 ms, and the scheduler (started in
    this process, which gets its own settings back) steals work every second (Dask's
    defaults cost a 10,000-design study 11 % against the loop)."""
    assert dask.config.get("distributed.worker.profile.enabled")  # Dask's default here
    client = local_client(1)
    try:
        on_worker = client.run(lambda: {k: dask.config.get(k) for k in QUIET})
        assert list(on_worker.values()) == [QUIET]
        (worker,) = client.run(_callbacks).values()
        assert "profile" not in worker and "profile-cycle" not in worker
        assert worker["tick"] == 1000 and worker["memory_monitor"] == 1000
        assert client.run_on_scheduler(_callbacks)["stealing"] == 1000
    finally:
        cluster = client.cluster
        client.close()
        cluster.close()
    assert dask.config.get("distributed.worker.profile.enabled")  # this process untouched
