"""Regressions of the optimal clamping law found by the hardening campaign (issue 23,
``python benchmarks/harden.py --task 2026:N``): every path refuses alike, and the
capacity search finds the force of the largest limiting torque."""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest

from ballcvt import Variator, load_builtin
from ballcvt.errors import InputError, TractionLimitError

# A design whose peak pressure at the optimal law's min_force (100 N) already exceeds
# max_pressure (3 GPa): tasks 2026:2877 (isothermal) and 2026:3480 (viscoelastic).
TASK_2877 = (
    '{"aspect_ratio": 33.647626207683146, "roller_radius": 0.0022066813559994273, '
    '"theta0_deg": 46.881057537785516, "theta2_deg": 78.23997660054411, '
    '"alpha_deg": 48.60641267328379, "n_rollers": 4, '
    '"roller_bearing_diameter": 0.00011925566089517184, '
    '"idler_bearing_diameter": 0.00047355996363177276, "disc_groove_ratio": 40.33929771574016, '
    '"idler_groove_ratio": 1.8903422706133852, "single_idler_groove_ratio": Infinity, '
    '"tilt_safety_factor": 0.7618636441924336, "creep_limit": 0.05932476996469723, '
    '"min_roller_gap": 7.2017228401158265e-06}'
)
TASK_3480 = (
    '{"aspect_ratio": 1.7298191799674418, "roller_radius": 0.005825628936619141, '
    '"theta0_deg": 29.569929052471753, "theta2_deg": 14.688033641794831, '
    '"alpha_deg": 73.5559182207278, "n_rollers": 7, '
    '"roller_bearing_diameter": 0.0023630258104654915, '
    '"idler_bearing_diameter": 0.00029961552618995016, "disc_groove_ratio": 69.63546992520158, '
    '"idler_groove_ratio": 3.8892207118316886, "single_idler_groove_ratio": Infinity, '
    '"tilt_safety_factor": 0.24160154902920516, "creep_limit": 0.02373071086164815, '
    '"min_roller_gap": 3.228252009188315e-05}'
)


def _variator(fields: str, law: str) -> Variator:
    d, f = load_builtin("table1")
    return Variator(d.replace(name="random", **json.loads(fields)), f, "double", traction_law=law)


@pytest.mark.parametrize(
    "fields, law, ratio, rpm",
    [
        (TASK_2877, "isothermal", 0.18167843062938144, 13148.992456407552),
        (TASK_3480, "viscoelastic", 0.9777208182091114, 413.1221411730119),
    ],
)
def test_optimal_refuses_empty_force_range_on_every_path(fields, law, ratio, rpm):
    """2026:2877, 2026:3480: `solve` refused (peak pressure at min_force above
    max_pressure) but `limit_torque` reported 0.28 / 0.82 N m."""
    v = _variator(fields, law)
    kw = {"clamp_law": "optimal", "input_speed_rpm": rpm}
    calls = {
        "solve": lambda: v.solve(ratio, 0.1, **kw),
        "limit_torque": lambda: v.limit_torque(ratio, **kw),
        "capacity": lambda: v.capacity(ratio, **kw),
        "sweep": lambda: v.sweep(ratio=ratio, output_torque=[0.0, 0.1], **kw),
    }
    messages = set()
    for name, call in calls.items():
        with pytest.raises(InputError) as err:
            call()
        assert type(err.value) is InputError, name
        messages.add(str(err.value))
    (message,) = messages  # one message, the same from every path
    assert "\n" not in message
    assert "max_pressure" in message and "min_force = 100 N" in message
    assert "raise max_pressure or lower min_force" in message


# 2026:4546: the limiting torque peaks at about 68 kN, below the pressure bound F_p
# (96.7 kN); the scan's best force was F_p and was kept.
TASK_4546 = (
    '{"aspect_ratio": 4.673148467852668, "roller_radius": 0.0729194384669077, '
    '"theta0_deg": 45.296065226165155, "theta2_deg": 45.39526044909398, '
    '"alpha_deg": 29.0524009259784, "n_rollers": 10, '
    '"roller_bearing_diameter": 0.010287296312787214, '
    '"idler_bearing_diameter": 0.02152426811470828, "disc_groove_ratio": 1.7517581408872416, '
    '"idler_groove_ratio": 2.2573338876124494, "single_idler_groove_ratio": 4.686741569908589, '
    '"tilt_safety_factor": 0.7396640943185151, "creep_limit": 0.0809571601738469, '
    '"min_roller_gap": 0.0009233873085799592}'
)


def test_optimal_capacity_finds_peak_below_pressure_bound():
    """2026:4546: solve converged at 1789.58 N m, 1.031 x the reported limit 1735.35 N m
    (the limit at F_p); the limit peaks near 68 kN at about 1836.4 N m."""
    v = _variator(TASK_4546, "isothermal")
    ratio, rpm = 3.9329923939731093, 84.08804415981695
    limit = v.limit_torque(ratio, clamp_law="optimal", input_speed_rpm=rpm)
    assert limit >= 1836.4
    # no constant force up to the pressure bound carries more (to 1e-3)
    constant = [
        v.limit_torque(ratio, clamp_force=f, input_speed_rpm=rpm)
        for f in np.geomspace(40e3, 96e3, 9)
    ]
    assert max(constant) <= limit * (1 + 1e-3)
    assert v.solve(ratio, 1789.5799942363294, clamp_law="optimal", input_speed_rpm=rpm).converged
    with pytest.raises(TractionLimitError):
        v.solve(ratio, 1.001 * limit, clamp_law="optimal", input_speed_rpm=rpm)


