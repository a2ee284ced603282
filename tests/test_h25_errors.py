"""Issue 25: errors in the user's terms (flags and units typed, unit-mistake hints)."""

import warnings

import pytest

from ballcvt import Variator
from ballcvt.api import load_builtin
from ballcvt.errors import BallCVTError, InputError, UnitHintWarning
from ballcvt.interfaces.cli.main import main

DESIGN, FLUID = load_builtin("table1")


def test_no_equilibrium_names_the_flag_and_rpm(capsys):
    assert main(["limit", "--clamp", "5", "--speed", "2000"]) == 2
    err = capsys.readouterr().err
    assert "--speed 2000 rpm" in err and "--clamp 5 N" in err
    assert "rad/s" not in err


def test_no_equilibrium_keeps_si_units_in_python():
    with pytest.raises(BallCVTError) as got:
        Variator().limit_torque(1.0, clamp_force=5.0, input_speed_rpm=2000)
    assert "input speed 209.44 rad/s" in str(got.value)
    assert "--speed" in got.value.restated({"input_speed": "--speed 2000 rpm"})


def test_integer_field_says_whole_number():
    with pytest.raises(InputError, match=r"n_rollers = 6.5 must be a whole number "
                                         r"\(allowed >= 1 and <= 64\)"):
        DESIGN.replace(n_rollers=6.5)


@pytest.mark.parametrize("field", ["theta0_deg", "theta2_deg"])
def test_radians_in_a_degree_field_are_hinted(field, capsys, tmp_path):
    with pytest.warns(UnitHintWarning, match=f"{field} = 0.785 deg looks like radians: "
                                             "did you mean 45.0 deg"):
        DESIGN.replace(**{field: 0.785})
    toml = (tmp_path / "rad.toml")
    from ballcvt.api import builtin_text
    toml.write_text(builtin_text("table1").replace(f"{field} = 45.0 ", f"{field} = 0.785"))
    main(["limit", "--design", str(toml)])
    assert f"ballcvt: warning: {field} = 0.785 deg looks like radians" in capsys.readouterr().err


@pytest.mark.parametrize("field, value, hint", [
    ("roller_radius", 3.5, "3.5 m ball radius: mm given as m"),
    ("idler_bearing_diameter", 10.0 - 1e-9, "mm given as m"),
])
def test_unit_mistakes_are_refused_with_a_hint(field, value, hint):
    with pytest.raises(InputError, match=hint) as got:
        DESIGN.replace(**{field: value})
    assert got.value.quantity.endswith(field)


def test_plausible_values_pass():
    DESIGN.replace(theta0_deg=30.0, theta2_deg=30.0)
    DESIGN.replace(roller_radius=0.045, roller_bearing_diameter=0.012)


def test_rpm_given_as_rad_s_is_hinted():
    with pytest.warns(UnitHintWarning, match="did you mean input_speed_rpm=2000"):
        Variator().limit_torque(1.0, clamp_force=2000.0, input_speed=2000.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", UnitHintWarning)
        Variator().solve(1.0, 10.0, clamp_force=2000.0, input_speed=209.44)
