"""Issue 24: hostile command lines and input files get one line and the right exit status
(2 for bad input), never "internal error", a traceback or a silently wrong reading."""

from __future__ import annotations

import pytest
from test_cli_support import TINY_CURVES, TINY_CYCLE, TINY_STUDY, one_line, run

from ballcvt.interfaces.cli.main import build_parser
from ballcvt.params.io import builtin_text

#: Arguments each command needs besides its options, so that parsing reaches the options.
REQUIRED = {
    "design": ["show"],
    "cycle": [TINY_CYCLE],
    "fit-fluid": [TINY_CURVES],
    "explore": [str(TINY_STUDY)],
    "traction-curve": ["--rx", "0.01", "--ry", "0.02", "--load", "1000", "--speed", "10"],
    "shift": ["--from", "0.8", "--to", "1.2", "--skew", "1"],
}


@pytest.fixture(autouse=True)
def _no_server(monkeypatch):
    """`explore-ui` must refuse its input before any server starts."""
    import ballcvt.interfaces.ui

    def serve(*args, **kwargs):
        raise AssertionError("the server was started")

    monkeypatch.setattr(ballcvt.interfaces.ui, "serve", serve)


def _abbreviations():
    """(command, abbreviated flag, the flag) for every long option of every command."""
    parser = build_parser()
    sub = next(a for a in parser._actions if a.dest == "command")
    cases = []
    for name, p in sub.choices.items():
        flags = {f for a in p._actions for f in a.option_strings}
        for action in p._actions:
            for flag in action.option_strings:
                short = flag[:-1]
                if flag.startswith("--") and len(short) > 3 and short not in flags:
                    cases.append((name, short, flag))
    return cases


ABBREVIATIONS = _abbreviations()


def test_the_examples_of_the_issue_are_among_the_abbreviations():
    assert ("point", "--rati", "--ratio") in ABBREVIATIONS
    assert ("map", "--torque-ma", "--torque-max") in ABBREVIATIONS
    assert len(ABBREVIATIONS) > 100


@pytest.mark.parametrize("command, short, flag", ABBREVIATIONS)
def test_abbreviated_options_are_refused(capsys, tmp_path, monkeypatch, command, short, flag):
    monkeypatch.chdir(tmp_path)  # were one accepted (``--ou 1``), it would write ./1 here
    code, out, err = run(capsys, command, *REQUIRED.get(command, []), short, "1")
    assert code == 2 and out == "" and one_line(err), err
    assert f"unrecognized arguments: {short}" in err


@pytest.mark.parametrize("argv", [["point", "--rat", "1"], ["map", "--torque", "30"]])
def test_the_issue_s_abbreviations(capsys, tmp_path, monkeypatch, argv):
    monkeypatch.chdir(tmp_path)
    code, _, err = run(capsys, *argv)
    assert code == 2 and one_line(err) and "unrecognized arguments" in err


@pytest.mark.parametrize("argv, fragment", [
    (["point", "--clamp", "1e308"], "--clamp: clamp_force = 1e+308 N is out of range"),
    (["limit", "--clamp", "1e308"], "--clamp: clamp_force = 1e+308 N"),
    (["clamp", "--max-pressure", "1e308"], "--max-pressure: max_pressure = 1e+308 Pa"),
    (["point", "--torque", "1e308"], "--torque: output_torque = 1e+308 N m"),
    (["point", "--speed", "1e12"], "--speed: speed = 1e+12 rpm"),
    (["point", "--held-speed=-1e308"], "--held-speed: held_speed = -1e+308 rpm"),
    (["point", "--clamp-law", "cam", "--cam-preload", "1e308"], "--cam-preload"),
    (["map", "--speed", "1e12"], "--speed: speed = 1e+12 rpm"),
    (["map", "--torque-max", "1e308"], "--torque-max"),
    (["table", "--speed-range", "500", "1e308"], "--speed-range"),
    (["cycle", TINY_CYCLE, "--target-speed", "1e308"], "--target-speed"),
    (["traction-curve", "--rx", "0.01", "--ry", "0.02", "--load", "1e308", "--speed", "10",
      "--json"], "--load: load = 1e+308 N"),
    (["traction-curve", "--rx", "1e-308", "--ry", "0.02", "--load", "1e3", "--speed", "10"],
     "--rx: rx = 1e-308 m"),
    (["traction-curve", "--rx", "0.01", "--ry", "0.02", "--pmax", "1e308", "--speed", "10"],
     "--pmax"),
    (["traction-curve", "--rx", "0.01", "--ry", "0.02", "--load", "1e3", "--speed", "1e308"],
     "--speed: speed = 1e+308 m/s"),
])
def test_absurd_values_are_refused_with_flag_unit_and_range(capsys, tmp_path, argv, fragment):
    code, out, err = run(capsys, *argv, "--out", tmp_path / "o") if argv[0] in (
        "map", "table", "cycle") else run(capsys, *argv)
    assert code == 2 and out == "" and one_line(err), err
    assert fragment in err and "allowed" in err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("command", ["fit-fluid", "cycle", "explore"])
