"""The variator as a planetary (docs/model.md §13): modes, carrier effects, results."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ballcvt import Variator, load_builtin
from ballcvt.equilibrium.problem import (CarrierFrame, OperatingInputs, roller_mass, build_problem,
                                         centrifugal_force, idler_share, make_problem)
from ballcvt.params import Drive
from ballcvt.errors import InputError
from ballcvt.model.modes import MEMBERS, OperatingMode, relative_ratio_coefficients
from ballcvt.results.planetary import PlanetaryResult
from ballcvt.solvers.planetary import ModePoint, solve_mode
from ballcvt.solvers.point import solve_point
from drives import fixed_oil_hub

F = 2000.0
MODES = [OperatingMode(h, d) for h in MEMBERS for d in MEMBERS if h != d]
#: The five modes beyond the paper (the default returns the paper's OperatingResult).
PLANETARY = [m for m in MODES if not m.is_default]


@pytest.fixture(scope="module")
def v():
    return Variator()


def test_modes_name_their_members():
    m = OperatingMode("disc2", "carrier")
    assert m.driven == "disc0" and not m.is_default
    assert OperatingMode().is_default and OperatingMode().driven == "disc2"
    with pytest.raises(InputError, match="driver"):
        OperatingMode("disc0", "disc0")
    with pytest.raises(InputError, match="held"):
        OperatingMode("sun", "disc0")


@pytest.mark.parametrize("mode", MODES, ids=lambda m: m.label)
def test_speeds_satisfy_willis_relation(mode):
    for tau in (0.5, 0.9, 1.7):
        if abs(relative_ratio_coefficients(tau)[mode.driven]) < 1e-9:
            continue
        w = mode.speeds(120.0, tau)
        assert w[mode.held] == 0.0 and w[mode.driver] == 120.0
        assert w["disc2"] - w["carrier"] == pytest.approx(tau * (w["disc0"] - w["carrier"]),
                                                          abs=1e-9)


def test_infinite_speed_is_refused():
    with pytest.raises(InputError, match="infinitely fast"):
        OperatingMode("disc2", "disc0").speeds(100.0, 1.0)


def test_the_default_mode_is_the_paper_drive(v):
    a = v.solve(1.3, 50.0, clamp_force=F, input_speed_rpm=2000)
    b = v.solve(1.3, 50.0, clamp_force=F, input_speed_rpm=2000, mode=OperatingMode())
    assert a == b


def test_carrier_held_through_the_mode_solver_equals_solve(v):
    """The fixed point of the mode solver, with the carrier held, adds nothing."""
    got = solve_mode(v, OperatingMode(), ModePoint(1.3, 50.0, 2000 * math.pi / 30, F))
    r = v.solve(1.3, 50.0, clamp_force=F, input_speed_rpm=2000)
    assert got.sign == 1.0 and got.speeds["carrier"] == 0.0
    assert np.allclose(got.solution.state.creep, [c.creep for c in r.contacts.values()],
                       rtol=1e-12, atol=1e-15)


def test_the_contacts_see_relative_speeds_only(v):
    """Without the carrier's inertia effects a turning carrier changes nothing in the
    carrier frame: the same creeps as the carrier held at the same relative speed and
    output torque."""
    mode = OperatingMode("disc2", "carrier", centrifugal=False, gyroscopic=False)
    r = v.solve(1.5, 20.0, clamp_force=F, input_speed=100.0, mode=mode)
    assert r.speeds["carrier"] == 100.0
    rel = r.relative
    held = make_problem(v, OperatingInputs(1.5, rel.output_torque, F, rel.input_speed),
                        CarrierFrame(signed_torque=True))
    sol = solve_point(held)
    assert np.allclose(sol.state.creep, [c.creep for c in rel.contacts.values()],
                       rtol=1e-9, atol=1e-14)


def test_zero_driver_speed_is_refused(v):
    with pytest.raises(InputError, match="driver_speed"):
        v.solve(1.5, 20.0, clamp_force=F, input_speed=0.0, mode=OperatingMode("disc2",
                                                                                "carrier"))


@pytest.mark.parametrize("mode", PLANETARY, ids=lambda m: m.label)
def test_ideal_relation_at_zero_torque(v, mode):
    ratio = 0.7
    # 20 rad/s: the modes that drive the carrier from a disc spin it up to 3.3 times faster
    r = v.solve(ratio, 0.0, clamp_force=F, input_speed=20.0, mode=mode)
    w = r.speeds
    tau = r.relative.actual_ratio
    assert w["disc2"] - w["carrier"] == pytest.approx(tau * (w["disc0"] - w["carrier"]),
                                                      rel=1e-12, abs=1e-9)
    assert tau == pytest.approx(ratio, rel=2e-2)      # only the drag's creep


@pytest.mark.parametrize("mode", PLANETARY, ids=lambda m: m.label)
def test_power_balance_per_mode(v, mode):
    for ratio in (0.6, 1.4):
        r = v.solve(ratio, 15.0, clamp_force=F, input_speed=20.0, mode=mode)
        p = r.powers
        assert sum(r.torques.values()) == pytest.approx(0.0, abs=1e-9)
        # power in through the shafts = losses in the carrier frame (to the residual)
        assert sum(p.values()) == pytest.approx(r.loss, rel=1e-8)
        assert r.relative.losses["total"] >= 0.0


def test_geared_neutral_is_where_the_kinematics_put_it(v):
    """Disc 0 held, the carrier drives: omega_2 = omega_c (1 - tau_R), zero at tau_R = 1
    (tau_ID a little below 1, by the creep), with a finite torque on the held disc."""
    mode = OperatingMode("disc0", "carrier")
    below = v.solve(0.98, 20.0, clamp_force=F, input_speed=100.0, mode=mode)
    above = v.solve(1.02, 20.0, clamp_force=F, input_speed=100.0, mode=mode)
    assert below.overall_ratio > 0 > above.overall_ratio
    # at neutral itself (found by bisection on the ratio): the output at rest, a finite
    # torque on the held disc, and the result says so
    lo, hi = 0.98, 1.02
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        r = v.solve(mid, 20.0, clamp_force=F, input_speed=100.0, mode=mode)
        lo, hi = (mid, hi) if r.overall_ratio > 0 else (lo, mid)
    assert r.geared_neutral and abs(r.speeds["disc2"]) < 1e-6 * 100.0
    assert r.relative.actual_ratio == pytest.approx(1.0, abs=1e-8)
    assert 1.0 < r.torque_ratio < 10.0 and r.to_dict()["geared_neutral"]
    for r in (below, above):
        assert r.speeds["disc2"] == pytest.approx(
            r.speeds["carrier"] * (1 - r.relative.actual_ratio), abs=1e-9)
        assert math.isfinite(r.torques["disc0"]) and r.torques["disc0"] > 0
        assert r.circulating_power > abs(r.input_power)     # power circulates near neutral
        assert "circulating" in r.power_flow


def test_centrifugal_force_unloads_the_idlers_only(v):
    d, fl = load_builtin()
    rest = build_problem(d, fl, "double", 1.2, 20.0, F, 100.0)
    turning = make_problem(Drive(d, fl), OperatingInputs(1.2, 20.0, F, 100.0),
                           CarrierFrame(carrier_speed=120.0))
    fc = roller_mass(d) * 120.0 ** 2 * d.roller_radius * (1 + d.aspect_ratio)
    assert centrifugal_force(d, 120.0) == pytest.approx(fc)
    assert np.allclose(rest.load - turning.load, fc * idler_share(rest.layout, d))
    assert turning.load[0] == rest.load[0] and turning.load[-1] == rest.load[-1]
    with pytest.raises(InputError, match="carrier_speed"):
        make_problem(Drive(d, fl), OperatingInputs(1.2, 20.0, F, 100.0),
                     CarrierFrame(carrier_speed=400.0))


def test_gyroscopic_moment_loads_the_ball_bearings(v):
    on = OperatingMode("disc2", "carrier", centrifugal=False, gyroscopic=True)
    off = OperatingMode("disc2", "carrier", centrifugal=False, gyroscopic=False)
    a = v.solve(1.6, 20.0, clamp_force=F, input_speed=150.0, mode=on)
    b = v.solve(1.6, 20.0, clamp_force=F, input_speed=150.0, mode=off)
    assert a.relative.losses["roller_bearings"] > b.relative.losses["roller_bearings"]
    # no gyroscopic moment with the spin axis along the main axis (tau_ID ~ 1, tilt 0)
    c = v.solve(1.0, 20.0, clamp_force=F, input_speed=100.0, mode=on)
    d = v.solve(1.0, 20.0, clamp_force=F, input_speed=100.0, mode=off)
    assert c.relative.losses["roller_bearings"] == pytest.approx(
        d.relative.losses["roller_bearings"], rel=1e-9)


def test_result_round_trip_and_edits_refused(v, tmp_path):
    r = v.solve(1.4, 15.0, clamp_force=F, input_speed=80.0, mode=OperatingMode("disc2",
                                                                                "carrier"))
    path = tmp_path / "r.json"
    r.save(path)
    back = PlanetaryResult.load(path)
    assert back.torques == r.torques and back.speeds == r.speeds and back.mode == r.mode
    d = r.to_dict()
    for key in ("overall_ratio", "carrier_speed", "carrier_torque", "power_flow", "speeds",
                "torques", "eta", "creep" if "creep" in d else "contacts"):
        assert key in d
    d["torques"]["carrier"] += 1.0
    with pytest.raises(InputError, match="torques.carrier"):
        PlanetaryResult.from_dict(d)


def test_planetary_modes_refuse_what_they_do_not_model():
    hub = Variator(*fixed_oil_hub())
    mode = OperatingMode("disc2", "carrier")
    with pytest.raises(InputError, match="parasitic"):
        hub.solve(1.2, 10.0, clamp_force=F, input_speed=50.0, mode=mode)
    with pytest.raises(InputError, match="clamp_law"):
        Variator(*fixed_oil_hub()).solve(1.2, 10.0, clamp_law="cam", input_speed=50.0,
                                             mode=mode)


@settings(max_examples=12, deadline=None)
@given(mode=st.sampled_from([OperatingMode("disc2", "carrier"),
                             OperatingMode("disc0", "carrier"),
                             OperatingMode("carrier", "disc2"),
                             OperatingMode("disc2", "disc0")]),
       ratio=st.floats(0.5, 1.9), torque=st.floats(0.0, 25.0), speed=st.floats(20.0, 120.0))
def test_invariants_across_modes(mode, ratio, torque, speed):
    v = Variator()
    try:
        r = v.solve(ratio, torque, clamp_force=F, input_speed=speed, mode=mode)
    except InputError:                 # beyond the capacity, or a speed out of range
        return
    assert all(value >= 0.0 for value in r.relative.losses.values())
    # the power balance holds to the residual: torques off by n F_N0 r_S eps at most, times
    # the carrier-frame speeds (as in test_invariants), with a factor 2 for round-off
    rel = r.relative
    speeds = abs(rel.roller_speed) + sum(abs(c.body_speed) for c in rel.contacts.values())
    slack = 2 * v.design.n_rollers * F * v.design.roller_radius * rel.residual_norm * speeds
    assert sum(r.powers.values()) == pytest.approx(r.loss, abs=1e-12 + slack)
    if r.input_power > 0 and r.output_power >= 0:
        assert 0.0 <= r.eta <= 1.0
        assert r.eta == pytest.approx(r.eta_loss, abs=1e-12 + slack / r.input_power)


def test_free_differential_takes_two_speeds(v):
    """Disc 2 at a given speed instead of held: Willis' relation with both given speeds,
    the power balance over three shafts, and held_speed = 0 is the held mode."""
    free = OperatingMode("disc2", "carrier", held_speed=-5.0)
    r = v.solve(1.5, 15.0, clamp_force=F, input_speed=40.0, mode=free)
    w = r.speeds
    assert w["disc2"] == -5.0 and w["carrier"] == 40.0
    assert w["disc2"] - w["carrier"] == pytest.approx(
        r.relative.actual_ratio * (w["disc0"] - w["carrier"]), rel=1e-12)
    assert r.powers["disc2"] != 0.0
    assert sum(r.powers.values()) == pytest.approx(r.loss, rel=1e-8)
    assert r.input_power - r.output_power == pytest.approx(r.loss, rel=1e-8)
    held = v.solve(1.5, 15.0, clamp_force=F, input_speed=40.0,
                   mode=OperatingMode("disc2", "carrier", held_speed=0.0))
    assert held.speeds["disc2"] == 0.0 and "free differential" in free.label


def test_batch_equals_point_solves(v):
    from ballcvt.solvers.planetary_batch import solve_mode_batch
    mode = OperatingMode("disc0", "carrier")
    ratios = np.array([0.6, 0.95, 1.3])
    got = solve_mode_batch(v, mode, ModePoint(ratios, 20.0, 100.0, F))
    assert (got.status == 0).all()
    for i, ratio in enumerate(ratios):
        r = v.solve(ratio, 20.0, clamp_force=F, input_speed=100.0, mode=mode)
        for j, m in enumerate(MEMBERS):
            assert got.speeds[j, i] == pytest.approx(r.speeds[m], rel=1e-9, abs=1e-9)
            assert got.torques[j, i] == pytest.approx(r.torques[m], rel=1e-8, abs=1e-8)
        assert got.eta[i] == pytest.approx(r.eta, abs=1e-9)
    # speeds out of range are flagged, not raised
    far = solve_mode_batch(v, OperatingMode("disc2", "disc0"),
                           ModePoint(np.array([0.5, 0.9]), 10.0, 100.0, F))
    assert far.status.tolist() == [0, 3]


def test_capacity_per_mode_matches_the_limit_with_the_carrier_held(v):
    from ballcvt.solvers.planetary_batch import limit_load_batch
    ratios = np.array([0.7, 1.5])
    got = limit_load_batch(v, "carrier_held", ModePoint(ratios, 0.0, 100.0, F))
    for ratio, limit in zip(ratios, got):
        ref = v.limit_torque(ratio, clamp_force=F, input_speed=100.0)
        assert limit == pytest.approx(ref, rel=2e-3) and limit <= ref * (1 + 1e-9)


@pytest.mark.parametrize("mode", [OperatingMode(), OperatingMode("disc0", "carrier"),
                                  OperatingMode("disc2", "carrier"),
                                  OperatingMode("disc2", "disc0")], ids=lambda m: m.label)
def test_carrier_torque_from_its_reactions(v, mode):
    """The carrier's torque from the axle reactions and bearing torques equals the balance
    of the three shafts, T_2 - T_0, in the carrier frame, held or turning."""
    from ballcvt.equilibrium.residual import carrier_reaction_torque
    from ballcvt.solvers.planetary import solve_mode
    for ratio in (0.6, 1.7):
        if mode.driver == "disc0" and mode.held == "disc2" and ratio > 1:
            continue                          # the carrier would turn too fast
        got = solve_mode(v, mode, ModePoint(ratio, 20.0, 60.0, F))
        st, pb = got.solution.state, got.problem
        balance = float(pb.output_torque) - float(st.input_torque)
        assert float(carrier_reaction_torque(pb, st)) == pytest.approx(balance, rel=1e-9,
                                                                         abs=1e-9)
