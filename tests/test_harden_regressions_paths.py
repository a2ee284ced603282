"""Regressions of the hardening campaign (benchmarks/harden.py, issue 23): one answer
whatever path computed it (cycle step, map, table = solve)."""

from __future__ import annotations

import numpy as np
import pytest

from ballcvt import SolveSettings, Variator, load_builtin
from ballcvt.analysis.sweeps.curves import OperatingRows
from ballcvt.analysis.sweeps.points import evaluate_points
from ballcvt.model.clamping import clamp_law
from ballcvt.params.drive import Drive
from ballcvt.solvers.planetary import ModePoint
from ballcvt.solvers.planetary_batch import solve_mode_batch
from ballcvt.status import Status
from ballcvt.units import rpm_to_rad_s

ETA_TOL = 1e-6  # as the campaign's "= solve" checks

#: harden 2026:4129: table1 reshaped, a loading cam on the input disc (slow fixed point).
CAM_INPUT = {
    "aspect_ratio": 4.350598308291474,
    "roller_radius": 0.012232982716582012,
    "theta0_deg": 48.39239476001076,
    "theta2_deg": 32.02303784794462,
    "alpha_deg": 27.905590179705637,
    "n_rollers": 4,
    "roller_bearing_diameter": 0.0027298613813240306,
    "idler_bearing_diameter": 0.0015437480933510274,
    "disc_groove_ratio": 2.5505811090558463,
    "idler_groove_ratio": 3.715033434292562,
    "single_idler_groove_ratio": float("inf"),
    "tilt_safety_factor": 0.7712482137359636,
    "creep_limit": 0.08324115022073728,
    "min_roller_gap": 0.0012130641263857816,
    "cam": {
        "disc": "input",
        "preload": 39.89931105371988,
        "ramp_angle_deg": 2.3739642067295406,
        "mean_radius": 0.015472043473985,
        "friction": 0.019455734903024574,
    },
}

#: harden 2026:1658: hub reshaped, disc 2 held, disc 0 drives the carrier.
HELD_DISC2 = {
    "aspect_ratio": 0.6159809872456331,
    "roller_radius": 0.02415338826047383,
    "theta0_deg": 38.70300316184657,
    "theta2_deg": 58.927745845537196,
    "alpha_deg": 16.01386150410319,
    "n_rollers": 4,
    "roller_bearing_diameter": 0.023206486902747642,
    "idler_bearing_diameter": 0.009307397455226874,
    "disc_groove_ratio": 1.8857251537670425,
    "idler_groove_ratio": 1.4747740731017265,
    "single_idler_groove_ratio": 4.219891676789546,
    "tilt_safety_factor": 0.6255868588372836,
    "creep_limit": 0.1335101899303604,
    "min_roller_gap": 0.002494604661276838,
    "cam": {
        "disc": "output",
        "preload": 94.34047275566968,
        "ramp_angle_deg": 14.584035873728258,
        "mean_radius": 0.04608738415011445,
        "friction": 0.027737143258600872,
    },
    "parasitic": None,
}


def _variator(base: str, fields: dict, law: str) -> Variator:
    d, f = load_builtin(base)
    return Variator(d.replace(name="random", **fields), f, "single", traction_law=law)


def test_batched_cam_point_is_its_solve_answer():
    """A batched point under an input-side cam settles as it does alone, although another
    point of the batch (beyond the capacity) keeps the clamping fixed point running: it
    used to be re-solved at forces within round-off of its own until its input torque's
    noise failed the clamping equation (cycle step status 2 where solve converged)."""
    v = _variator("table1", CAM_INPUT, "isothermal")
    rpm = 1162.9161284035276
    ratio = np.array([0.7591640877442368, 0.770716999])
    torque = np.array([0.1780394883769882, 2.0])  # the second: 1.66 x limit
    rows = OperatingRows.of(
        Drive(v.design, v.fluid, v.architecture),
        ratio,
        np.full(2, rpm_to_rad_s(rpm)),
        clamp_force=None,
        law=clamp_law("cam", v.design, None),
        options=v.options,
    )
    got = evaluate_points(rows, torque)
    ref = v.solve(ratio[0], torque[0], clamp_law="cam", input_speed_rpm=rpm)
    assert got["status"][0] == Status.CONVERGED
    assert abs(got["eta"][0] - ref.eta) <= ETA_TOL
    assert got["status"][1] != Status.CONVERGED


