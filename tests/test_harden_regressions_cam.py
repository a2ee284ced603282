"""Campaign regression (issue 23, seed 2029, task 5846) of the limiting torque under an
input-disc loading cam: the clamping fixed point ``F <- law(T_0(F))`` contracts slowly
(some 0.5 per step) and ran out of plain iterations below the pressure limit, so the
reported limit was where the iteration budget ended and `Variator.solve` refused it.
The inputs are the campaign's (``python benchmarks/harden.py --task 2029:5846``)."""

import json

import pytest

from ballcvt import Variator, load_builtin
from ballcvt.errors import TractionLimitError
from drives import fixed_oil_hub

FIELDS = (
    '{"aspect_ratio": 3.9689581221795067, "roller_radius": 0.01541036563610668, '
    '"theta0_deg": 45.35205703688381, "theta2_deg": 44.48768613009885, '
    '"alpha_deg": 24.726475482103574, "n_rollers": 12, '
    '"roller_bearing_diameter": 0.002649118660475401, '
    '"idler_bearing_diameter": 0.0038596497699255813, "disc_groove_ratio": 3.268274307448465, '
    '"idler_groove_ratio": 1.476557036869849, "single_idler_groove_ratio": Infinity, '
    '"tilt_safety_factor": 0.8226677378905669, "creep_limit": 0.18166319097846179, '
    '"min_roller_gap": 0.0003844983622049341, "cam": {"disc": "input", '
    '"preload": 1475.0683341758208, "ramp_angle_deg": 5.915891030421806, '
    '"mean_radius": 0.02042439704300432, "friction": 0.027174304643710852}}'
)
RATIO = 1.1965166050522258
RPM = 234.16495632484862


@pytest.fixture(scope="module")
def drive() -> Variator:
    d, f = fixed_oil_hub()
    d = d.replace(name="random", **json.loads(FIELDS))
    return Variator(d, f, "double", traction_law="viscoelastic")


def test_cam_fixed_point_converges_below_the_old_limit(drive):
    # 22.84 N m was the limit reported before: the plain fixed point failed already at
    # 0.999 x it (its step 2.3e-7 N above 1e-10 of 2170 N after 30 iterations)
    got = drive.solve(RATIO, 22.8, clamp_law="cam", input_speed_rpm=RPM)
    assert max(abs(c.creep) for c in got.contacts.values()) < drive.design.creep_limit


def test_cam_limit_is_the_largest_solvable_torque(drive):
    lim = drive.limit_torque(RATIO, clamp_law="cam", input_speed_rpm=RPM)
    assert lim > 30.0  # the pressure limit (38.6 N m), not the iteration budget (22.84)
    drive.solve(RATIO, lim, clamp_law="cam", input_speed_rpm=RPM)
    with pytest.raises(TractionLimitError):
        drive.solve(RATIO, lim * 1.001, clamp_law="cam", input_speed_rpm=RPM)


# Harden task 2701:139 (session 28): an input-disc cam on a hub drive at 40 % efficiency.
# The fixed point's first force is the law's at the lossless input torque ``T_2 tau``,
# short of its own by the losses; above 1.88 N m it did not carry the torque, the creeps
# ran off, and the capacity scan called those torques beyond the creep limit (the limit
# 1.882 N m, set by "creep" at a largest creep of 0.0365 against 0.121). A first pass that
# fails is solved again from the pressure limit's force (`ballcvt.solvers.clamped._from_ceiling`).
FIELDS_2701 = '{"aspect_ratio": 2.8328181145275217, "roller_radius": 0.013378524575783556, "theta0_deg": 37.16090462662911, "theta2_deg": 38.447646488402555, "alpha_deg": 14.74679309132041, "n_rollers": 6, "roller_bearing_diameter": 0.0021017435109195516, "idler_bearing_diameter": 0.011423525490417221, "disc_groove_ratio": 2.1445171594831898, "idler_groove_ratio": 4.2611773244540085, "single_idler_groove_ratio": 5.843768649639814, "tilt_safety_factor": 0.7707906490924148, "creep_limit": 0.12143246911372675, "min_roller_gap": 0.00043613472094949256, "cam": {"disc": "input", "preload": 601.7389213868083, "ramp_angle_deg": 17.671190055975238, "mean_radius": 0.0405101889762365, "friction": 0.029192065080532986}}'
RATIO_2701, RPM_2701 = 2.213370504285433, 2386.3774327979577


def test_a_cam_first_force_short_of_the_torque_does_not_end_the_capacity():
    d, f = load_builtin("hub")
    d = d.replace(name="random", **json.loads(FIELDS_2701))
    v = Variator(d, f, "single", traction_law="viscoelastic")
    from ballcvt.api import with_oil_temperature

    v = with_oil_temperature(v, "fixed")
    kw = {"clamp_law": "cam", "input_speed_rpm": RPM_2701}
    limit = v.limit_torque(RATIO_2701, **kw)
    assert limit > 7.0  # 1.882 N m before
    at = v.solve(RATIO_2701, limit * (1 - 1e-3), **kw)
    largest = max(abs(c.creep) for c in at.contacts.values())
    assert largest == pytest.approx(d.creep_limit, rel=2e-2)  # the limit is the creep's
    with pytest.raises(TractionLimitError):
        v.solve(RATIO_2701, limit * 1.001, **kw)


