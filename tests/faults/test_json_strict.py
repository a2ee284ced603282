"""Issue 24: every ``--json`` the command line prints parses under a strict JSON parser
(RFC 8259: no ``NaN``, ``Infinity`` or ``-Infinity``), also at extreme accepted inputs."""

from __future__ import annotations

import json

import pytest
from test_cli_support import TINY_CURVES, TINY_CYCLE, TINY_STUDY, one_line, run

from ballcvt.interfaces.cli.main import build_parser


def strict(text: str):
    """``json.loads`` that refuses NaN and the infinities."""

    def refuse(constant):
        raise ValueError(f"{constant} is not JSON")

    return json.loads(text, parse_constant=refuse)


TC = ["--rx", "0.01", "--ry", "0.02", "--speed", "10"]
SHIFT = ["--from", "0.8", "--to", "1.2", "--samples", "5"]
#: Every command with --json, at ordinary and at extreme (but accepted) inputs.
CASES = {
    "point": [[], ["--clamp", "1e6"], ["--speed", "1e5"], ["--torque", "0"],
              ["--held", "disc0", "--driver", "carrier", "--ratio", "1.0", "--torque", "20",
               "--speed", "100"]],
    "limit": [[], ["--clamp", "1"], ["--speed", "1e5"]],
    "clamp": [[], ["--max-pressure", "1e10"], ["--torque", "0"]],
    "cycle": [[TINY_CYCLE, "--target-speed", "180"], [TINY_CYCLE, "--target-speed", "1e5"],
              [TINY_CYCLE, "--target-speed", "180", "--life"]],
    "traction-curve": [[*TC, "--load", "1000"], [*TC, "--load", "1e6"],
                       ["--rx", "1e-6", "--ry", "1e3", "--load", "1e6", "--speed", "1e3"],
                       [*TC, "--pmax", "1e10", "--law", "thermal"],
                       [*TC, "--load", "1e-300", "--law", "viscoelastic"]],
    "fit-fluid": [[TINY_CURVES]],
    "explore": [[str(TINY_STUDY), "--in-process", "--quiet"]],
    "life": [[], ["--torque", "0"], ["--life-model", "iso-fatigue-limit", "--clamp", "500"],
             ["--design", "hub", "--speed", "1e5"],
             ["--design", "hub", "--cycle", TINY_CYCLE, "--target-speed", "180"]],
    "shift": [[*SHIFT, "--skew", "1"], [*SHIFT, "--tilt-rate", "20"],
              [*SHIFT, "--skew", "9.99", "--speed", "1e5", "--torque", "1e6"],
              ["--design", "hub", "--from", "0.5", "--to", "1.8", "--skew", "0.01"]],
    "uncertainty": [["--samples", "2", "--power", "100", "--speed", "114"],  # oil balance
                    ["--samples", "2", "--torque", "1e6", "--speed", "1e5"]],
}
NEEDS_OUT = ("cycle", "fit-fluid", "explore", "shift", "uncertainty")


def test_every_json_command_is_covered():
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    with_json = {name for name, p in sub.choices.items()
                 if any("--json" in a.option_strings for a in p._actions)}
    assert with_json == set(CASES)


@pytest.mark.parametrize("command, argv", [(c, a) for c, cases in CASES.items()
                                           for a in cases])
def test_json_output_is_strict(capsys, tmp_path, command, argv):
    out_dir = ["--out", tmp_path / "o"] if command in NEEDS_OUT else []
    code, out, err = run(capsys, command, *argv, *out_dir, "--json")
    if code == 2:  # refused: one line, nothing on stdout
        assert out == "" and one_line(err), err
        return
    assert code == 0, err
    assert isinstance(strict(out), dict)


def test_traction_curve_at_an_absurd_load_is_refused_not_nan(capsys):
    """The issue's case: it printed NaN and Infinity; now exit 2 naming --load."""
    code, out, err = run(capsys, "traction-curve", *TC, "--load", "1e308", "--json")
    assert code == 2 and out == "" and one_line(err) and "--load" in err


def test_non_finite_numbers_are_written_null(capsys):
    from ballcvt.interfaces.cli.options import emit_json

    emit_json({"a": float("nan"), "b": [1.0, float("inf")], "c": {"d": -float("inf")}})
    assert strict(capsys.readouterr().out) == {"a": None, "b": [1.0, None], "c": {"d": None}}
