"""Issue 24: output streams and the environment fail in one line (or quietly, for a broken
pipe), never as an "internal error" or a traceback; no RuntimeWarning reaches the user.
These run ballcvt in a subprocess: the stream itself is what is tested."""

from __future__ import annotations

import os
import subprocess
import sys
import time

import pytest
from test_cli_support import TINY_STUDY, one_line, run, spawn


def test_broken_pipe_is_a_quiet_exit():
    """``ballcvt point --json | head -0``: the reader is gone before ballcvt writes."""
    env = {k: v for k, v in os.environ.items() if k != "BALLCVT_DEBUG"}
    proc = subprocess.Popen(
        [sys.executable, "-m", "ballcvt.interfaces.cli.main", "point", "--json"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        env=env,
    )
    proc.stdout.close()  # the reader went away
    err = proc.stderr.read().decode()
    proc.stderr.close()
    assert proc.wait(timeout=120) == 141  # 128 + SIGPIPE, as a shell reports it
    assert err == ""


def test_full_disk_on_stdout_is_one_line_exit_1():
    with open("/dev/full", "w") as full:
        proc = spawn("point", "--json", stdout=full, stderr=subprocess.PIPE)
    assert proc.returncode == 1
    assert one_line(proc.stderr), proc.stderr
    assert "cannot write to standard output: No space left on device" in proc.stderr
    assert "internal error" not in proc.stderr


def test_full_disk_on_a_short_output_is_one_line_exit_1():
    with open("/dev/full", "w") as full:
        proc = spawn("limit", stdout=full, stderr=subprocess.PIPE)
    assert proc.returncode == 1 and one_line(proc.stderr), proc.stderr
    assert "No space left on device" in proc.stderr and "internal error" not in proc.stderr


@pytest.mark.parametrize("argv", [["design", "show"], ["point", "--json"]])
def test_closed_stdout_is_quiet(argv):
    """``ballcvt design show >&-``: no AttributeError; the command runs, prints nothing."""
    proc = subprocess.run(
        ["sh", "-c", 'exec "$@" >&-', "sh", sys.executable, "-m",
         "ballcvt.interfaces.cli.main", *argv],
        capture_output=False, stderr=subprocess.PIPE, text=True, timeout=120,
    )
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""


@pytest.mark.parametrize("argv, flag", [
    (["point", "--clamp", "1e308"], "--clamp"),
    (["clamp", "--max-pressure", "1e308"], "--max-pressure"),
    (["map", "--clamp", "1e-6", "--n-ratio", "2", "--n-torque", "2"], None),
])
def test_no_runtime_warning_reaches_the_user(tmp_path, argv, flag):
    out = ["--out", tmp_path / "o"] if argv[0] == "map" else []
    proc = spawn(*argv, *out, capture_output=True)
    assert proc.returncode == 2, proc.stderr
    assert one_line(proc.stderr), proc.stderr      # the one line, and nothing else
    assert "RuntimeWarning" not in proc.stderr and "internal error" not in proc.stderr
    if flag:
        assert flag in proc.stderr


def test_unreachable_scheduler_is_one_line_exit_1_within_10_s(capsys, tmp_path):
    out = tmp_path / "study"
    start = time.perf_counter()
    code, stdout, err = run(capsys, "explore", TINY_STUDY, "--out", out,
                            "--scheduler", "tcp://127.0.0.1:1")
    assert time.perf_counter() - start < 10
    assert code == 1 and one_line(err), err
    assert "cannot reach the Dask scheduler at tcp://127.0.0.1:1" in err
    assert "internal error" not in err and not out.exists()


@pytest.mark.parametrize("address", ["tcp://127.0.0.1:notaport", "tcp://999.999.1.1:8786",
                                     "tcp://127.0.0.1:70000"])
def test_malformed_scheduler_address_is_bad_input(capsys, tmp_path, address):
    code, _, err = run(capsys, "explore", TINY_STUDY, "--out", tmp_path / "s",
                       "--scheduler", address)
    assert code == 2 and one_line(err) and "--scheduler" in err, err