# Harden task 3902:3522 (session 39): an input-disc cam on a hub drive at 39,000 rpm and
# 26 % efficiency. The first pass's force (1,866 N, at the lossless input torque) ran the
# creeps off; the retry at the pressure limit's force (8,305 N) failed too with its creeps
# within the limit (Newton's failure, residual 2e-3), but the first pass's creeps were
# kept, and the study's scattered points (`evaluate_points`) called 118.5 N m beyond the
# capacity where `solve` settles at 6,289 N and an efficiency of 0.2573. The retry's
# outcome is now kept, so the point solver takes the point; and the rescued point reports
# the force of its own fixed point (it reported the ceiling's, and an efficiency of 0.2145).
FIELDS_3902 = '{"aspect_ratio": 1.5163765125592006, "roller_radius": 0.032792726409047505, "theta0_deg": 63.79660732670419, "theta2_deg": 29.746984039219374, "alpha_deg": 4.574072056977254, "n_rollers": 7, "roller_bearing_diameter": 0.014184185875363409, "idler_bearing_diameter": 0.01831047338935479, "disc_groove_ratio": 1.5494789096618757, "idler_groove_ratio": 3.8331286062232808, "single_idler_groove_ratio": Infinity, "tilt_safety_factor": 0.8489449705042413, "creep_limit": 0.06253980110952811, "min_roller_gap": 0.0007436644349215738, "cam": {"disc": "input", "preload": 1422.9404281005163, "ramp_angle_deg": 6.6689110245419405, "mean_radius": 0.07308961099831203, "friction": 0.04603306777175495}}'


def test_scattered_points_under_an_input_cam_are_solve():
    import numpy as np

    from ballcvt.analysis.sweeps.curves import OperatingRows
    from ballcvt.analysis.sweeps.points import evaluate_points

    d, f = fixed_oil_hub()
    v = Variator(d.replace(name="random", **json.loads(FIELDS_3902)), f, "double",
                 traction_law="viscoelastic")  # fmt: skip
    ratio, rpm, torque = 1.0407904943055502, 39182.60541471054, 118.47531467747233
    solved = v.solve(ratio, torque, clamp_law="cam", input_speed_rpm=rpm)
    rows = OperatingRows.of(v, [ratio], [rpm * np.pi / 30], None, v.clamp_law("cam", None),
                            v.options)  # fmt: skip
    got = evaluate_points(rows, [torque])
    assert got["status"][0] == 0
    assert got["eta"][0] == pytest.approx(solved.eta, abs=1e-8)
    assert got["clamp_force"][0] == pytest.approx(solved.clamp_force, rel=1e-8)


# Harden task 3903:1810 (session 39, fixed in session 40): an output cam on a hub-derived
# drive at 6,364 rpm, the visco-elastic law. Its capacity is an island, 6.1 to 7.1 N m
# (below it the cam's force is too low for an equilibrium). From the kinematic start,
# Newton ran the creeps at 6.42 N m past the limit and failed, and the rule "failed beyond
# the limit: beyond the capacity at once" called it beyond; `solve`'s point solver
# converges there at a creep of 0.098 (limit 0.106). Scattered points start cold, so their
# failed runs now go to the point solver whatever their creeps (`solve_admissible(cold=)`).
FIELDS_3903 = '{"aspect_ratio": 1.3076633568699165, "roller_radius": 0.011185472573352949, "theta0_deg": 52.4939572484161, "theta2_deg": 37.74995876254124, "alpha_deg": 26.47135337321228, "n_rollers": 4, "roller_bearing_diameter": 0.0030656420153080087, "idler_bearing_diameter": 0.002247119158212487, "disc_groove_ratio": 3.398570382553157, "idler_groove_ratio": 3.5402840519143135, "single_idler_groove_ratio": Infinity, "tilt_safety_factor": 0.7255145036550007, "creep_limit": 0.10557773898055862, "min_roller_gap": 0.0007979790923117707, "cam": {"disc": "output", "preload": 156.9558255049127, "ramp_angle_deg": 9.264061162611611, "mean_radius": 0.01294203294192072, "friction": 0.00020565363191006326}}'
#: The study's fifteen torques [N m] (the batch matters: Newton's iterates depend on it).
TORQUES_3903 = [2.3397777515283127, 1.88635874540693, 0.4773984402340024, 4.2229320487125115,
                2.0435290342133734, 4.111951591494649, 4.264621342081864, 1.8901099681864335,
                2.1451863118469454, 1.870234149987232, 3.094235752027243, 1.5556650560697254,
                2.3606526966214836, 6.420379891146298, 9.273882064989097]  # fmt: skip


def test_scattered_points_from_the_kinematic_start_are_solve():
    import numpy as np

    from ballcvt.analysis.sweeps.curves import OperatingRows
    from ballcvt.analysis.sweeps.points import evaluate_points

    d, f = fixed_oil_hub()
    v = Variator(d.replace(name="random", **json.loads(FIELDS_3903)), f, "double",
                 traction_law="viscoelastic")  # fmt: skip
    ratio, rpm = 1.1265220727976604, 6364.077182642165
    rows = OperatingRows.of(v, np.full(15, ratio), np.full(15, rpm * np.pi / 30), None,
                            v.clamp_law("cam", None), v.options)  # fmt: skip
    got = evaluate_points(rows, TORQUES_3903)
    solved = v.solve(ratio, TORQUES_3903[13], clamp_law="cam", input_speed_rpm=rpm)
    assert got["status"][13] == 0  # 1 (beyond) before
    assert got["eta"][13] == pytest.approx(solved.eta, abs=1e-8)
    assert all(got["status"][:13] != 0)  # below the island
    with pytest.raises(TractionLimitError):  # where `solve` finds no equilibrium either
        v.solve(ratio, TORQUES_3903[3], clamp_law="cam", input_speed_rpm=rpm)
