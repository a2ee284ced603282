"""The command-line contract: JSON keys, tables, design files, and every bad-input case."""

import json
import math
import subprocess
import sys

import pytest

from ballcvt.interfaces.cli.main import main

DOUBLE = ["input", "idler_a", "idler_b", "output"]
SINGLE = ["input", "idler", "output"]


def run(capsys, *argv):
    try:
        code = main(list(argv))
    except SystemExit as exc:  # argparse's own usage errors
        code = exc.code
    out, err = capsys.readouterr()
    return code, out, err


@pytest.mark.parametrize("arch, names", [("double", DOUBLE), ("single", SINGLE)])
def test_point_json_keys(capsys, arch, names):
    code, out, err = run(capsys, "point", "--arch", arch, "--ratio", "1.5", "--torque", "40",
                         "--clamp", "2000", "--speed", "2000", "--json")
    assert code == 0, err
    data = json.loads(out)
    for key in ("eta", "eta_loss", "eta_speed", "eta_torque", "input_torque", "output_torque",
                "tilt_deg", "actual_ratio", "version", "residual_norm", "converged"):
        assert key in data
    for key in ("creep", "spin", "mu", "chi", "p_max", "film_thickness"):
        assert list(data[key]) == names
        assert all(math.isfinite(v) for v in data[key].values())
    # issue 25: losses holds components and one total; the subtotals sit beside it
    assert {"creep", "spin", "roller_bearings", "idler_bearings", "total"} <= set(data["losses"])
    assert "bearing" not in data["losses"] and "parasitic" not in data["losses"]
    assert data["losses"]["total"] == pytest.approx(
        data["losses"]["creep"] + data["losses"]["spin"] + data["loss_subtotals"]["bearing"])
    assert "NaN" not in out


def test_point_table(capsys):
    code, out, _ = run(capsys, "point")
    assert code == 0
    assert "efficiency" in out and "idler_a" in out and "converged" in out


def test_limit_json(capsys):
    code, out, _ = run(capsys, "limit", "--ratio", "2", "--json")
    assert code == 0
    assert 70 < json.loads(out)["limit_torque"] < 80


def test_design_show_export_and_reload(capsys, tmp_path):
    code, out, _ = run(capsys, "design", "show")
    assert code == 0 and "[design]" in out and "Table I" in out
    path = tmp_path / "mine.toml"
    assert run(capsys, "design", "export", str(path))[0] == 0
    path.write_text(path.read_text().replace("n_rollers = 8", "n_rollers = 6"))
    code, out, _ = run(capsys, "point", "--design", str(path), "--json")
    assert code == 0 and json.loads(out)["design"]["n_rollers"] == 6
    code, out, _ = run(capsys, "design", "show", "--design", str(path))
    assert code == 0 and "n_rollers = 6" in out


BAD = [
    (["point", "--clamp", "-5"], "clamp_force = -5"),
    (["point", "--clamp", "0"], "clamp_force = 0"),
    (["point", "--speed", "0"], "speed = 0"),
    (["point", "--speed", "-100"], "speed = -100"),
    (["point", "--torque", "-1"], "output_torque = -1"),
    (["point", "--ratio", "10"], "ratio = 10"),
    (["point", "--ratio", "nan"], "--ratio: 'nan' is not a finite number"),
    (["point", "--arch", "triple"], "invalid choice: 'triple'"),
    (["point", "--torque", "400"], "exceeds the traction capacity"),
    (["limit", "--creep-limit", "1.5"], "creep_limit = 1.5"),
    (["point", "--design", "/no/such/file.toml"], "cannot be read"),
]


@pytest.mark.parametrize("argv, fragment", BAD)
def test_bad_input_exits_2_with_one_line(capsys, argv, fragment):
    code, out, err = run(capsys, *argv)
    assert code == 2 and out == ""
    assert fragment in err
    assert err.count("\n") == 1 and "Traceback" not in err


def test_capacity_message_gives_limit(capsys):
    code, _, err = run(capsys, "point", "--torque", "400", "--ratio", "1")
    assert code == 2 and "158." in err


@pytest.mark.parametrize("edit, fragment", [
    (("aspect_ratio = 1.7", "aspect_ratio = \"big\""), "aspect_ratio"),
    ((None, "aspect_ratio"), "incomplete"),
    (("[fluid]", "[fluid"), "not valid TOML"),
])
def test_bad_design_file_exits_2(capsys, tmp_path, edit, fragment):
    path = tmp_path / "bad.toml"
    assert run(capsys, "design", "export", str(path))[0] == 0
    text = path.read_text()
    if edit[0] is None:  # drop the whole line of a key
        text = "\n".join(l for l in text.splitlines() if not l.startswith(edit[1]))
    else:
        assert edit[0] in text
        text = text.replace(*edit)
    path.write_text(text)
    code, _, err = run(capsys, "point", "--design", str(path))
    assert code == 2 and fragment in err and err.count("\n") == 1


def test_console_script_entry_point():
    proc = subprocess.run([sys.executable, "-m", "ballcvt.interfaces.cli.main", "point", "--clamp", "-1"],
                          capture_output=True, text=True)
    assert proc.returncode == 2 and proc.stderr.startswith("ballcvt: error: clamp_force")
