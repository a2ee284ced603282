"""Issue 29: shift kinematics (side slip, skew-steered tilt rate) and the shift transient
(docs/shifting.md)."""

import json
import math
import types

import numpy as np
import pytest

from ballcvt import InputError, Variator, load_builtin
from ballcvt.analysis.shift import LinearViscousMoments, ShiftCommand, ShiftDrive, run_shift
from ballcvt.analysis.shift.transient import _Dynamics, _integrate
from ballcvt.interfaces.cli.main import main
from ballcvt.model.architectures import contact_layout
from ballcvt.model.kinematics import ideal_ratio, rolling_radius, tilt_from_ratio
from ballcvt.model.shift_kinematics import (
    ball_angular_velocity,
    ball_spin_speed,
    side_slip,
    skew_tilt_rate,
)
from ballcvt.units import rpm_to_rad_s
from drives import fixed_oil_hub

HUB = fixed_oil_hub()
CAM = {"clamp_law": "cam"}


@pytest.fixture(scope="module")
def hub():
    return Variator(*HUB)


def _tilts(design):
    return tilt_from_ratio(np.array([0.3, 0.5, 1.0, 1.8, 3.0]), design.theta0, design.theta2,
                           design.aspect_ratio)


@pytest.mark.parametrize("arch", ["double", "single"])
def test_side_slip_vanishes_at_every_contact_at_the_skew_steered_rate(arch):
    design = HUB[0]
    layout = contact_layout(design, arch)
    gamma = _tilts(design)[:, None]
    skew = np.radians([-3.0, -0.5, 0.2, 1.0, 5.0])[None, :]
    omega_b = ball_spin_speed(layout, gamma, rpm_to_rad_s(114.0))
    rate = skew_tilt_rate(omega_b, gamma, skew)
    for skew_rate in (0.0, 0.7, -2.0):  # a skew actuator moving does not add side slip
        slip = side_slip(layout, gamma, omega_b, skew, rate, skew_rate)
        assert slip.shape == (5, 5, layout.n_contacts)
        assert np.max(np.abs(slip)) < 1e-12
    # and not at another rate
    assert np.min(np.abs(side_slip(layout, gamma, omega_b, skew, 1.1 * rate))) > 1e-6


def test_tilt_direct_side_slip_is_the_rate_times_r_s_over_the_rolling_speed():
    design = HUB[0]
    layout = contact_layout(design, "double")
    gamma, rate, w0 = _tilts(design), 0.8, rpm_to_rad_s(114.0)
    omega_b = ball_spin_speed(layout, gamma, w0)
    r_s = design.roller_radius
    rolling = np.abs(omega_b[:, None] * rolling_radius(layout, gamma)) * r_s  # U_c [m/s]
    slip = side_slip(layout, gamma, omega_b, 0.0, rate)
    np.testing.assert_allclose(slip, rate * r_s / rolling, rtol=1e-13)


def test_hand_calculation_at_zero_tilt():
    # gamma = 0 on Table I's geometry: omega_b = omega_0 (1 + k + cos 45) / cos 45
    design = HUB[0]
    layout = contact_layout(design, "double")
    w0 = 10.0
    omega_b = float(ball_spin_speed(layout, 0.0, w0))
    assert omega_b == pytest.approx(10.0 * (2.7 + math.sqrt(0.5)) / math.sqrt(0.5), rel=1e-14)
    # skew 1 deg: 48.18... * tan(1 deg) = 0.841 rad/s
    assert float(skew_tilt_rate(omega_b, 0.0, math.radians(1.0))) == pytest.approx(
        omega_b * math.tan(math.radians(1.0)), rel=1e-14)
    # to first order in the skew: omega_b zeta cos(gamma) (the formula)
    z = math.radians(0.5)
    assert float(skew_tilt_rate(omega_b, 0.3, z)) == pytest.approx(
        omega_b * z * math.cos(0.3), rel=1e-4)
    # the input contact at 1 deg/s: s = gamma_dot r_S / (omega_b r_S cos 45)
    slip = side_slip(layout, 0.0, omega_b, 0.0, math.radians(1.0))
    assert slip[0] == pytest.approx(math.radians(1.0) / (omega_b * math.sqrt(0.5)), rel=1e-13)


