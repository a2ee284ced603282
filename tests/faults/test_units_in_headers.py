"""Issue 24: the units in the headers of the files ballcvt reads are converted to SI, or
refused by name when unknown (the curves of ``fit-fluid`` and duty cycles). Before, a
``load [kN]`` column of a curves file was read as newtons (a limiting shear stress of
0.28 Pa instead of 2e7 Pa) and a cycle's ``output_torque [kN m]`` was refused."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from test_cli_support import DATA, one_line, run

from ballcvt.api import read_curves, read_cycle
from ballcvt.errors import InputError
from ballcvt.units import QUANTITY_UNITS, convert, parse_header, unit_factor

CURVES = DATA / "tiny_curves.csv"


def _rescaled(tmp_path, renames: dict, scale: dict):
    """The tiny curves file with some columns in other units."""
    import pandas as pd

    frame = pd.read_csv(CURVES, comment="#")
    for old, new in renames.items():
        frame[old] = frame[old] * scale[old]
        frame = frame.rename(columns={old: new})
    path = tmp_path / "curves.csv"
    frame.to_csv(path, index=False)
    return path


def test_curves_in_other_units_read_as_the_same_points(tmp_path):
    base = read_curves(CURVES)
    path = _rescaled(
        tmp_path,
        {"load [N]": "load [kN]", "rx [m]": "rx [mm]", "ry [m]": "ry [um]",
         "speed [m/s]": "speed [mm/s]"},
        {"load [N]": 1e-3, "rx [m]": 1e3, "ry [m]": 1e6, "speed [m/s]": 1e3},
    )
    other = read_curves(path)
    for name in ("load", "rx", "ry", "speed", "creep", "mu", "spin"):
        np.testing.assert_allclose(getattr(other, name), getattr(base, name), rtol=1e-12)


def test_fit_fluid_with_a_load_in_kN_finds_the_same_fluid(tmp_path, capsys):
    path = _rescaled(tmp_path, {"load [N]": "load [kN]"}, {"load [N]": 1e-3})
    code, _, err = run(capsys, "fit-fluid", path, "--out", tmp_path / "kN", "--json")
    assert code == 0, err
    code, _, err = run(capsys, "fit-fluid", CURVES, "--out", tmp_path / "N", "--json")
    assert code == 0, err
    kn = json.loads((tmp_path / "kN" / "fit.json").read_text())["estimates"]
    n = json.loads((tmp_path / "N" / "fit.json").read_text())["estimates"]
    assert kn["limiting_shear_stress"] > 1e6  # 0.28 Pa when kN was read as N
    assert math.isclose(kn["limiting_shear_stress"], n["limiting_shear_stress"], rel_tol=1e-6)


@pytest.mark.parametrize("header, column, unit", [
    ("load [lbf]", "load [lbf]", "lbf"),
    ("speed [mph]", "speed [mph]", "mph"),
    ("rx [inch]", "rx [inch]", "inch"),
    ("mu [%]", "mu [%]", "%"),
])
def test_curves_with_an_unknown_unit_are_refused_by_name(tmp_path, capsys, header, column,
                                                         unit):
    lines = CURVES.read_text().splitlines()
    name = header.split(" [")[0]
    head = [header if parse_header(h)[0] == name else h for h in lines[1].split(",")]
    path = tmp_path / "curves.csv"
    path.write_text("\n".join([",".join(head), *lines[2:]]) + "\n")
    with pytest.raises(InputError) as err:
        read_curves(path)
    msg = str(err.value)
    assert f"'{column}'" in msg and f"[{unit}]" in msg and "allowed" in msg
    code, _, out = run(capsys, "fit-fluid", path, "--out", tmp_path / "out")
    assert code == 2 and one_line(out) and unit in out


def test_cycles_in_other_units_read_as_the_same_cycle(tmp_path):
    si = tmp_path / "si.csv"
    si.write_text("time [s],output_speed [rad/s],output_torque [N m]\n0,20,12\n60,25,14\n")
    other = tmp_path / "other.csv"
    other.write_text("time [min],output_speed [rpm],output_torque [kN m]\n"
                     f"0,{20 * 30 / math.pi!r},0.012\n1,{25 * 30 / math.pi!r},0.014\n")
    a, b = read_cycle(si), read_cycle(other)
    for name in ("time", "output_speed", "output_torque"):
        np.testing.assert_allclose(getattr(b, name), getattr(a, name), rtol=1e-12)
    power = tmp_path / "power.csv"
    power.write_text("time [ms],input_speed [rpm],input_power [MW]\n0,1000,0.001\n500,1000,0.002\n")
    c = read_cycle(power)
    np.testing.assert_allclose(c.time, [0.0, 0.5])
    np.testing.assert_allclose(c.input_power, [1e3, 2e3])


def test_a_cycle_with_an_unknown_unit_is_refused_by_name(tmp_path):
    path = tmp_path / "cycle.csv"
    path.write_text("time [s],output_speed [rpm],output_torque [lbf ft]\n0,100,10\n")
    with pytest.raises(InputError) as err:
        read_cycle(path)
    msg = str(err.value)
    assert "'output_torque [lbf ft]'" in msg and "[lbf ft]" in msg and "N m" in msg


def test_the_converter():
    assert parse_header(" load [kN] ") == ("load", "kN")
    assert parse_header("spin") == ("spin", None)
    assert parse_header("spin []") == ("spin", "")
    cases = [("kN", "force", 1e3), ("MPa", "pressure", 1e6), ("GPa", "pressure", 1e9),
             ("mm", "length", 1e-3), ("um", "length", 1e-6), ("µm", "length", 1e-6),
             ("km/h", "speed", 1 / 3.6), ("N mm", "torque", 1e-3), ("kNm", "torque", 1e3),
             ("N·m", "torque", 1.0), ("kW", "power", 1e3), ("ms", "time", 1e-3),
             ("min", "time", 60.0), ("rpm", "angular_speed", math.pi / 30),
             ("deg", "angle", math.pi / 180), ("-", "dimensionless", 1.0)]
    for unit, quantity, factor in cases:
        assert math.isclose(unit_factor(unit, quantity), factor, rel_tol=1e-15), unit
    assert unit_factor("N  m", "torque") == 1.0  # spaces normalised
    np.testing.assert_allclose(convert(np.array([1.0, 2.0]), "kN", "force"), [1e3, 2e3])
    for quantity in QUANTITY_UNITS:
        with pytest.raises(InputError, match="column 'x \\[furlong\\]': unit \\[furlong\\]"):
            unit_factor("furlong", quantity, "x [furlong]")
