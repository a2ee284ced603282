"""Issue 25, the drive file: parameters that depend on the geometry are checked against it,
the cam is sized for the drive, the drive file says where the drive runs, and
``design export`` takes its options in any order."""

import argparse
import json

import pytest

from ballcvt import Variator, load_builtin
from ballcvt.api import (
    builtin_text,
    drive_to_toml,
    drive_warnings,
    operating_ratio_range,
    size_cam,
    with_oil_temperature,
)
from ballcvt.errors import InputError
from ballcvt.interfaces.cli import options
from ballcvt.interfaces.cli.main import build_parser, main
from ballcvt.params import parse_drive


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture(scope="module")
def hub():
    return load_builtin("hub")


def enlarged(hub, disc_radius=0.125):
    """The hub with 35 mm balls: disc contacts at 0.119 m."""
    d, _ = hub
    return d.replace(roller_radius=0.035, parasitic=d.parasitic.replace(disc_radius=disc_radius))


# -- 1. dependent parameters against the geometry ------------------------------------------


@pytest.mark.parametrize("disc_radius", [0.115, 0.05])
def test_disc_radius_inside_the_contacts_is_refused_in_one_line(hub, disc_radius):
    with pytest.raises(InputError) as err:
        enlarged(hub, disc_radius)
    text = str(err.value)
    assert "parasitic.disc_radius" in text and f"{disc_radius:g}" in text
    assert "0.1192 m" in text and ">= 0.1202 m" in text and "\n" not in text


def test_enlarged_hub_file_is_refused(hub):
    text = builtin_text("hub").replace("roller_radius = 0.03 ", "roller_radius = 0.035 ")
    with pytest.raises(InputError, match=r"parasitic\.disc_radius = 0\.115.*>= 0\.1202 m"):
        parse_drive(text)


@pytest.mark.parametrize(
    "table, change, field",
    [
        ("parasitic", {"seal_diameter": 0.3}, "parasitic.seal_diameter"),
        ("parasitic", {"disc_bearing_diameter": 0.25}, "parasitic.disc_bearing_diameter"),
        ("cam", {"mean_radius": 0.2}, "cam.mean_radius"),
    ],
)
def test_seals_bearings_and_cam_must_fit_the_discs(hub, table, change, field):
    d, _ = hub
    with pytest.raises(InputError, match=field.replace(".", r"\.") + r" = .* allowed [<>]"):
        d.replace(**{table: getattr(d, table).replace(**change)})


def test_table1_loads_unchanged():
    d, f = load_builtin("table1")
    assert d.operating is None and "operating" not in d.model_dump()
    assert drive_to_toml(d, f) == builtin_text("table1")
    assert "[operating]" not in builtin_text("table1")


def test_a_cam_for_another_design_is_a_warning_naming_the_fix(hub):
    d, f = hub
    assert drive_warnings(Variator(d, f)) == []
    weak = d.replace(cam=d.cam.replace(preload=20.0))  # holds no load below a few N m
    (line,) = drive_warnings(Variator(weak, f))
    assert "[design.cam]" in line and "size-cam" in line and "0 to 100 N m" in line


def test_table1_shows_without_warnings(capsys):
    code, out, err = run(capsys, "design", "show")
    assert code == 0 and out.rstrip("\n") == builtin_text("table1").rstrip("\n") and err == ""


def test_a_disc_far_beyond_its_track_is_a_warning(hub):
    d, f = hub
    big = d.replace(parasitic=d.parasitic.replace(disc_radius=0.3))
    (line,) = drive_warnings(Variator(big, f), cam=False)
    assert "disc_radius = 0.3" in line and "set it to about" in line


def test_operating_ratio_range_beyond_the_usable_range_is_refused(hub):
    text = builtin_text("hub").replace("ratio_range = [0.5, 1.9]", "ratio_range = [0.1, 1.9]")
    d, f = parse_drive(text)
    with pytest.raises(InputError, match=r"operating\.ratio_range .*within the usable range"):
        Variator(d, f)


def test_operating_table_is_checked():
    text = builtin_text("hub")
    for old, new, field in [
        ("ratio_range = [0.5, 1.9]", "ratio_range = [1.9, 0.5]", "ratio_range"),
        ("input_speed_rpm = 150.0", "input_speed_rpm = 500.0", "input_speed_rpm"),
        ("rated_torque = 100.0", "rated_torque = -1.0", "rated_torque"),
        ("clamp_law = \"cam\"", "clamp_lew = \"cam\"", "clamp_lew"),
    ]:
        with pytest.raises(InputError, match=field):
            parse_drive(text.replace(old, new))


# -- 2. cam sizing -----------------------------------------------------------------------------


def test_sized_cam_on_the_enlarged_hub_carries_from_zero_over_the_ratio_range(hub):
    _, f = hub
    v = Variator(enlarged(hub), f)
    sized = size_cam(v, margin=1.2)
    assert sized.rated_torque == 100.0 and sized.design.cam == sized.cam
    s = with_oil_temperature(Variator(sized.design, f), "fixed")  # the basis it is sized on
    lo, hi = operating_ratio_range(s.design)
    for ratio in (lo, 0.8, 1.2, hi):
        cap = s.capacity(ratio, clamp_law="cam", input_speed_rpm=150.0)
        assert cap.intervals[0][0] == 0.0 and cap.intervals[0][1] >= 100.0, (ratio, cap)
    assert drive_warnings(s) == []


def test_size_cam_needs_a_cam():
    with pytest.raises(InputError, match="design.cam"):
        size_cam(Variator(Variator().design.replace(cam=None)))


