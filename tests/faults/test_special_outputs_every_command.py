"""Every command that writes an output folder refuses a special file given as --out, or
found where one of its files goes: one line, exit 2, and the special file is kept."""

import os
import stat
from pathlib import Path

import pytest

from ballcvt.interfaces.cli.main import main

DATA = Path(__file__).resolve().parents[1] / "data"
COMMANDS = {
    "map": (["map", "--n-ratio", "3", "--n-torque", "3"], "map.csv"),
    "table": (["table", "--n-ratio", "2", "--n-speed", "2", "--n-torque", "2"], "table.csv"),
    "cycle": (["cycle", str(DATA / "tiny_cycle.csv"), "--target-speed", "2000"], "steps.csv"),
    "traction-curve": (["traction-curve", "--rx", "0.02", "--ry", "0.05", "--speed", "10",
                        "--load", "1000"],
                       "traction_curve.csv"),
    "fit-fluid": (["fit-fluid", str(DATA / "tiny_curves.csv")], "fluid.toml"),
    "explore": (["explore", str(DATA / "study_tiny.toml"), "--in-process"], "designs.csv"),
    "uncertainty": (["uncertainty", "--samples", "2", "--power", "100", "--speed", "114",
                     "--oil-temperature", "40"], "band.csv"),  # fixed oil: seconds, not minutes
}


def _run(argv) -> int:
    try:
        return main(argv)
    except SystemExit as exc:  # argparse's own refusals
        return int(exc.code)


QUIET = {"map", "table", "cycle", "explore", "uncertainty"}


def _one_line(err: str) -> bool:
    lines = [ln for ln in err.splitlines() if ln.strip()]
    return len(lines) == 1 and "Traceback" not in err and "internal error" not in err


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_a_fifo_as_out_is_refused_and_kept(tmp_path, capsys, command):
    argv, _ = COMMANDS[command]
    fifo = tmp_path / "out"
    os.mkfifo(fifo)
    code = _run([*argv, "--out", str(fifo)] + (["--quiet"] if command in QUIET else []))
    err = capsys.readouterr().err
    assert code == 2 and _one_line(err), err
    assert stat.S_ISFIFO(os.lstat(fifo).st_mode)


@pytest.mark.parametrize("command", ["map", "cycle", "traction-curve", "uncertainty"])
def test_a_fifo_where_an_output_file_goes_is_refused_and_kept(tmp_path, capsys, command):
    argv, name = COMMANDS[command]
    out = tmp_path / "out"
    out.mkdir()
    os.mkfifo(out / name)
    code = _run([*argv, "--out", str(out)] + (["--quiet"] if command in QUIET else []))
    err = capsys.readouterr().err
    assert code == 2 and _one_line(err), err
    assert stat.S_ISFIFO(os.lstat(out / name).st_mode)