# 2026:124 (thermal, single idler): a lookup table (four points batched) chose other forces
# than limit_torque (one point) and reported 30.8 N m where limit_torque gave 233 N m.
TASK_124 = (
    '{"aspect_ratio": 3.4670130275144313, "roller_radius": 0.030299734257498417, '
    '"theta0_deg": 47.21773513241391, "theta2_deg": 43.885068642803375, '
    '"alpha_deg": 11.511802721120487, "n_rollers": 7, '
    '"roller_bearing_diameter": 0.00852226012126403, '
    '"idler_bearing_diameter": 0.0067434542965305955, "disc_groove_ratio": 1.4529350234168292, '
    '"idler_groove_ratio": 4.657299799465973, "single_idler_groove_ratio": 4.8406152410665415, '
    '"tilt_safety_factor": 0.7158780411344113, "creep_limit": 0.14585105376837615, '
    '"min_roller_gap": 0.0021050649170601832}'
)


def test_thermal_capacity_force_does_not_depend_on_the_batch():
    """2026:124: under the thermal law a lookup table (four points batched) chose other
    forces than `limit_torque` (one point): the limit at a force, a continuation to the
    fold stopped by a step failing at the solver's tolerance, depended on the batch. Each
    point was then searched alone. Since session 37 the points are searched in one batch,
    the limit at a force being the walk's and the climb's, each point's own, with every
    point's Newton iterates its own (``split_min`` 1, no predictor stage: the options the
    search takes): the forces and the limits found for each point of a batch are the same
    bits as alone (here also Table I's drive at three ratios in one batch)."""
    from ballcvt.equilibrium.problem import build_problem
    from ballcvt.solvers import optimal_capacity
    from ballcvt.solvers.limit import limit_search
    from ballcvt.units import rpm_to_rad_s

    d, f = load_builtin("table1")
    v = Variator(d.replace(name="random", **json.loads(TASK_124)), f, "single",
                 traction_law="thermal")  # fmt: skip
    ratio, rpm = 0.2319683468011616, 5136.558372831595
    ratios = np.array([ratio, ratio, ratio * 1.001, ratio * 1.001])
    speeds = rpm_to_rad_s(np.array([rpm, rpm * 1.05, rpm, rpm * 1.05]))
    pb = build_problem(v.design, v.fluid, v.architecture, ratios, 0.0, np.ones(4), speeds)
    p_lim, c_lim = v.design.max_pressure, v.design.creep_limit
    batch = optimal_capacity.capacity_force(pb, p_lim, c_lim, 100.0, v.options)
    alone = [
        float(optimal_capacity.capacity_force(pb.take(np.array([i])), p_lim, c_lim, 100.0,
                                              v.options)[0])
        for i in range(4)
    ]  # fmt: skip
    assert batch.tolist() == alone
    t1 = Variator(traction_law="thermal")
    own = replace(t1.options, split_min=1, predictor_min_points=10**9)
    rows = build_problem(t1.design, t1.fluid, t1.architecture, np.array([0.6, 1.3, 1.9]), 0.0,
                         np.array([900.0, 2500.0, 6000.0]), rpm_to_rad_s(2000.0)).flat()  # fmt: skip
    together = limit_search(rows, t1.design.creep_limit, own).torque
    apart = [limit_search(rows.take(np.array([i])), t1.design.creep_limit, own).torque[0]
             for i in range(3)]  # fmt: skip
    assert np.isfinite(together).all() and together.tolist() == apart


# Harden task 0:28: a hub-derived design whose efficiency has a kink in the clamping force
# next to its optimum (3827 N: the slope falls from +2e-6 to -0.7e-6 per N).
TASK_0_28 = (
    '{"aspect_ratio": 4.731570287476876, "roller_radius": 0.017228841031036553, '
    '"theta0_deg": 45.08868892823976, "theta2_deg": 52.69776781233699, '
    '"alpha_deg": 9.524291373185298, "n_rollers": 9, '
    '"roller_bearing_diameter": 0.005172236195644021, '
    '"idler_bearing_diameter": 0.004827810839893421, "disc_groove_ratio": 1.6451820903188903, '
    '"idler_groove_ratio": 3.0401146183893175, "single_idler_groove_ratio": 14.748098338264537, '
    '"tilt_safety_factor": 0.7065229652401077, "creep_limit": 0.089833878284545, '
    '"min_roller_gap": 0.0019800285619062615, "cam": {"disc": "input", '
    '"preload": 3221.917120644948, "ramp_angle_deg": 10.088707023741865, '
    '"mean_radius": 0.021574065371601864, "friction": 0.04507258810681003}}'
)


def test_optimal_sweep_equals_solve_at_a_kink_of_the_efficiency():
    """0:28: with the first round of a large batch alone on the coarse rule (3bf7d44), a
    table or sweep certified 3839 N and `solve` 3827 N, 1.6e-5 apart in efficiency; every
    batch size now takes the same path (`ballcvt.solvers.optimal_batch._first_round`)."""
    from ballcvt.api import with_oil_temperature

    d, f = load_builtin("hub")
    d = d.replace(name="random", **json.loads(TASK_0_28))
    v = with_oil_temperature(Variator(d, f, "double", traction_law="isothermal"), "fixed")
    ratio, top, rpm = 0.8855605378778486, 291.30494426069623, 298.27855595515643
    kw = {"clamp_law": "optimal", "input_speed_rpm": rpm}
    ds = v.sweep(ratio=[ratio], output_torque=np.linspace(top / 12, top, 12), progress=False, **kw)
    one = v.solve(ratio, top, **kw)
    assert float(ds["eta"].values.ravel()[-1]) == pytest.approx(one.eta, abs=1e-6)
    assert float(ds["clamp_force"].values.ravel()[-1]) == pytest.approx(one.clamp_force, rel=1e-6)
