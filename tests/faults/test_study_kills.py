"""Design studies survive ``kill -9`` (issue 24): every append commits atomically, resume
gives exactly the uninterrupted result, resume checks the study, one run per folder.

A tiny study (tests/data/study_tiny.toml, one design per append) runs in a subprocess that
is killed with SIGKILL at seeded random instants, then resumed, a few times over; the
finished folder must equal an uninterrupted run's (the same designs, each once, the same
numbers, the same tables and chosen design). The default suite kills about 12 in-process
runs and 6 on a one-worker local Dask cluster; ``-m slow`` about 60 more in process and 12
on two workers (a run that finishes before its instant is counted, not killed).
Deterministic tests tear an append in the middle (some arrays grown, others not).
"""

import json
import os
import random
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from ballcvt import InputError
from ballcvt.analysis.studies import run as run_module
from ballcvt.analysis.studies.lock import LOCK
from ballcvt.analysis.studies.run import run_study
from ballcvt.analysis.studies.spec import parse_study
from ballcvt.analysis.studies.store import MANIFEST, STORE
from ballcvt.interfaces.cli import main as cli

DATA = Path(__file__).resolve().parents[1] / "data"
TINY = DATA / "study_tiny.toml"
#: The tiny study, one design per append (8 appends): more instants inside an append.
TEXT = TINY.read_text().replace("chunk = 2", "chunk = 1")
TABLES = ("designs.csv", "pareto.csv", "chosen_design.toml")

#: The study in a subprocess: argv = study file, folder, workers (0: in process), hook.
RUNNER = r"""
import os, sys
from ballcvt.analysis.studies.run import run_study
from ballcvt.analysis.studies.spec import read_study
spec = read_study(sys.argv[1])
hook = sys.argv[4]
if hook.startswith("tear:"):          # exit in the middle of an append, after n resizes
    import zarr
    real, calls = zarr.Array.resize, [0]
    def resize(self, *a, **k):
        real(self, *a, **k)
        calls[0] += 1
        if calls[0] == int(hook[5:]):
            os._exit(9)
    zarr.Array.resize = resize
if hook == "slow":                    # hold the folder a while
    import time
    from ballcvt.analysis.studies import run
    real_chunk = run.evaluate_chunk
    run.evaluate_chunk = lambda *a: time.sleep(0.3) or real_chunk(*a)
print("ready", flush=True)
kw = {"in_process": True} if sys.argv[3] == "0" else {"workers": int(sys.argv[3])}
r = run_study(spec, sys.argv[2], resume=True, progress=False, **kw)
print("done", r.evaluated_now, flush=True)
"""


@pytest.fixture(scope="module")
def study(tmp_path_factory):
    path = tmp_path_factory.mktemp("spec") / "study.toml"
    path.write_text(TEXT)
    return path


def start(study, out, workers=0, hook="-"):
    """The runner in its own session (its Dask workers die with it); waits for 'ready'."""
    proc = subprocess.Popen(
        [sys.executable, "-c", RUNNER, str(study), str(out), str(workers), hook],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
    )
    assert proc.stdout.readline().strip() == "ready", proc.stderr.read()
    return proc


def finish(study, out, workers=0, hook="-"):
    proc = start(study, out, workers, hook)
    t0 = time.perf_counter()
    stdout, stderr = proc.communicate(timeout=300)
    return proc.returncode, stdout, stderr, time.perf_counter() - t0


def kill(proc) -> bool:
    """SIGKILL the runner's process group (the runner and its Dask cluster); False if it
    had finished first."""
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    proc.communicate(timeout=60)
    return proc.returncode == -signal.SIGKILL


def torn(out):
    """True if the store holds what its commit does not name: design arrays of other
    lengths than the committed rows, or a first chunk cut short."""
    try:
        rows = json.loads((out / MANIFEST).read_text())["designs"]
    except (OSError, ValueError):
        return False
    lengths = set()
    for meta in (out / STORE).glob("*/.zarray"):
        try:
            dims = json.loads((meta.parent / ".zattrs").read_text())["_ARRAY_DIMENSIONS"]
        except OSError:
            return True                                   # an array cut short
        if dims[0] == "design":
            lengths.add(json.loads(meta.read_text())["shape"][0])
    return (out / STORE).exists() and lengths != {rows}


