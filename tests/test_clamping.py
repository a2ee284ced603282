"""Clamping laws (docs/model.md §11): the constant law is the paper's, the cam's force is
its closed form, an input-disc cam is solved with the equilibrium, and every path (point,
limit, sweep, CLI) agrees."""

import dataclasses
import json
import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from ballcvt import InputError, TractionLimitError, Variator, load_builtin
from ballcvt.interfaces.cli import main as cli
from ballcvt.model.clamping import CamClamp, ConstantClamp, axial_force
from ballcvt.params import drive_to_toml, parse_drive

RPM = 2000.0


@pytest.fixture(scope="module")
def v():
    return Variator()


@pytest.fixture(scope="module")
def cam(v):
    return CamClamp.from_design(v.design)


def test_constant_law_is_the_paper_path(v):
    a = v.solve(1.0, 40.0, clamp_force=2000.0, input_speed_rpm=RPM)
    b = v.solve(1.0, 40.0, clamp_law=ConstantClamp(2000.0), input_speed_rpm=RPM)
    c = v.solve(1.0, 40.0, clamp_law="constant", clamp_force=2000.0, input_speed_rpm=RPM)
    assert a.eta == b.eta == c.eta and a.clamp_law == "constant"
    assert a.axial_force == pytest.approx(8 * 2000.0 * math.sin(math.radians(45.0)), rel=1e-15)


def test_cam_force_closed_form(v, cam):
    # F_ax = F_pre + T / (r_m tan(phi + atan(mu))): Table I cam, by hand
    t2 = 60.0
    by_hand = 1000.0 + t2 / (0.05 * math.tan(math.radians(6.0) + math.atan(0.005)))
    r = v.solve(1.0, t2, clamp_law="cam", input_speed_rpm=RPM)
    assert r.axial_force == pytest.approx(by_hand, rel=1e-12)
    assert r.clamp_force == pytest.approx(by_hand / (8 * math.sin(math.radians(45))), rel=1e-12)
    assert r.clamp_law == "cam"
    # the cam result is the constant-law result at the cam's force
    ref = v.solve(1.0, t2, clamp_force=r.clamp_force, input_speed_rpm=RPM)
    assert r.eta == pytest.approx(ref.eta, abs=1e-12)


def test_input_cam_is_part_of_the_equilibrium(v, cam):
    law = dataclasses.replace(cam, disc="input")
    r = v.solve(1.0, 40.0, clamp_law=law, input_speed_rpm=RPM)
    # the clamping equation holds at the solution, with the solved input torque
    assert r.clamp_force == pytest.approx(law.clamp_force(v.design, r.input_torque, 40.0),
                                          rel=1e-10)
    # and it is not the output-cam guess (T_0 > tau T_2: the losses)
    assert r.clamp_force > law.clamp_force(v.design, 40.0, 40.0)


@settings(max_examples=8, deadline=None)
@given(ratio=st.floats(0.5, 2.0), torque=st.floats(1.0, 60.0),
       angle=st.floats(4.0, 12.0), preload=st.floats(200.0, 4000.0))
# issue 23: a 200 N preload at 8-11 deg admits 5-10 N m upwards (and, below 10.5 deg, a
# sliver near zero): 1 N m lies between, a TractionLimitError, never NoEquilibriumError
@example(ratio=1.0, torque=1.0, angle=8.0, preload=200.0)
@example(ratio=1.0, torque=1.0, angle=10.5, preload=200.0)
@example(ratio=1.0, torque=1.0, angle=11.0, preload=200.0)
@example(ratio=0.5, torque=1.0, angle=4.0, preload=2374.0)  # eta 0.58: 1.1e-9 apart
def test_input_cam_fixed_point_holds(ratio, torque, angle, preload):
    v = Variator()
    law = CamClamp(preload, math.radians(angle), 0.05, 0.005, disc="input")
    try:
        r = v.solve(ratio, torque, clamp_law=law, input_speed_rpm=RPM)
    except TractionLimitError:
        return
    assert r.converged
    assert abs(r.clamp_force - law.clamp_force(v.design, r.input_torque, torque)) <= \
        1e-10 * r.clamp_force
    # Eq. 38 = Eq. 39 to the power the equilibrium residual leaves unbalanced (a light
    # torque under a heavy preload has little input power: a fixed 1e-9 is not a bound)
    speeds = abs(r.roller_speed) + sum(abs(c.body_speed) for c in r.contacts.values())
    slack = v.design.n_rollers * r.clamp_force * v.design.roller_radius * r.residual_norm
    assert abs(r.eta - r.eta_loss) <= 1e-12 + 2.0 * slack * speeds / r.input_power
    assert r.eta == pytest.approx(r.eta_loss, abs=1e-8)


