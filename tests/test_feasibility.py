"""Feasibility bounds (docs/model.md §10, Eqs. F1-F6) and validity warnings."""

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from ballcvt import InputError, Variator, load_builtin
from ballcvt.params.feasibility import max_rollers
from ballcvt.params.io import builtin_text, parse_drive

DESIGN, FLUID = load_builtin()


def test_largest_number_of_balls_by_hand():
    # Table I: centres on a circle of 2.7 r_S; sin(pi/8) = 0.3827 >= 1.0167/2.7 = 0.3765
    # but sin(pi/9) = 0.3420 < 0.3765
    assert max_rollers(1.7, 0.03, 0.001) == 8
    assert max_rollers(0.2, 0.03, 0.001) == 3          # the example
    assert max_rollers(1.7, 0.03, 0.0) == 8
    assert max_rollers(3.0, 0.03, 0.0) == 12            # sin(pi/12) = 0.2588 >= 1/4
    assert DESIGN.replace(n_rollers=8).n_rollers == 8
    with pytest.raises(InputError, match=r"n_rollers = 9 is out of range: allowed <= 8"):
        DESIGN.replace(n_rollers=9)
    with pytest.raises(InputError, match=r"n_rollers = 4 .* allowed <= 3"):
        DESIGN.replace(aspect_ratio=0.2, n_rollers=4)
    with pytest.raises(InputError, match=r"n_rollers = 2 .* >= 3"):
        DESIGN.replace(n_rollers=2)


def test_ball_gap_bound_on_each_side():
    gap = 2 * 0.03 * 2.7 * math.sin(math.pi / 8) - 0.06      # 1.99 mm between 8 balls
    assert DESIGN.replace(min_roller_gap=gap * (1 - 1e-9)).n_rollers == 8
    with pytest.raises(InputError, match="n_rollers = 8"):
        DESIGN.replace(min_roller_gap=gap * (1 + 1e-6))


def test_disc_contacts_apart():
    need = math.degrees(math.asin(0.001 / 0.06))                # 2 r_S sin(theta) >= g
    assert DESIGN.replace(theta0_deg=need * 1.01, theta2_deg=need * 1.01)
    with pytest.raises(InputError, match="theta0_deg"):
        DESIGN.replace(theta0_deg=need * 0.99, theta2_deg=need * 0.99)


def test_axle_bearing_inside_the_ball():
    assert DESIGN.replace(roller_bearing_diameter=0.0599)
    with pytest.raises(InputError, match=r"roller_bearing_diameter = 0.06 .* < 2 r_S"):
        DESIGN.replace(roller_bearing_diameter=0.06)


def test_idler_rolling_radius_keeps_its_sign():
    # usable tilt +-0.8 x 45 deg = +-36 deg: alpha < 90 - 36 = 54 deg (double idler only)
    ok, bad = DESIGN.replace(alpha_deg=53.9), DESIGN.replace(alpha_deg=54.1)
    assert Variator(ok, FLUID, "double")
    with pytest.raises(InputError, match=r"alpha_deg = 54.1 .* < 54 deg"):
        Variator(bad, FLUID, "double")
    assert Variator(bad, FLUID, "single")                        # the single idler has no alpha


def test_two_idlers_need_an_angle():
    need = math.degrees(math.asin(0.001 / 0.06))
    with pytest.raises(InputError, match="alpha_deg = 0 .* for two idlers"):
        Variator(DESIGN.replace(alpha_deg=0.0), FLUID, "double")
    assert Variator(DESIGN.replace(alpha_deg=need * 1.01), FLUID, "double")
    assert Variator(DESIGN.replace(alpha_deg=0.0), FLUID, "single")


def test_idler_bearing_inside_the_idler():
    # double: 2 r_S (1 + k - cos 10 deg) = 0.10291 m; single: 2 k r_S = 0.102 m
    d = DESIGN.replace(idler_bearing_diameter=0.1025)
    assert Variator(d, FLUID, "double")
    with pytest.raises(InputError, match="idler_bearing_diameter = 0.1025 .* single idler"):
        Variator(d, FLUID, "single")
    with pytest.raises(InputError, match="idler_bearing_diameter"):
        Variator(DESIGN.replace(idler_bearing_diameter=0.103), FLUID, "double")