def test_held_disc2_solve_finds_the_maps_equilibrium():
    """disc 2 held, disc 0 drives the carrier: the first pass of the fixed point on the
    actual ratio lands on a far root (output creep -0.35); solve used to restart the next
    pass from it and fail, where the batched map (whose fallback starts cold) converged.
    The equilibrium is real: it continues the branch from zero load (eta 0 there: the
    held disc takes no power) with every creep below the limit."""
    v = _variator("hub", HELD_DISC2, "viscoelastic")
    mode = "disc2_held_disc0_drives"
    ratio, load, force = 1.0502978281305768, 0.11037121232328626, 5370.154102090278
    rpm = 93.33801756001583
    got = v.solve(
        ratio, load, clamp_force=force, input_speed_rpm=rpm, settings=SolveSettings(mode=mode)
    )
    batch = solve_mode_batch(
        Drive(v.design, v.fluid, v.architecture),
        mode,
        ModePoint(np.array([ratio]), load, rpm_to_rad_s(rpm), force),
        v.options,
    )
    assert batch.status[0] == Status.CONVERGED
    assert got.eta == pytest.approx(float(batch.eta[0]), abs=ETA_TOL)
    assert 0.0 < got.eta < 0.02


#: harden 3:444: table1 reshaped (double idler), a loading cam on the input disc.
CAM_DOUBLE = {
    "aspect_ratio": 22.13293477175882,
    "roller_radius": 0.10469646910178414,
    "theta0_deg": 27.873639055071173,
    "theta2_deg": 2.404687572072379,
    "alpha_deg": 24.834660929546022,
    "n_rollers": 16,
    "roller_bearing_diameter": 0.030234955680673196,
    "idler_bearing_diameter": 0.005338976559591608,
    "disc_groove_ratio": 31.265278040784843,
    "idler_groove_ratio": 1.2153996912878904,
    "single_idler_groove_ratio": 1.0143630980497929,
    "tilt_safety_factor": 0.7249376182468789,
    "creep_limit": 0.021267258472334113,
    "min_roller_gap": 0.003639678792044591,
    "cam": {
        "disc": "input",
        "preload": 1509.3574738656012,
        "ramp_angle_deg": 6.5738702562256695,
        "mean_radius": 0.14234492881876493,
        "friction": 0.02637667390911075,
    },
}


def test_cam_points_settle_in_the_noise_floor_on_every_path():
    """The clamping fixed point of these points ends in a two-cycle of steps at 1e-10 to
    3e-10 of the force (the input torque's noise), above ``CLAMP_RTOL``: the batched
    admissibility test failed them, so the capacity came out in three pieces and the
    table said "beyond capacity" at torques solve carried (and solve itself failed some).
    Every path now settles them at that noise floor, with one answer."""
    d, f = load_builtin("table1")
    v = Variator(d.replace(name="random", **CAM_DOUBLE), f, "double", traction_law="isothermal")
    ratio, rpm = 1.1390610691340357, 298.4838074708887
    torque = np.array([3.4308204808307132, 10.29246144249214, 27.446563846645706])
    rows = OperatingRows.of(
        Drive(v.design, v.fluid, v.architecture),
        np.full(torque.size, ratio),
        np.full(torque.size, rpm_to_rad_s(rpm)),
        clamp_force=None,
        law=clamp_law("cam", v.design, None),
        options=v.options,
    )
    got = evaluate_points(rows, torque)
    assert np.all(got["status"] == Status.CONVERGED)
    for t, eta in zip(torque, got["eta"]):
        ref = v.solve(ratio, t, clamp_law="cam", input_speed_rpm=rpm)
        assert abs(eta - ref.eta) <= ETA_TOL