@pytest.fixture(scope="module")
def reference(study, tmp_path_factory):
    """The uninterrupted run (in a subprocess) and its duration after start-up [s]."""
    out = tmp_path_factory.mktemp("reference")
    code, stdout, stderr, seconds = finish(study, out)
    assert code == 0 and "done 8" in stdout, stderr
    return out, seconds


def assert_same_as(out, ref):
    """The folder ``out`` holds exactly the reference's designs, numbers and tables."""
    raw = xr.open_zarr(out / STORE, consolidated=False)
    assert sorted(raw["design"].values.tolist()) == list(range(8))  # each design once
    a = raw.load().sortby("design")
    b = xr.open_zarr(ref / STORE, consolidated=False).load().sortby("design")
    for name in b.data_vars:
        x, y = a[name].values, b[name].values
        if x.dtype.kind == "f":
            np.testing.assert_array_equal(x, y, err_msg=name)
        else:
            assert np.array_equal(x, y), name
    for name in TABLES:
        assert (out / name).read_text() == (ref / name).read_text(), name
    assert not (out / LOCK).exists()


@pytest.fixture(scope="module")
def dask_seconds(study, reference, tmp_path_factory):
    """An uninterrupted run on a one-worker Dask cluster (equal to the reference): its
    duration after start-up [s]."""
    out = tmp_path_factory.mktemp("dask")
    code, stdout, stderr, seconds = finish(study, out, workers=1)
    assert code == 0 and "done 8" in stdout, stderr
    assert_same_as(out, reference[0])
    return seconds


def kill_and_resume(study, reference, tmp_path, workers, trials, seed, seconds=None):
    """``trials`` folders, each killed 3 times at random instants, then finished."""
    ref, seconds = reference[0], seconds or reference[1]
    rng = random.Random(seed)
    stats = {"kills": 0, "torn": 0, "finished before the kill": 0}
    for trial in range(trials):
        out = tmp_path / f"trial{trial}"
        for _ in range(3):
            left = 8 - (json.loads((out / MANIFEST).read_text())["designs"]
                        if (out / MANIFEST).exists() else 0)
            # the rest of the run: its designs and the tables (and a Dask cluster's start)
            span = seconds * (max(left, 1) + 1) / 9
            proc = start(study, out, workers)
            time.sleep(rng.uniform(0.0, span))
            if kill(proc):
                stats["kills"] += 1
                stats["torn"] += torn(out)
            else:
                stats["finished before the kill"] += 1
        code, stdout, stderr, _ = finish(study, out, workers)
        assert code == 0, stderr
        assert_same_as(out, ref)
    print(f"\n{workers or 'in-process'} kills: {stats}")
    return stats


def test_random_kills_in_process(study, reference, tmp_path):
    stats = kill_and_resume(study, reference, tmp_path, workers=0, trials=4, seed=24)
    assert stats["kills"] >= 9


def test_random_kills_on_dask(study, reference, dask_seconds, tmp_path):
    stats = kill_and_resume(study, reference, tmp_path, workers=1, trials=2, seed=25,
                            seconds=dask_seconds)
    assert stats["kills"] >= 3


@pytest.mark.slow
def test_many_random_kills_in_process(study, reference, tmp_path):
    kill_and_resume(study, reference, tmp_path, workers=0, trials=20, seed=240)


@pytest.mark.slow
def test_many_random_kills_on_dask(study, reference, dask_seconds, tmp_path):
    kill_and_resume(study, reference, tmp_path, workers=2, trials=4, seed=250,
                    seconds=dask_seconds * 1.2)  # two workers start a little later


@pytest.mark.parametrize("resizes", [1, 4, 9])
def test_kill_inside_an_append_is_repaired(study, reference, tmp_path, resizes):
    """os._exit in the middle of the second append: arrays of different lengths; the store
    opens again and resume finishes with the planned designs, each once."""
    out = tmp_path / "torn"
    code, _, stderr, _ = finish(study, out, hook=f"tear:{resizes}")
    assert code == 9, stderr
    assert torn(out)
    code, stdout, stderr, _ = finish(study, out)
    assert code == 0 and "done 7" in stdout, stderr  # the torn append's design again
    assert "taking over the stale lock" in stderr
    assert_same_as(out, reference[0])