def test_infeasible_design_file_is_refused_on_load():
    text = builtin_text().replace("n_rollers = 8 ", "n_rollers = 10")
    with pytest.raises(InputError, match="n_rollers = 10 is out of range: allowed <= 8"):
        parse_drive(text)


def test_edited_design_says_so():
    assert DESIGN.replace(n_rollers=6).name.endswith("(edited: n_rollers)")
    assert DESIGN.replace(n_rollers=6).replace(aspect_ratio=1.8).name.endswith(
        "(edited: aspect_ratio)")
    assert DESIGN.replace(n_rollers=8).name == DESIGN.name            # nothing changed
    assert DESIGN.replace(n_rollers=6, name="mine").name == "mine"


def test_ratio_outside_the_tilt_range_is_refused(double):
    lo, hi = double.ratio_range
    with pytest.raises(InputError, match="ratio"):
        double.solve(ratio=hi * 1.01, output_torque=1.0, clamp_force=2000.0,
                     input_speed_rpm=2000)


def test_extreme_clamps_end_cleanly(double):
    from ballcvt.errors import NoEquilibriumError
    with pytest.raises(InputError, match=r"clamp_force = 1e\+09 .* Roelands"):
        double.solve(ratio=1.0, output_torque=40.0, clamp_force=1e9, input_speed_rpm=2000)
    with pytest.raises(NoEquilibriumError, match="raise clamp_force"):
        double.solve(ratio=1.0, output_torque=40.0, clamp_force=1e-3, input_speed_rpm=2000)
    with pytest.raises(NoEquilibriumError, match="already exceeds creep_limit"):
        double.solve(ratio=1.0, output_torque=40.0, clamp_force=1e8, input_speed_rpm=2000)


# --- validity warnings: present exactly where their condition holds -----------------------

def test_paper_point_has_no_warning(double):
    r = double.solve(ratio=1.0, output_torque=40.0, clamp_force=2000.0, input_speed_rpm=2000)
    assert r.warnings == ()
    assert min(c.lambda_ratio for c in r.contacts.values()) > 3


def _conditions(v, r):
    return {
        "mixed_lubrication": min(c.lambda_ratio for c in r.contacts.values()) < 3,
        "pressure_above_limit": max(c.p_max for c in r.contacts.values())
        > v.design.max_pressure,
        "large_contact": max(max(c.semi_axis_x, c.semi_axis_y) for c in r.contacts.values())
        > 0.1 * v.design.roller_radius,
    }


@given(clamp=st.floats(200.0, 3e5), rpm=st.floats(5.0, 8000.0), frac=st.floats(0.0, 0.8))
def test_warnings_exactly_where_their_condition_holds(double, clamp, rpm, frac):
    try:
        limit = double.limit_torque(ratio=1.0, clamp_force=clamp, input_speed_rpm=rpm)
    except Exception:
        return
    r = double.solve(ratio=1.0, output_torque=frac * limit, clamp_force=clamp,
                     input_speed_rpm=rpm)
    kinds = {w.split(":")[0] for w in r.warnings}
    for name, holds in _conditions(double, r).items():
        assert (name in kinds) == holds, (name, r.warnings)


def test_speed_warning_on_each_side():
    op = dict(ratio=1.0, output_torque=40.0, clamp_force=2000.0, input_speed_rpm=2000)
    slow = Variator(DESIGN, FLUID.replace(max_rolling_speed=10.0)).solve(**op)
    fast = Variator(DESIGN, FLUID.replace(max_rolling_speed=100.0)).solve(**op)
    assert any(w.startswith("speed_beyond_fluid_data") for w in slow.warnings)
    assert fast.warnings == ()


def test_sweep_flags_match_results(double):
    ds = double.sweep(ratio=1.0, output_torque=[10.0, 40.0], clamp_force=[2000.0, 2e5],
                      input_speed_rpm=[100.0, 2000.0], progress=False)
    for f in (2000.0, 2e5):
        for rpm in (100.0, 2000.0):
            for t in (10.0, 40.0):
                r = double.solve(ratio=1.0, output_torque=t, clamp_force=f, input_speed_rpm=rpm)
                flags = int(ds.warnings.sel(clamp_force=f, input_speed_rpm=rpm,
                                            output_torque=t).squeeze())
                names = [n for n, b in zip(ds.warnings.attrs["flag_meanings"].split(),
                                           ds.warnings.attrs["flag_masks"]) if flags & b]
                assert names == [w.split(":")[0] for w in r.warnings]
