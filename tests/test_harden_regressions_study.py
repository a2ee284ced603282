"""Campaign regression (issue 23, seed 2029, task 2727) of the study evaluation: a cam on
the input disc whose fixed point runs away at a high torque was clipped at the force of the
Roelands overflow pressure (`ballcvt.solvers.clamped.pressure_bound_force`); the problem
rebuilt there came out one round-off above that pressure and was refused, which failed the
whole design, while `Variator.solve` solved its other points (docs/model.md §10, §11)."""

import json

import numpy as np

from ballcvt import Variator, load_builtin
from ballcvt.analysis.studies.evaluate import evaluate_chunk, make_context
from ballcvt.analysis.studies.spec import StudySpec
from ballcvt.equilibrium.problem import build_problem
from ballcvt.solvers.clamped import pressure_bound_force, with_clamp

# 2029:2727 (visco-elastic, single, cam on the input disc, carrier held)
FIELDS = json.loads(
    '{"aspect_ratio": 97.15018969391978, "roller_radius": 0.3450702297348293, '
    '"theta0_deg": 23.26285741542518, "theta2_deg": 26.85054496103646, '
    '"alpha_deg": 83.63048442778303, "n_rollers": 21, '
    '"roller_bearing_diameter": 0.034566054562587635, '
    '"idler_bearing_diameter": 0.31819387398929677, "disc_groove_ratio": Infinity, '
    '"idler_groove_ratio": 1.058197265014879, "single_idler_groove_ratio": 1.5063523531000542, '
    '"tilt_safety_factor": 0.7380331965117761, "creep_limit": 0.44488561936543813, '
    '"min_roller_gap": 0.007464673266908551, "cam": {"disc": "input", '
    '"preload": 75045.15333817796, "ramp_angle_deg": 17.02709030539163, '
    '"mean_radius": 0.38136531948587976, "friction": 0.034886375102174086}}'
)
RATIO, RPM = 1.3591587599419814, 188.93206278278498
#: a torque both paths solve, and one whose cam fixed point runs away to the bound
TORQUES = [9355.943066437867, 39566.90341042956]


def _study() -> StudySpec:
    fixed = {k: v for k, v in FIELDS.items() if k != "n_rollers"}
    return StudySpec.model_validate(
        {
            "study": {
                "name": "harden",
                "drive": "table1",
                "samples": 1,
                "architecture": "single",
                "traction_law": "viscoelastic",
                "capacity_ratios": [RATIO],
            },
            "parameters": {"n_rollers": {"values": [21]}},
            "fixed": fixed,
            "operating": {
                "ratio": [RATIO],
                "output_torque": TORQUES,
                "input_speed_rpm": [RPM],
                "clamp_law": "cam",
            },
            "objectives": {"eta_mean": "max", "capacity": "max"},
        }
    )


def test_study_evaluates_the_point_solve_solves():
    out = evaluate_chunk(make_context(_study()), np.arange(1), np.array([[21.0]]))
    # the runaway point is flagged, not raised: the design is judged, not "not solved"
    assert "Roelands" not in out["reason"][0]
    assert list(out["point_status"][0]) == [0, 1]
    d, f = load_builtin("table1")
    v = Variator(d.replace(name="random", **FIELDS), f, "single", traction_law="viscoelastic")
    res = v.solve(RATIO, TORQUES[0], clamp_law="cam", input_speed_rpm=RPM)
    assert res.converged
    assert abs(out["eta"][0, 0] - res.eta) <= 1e-9


def test_problem_at_the_roelands_bound_is_built():
    d, f = load_builtin("table1")
    design = d.replace(name="random", **FIELDS)
    fluid = f.with_traction_law("viscoelastic")
    for force in np.geomspace(1e3, 1e10, 60):
        pb = build_problem(design, fluid, "single", RATIO, 1000.0, force, 20.0)
        with_clamp(pb, pressure_bound_force(pb, np.inf))  # no InputError


# 3005:3406 (all cases, session 30; isothermal, single, optimal clamp, carrier held): a
# 53-roller drive at 0.92 MN m, 4.3 rpm. The optimum lies on the creep bound; the study's
# force left a creep 1.8e-9 of itself over the limit, which `solve` carries (within
# `CREEP_RTOL`, as every refusal) and the study's admissibility test (`solve_admissible`,
# no margin before session 31) refused: status 1 where solve converged.
FIELDS_3406 = json.loads(
    '{"aspect_ratio": 63.16967595723492, "roller_radius": 0.2717469464948747, '
    '"theta0_deg": 52.29435237318947, "theta2_deg": 85.12690504108912, '
    '"alpha_deg": 67.93228132206043, "n_rollers": 53, '
    '"roller_bearing_diameter": 0.07582134436599156, '
    '"idler_bearing_diameter": 0.04413288307264726, "disc_groove_ratio": 1.0125345804319403, '
    '"idler_groove_ratio": 3.9027189480838955, "single_idler_groove_ratio": 10.202446611280685, '
    '"tilt_safety_factor": 0.8048334954825113, "creep_limit": 0.06884179964555406, '
    '"min_roller_gap": 0.003667356246331326, "cam": {"disc": "output", '
    '"preload": 20240.733001216428, "ramp_angle_deg": 16.397992024932755, '
    '"mean_radius": 0.30313265599957484, "friction": 0.024696421384477158}}'
)
RATIO_3406, RPM_3406, TORQUE_3406 = 0.10408978365716394, 4.321927821873086, 921215.6153196994