def test_size_cam_without_operating_context_sizes_for_the_constant_clamp_capacity():
    v = Variator()  # Table I: its cam, the usable ratio range, the paper's 2000 N and speed
    sized = size_cam(v)
    assert sized.ratios[0] == pytest.approx(v.ratio_range[0])
    assert sized.rated_torque == pytest.approx(
        min(
            v.limit_torque(r, clamp_force=2000.0, input_speed_rpm=2000, creep_limit=0.1 / 1.2)
            for r in sized.ratios
        )
    )
    s = Variator(sized.design, v.fluid)
    for ratio in sized.ratios:
        cap = s.capacity(ratio, clamp_law="cam", input_speed_rpm=2000, creep_limit=0.1 / 1.2)
        assert cap.intervals[0][0] == 0.0 and cap.intervals[0][1] >= sized.rated_torque


def test_cli_size_cam_writes_a_drive_with_the_sized_cam(capsys, tmp_path):
    path = tmp_path / "sized.toml"
    code, out, err = run(capsys, "design", "size-cam", "--design", "hub", "--out", str(path))
    assert code == 0 and out == "" and "sized [design.cam] preload" in err
    d, _ = parse_drive(path.read_text())
    assert (d.cam.preload, d.cam.ramp_angle_deg) != (1000.0, 6.0)
    assert d.operating == load_builtin("hub")[0].operating
    code, out, _ = run(capsys, "design", "size-cam", "--design", "hub", "--margin", "1.5")
    assert code == 0 and "[design.cam]" in out


# -- 3. operating context ------------------------------------------------------------------------


def parsed(*argv):
    args = build_parser().parse_args(list(argv))
    options.apply_operating(args, list(argv))
    return args


def test_hub_commands_start_where_the_hub_runs():
    a = parsed("point", "--design", "hub")
    assert (a.speed, a.clamp_law, a.ratio) == (150.0, "cam", 1.0)
    a = parsed("table", "--design", "hub")
    assert a.speed_range == (90.0, 200.0) and a.ratio_range == (0.5, 1.9)
    a = parsed("cycle", "x.csv", "--design", "hub")
    assert a.ratio_range == (0.5, 1.9) and a.clamp_law == "cam" and a.operating_target_speed == 150.0
    a = parsed("map", "--design", "hub")
    assert a.speed == 150.0 and a.ratio_range == (0.5, 1.9)


def test_single_contact_commands_keep_their_own_speed():
    a = argparse.Namespace(command="traction-curve", design="hub", speed=5.0)  # [m/s]
    options.apply_operating(a, [])
    assert a.speed == 5.0


def test_typed_flags_win():
    a = parsed("point", "--design", "hub", "--speed", "2000", "--clamp-law", "constant")
    assert (a.speed, a.clamp_law, a.clamp) == (2000.0, "constant", 2000.0)
    a = parsed("point", "--speed=300", "--design", "hub", "--clamp", "1500")
    assert (a.speed, a.clamp_law, a.clamp) == (300.0, "constant", 1500.0)
    a = parsed("table", "--design", "hub", "--speed-range", "500", "4000")
    assert a.speed_range == [500.0, 4000.0]


def test_table1_keeps_the_papers_defaults():
    for design in ([], ["--design", "table1"]):
        a = parsed("point", *design)
        assert (a.speed, a.clamp_law, a.clamp) == (2000.0, "constant", None)
        assert parsed("table", *design).speed_range == (500.0, 4000.0)


def test_point_on_the_hub_runs_at_its_speed_with_its_cam(capsys):
    code, out, _ = run(capsys, "point", "--design", "hub", "--json")
    r = json.loads(out)
    assert code == 0 and r["input_speed_rpm"] == 150.0 and r["clamp_law"] == "cam"


def test_explorer_opens_at_the_drives_operating_context(hub):
    from ballcvt.interfaces.ui.app import _State

    s = _State(*hub, "double")
    assert s.values["input_speed_rpm"] == 150.0 and s.clamp_law == "cam"
    assert s.slider_range("input_speed_rpm")[0] <= 150.0 <= s.slider_range("input_speed_rpm")[1]
    assert s.slider_range("ratio")[:2] == (0.5, 1.9)
    s.rebuild()
    assert s.point()["eta"] is not None and s.point()["clamp_law"] == "cam"
    s.clamp_law = "constant"
    assert s.clamp() == {"clamp_force": 2000.0}
    paper = _State(*load_builtin("table1"), "double")
    assert paper.values["input_speed_rpm"] == 2000.0 and paper.clamp_law == "constant"


# -- 4. design export in every order ---------------------------------------------------------------


@pytest.mark.parametrize(
    "order",
    [
        ("design", "export", "--design", "hub", "{}"),
        ("design", "--design", "hub", "export", "{}"),
        ("design", "export", "{}", "--design", "hub"),
    ],
)
def test_design_export_takes_options_in_any_order(capsys, tmp_path, order):
    path = tmp_path / "hub.toml"
    code, _, err = run(capsys, *(w.format(path) for w in order))
    assert code == 0, err
    assert path.read_text() == builtin_text("hub")


def test_design_show_warns_about_a_disc_far_beyond_its_track(capsys, tmp_path):
    path = tmp_path / "big.toml"
    path.write_text(builtin_text("hub").replace("disc_radius = 0.115", "disc_radius = 0.3"))
    code, out, err = run(capsys, "design", "show", "--design", str(path))
    assert code == 0 and "disc_radius = 0.3" in out
    assert err.startswith("ballcvt: warning: [design.parasitic] disc_radius = 0.3 m")
