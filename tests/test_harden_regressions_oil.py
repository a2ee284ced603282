"""Harden task 4242:951 (session 16, the campaign run with the drives' own oil models,
``HARDEN_OIL=drive``): the optimal clamp under the hub's oil heat balance at a point where
no clamping force carries even zero torque. The balance's limit point then found no
admissible torque, and `api.oil.limit_with_oil` compared the empty `Capacity` itself with
zero: a TypeError. It is now refused in one line, as at a fixed oil."""

import json

import numpy as np
import pytest

from ballcvt import Variator, load_builtin
from ballcvt.errors import InputError, TractionLimitError

FIELDS = json.loads(
    '{"aspect_ratio": 3.984068845432138, "roller_radius": 0.016744705901889763, '
    '"theta0_deg": 40.13702294699061, "theta2_deg": 52.38991569735095, '
    '"alpha_deg": 18.172229153658957, "n_rollers": 7, '
    '"roller_bearing_diameter": 0.0022580547806748683, '
    '"idler_bearing_diameter": 0.011813279421136661, "disc_groove_ratio": 4.402706008328007, '
    '"idler_groove_ratio": 2.984465193360027, "single_idler_groove_ratio": 18.140661686734365, '
    '"tilt_safety_factor": 0.6850785918427186, "creep_limit": 0.11031957063366421, '
    '"min_roller_gap": 0.0015013946237711882, "cam": {"disc": "output", '
    '"preload": 2284.416153297007, "ramp_angle_deg": 6.129778976338305, '
    '"mean_radius": 0.027114616069329158, "friction": 0.0007028691859399805}}'
)


def test_no_admissible_torque_under_the_oil_balance_is_refused():
    design, fluid = load_builtin("hub")
    v = Variator(design.replace(name="random", **FIELDS), fluid, "single",
                 traction_law="viscoelastic")  # fmt: skip
    assert v.design.models.oil_temperature == "balance"
    with pytest.raises(TractionLimitError, match="no clamping force"):
        v.solve(0.798144430811826, 0.0, clamp_law="optimal", input_speed_rpm=64928.38950606848)


FIELDS_863 = json.loads(
    '{"aspect_ratio": 1.2191992264694425, "roller_radius": 0.02810016206953253, '
    '"theta0_deg": 35.25840373900531, "theta2_deg": 51.3040266005169, '
    '"alpha_deg": 2.8799870311459337, "n_rollers": 6, '
    '"roller_bearing_diameter": 0.02575861020657367, '
    '"idler_bearing_diameter": 0.0031997092835864206, "disc_groove_ratio": 2.323546693444718, '
    '"idler_groove_ratio": 1.5203818306257366, "single_idler_groove_ratio": 9.72351911273427, '
    '"tilt_safety_factor": 0.6582755574992313, "creep_limit": 0.15579692221733976, '
    '"min_roller_gap": 0.0006827891313145859}'
)


def test_a_point_beyond_the_capacity_on_the_way_to_its_balance_has_losses():
    """Harden task 4242:863: a sweep's limit under the oil balance 0.26 % under
    `limit_torque`'s (94.240 against 94.490 N m, where the oil runs away above 150 C). At
    94.287 N m the point is carried at its balance (148.7 C, creep 0.141 < 0.156) but
    beyond the creep limit at 109 C (creep 0.1564), where the admissibility test stopped
    its run as soon as the creep passed the limit: no losses at that rung, so the ladder
    refused it there. `evaluate_points(beyond=True)` now solves such points on (as `solve`
    with ``check_capacity=False`` does); the sweep's limit is then limit_torque's to 1e-15
    (a 131-rung ladder: 46 s, not run here)."""
    import numpy as np

    from ballcvt.analysis.sweeps.curves import OperatingRows
    from ballcvt.analysis.sweeps.points import evaluate_points
    from ballcvt.model.oil import fluid_at
    from ballcvt.params.drive import Drive

    design, fluid = load_builtin("hub")
    design = design.replace(name="random", **FIELDS_863)
    fluid = fluid_at(fluid.with_traction_law("viscoelastic"), 382.15)
    rows = OperatingRows.of(Drive(design, fluid, "single"), [0.2913899611465347],
                            [697.2780370252146 * np.pi / 30], [2985.521529660266], None)  # fmt: skip
    got = evaluate_points(rows, np.array([94.287]), beyond=True)
    assert got["status"][0] == 1  # beyond the creep limit at this oil temperature
    assert 0.76 < got["eta"][0] < 0.77 and got["losses"][0].min() >= 0.0  # 0.76618
    assert np.isnan(evaluate_points(rows, np.array([94.287]))["eta"][0])  # the default