def test_angular_velocity_has_no_rolling_axis_component_at_the_steered_rate():
    w = ball_angular_velocity(0.4, 50.0, 0.02, skew_tilt_rate(50.0, 0.4, 0.02), 1.0)
    assert abs(w[0]) < 1e-13
    assert w[1] == pytest.approx(50.0 * math.cos(0.4) / math.cos(0.02), rel=1e-13)


def _drive(hub, rpm=114.0, torque=20.0, moments=None):
    speed = rpm_to_rad_s(rpm)
    return ShiftDrive(hub.design, contact_layout(hub.design, "double"), speed, torque,
                      lambda r: hub.solve(r, torque, input_speed=speed, **CAM), moments)


def test_zero_skew_keeps_the_ratio_over_a_long_run(hub):
    dyn = _Dynamics(_drive(hub), ShiftCommand("skew", math.radians(1.0), lag=0.2))
    g = float(tilt_from_ratio(1.3, hub.design.theta0, hub.design.theta2,
                              hub.design.aspect_ratio))
    sol = _integrate(dyn, [g, 0.0], (0.0, 3600.0), 0.0)
    assert sol.status == 0 and sol.t[-1] == 3600.0
    assert np.all(sol.y[0] == g)


def test_skew_shift_time_is_inversely_proportional_to_input_speed(hub):
    times = [hub.shift(0.5, 1.8, 20.0, skew_deg=1.0, input_speed_rpm=rpm, samples=5,
                       **CAM).shift_time_s for rpm in (60.0, 120.0)]
    assert times[0] / times[1] == pytest.approx(2.0, rel=0.01)
    assert times[0] / times[1] == pytest.approx(2.0, rel=1e-6)  # rigid kinematics: exact


def test_skew_shift_reaches_the_target_and_rolls_without_side_slip(hub):
    r = hub.shift(0.5, 1.8, 20.0, skew_deg=1.0, input_speed_rpm=114.0, **CAM)
    s = r.samples
    assert s["ratio"].iloc[0] == pytest.approx(0.5) and s["ratio"].iloc[-1] == pytest.approx(1.8)
    assert np.all(np.diff(s["ratio"]) > 0)
    assert np.max(np.abs(s.filter(like="side_slip_").to_numpy())) < 1e-12
    assert s["converged"].all() and (s["eta"] > 0.8).all()
    # the reverse shift takes the other sign of skew and about as long
    back = hub.shift(1.8, 0.5, 20.0, skew_deg=1.0, input_speed_rpm=114.0, samples=5, **CAM)
    assert back.samples["skew_deg"].iloc[0] == -1.0
    assert back.shift_time_s == pytest.approx(r.shift_time_s, rel=1e-6)


def test_a_skew_removed_with_a_lag_overshoots(hub):
    r = hub.shift(0.8, 1.2, 20.0, skew_deg=0.5, input_speed_rpm=114.0, actuator_lag=0.05,
                  samples=11, **CAM)
    assert r.final_ratio > 1.2
    assert r.samples["skew_deg"].iloc[0] == 0.0 and abs(r.samples["skew_deg"].iloc[-1]) < 0.01


def test_tilt_direct_at_a_constant_rate_takes_the_tilt_change_over_the_rate(hub):
    d = hub.design
    g1, g2 = (float(tilt_from_ratio(x, d.theta0, d.theta2, d.aspect_ratio)) for x in (0.6, 1.6))
    r = hub.shift(0.6, 1.6, 20.0, tilt_rate_deg_s=40.0, input_speed_rpm=114.0, samples=5, **CAM)
    assert r.shift_time_s == pytest.approx((g2 - g1) / math.radians(40.0), rel=1e-9)
    lag = hub.shift(0.6, 1.6, 20.0, tilt_rate_deg_s=40.0, input_speed_rpm=114.0, samples=5,
                    actuator_lag=0.01, **CAM)
    assert lag.shift_time_s == pytest.approx(r.shift_time_s + 0.01, rel=1e-6)
    slip = r.samples["side_slip_input"].to_numpy()
    assert np.all(slip > 0)


