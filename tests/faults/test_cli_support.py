"""Running the command line in-process and in a subprocess, for the fault tests (helpers
only: no tests here)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from ballcvt.interfaces.cli.main import main

DATA = Path(__file__).parents[1] / "data"
TINY_CYCLE = str(DATA / "tiny_cycle.csv")
TINY_CURVES = str(DATA / "tiny_curves.csv")
TINY_STUDY = DATA / "study_tiny.toml"


def run(capsys, *argv):
    """(exit status, stdout, stderr) of ``ballcvt ARGV`` run in this process."""
    try:
        code = main([str(a) for a in argv])
    except SystemExit as exc:
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err


def one_line(err: str) -> bool:
    """stderr is exactly one line from ballcvt, with no traceback and no warning."""
    return (
        err.count("\n") == 1
        and err.startswith("ballcvt")
        and "Traceback" not in err
        and "Warning" not in err
    )


def spawn(*argv, **kwargs) -> subprocess.CompletedProcess:
    """``python -m ballcvt.interfaces.cli.main ARGV`` in a subprocess (text mode)."""
    env = {**os.environ, "PYTHONWARNINGS": "default"}  # a warning would show
    env.pop("BALLCVT_DEBUG", None)
    return subprocess.run(
        [sys.executable, "-m", "ballcvt.interfaces.cli.main", *map(str, argv)],
        text=True,
        env=env,
        timeout=120,
        **kwargs,
    )