FIELDS_30 = json.loads(
    '{"aspect_ratio": 1.2405409561313507, "roller_radius": 0.02781995724176246, '
    '"theta0_deg": 58.45367582111593, "theta2_deg": 54.23295667905798, '
    '"alpha_deg": 24.460889511989897, "n_rollers": 3, '
    '"roller_bearing_diameter": 0.021316620621591783, '
    '"idler_bearing_diameter": 0.007060641320250169, '
    '"disc_groove_ratio": 1.7884782056845592, "idler_groove_ratio": 1.5266691474398812, '
    '"single_idler_groove_ratio": Infinity, "tilt_safety_factor": 0.5270806351742231, '
    '"creep_limit": 0.1010927501862938, "min_roller_gap": 0.00048546611329105264, '
    '"cam": {"disc": "output", "preload": 344.79279879064995, '
    '"ramp_angle_deg": 6.005124470002885, "mean_radius": 0.05353387789268339, '
    '"friction": 0.03736826943267844}}'
)
#: Harden task 2719:30's cycle: output speeds [rad/s] and torques [N m], one step a second.
SPEED_30 = [3.6102836963802187, 3.643833122739064, 3.540902244030548, 3.529688130239486, 3.573963857828056, 3.6629173161795663, 3.6915571762294705, 3.6095286957010604, 3.504514727658006, 3.658360450932037, 3.528313521895382, 3.54432608014051, 3.5033029619667273, 3.710350177425629, 3.694231197001443]
TORQUE_30 = [10.08840916451613, 11.943188970729132, 5.774342507495622, 10.74012152488915, 11.687117195579717, 8.550663173522565, 7.907888962154971, 6.093869344227491, 7.833582204427633, 11.773120077441915, 6.9116394426075844, 1.3282935384438348, 10.277171146703132, 19.454316026670796, 28.100678705191147]


def test_a_cycle_step_near_a_flag_change_of_its_runs_is_solved_at_its_oil_temperature():
    """Harden task 2719:30 (session 19): a cycle under the oil's transient, every step near
    the creep limit (0.101) at 20 C ambient. A step's efficiency there falls 9e-3 per K of
    oil, and at 21 C the step is beyond the capacity: with the run at 21 C failed, the step
    took the 20 C run's row as it was, 1.4e-5 above `solve` at its own 20.0015 C. A step
    whose four runs do not share its status and flag is now solved alone at its own
    temperature: the same as `solve` there (here to the bit)."""
    import numpy as np

    from ballcvt.analysis.cycle_files import cycle_from_arrays
    from ballcvt.api import CycleSettings, with_oil_temperature

    design, fluid = load_builtin("hub")
    v = Variator(design.replace(name="random", **FIELDS_30), fluid, "single",
                 traction_law="viscoelastic")  # fmt: skip
    cycle = cycle_from_arrays(time=np.arange(15.0), output_speed=SPEED_30,
                              output_torque=TORQUE_30)  # fmt: skip
    res = v.run_cycle(cycle, clamp_law="cam",
                      settings=CycleSettings(target_input_speed_rpm=28.20188519097594,
                                             progress=False))  # fmt: skip
    assert res.summary["oil_temperature"]["steps_solved_alone"] >= 1
    solved = 0
    for row in res.steps.to_dict("records"):
        if row["status"] != 0:
            continue
        hot = with_oil_temperature(v, row["oil_temperature_C"] + 273.15)
        ref = hot.solve(row["ratio"], row["output_torque"], clamp_law="cam",
                        input_speed_rpm=row["input_speed_rpm"])  # fmt: skip
        assert abs(row["eta"] - ref.eta) <= 1e-9
        solved += 1
    assert solved == 5


FIELDS_153 = json.loads(
    '{"aspect_ratio": 6.640757154305697, "roller_radius": 0.008199572924710338, '
    '"theta0_deg": 56.8420093376884, "theta2_deg": 70.70731018288711, '
    '"alpha_deg": 84.0840444500404, "n_rollers": 9, '
    '"roller_bearing_diameter": 0.004020011004438964, '
    '"idler_bearing_diameter": 0.0008702183439789268, '
    '"disc_groove_ratio": 1.0713664011687816, "idler_groove_ratio": Infinity, '
    '"single_idler_groove_ratio": 5.5132759832279055, '
    '"tilt_safety_factor": 0.6150022644630091, "creep_limit": 0.24620773760943332, '
    '"min_roller_gap": 0.0003808865853319412, "cam": {"disc": "output", '
    '"preload": 123.4603487137352, "ramp_angle_deg": 17.636898652827703, '
    '"mean_radius": 0.0248646214988077, "friction": 0.001893971269180178}}'
)