def test_energy_is_the_trapezoid_of_the_sampled_losses_and_shift_work(hub):
    model = LinearViscousMoments(holding=0.05, damping=0.02)
    r = hub.shift(0.6, 1.6, 20.0, tilt_rate_deg_s=40.0, input_speed_rpm=114.0, samples=21,
                  moment_model=model, **CAM)
    s = r.samples
    t = s["time_s"].to_numpy()
    loss = np.trapezoid(s["power_loss_W"].to_numpy(), t)
    work = np.trapezoid(8 * 0.02 * math.radians(40.0) ** 2 * np.ones_like(t), t)
    assert r.loss_energy_J == pytest.approx(loss, rel=1e-12)
    assert r.shift_work_J == pytest.approx(work, rel=1e-9)
    assert r.energy_lost_J == pytest.approx(loss + work, rel=1e-12)
    assert r.peak_shift_moment_Nm == pytest.approx(8 * (0.05 + 0.02 * math.radians(40.0)))


def test_actuator_moment_sets_the_rate_through_the_moment_model(hub):
    model = LinearViscousMoments(holding=0.05, damping=0.02)
    d = hub.design
    g1, g2 = (float(tilt_from_ratio(x, d.theta0, d.theta2, d.aspect_ratio)) for x in (0.6, 1.6))
    r = hub.shift(0.6, 1.6, 20.0, actuator_moment=2.0, input_speed_rpm=114.0, samples=5,
                  moment_model=model, **CAM)
    rate = (2.0 / 8 - 0.05) / 0.02
    assert r.shift_time_s == pytest.approx((g2 - g1) / rate, rel=1e-8)
    assert r.samples["shifter_moment_Nm"].to_numpy() == pytest.approx(2.0, rel=1e-8)
    with pytest.raises(InputError, match="never arrives"):  # does not beat the holding moment
        hub.shift(0.6, 1.6, 20.0, actuator_moment=0.3, input_speed_rpm=114.0, samples=5,
                  moment_model=model, max_time=5.0, **CAM)


def test_the_contact_model_moments_are_used_when_the_variator_has_them(hub, monkeypatch):
    calls = []

    def shift_moments(self, ratio, output_torque, *, tilt_rate=0.0, **point):
        calls.append(point)
        return types.SimpleNamespace(holding_moment=0.001 * output_torque,
                                     shift_moment=0.01 * tilt_rate)

    monkeypatch.setattr(Variator, "shift_moments", shift_moments, raising=False)
    r = hub.shift(0.6, 1.6, 20.0, tilt_rate_deg_s=40.0, input_speed_rpm=114.0, samples=5,
                  **CAM)
    assert r.peak_shift_moment_Nm == pytest.approx(8 * (0.02 + 0.01 * math.radians(40.0)))
    assert calls[0] == {"clamp_law": "cam", "input_speed_rpm": pytest.approx(114.0)}


@pytest.mark.parametrize("kwargs, fragment", [
    ({}, "exactly one of"),
    ({"skew_deg": 1.0, "tilt_rate_deg_s": 5.0}, "exactly one of"),
    ({"skew_deg": 0.0}, "never arrives"),
    ({"skew_deg": 12.0}, "< 10 deg"),
    ({"tilt_rate_deg_s": -5.0}, "> 0 deg/s"),
    ({"skew_deg": 1.0, "actuator_lag": -1.0}, "actuator_lag"),
    ({"skew_deg": 1.0, "sped": 3}, "sped"),
])
def test_bad_shift_input_is_refused(double, kwargs, fragment):
    with pytest.raises(InputError, match=fragment):
        double.shift(0.8, 1.2, 20.0, input_speed_rpm=2000, clamp_force=2000.0, **kwargs)


def test_single_idler_and_the_paper_drive(single):
    r = single.shift(0.8, 1.5, 30.0, skew_deg=0.5, input_speed_rpm=2000, clamp_force=2000.0,
                     samples=5)
    assert r.samples["ratio"].iloc[-1] == pytest.approx(1.5)
    assert list(r.samples.filter(like="side_slip_").columns) == [
        "side_slip_input", "side_slip_idler", "side_slip_output"]
    assert json.loads(r.to_json())["shift_time_s"] == r.shift_time_s


