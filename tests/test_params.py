"""Parameter sets: the cited Table I drive, TOML round trip, validation messages."""

import math
import re

import pytest

from ballcvt import Design, Fluid, InputError, OperatingPoint
from ballcvt.params import builtin_text, drive_to_toml, load_builtin, load_drive, parse_drive


def test_table1_values(drive):
    d, f = drive
    # Table I of Tomaselli et al. (2020).
    assert (d.aspect_ratio, d.roller_radius, d.theta0_deg, d.theta2_deg, d.alpha_deg,
            d.n_rollers) == (1.7, 0.03, 45.0, 45.0, 10.0, 8)
    assert (f.viscosity, f.roelands_index, f.pressure_viscosity_coefficient) == (3.25e-3, 0.85,
                                                                                1.71e-8)
    assert (f.limiting_shear_stress, f.limiting_shear_slope, f.pole_pressure,
            f.pole_viscosity) == (0.02e9, 0.085, 1.96e8, 6.31e-5)
    assert math.isinf(d.single_idler_groove_ratio)


def test_builtin_text_is_cited():
    text = builtin_text()
    assert "doi:10.1016/j.mechmachtheory.2020.103877" in text
    assert "CALIBRATED" in text and "ASSUMED" in text


def test_toml_round_trip(drive, tmp_path):
    text = drive_to_toml(*drive)
    assert parse_drive(text) == drive
    path = tmp_path / "d.toml"
    path.write_text(text.replace("n_rollers = 8", "n_rollers = 6"))
    d, _ = load_drive(path)
    assert d.n_rollers == 6


def test_models_are_frozen(drive):
    with pytest.raises(Exception):
        drive[0].aspect_ratio = 2.0


@pytest.mark.parametrize("edit, fragment", [
    (("aspect_ratio = 1.7", "aspect_ratio = -1.7"), "aspect_ratio = -1.7 is out of range"),
    ((r"aspect_ratio = 1.7.*\n", ""), "required key 'aspect_ratio' is missing"),
    (("poisson_ratio = 0.3", "poisson_ratio = 0.6"), "material.poisson_ratio = 0.6"),
    (("viscosity = 3.25e-3", "viscosity = 0.0"), "viscosity = 0"),
    (("n_rollers = 8", "n_rolers = 8"), "unknown key 'n_rolers'"),
    ((r"\[fluid\]", "[fluids]"), "table [fluid] is missing"),
    ((r"\[design\]", "[design"), "not valid TOML"),
])
def test_bad_design_file(drive, edit, fragment):
    text = drive_to_toml(*drive)
    assert re.search(edit[0], text)
    with pytest.raises(InputError) as err:
        parse_drive(re.sub(edit[0], edit[1], text, count=1))
    message = str(err.value)
    assert fragment in message and "\n" not in message


def test_error_names_range(drive):
    with pytest.raises(InputError, match=r"theta0_deg = 95 is out of range: allowed > 0 and < 90"):
        drive[0].replace(theta0_deg=95)


def test_operating_point_validation():
    op = OperatingPoint(ratio=1.0, output_torque=0.0, clamp_force=2e3, input_speed=100.0)
    assert op.input_speed_rpm == pytest.approx(954.93, rel=1e-4)
    with pytest.raises(InputError, match="clamp_force = -1"):
        OperatingPoint(ratio=1.0, output_torque=1.0, clamp_force=-1.0, input_speed=100.0)


def test_unknown_builtin():
    with pytest.raises(InputError, match="drive"):
        load_builtin("nope")


def test_units_recorded():
    assert Design.unit("roller_radius") == "m"
    assert Fluid.unit("viscosity") == "Pa s"