def test_a_folder_given_as_the_input_file(capsys, tmp_path, command):
    code, out, err = run(capsys, command, tmp_path, "--out", tmp_path / "o")
    assert code == 2 and one_line(err), err
    assert "is a folder" in err and "internal error" not in err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("address", ["999.999.1.1", "no such host!", "1.2.3", "-x"])
def test_invalid_explore_ui_address_before_any_server(capsys, address):
    code, out, err = run(capsys, "explore-ui", "--address", address)
    assert code == 2 and one_line(err), err
    assert "--address" in err and "internal error" not in err


def _study(tmp_path, old, new):
    text = TINY_STUDY.read_text()
    assert old in text
    path = tmp_path / "study.toml"
    path.write_text(text.replace(old, new))
    return path


@pytest.mark.parametrize("old, new, fragment", [
    ("samples = 8", 'samples = "8"', 'study.samples = "8" is a string'),
    ("samples = 8", "samples = true", "study.samples = true is a boolean"),
    ("max = 0.032", "max = true", "parameters.roller_radius.max = true is a boolean"),
    ("values = [7, 8, 9]", "values = [7, true, 9]", "is a boolean"),
    ("clamp_force = 2000.0", "clamp_force = true", "operating.clamp_force = true"),
    ("input_speed_rpm = [2000.0]", 'input_speed_rpm = ["2000"]', "is a string"),
    ("[operating]", "[fixed]\ntheta2_deg = 145.0\n\n[operating]",
     "[fixed] theta2_deg = 145 is out of range: allowed > 0 and < 90 deg"),
    ("[operating]", "[fixed]\naspect_ratio = 0.0\n\n[operating]", "[fixed] aspect_ratio = 0"),
    ("[operating]", "[fixed]\ncreep_limit = false\n\n[operating]", "creep_limit = false"),
])
def test_silently_wrong_study_values_are_refused_up_front(capsys, tmp_path, old, new,
                                                          fragment):
    path = _study(tmp_path, old, new)
    code, out, err = run(capsys, "explore", path, "--in-process", "--out", tmp_path / "o")
    assert code == 2 and one_line(err), err
    assert fragment in err
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("old, new, fragment", [
    ("n_rollers = 8", "n_rollers = true", "n_rollers = true is a boolean: allowed a number"),
    ("aspect_ratio = 1.7", "aspect_ratio = false", "aspect_ratio = false is a boolean"),
    ("aspect_ratio = 1.7", 'aspect_ratio = "1.7"', 'aspect_ratio = "1.7" is a string'),
])
def test_booleans_and_strings_are_not_numbers_in_a_design(capsys, tmp_path, old, new,
                                                          fragment):
    text = builtin_text()
    assert old in text
    path = tmp_path / "drive.toml"
    path.write_text(text.replace(old, new))
    code, out, err = run(capsys, "design", "show", "--design", path)
    assert code == 2 and one_line(err) and fragment in err, err


def test_a_boolean_in_a_nested_table_names_its_path(capsys, tmp_path):
    text = builtin_text()
    start = text.index("youngs_modulus")
    end = text.index("\n", start)
    path = tmp_path / "drive.toml"
    path.write_text(text[:start] + "youngs_modulus = true" + text[end:])
    code, _, err = run(capsys, "design", "show", "--design", path)
    assert code == 2 and "material.youngs_modulus = true is a boolean" in err, err


def test_a_utf8_bom_is_accepted_in_design_fluid_and_study_files(capsys, tmp_path):
    drive = tmp_path / "drive.toml"
    drive.write_bytes(b"\xef\xbb\xbf" + builtin_text().encode())
    code, out, err = run(capsys, "design", "show", "--design", drive)
    assert code == 0, err
    code, out, err = run(capsys, "limit", "--fluid", drive, "--json")
    assert code == 0, err
    study = tmp_path / "study.toml"
    study.write_bytes(b"\xef\xbb\xbf" + TINY_STUDY.read_bytes())
    from ballcvt.api import read_study

    assert read_study(study).study.samples == 8