def _cli(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_cli_json_csv_and_figure(capsys, tmp_path):
    code, out, err = _cli(capsys, "shift", "--design", "hub", "--oil-temperature", "fixed", "--from", "0.5", "--to", "1.8",
                          "--skew", "1", "--speed", "114", "--torque", "20", "--samples", "9",
                          "--out", str(tmp_path), "--json")
    assert code == 0, err
    data = json.loads(out)
    assert {"shift_time_s", "peak_shift_moment_Nm", "energy_lost_J"} <= set(data)
    assert data["inputs"]["input_speed_rpm"] == 114.0
    header = (tmp_path / "shift.csv").read_text().splitlines()[0].split(",")
    for column in ("time_s", "ratio", "tilt_deg", "skew_deg", "tilt_rate_deg_s",
                   "side_slip_input", "side_slip_output", "holding_moment_Nm",
                   "shifter_moment_Nm", "eta", "power_loss_W"):
        assert column in header
    assert len((tmp_path / "shift.csv").read_text().splitlines()) == 10
    assert (tmp_path / "shift.png").stat().st_size > 0
    assert json.loads((tmp_path / "summary.json").read_text())["mechanism"] == "skew"


def test_cli_defaults_come_from_the_hub_operating_table(capsys, tmp_path):
    code, out, _ = _cli(capsys, "shift", "--design", "hub", "--oil-temperature", "fixed", "--from", "0.5", "--to", "1.8",
                        "--skew", "1", "--samples", "3", "--out", str(tmp_path), "--json")
    assert code == 0
    assert json.loads(out)["inputs"]["input_speed_rpm"] == 150.0  # [operating] input speed


@pytest.mark.parametrize("argv, fragment", [
    (["--from", "0.1", "--to", "1.8", "--skew", "1"], "from_ratio = 0.1"),
    (["--from", "0.5", "--to", "9", "--skew", "1"], "to_ratio = 9"),
    (["--from", "0.5", "--to", "1.8", "--skew", "0"], "never arrives"),
    (["--from", "0.5", "--to", "1.8", "--skew", "1", "--tilt-rate", "3"], "not allowed with"),
    (["--from", "0.5", "--to", "1.8"], "one of the arguments"),
    (["--from", "0.5", "--to", "0.5", "--tilt-rate", "3"], "other than from_ratio"),
    (["--from", "0.5", "--to", "1.8", "--tilt-rate", "0.1", "--max-time", "2"],
     "never arrives"),
])
def test_cli_bad_input_exits_2_with_one_line(capsys, tmp_path, argv, fragment):
    try:
        code, _, err = _cli(capsys, "shift", "--design", "hub", "--oil-temperature", "fixed", *argv, "--out", str(tmp_path))
    except SystemExit as exc:
        code, err = exc.code, capsys.readouterr().err
    assert code == 2
    assert len(err.strip().splitlines()) == 1 and fragment in err


def test_ratio_of_the_samples_is_the_ideal_ratio_of_their_tilt(hub):
    r = hub.shift(0.7, 1.1, 20.0, tilt_rate_deg_s=20.0, input_speed_rpm=114.0, samples=5, **CAM)
    d = hub.design
    np.testing.assert_allclose(
        r.samples["ratio"],
        ideal_ratio(np.radians(r.samples["tilt_deg"]), d.theta0, d.theta2, d.aspect_ratio),
        rtol=1e-12)


def test_an_actuator_moment_beyond_the_saturated_side_forces_is_refused(hub):
    def saturating(ratio, output_torque, tilt_rate, input_speed):
        return 0.001 * output_torque, 0.3 * math.tanh(tilt_rate / 2.0)

    r = hub.shift(0.5, 1.8, 20.0, actuator_moment=1.0, input_speed_rpm=114.0, samples=5,
                  moment_model=saturating, **CAM)
    rate = 2.0 * math.atanh((1.0 / 8 - 0.02) / 0.3)
    assert r.samples["tilt_rate_deg_s"].to_numpy() == pytest.approx(math.degrees(rate))
    with pytest.raises(InputError, match="saturate"):
        hub.shift(0.5, 1.8, 20.0, actuator_moment=5.0, input_speed_rpm=114.0, samples=5,
                  moment_model=saturating, **CAM)