# --- resume checks the study -------------------------------------------------------------


@pytest.fixture(scope="module")
def finished(study, tmp_path_factory):
    out = tmp_path_factory.mktemp("finished")
    run_study(parse_study(TEXT, base=DATA), out, in_process=True, progress=False)
    return out


def test_resume_of_another_study_is_refused_naming_what_changed(finished, tmp_path, capsys):
    other = TEXT.replace("output_torque = [20.0, 40.0]", "output_torque = [20.0, 45.0]")
    with pytest.raises(InputError, match=r"another study .*changed: operating\.output_torque"):
        run_study(parse_study(other, base=DATA), finished, in_process=True, resume=True,
                  progress=False)
    path = tmp_path / "other.toml"
    path.write_text(other.replace("seed = 3", "seed = 4"))
    args = ["explore", str(path), "--out", str(finished), "--in-process", "--resume"]
    assert cli.main(args) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert "operating.output_torque, study.seed" in err
    assert not (finished / LOCK).exists()                    # released on the error


def test_resume_of_the_same_study_with_other_chunks_is_accepted(finished):
    again = run_study(parse_study(TEXT.replace("chunk = 1", "chunk = 3"), base=DATA),
                      finished, in_process=True, resume=True, progress=False)
    assert again.evaluated_now == 0 and again.dataset.sizes["design"] == 8


def test_store_of_an_older_ballcvt_is_adopted_or_refused_when_torn(finished, tmp_path):
    import shutil

    old = tmp_path / "old"
    shutil.copytree(finished, old)
    (old / MANIFEST).unlink()                                 # written before manifests
    spec = parse_study(TEXT, base=DATA)
    again = run_study(spec, old, in_process=True, resume=True, progress=False)
    assert again.evaluated_now == 0 and (old / MANIFEST).exists()
    (old / MANIFEST).unlink()
    meta = old / STORE / "status" / ".zarray"
    shape = json.loads(meta.read_text())
    shape["shape"][0] += 2                                    # torn: lengths differ
    meta.write_text(json.dumps(shape))
    with pytest.raises(InputError, match="torn by an interrupted run"):
        run_study(spec, old, in_process=True, resume=True, progress=False)


# --- one run per folder ------------------------------------------------------------------


def test_second_run_into_a_held_folder_is_refused(study, tmp_path, capsys):
    out = tmp_path / "held"
    first = start(study, out, hook="slow")
    for _ in range(200):                                      # until it holds the folder
        if (out / LOCK).exists():
            break
        time.sleep(0.02)
    args = ["explore", str(study), "--out", str(out), "--in-process", "--resume"]
    assert cli.main(args) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and f"process {first.pid}" in err and "in use" in err
    stdout, stderr = first.communicate(timeout=120)
    assert first.returncode == 0 and "done 8" in stdout, stderr
    raw = xr.open_zarr(out / STORE, consolidated=False)
    assert sorted(raw["design"].values.tolist()) == list(range(8))
    assert not (out / LOCK).exists()


def test_stale_lock_is_taken_over_saying_so(tmp_path, capsys):
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    (tmp_path / LOCK).write_text(json.dumps({"pid": dead.pid, "host": socket.gethostname()}))
    run_study(parse_study(TEXT, base=DATA), tmp_path, in_process=True, progress=False)
    err = capsys.readouterr().err
    assert f"taking over the stale lock of {tmp_path}" in err and str(dead.pid) in err
    assert not (tmp_path / LOCK).exists()


def test_lock_is_released_on_an_exception(tmp_path, monkeypatch):
    def interrupted(ctx, index, x):
        raise KeyboardInterrupt

    monkeypatch.setattr(run_module, "evaluate_chunk", interrupted)
    with pytest.raises(KeyboardInterrupt):
        run_study(parse_study(TEXT, base=DATA), tmp_path, in_process=True, progress=False)
    assert not (tmp_path / LOCK).exists()