def test_cam_force_rises_with_torque_and_efficiency_beats_overclamping(v):
    forces = [v.solve(1.0, t, clamp_law="cam", input_speed_rpm=RPM).clamp_force
              for t in (5.0, 20.0, 40.0)]
    assert forces == sorted(forces)
    # at light load the cam clamps far less than the rig's 2 kN: less spin loss
    cam = v.solve(1.0, 5.0, clamp_law="cam", input_speed_rpm=RPM)
    rig = v.solve(1.0, 5.0, clamp_force=2000.0, input_speed_rpm=RPM)
    assert cam.eta > rig.eta


def test_cam_capacity_is_creep_or_pressure_bound(v):
    lim = v.limit_torque(1.0, clamp_law="cam", input_speed_rpm=RPM)
    # just below: admissible, peak pressure within max_pressure
    r = v.solve(1.0, 0.999 * lim, clamp_law="cam", input_speed_rpm=RPM)
    assert max(c.p_max for c in r.contacts.values()) <= v.design.max_pressure * (1 + 1e-9)
    assert max(abs(c.creep) for c in r.contacts.values()) <= v.design.creep_limit
    with pytest.raises(TractionLimitError):
        v.solve(1.0, 1.01 * lim, clamp_law="cam", input_speed_rpm=RPM)
    # a steep ramp (little thrust per torque) makes the creep limit bind first
    weak = CamClamp(500.0, math.radians(30.0), 0.05, 0.005)
    lim_w = v.limit_torque(1.0, clamp_law=weak, input_speed_rpm=RPM)
    assert lim_w < lim
    r = v.solve(1.0, 0.999 * lim_w, clamp_law=weak, input_speed_rpm=RPM)
    assert max(abs(c.creep) for c in r.contacts.values()) > 0.5 * v.design.creep_limit


def test_optimal_law_equals_the_optimiser(v):
    opt = v.optimal_clamp_force(1.0, 60.0, input_speed_rpm=RPM)
    r = v.solve(1.0, 60.0, clamp_law="optimal", input_speed_rpm=RPM)
    assert r.clamp_force == pytest.approx(opt.clamp_force) and r.clamp_law == "optimal"
    # no constant force does better
    for f in (0.8 * opt.clamp_force, 1.25 * opt.clamp_force, 2000.0):
        try:
            other = v.solve(1.0, 60.0, clamp_force=f, input_speed_rpm=RPM)
        except TractionLimitError:
            continue
        assert other.eta <= r.eta + 1e-6


def test_sweep_under_cam_law_equals_points(v):
    ds = v.sweep(ratio=[0.6, 1.4], output_torque=[10.0, 50.0, 500.0], clamp_law="cam",
                 input_speed_rpm=RPM)
    assert "clamp_force" not in ds.dims and ds.attrs["clamp_law"] == "cam"
    assert ds.clamp_force.attrs["units"] == "N"
    for ratio in (0.6, 1.4):
        one = ds.sel(ratio=ratio).squeeze()
        for k, t in enumerate((10.0, 50.0)):
            r = v.solve(ratio, t, clamp_law="cam", input_speed_rpm=RPM)
            assert float(one.eta[k]) == pytest.approx(r.eta, abs=1e-9)
            assert float(one.clamp_force[k]) == pytest.approx(r.clamp_force, rel=1e-12)
            assert float(one.axial_force[k]) == pytest.approx(r.axial_force, rel=1e-12)
        assert int(one.status[2]) == 1                   # 500 N m: beyond the capacity
        assert float(one.limit_torque) == pytest.approx(
            v.limit_torque(ratio, clamp_law="cam", input_speed_rpm=RPM), rel=1e-12)