def test_an_optimal_force_on_the_creep_bound_is_admissible_to_the_study_as_to_solve():
    fixed = {k: v for k, v in FIELDS_3406.items() if k != "n_rollers"}
    operating = {"output_torque": [TORQUE_3406], "input_speed_rpm": [RPM_3406],
                 "clamp_law": "optimal"}  # fmt: skip
    spec = _one_design("isothermal", RATIO_3406, fixed, 53, operating, oil_temperature="fixed")
    out = evaluate_chunk(make_context(spec), np.arange(1), np.array([[53.0]]))
    assert list(out["point_status"][0]) == [0]
    d, f = load_builtin("table1")
    v = Variator(d.replace(name="random", **FIELDS_3406), f, "single")
    res = v.solve(RATIO_3406, TORQUE_3406, clamp_law="optimal", input_speed_rpm=RPM_3406)
    assert abs(out["eta"][0, 0] - res.eta) <= 1e-6


# 3103:847 (all cases, session 31; visco-elastic, single, cam on the input disc): the cam's
# fixed point stepped to a negative force (Wegstein's step on a curved law,
# `ballcvt.solvers.clamped._wegstein`) and the study's whole design failed, status 2,
# where `Variator` solves its points.
FIELDS_847 = json.loads(
    '{"aspect_ratio": 2.9739349192170543, "roller_radius": 0.037249859551069006, '
    '"theta0_deg": 58.398743655110216, "theta2_deg": 39.134764191959164, '
    '"alpha_deg": 23.024781701146637, "idler_bearing_diameter": 0.007432530876024789, '
    '"roller_bearing_diameter": 0.012418098396548352, "disc_groove_ratio": 1.9475264934078376, '
    '"idler_groove_ratio": 3.434936992746253, "single_idler_groove_ratio": 18.280249940123557, '
    '"tilt_safety_factor": 0.8372754737299692, "creep_limit": 0.15713645605017537, '
    '"min_roller_gap": 0.0007281126323060228, "cam": {"disc": "input", '
    '"preload": 102.96004708864673, "ramp_angle_deg": 9.292149764336662, '
    '"mean_radius": 0.04935885153609169, "friction": 0.036494925682594465}}'
)
TORQUES_847 = [18.26248202335848, 4.378654027206467, 22.67778639703789, 13.463341952431263,
               19.787196595813622, 12.095524733311011, 4.346410136149618, 4.089703335787668,
               20.321504021372125, 11.594162838040017, 2.6868104934299724, 21.769721848192674,
               6.483003191320989, 34.457412321463295, 49.77181779766921]  # fmt: skip


def test_a_cam_step_past_zero_force_does_not_fail_the_design():
    ratio, rpm = 1.8593108225960322, 288.29739878910965
    operating = {"output_torque": TORQUES_847, "input_speed_rpm": [rpm], "clamp_law": "cam"}
    spec = _one_design("viscoelastic", ratio, FIELDS_847, 11, operating, oil_temperature="fixed")
    out = evaluate_chunk(make_context(spec), np.arange(1), np.array([[11.0]]))
    assert "clamp_force" not in out["reason"][0]
    d, f = load_builtin("table1")
    v = Variator(d.replace(name="random", n_rollers=11, **FIELDS_847), f, "single",
                 traction_law="viscoelastic")  # fmt: skip
    for j in np.flatnonzero(out["point_status"][0] == 0)[:3]:
        res = v.solve(ratio, TORQUES_847[j], clamp_law="cam", input_speed_rpm=rpm)
        assert abs(out["eta"][0, j] - res.eta) <= 1e-9


def _one_design(law, ratio, fixed, n_rollers, operating, **study):
    """A harden study of one design (``n_rollers`` its one parameter) at one ratio."""
    return StudySpec.model_validate(
        {
            "study": {"name": "harden", "drive": "table1", "samples": 1,
                      "architecture": "single", "traction_law": law,
                      "capacity_ratios": [ratio], **study},
            "parameters": {"n_rollers": {"values": [n_rollers]}},
            "fixed": fixed,
            "operating": {"ratio": [ratio], **operating},
            "objectives": {"eta_mean": "max", "capacity": "max"},
        }
    )  # fmt: skip