def test_a_limit_curve_whose_capacity_vanishes_between_two_rungs_is_balanced_alone():
    """Harden task 2719:153 (session 19): under the oil balance, a drive whose capacity is
    0.082 N m with the oil at 20 C and none at 30-50 C (not even zero torque carried). The
    limit curve's ladder (rungs 10 K apart) found no limit point at 30 C and gave NaN;
    `limit_torque` (one balance, Brent's method on the limit point's loss) found 0.0416 N m
    at 23 C. Such a row is now balanced alone between its two rungs: the same limit."""
    design, fluid = load_builtin("hub")
    v = Variator(design.replace(name="random", **FIELDS_153), fluid, "single",
                 traction_law="viscoelastic")  # fmt: skip
    kw = dict(clamp_law="cam", input_speed_rpm=562.4551095892948)
    ratio = 0.18771236364447458
    limit = v.limit_torque(ratio, **kw)
    curve = v.limit_curve([ratio], progress=False, **kw)
    assert limit == pytest.approx(0.0416, rel=1e-3)
    assert curve.torque[0] == pytest.approx(limit, rel=1e-6)
    assert 20.0 < curve.oil_temperature[0] - 273.15 < 30.0


FIELDS_2720_11 = json.loads(
    '{"aspect_ratio": 2.4045693728679307, "roller_radius": 0.00935547022285549, '
    '"theta0_deg": 44.976325324004705, "theta2_deg": 44.862266460799525, '
    '"alpha_deg": 13.93591573690753, "n_rollers": 3, '
    '"roller_bearing_diameter": 0.004957467637503604, '
    '"idler_bearing_diameter": 0.008328764115360163, '
    '"disc_groove_ratio": 3.1374049673726687, "idler_groove_ratio": 2.4612088437858506, '
    '"single_idler_groove_ratio": Infinity, "tilt_safety_factor": 0.6655134260728978, '
    '"creep_limit": 0.05008791163109262, "min_roller_gap": 0.0008260827806432416, '
    '"cam": {"disc": "output", "preload": 37.8828925568106, '
    '"ramp_angle_deg": 2.015261230323121, "mean_radius": 0.009171311516467983, '
    '"friction": 0.03575234546771804}}'
)


def test_an_optimal_clamp_trial_of_the_oil_balance_says_its_capacity_at_its_own_oil():
    """Harden task 2720:11 (session 19): the limit with the optimal clamp under the oil
    balance. A trial of the balance (a solve at a fixed oil temperature) whose optimiser
    found no force asked the drive's capacity to say why, and the capacity ran the drive
    file's balance, whose trials solved the point again: a RecursionError. The capacity is
    now the trial's own, at its fixed oil."""
    design, fluid = load_builtin("hub")
    v = Variator(design.replace(name="random", **FIELDS_2720_11), fluid, "single",
                 traction_law="viscoelastic")  # fmt: skip
    kw = dict(clamp_law="optimal", input_speed_rpm=332.1808171241499)
    limit = v.limit_torque(0.30322941254576086, **kw)
    assert limit >= 0.0
    v.solve(0.30322941254576086, limit, **kw)  # carried there


FIELDS_2720_23 = json.loads(
    '{"aspect_ratio": 1.801723800621378, "roller_radius": 0.018737781036281164, '
    '"theta0_deg": 39.876581830167, "theta2_deg": 61.896867889035, '
    '"alpha_deg": 20.02340726495088, "n_rollers": 8, '
    '"roller_bearing_diameter": 0.00530163988305487, '
    '"idler_bearing_diameter": 0.006643168716552575, '
    '"disc_groove_ratio": 2.996357682272229, "idler_groove_ratio": 4.842584996758772, '
    '"single_idler_groove_ratio": Infinity, "tilt_safety_factor": 0.6452125453273726, '
    '"creep_limit": 0.1628785693067723, "min_roller_gap": 0.0003053354499746505, '
    '"cam": {"disc": "output", "preload": 1608.826103156056, '
    '"ramp_angle_deg": 5.080526251199557, "mean_radius": 0.05375347904484559, '
    '"friction": 0.011562571869675103}}'
)


def test_a_drive_whose_oil_runs_away_at_every_torque_has_no_balanced_limit():
    """Harden task 2720:23 (session 19): at 8243 rpm the drive loses
    5.5 kW at zero torque with the oil at 150 C, 11 times what its housing rejects: every
    torque runs away. `limit_torque` reported the 150 C oil's limit, 9.17 N m, and the
    limit curve too, which `solve` refuses. Both now say there is none: `limit_torque`
    raises the runaway, as `solve` does at zero torque, and the curve is NaN."""
    design, fluid = load_builtin("hub")
    v = Variator(design.replace(name="random", **FIELDS_2720_23), fluid, "single",
                 traction_law="isothermal")  # fmt: skip
    kw = dict(clamp_force=353.89167369998955, input_speed_rpm=8242.689514121577)
    ratio = 0.9966910158760929
    with pytest.raises(InputError, match="runaway"):
        v.solve(ratio, 0.0, **kw)
    with pytest.raises(InputError, match="runaway"):
        v.limit_torque(ratio, **kw)
    curve = v.limit_curve([ratio], progress=False, **kw)
    assert np.isnan(curve.torque[0])