def test_axial_force_in_constant_sweeps(v):
    ds = v.sweep(ratio=1.0, output_torque=[20.0], clamp_force=[1000.0, 2000.0],
                 input_speed_rpm=RPM)
    expected = axial_force(v.design, ds.clamp_force.values)
    assert np.allclose(ds.axial_force.squeeze().values, expected, rtol=1e-14)


def test_law_errors_are_one_line(v):
    with pytest.raises(InputError, match="clamp_force"):
        v.solve(1.0, 40.0, input_speed_rpm=RPM)                        # neither
    with pytest.raises(InputError, match="not given with clamp_law"):
        v.solve(1.0, 40.0, clamp_force=2000.0, clamp_law="cam", input_speed_rpm=RPM)
    with pytest.raises(InputError, match="one of: constant, cam, optimal"):
        v.solve(1.0, 40.0, clamp_law="spring", input_speed_rpm=RPM)
    bare = Variator(design=v.design.replace(cam=None))
    with pytest.raises(InputError, match=r"\[design.cam\]"):
        bare.solve(1.0, 40.0, clamp_law="cam", input_speed_rpm=RPM)
    with pytest.raises(InputError, match="cam.disc"):
        CamClamp(1.0, 0.1, 0.05, 0.0, disc="both")
    with pytest.raises(InputError, match="cam.preload"):
        v.design.replace(cam={**v.design.cam.model_dump(), "preload": 0.0})


def test_cam_table_round_trips_and_is_optional():
    design, fluid = load_builtin()
    text = drive_to_toml(design, fluid)
    assert parse_drive(text) == (design, fluid)
    no_cam = design.replace(cam=None)
    text = drive_to_toml(no_cam, fluid)
    assert "[design.cam]" not in text
    assert parse_drive(text)[0].cam is None


def test_cli_clamp_law(capsys):
    assert cli.main(["point", "--clamp-law", "cam", "--torque", "60", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["clamp_law"] == "cam"
    assert data["axial_force"] == pytest.approx(
        data["clamp_force"] * 8 * math.sin(math.radians(45.0)), rel=1e-12)
    for argv, text in ((["point", "--clamp-law", "cam", "--clamp", "100"], "--clamp"),
                       (["point", "--cam-angle", "5"], "--cam-angle needs --clamp-law cam"),
                       (["point", "--clamp-law", "cam", "--cam-angle", "70"], "ramp_angle_deg")):
        assert cli.main(argv) == 2
        err = capsys.readouterr().err.strip()
        assert text in err and "\n" not in err


def test_cam_force_without_friction_is_preload_plus_torque_over_r_tan(v):
    # friction off: F_ax = F_pre + T / (r_m tan(phi)) at the solution (issue 9)
    law = CamClamp(800.0, math.radians(8.0), 0.04, 0.0, disc="input")
    r = v.solve(1.3, 30.0, clamp_law=law, input_speed_rpm=RPM)
    expected = 800.0 + r.input_torque / (0.04 * math.tan(math.radians(8.0)))
    assert r.axial_force == pytest.approx(expected, rel=1e-10)


def test_cam_between_constant_and_optimal_at_light_load(v):
    for torque in (5.0, 10.0, 20.0):
        cam = v.solve(1.0, torque, clamp_law="cam", input_speed_rpm=RPM).eta
        rig = v.solve(1.0, torque, clamp_force=2000.0, input_speed_rpm=RPM).eta
        opt = v.solve(1.0, torque, clamp_law="optimal", input_speed_rpm=RPM).eta
        assert cam > rig + 0.05            # far higher than the over-clamped rig
        assert cam <= opt + 1e-6           # never above the optimal clamp
