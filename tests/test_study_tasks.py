"""Studies group designs into few large tasks (issue 26): the rows stored do not depend on
the grouping, in process or on Dask."""

from pathlib import Path

import numpy as np
import pytest
from test_studies import same  # bitwise equality of two stores

from ballcvt.analysis.studies import run as run_module
from ballcvt.analysis.studies.run import MAX_TASK, local_client, run_study, task_size
from ballcvt.analysis.studies.spec import parse_study

TINY = Path(__file__).parent / "data" / "study_tiny.toml"


def tiny(chunk: int):
    return parse_study(TINY.read_text().replace("chunk = 2", f"chunk = {chunk}"),
                       base=TINY.parent)


@pytest.mark.parametrize("n, chunk, workers, size", [
    (8, 2, 2, 2),            # small studies keep the study's chunk
    (8, 1, 1, 2),            # a quarter of one worker's share
    (1000, 10, 2, 125),
    (10_000, 8, 2, MAX_TASK),
    (10_000, 2000, 2, 2000),  # never below the study's chunk
    (5, 3, 0, 3),
])
def test_task_size(n, chunk, workers, size):
    assert task_size(n, chunk, workers) == size


def test_same_rows_whatever_the_tasks(tmp_path, monkeypatch):
    sizes = []
    real = run_module.evaluate_chunk
    monkeypatch.setattr(run_module, "evaluate_chunk",
                        lambda ctx, index, x: sizes.append(len(index)) or real(ctx, index, x))
    one = run_study(tiny(1), tmp_path / "one", in_process=True, progress=False)
    assert sizes == [1] * 8
    sizes.clear()
    whole = run_study(tiny(8), tmp_path / "whole", in_process=True, progress=False)
    assert sizes == [8]
    same(one.dataset, whole.dataset)
    assert one.chosen == whole.chosen
    client = local_client(1)
    try:                                     # 1 worker, tasks of 2 designs (task_size)
        remote = run_study(tiny(1), tmp_path / "dask", client=client, progress=False)
    finally:
        cluster = client.cluster
        client.close()
        cluster.close()
    same(one.dataset, remote.dataset)
    assert np.array_equal(remote.dataset["design"].values, np.arange(8))
