"""Campaign regressions (issue 23, seed 2026) of the limiting torque: the fold of the
thermal law's branch from zero torque, and the creep at the limit (docs/model.md §8, §14).
Each test uses the campaign's inputs (/work/campaign/failures.jsonl, ``inputs.task``)."""

import json

import numpy as np
import pytest

from ballcvt import TractionLimitError, Variator, load_builtin
from ballcvt.api import with_oil_temperature
from ballcvt.solvers.continuation import REACH_STEP, continue_in_torque
from ballcvt.solvers.newton import branch_pinned, branch_solver
from ballcvt.solvers.options import at_residual_floor
from ballcvt.solvers.peak import peak_limits


def _drive(arch: str, law: str, fields: str, base: str = "table1") -> Variator:
    d, f = load_builtin(base)
    v = Variator(d.replace(name="random", **json.loads(fields)), f, arch, traction_law=law)
    return v if base == "table1" else with_oil_temperature(v, "fixed")


# 2026:1867 (visco-elastic, double, constant force)
V1867 = (
    "double",
    "viscoelastic",
    '{"aspect_ratio": 2.2806740011587983, "roller_radius": 0.01639939475665482, '
    '"theta0_deg": 64.12054199733294, "theta2_deg": 61.02155487851976, '
    '"alpha_deg": 3.5380891972843713, "n_rollers": 6, '
    '"roller_bearing_diameter": 0.009006941896407349, '
    '"idler_bearing_diameter": 0.00951626510032902, "disc_groove_ratio": 2.767942696333404, '
    '"idler_groove_ratio": 1.7619824025032502, "single_idler_groove_ratio": 6.941674559869742, '
    '"tilt_safety_factor": 0.936988527643371, "creep_limit": 0.09685324254621483, '
    '"min_roller_gap": 0.0011570397470541123}',
)
# 2026:2534 (thermal, single, constant force)
V2534 = (
    "single",
    "thermal",
    '{"aspect_ratio": 2.819485160206485, "roller_radius": 0.061113825023360845, '
    '"theta0_deg": 29.933380713197494, "theta2_deg": 60.14057651745948, '
    '"alpha_deg": 6.023354253725852, "n_rollers": 7, '
    '"roller_bearing_diameter": 0.039395549093931996, '
    '"idler_bearing_diameter": 0.042943874225527964, "disc_groove_ratio": 1.4618242818128762, '
    '"idler_groove_ratio": 4.406434310524949, "single_idler_groove_ratio": Infinity, '
    '"tilt_safety_factor": 0.6748468310795117, "creep_limit": 0.190040481909812, '
    '"min_roller_gap": 0.0009468266621847557}',
)
# 2026:2324 (thermal, single, optimal clamp: its capacity force 10432.91 N)
V2324 = (
    "single",
    "thermal",
    '{"aspect_ratio": 4.303217617245469, "roller_radius": 0.03850282468326104, '
    '"theta0_deg": 57.79678913236697, "theta2_deg": 47.868181639850874, '
    '"alpha_deg": 16.239365774632347, "n_rollers": 3, '
    '"roller_bearing_diameter": 0.03326918117850691, '
    '"idler_bearing_diameter": 0.01225715675442805, "disc_groove_ratio": 3.1868120455258717, '
    '"idler_groove_ratio": 1.5647280535147496, "single_idler_groove_ratio": 10.285232649166005, '
    '"tilt_safety_factor": 0.5786807437074853, "creep_limit": 0.12617880036389634, '
    '"min_roller_gap": 0.002374977284779246}',
)
P2324 = {"ratio": 1.4765078255711066, "clamp_force": 10432.91369231, "rpm": 708.703584065388}


def _problem(v, ratio, force, rpm):
    return v._capacity_basis(ratio, force, None, (None, rpm), None)[0].flat()


def test_creep_at_the_limit_within_the_creep_limit():
    """2026:1867: a solve at the reported limit had |C| 1.07e-9 (relative) above
    ``creep_limit``, unflagged: the pinned creep sat exactly at the limit and the solve
    meets it only to its tolerance. Now pinned just below it."""
    v = _drive(*V1867)
    kw = {"clamp_force": 204.59101903143033, "input_speed_rpm": 1796.4406637501907}
    lim = v.limit_torque(5.81666290612291, **kw)
    r = v.solve(5.81666290612291, lim, **kw)
    assert max(abs(c.creep) for c in r.contacts.values()) <= v.design.creep_limit


def test_thermal_limit_is_the_fold_constant_force():
    """2026:2534: the torque continuation stopped at 2452.33 N m where a Newton step
    failed (not at the fold); a solve at 1.001 x that converged. The fold, from a scan of
    the output creep, is about 3147.2 N m: the limit now lies within 1e-3 below it, the
    solve's continuation (with the held creep's walk from its first failed step, as
    `solve_batch` runs it) reaches it and not 1.001 x it. Without the walk, where the
    torque continuation's failed step stops below the fold turns on the last bits of the
    limit (session 27: 3147.14 N m, then 1979.10 for a limit 5e-14 different, the residual
    at the thermal law's noise floor)."""
    v = _drive(*V2534)
    ratio, force, rpm = 0.5841082469568752, 38405.46910945153, 180.94148874922226
    flat = _problem(v, ratio, force, rpm)
    lim = float(peak_limits(flat, v.design.creep_limit, v.options)[0][0])
    assert lim == pytest.approx(3147.2, rel=1e-3)
    goal = np.array([lim, 1.001 * lim])
    options = at_residual_floor(v.options, v.fluid)
    _, _, reached = continue_in_torque(flat.take([0, 0]), branch_solver(options), goal,
                                       REACH_STEP, pinned=branch_pinned(options))  # fmt: skip
    # 1.001 x the limit is not reached: it lies past the fold
    assert reached[0] == lim and reached[1] < goal[1]


def test_continuation_reaches_next_to_the_fold():
    """2026:2324 at its capacity force: Newton converges slowly next to the fold (fold
    240.014 N m) and ran out of iterations at every step to 239.95 N m; the continuation
    stopped at 237.245 (the limit reported) while another path passed it. A failed step
    is now resumed once from where it stopped."""
    v = _drive(*V2324)
    flat = _problem(v, P2324["ratio"], P2324["clamp_force"], P2324["rpm"])
    _, _, reached = continue_in_torque(flat, branch_solver(v.options), np.array([239.95]))
    assert reached[0] == 239.95
    lim = float(peak_limits(flat, v.design.creep_limit, v.options)[0][0])
    assert lim == pytest.approx(240.014, rel=1e-3) and lim < 240.014


# 2703:530 of a thermal-only campaign (thermal, single, constant force; session 27)
V2703_530 = (
    "single",
    "thermal",
    '{"aspect_ratio": 0.6613528407246477, "roller_radius": 0.02217227184285136, "theta0_deg": 52.206289351906484, "theta2_deg": 55.48195519281438, "alpha_deg": 3.0227832102966534, "n_rollers": 4, "roller_bearing_diameter": 0.011074602348366418, "idler_bearing_diameter": 0.016373733686909617, "disc_groove_ratio": 1.5241878105896136, "idler_groove_ratio": 1.7825417014710938, "single_idler_groove_ratio": 8.04448015924384, "tilt_safety_factor": 0.7839061404496156, "creep_limit": 0.11780711756984942, "min_roller_gap": 0.0004694674188048248, "cam": {"disc": "output", "preload": 66.20180759519765, "ramp_angle_deg": 16.444781355480316, "mean_radius": 0.01969922601694752, "friction": 0.0324027269230169}}',
)


def test_a_solve_at_a_limit_at_the_creep_limit_meets_it_next_to_a_fold():
    """The limit where the input contact's creep reaches the limit, next to a fold (the
    torque 3.5 N m per unit creep there): the creep is held `PEAK_PIN_MARGIN` (1e-6) below
    the limit, and a solve at its torque keeps every creep within the limit (held 1e-7
    below, at 18.74512537 N m, a solve met a creep 2e-8 above it)."""
    v = _drive(*V2703_530)
    kw = {"clamp_force": 1677.218709255241, "input_speed_rpm": 132.52626360721024}
    ratio = 1.56115061277818
    limit = v.limit_torque(ratio, **kw)
    assert limit == pytest.approx(18.7451, rel=1e-5)
    r = v.solve(ratio, limit, **kw)  # refused (TractionLimitError) with a creep beyond it
    assert r.converged
    assert max(abs(c.creep) for c in r.contacts.values()) <= v.design.creep_limit


# 2704:75 of a thermal-only campaign (thermal, single, constant force; session 27)
V2704_75 = (
    "single",
    "thermal",
    '{"aspect_ratio": 3.050120754449642, "roller_radius": 0.013498859680696087, "theta0_deg": 26.636541816939236, "theta2_deg": 64.6518200024462, "alpha_deg": 13.846675241558001, "n_rollers": 10, "roller_bearing_diameter": 0.003149018539607938, "idler_bearing_diameter": 0.0017709697730852985, "disc_groove_ratio": 1.8872677576347163, "idler_groove_ratio": 4.706817987816093, "single_idler_groove_ratio": 5.000460788226849, "tilt_safety_factor": 0.8217822313949761, "creep_limit": 0.06625928355510967, "min_roller_gap": 0.0025653925192644306, "cam": {"disc": "output", "preload": 31.334977808946554, "ramp_angle_deg": 4.888462892981418, "mean_radius": 0.03383639975097287, "friction": 0.04332307051863346}}',
)


def test_a_limit_at_the_creep_limit_next_to_a_fold_just_past_it():
    """The input contact's creep reaches the limit 0.3 % short of a fold (the hub's fluid,
    769.6 N, 3753 rpm, ratio 2.04): the limit is the torque there (9.1625 N m, as before
    session 27). Reported 1e-6 below it (a margin tried in session 27), Newton at the
    torque from the held creep's secant converged past the fold, and the limit fell back
    to the walk's start, 2.99 N m, while a solve converged at 1.5 times that. (A solve at
    the limit itself also lands past the fold and is refused, with session 26's code too:
    left open, README.)"""
    v = _drive(*V2704_75, base="hub")
    kw = {"clamp_force": 769.6321876468879, "input_speed_rpm": 3753.412212451262}
    limit = v.limit_torque(2.0388210123713475, **kw)
    assert limit == pytest.approx(9.1625, rel=1e-4)


# 2803:367 (session 28, thermal-only campaign; hub-derived, single idler, constant force):
# the solve at the top of the climb, a limit where the output creep reaches `C_lim`, met
# the held creep 1.4e-16 above `pin` (PEAK_PIN_MARGIN below `C_lim`), the check against
# `pin` refused it, and the limit fell to the walk's point before its last: 78.5 N m
# where the branch rises steadily to 171.6 N m at the creep limit.
F2803_367 = '{"aspect_ratio": 3.4019383229860796, "roller_radius": 0.020324773037363193, "theta0_deg": 34.77024779799424, "theta2_deg": 58.366678134896375, "alpha_deg": 17.088546580301127, "n_rollers": 9, "roller_bearing_diameter": 0.007114782716275515, "idler_bearing_diameter": 0.004131257083795595, "disc_groove_ratio": 3.4568553768155397, "idler_groove_ratio": 1.6066286566216688, "single_idler_groove_ratio": 29.727514477178975, "tilt_safety_factor": 0.8363114410224847, "creep_limit": 0.13598555458122363, "min_roller_gap": 0.0013704813189912774, "cam": {"disc": "output", "preload": 49.912514121028885, "ramp_angle_deg": 4.248769638249453, "mean_radius": 0.04595817339878044, "friction": 0.038622462309074436}}'


def test_a_limit_at_the_creep_limit_is_not_refused_for_round_off_above_the_held_creep():
    v = _drive("single", "thermal", F2803_367, base="hub")
    ratio, force, rpm = 0.2731443480816715, 4619.270782585251, 1637.5638960774936
    limit = v.limit_torque(ratio, clamp_force=force, input_speed_rpm=rpm)
    assert limit > 170.0  # 78.5 N m before
    at = v.solve(ratio, limit, clamp_force=force, input_speed_rpm=rpm)  # set by the creep
    largest = max(abs(c.creep) for c in at.contacts.values())
    assert largest == pytest.approx(v.design.creep_limit, rel=1e-5)  # held 1e-6 below


# 2803:167 (session 28, thermal-only campaign; Table I-derived, double idler; found under
# the optimal clamp, whose capacity is the constant force's limit at its best force): the
# branch from zero torque turns more than once. Held in the input creep it rises to a fold
# at 11.5838 N m (C_in 0.048, C_out 0.0711; a map of held-creep solves every 5e-4, session
# 29) and falls; further on it rises again to a second fold, 11.664 N m at C_out 0.0945. A
# walk's step passed the first fold and landed past the second, the climb in the output
# creep found the second, no solve reached it, and the limit fell back to the walk's point
# before its last, 10.64 N m, while a solve converged at 11.55 N m.
F2803_167 = '{"aspect_ratio": 0.9774952222129578, "roller_radius": 0.011621753391804112, "theta0_deg": 64.59402730591124, "theta2_deg": 43.940803839380564, "alpha_deg": 4.9296158197513, "n_rollers": 3, "roller_bearing_diameter": 0.0031799880884678194, "idler_bearing_diameter": 0.0014408294465737945, "disc_groove_ratio": 2.2476550171953917, "idler_groove_ratio": 1.9158505974108995, "single_idler_groove_ratio": Infinity, "tilt_safety_factor": 0.5810833239460864, "creep_limit": 0.12188113316294404, "min_roller_gap": 0.0008633202553063408, "cam": {"disc": "input", "preload": 398.73429068590326, "ramp_angle_deg": 15.476448540634262, "mean_radius": 0.029211594583267306, "friction": 0.03296176852975246}}'


def test_a_limit_is_the_first_fold_where_the_branch_turns_more_than_once():
    v = with_oil_temperature(_drive("double", "thermal", F2803_167), "fixed")
    kw = {"clamp_force": 1605.481187021577, "input_speed_rpm": 5916.3412150143695}
    ratio = 0.7472033245932123
    limit = v.limit_torque(ratio, **kw)
    # the first fold, less the reporting margin (FOLD_MARGIN 2e-4) and the map's spacing
    assert limit == pytest.approx(11.5838, rel=3e-4)
    v.solve(ratio, limit, **kw)  # converges
    with pytest.raises(TractionLimitError):
        v.solve(ratio, limit * 1.001, **kw)


def test_a_solve_just_below_a_limit_next_to_a_fold_stays_on_the_branch():
    """2704:75's drive (as above): at 0.9999 of its limit the continuation's last step
    landed on the equilibrium past the fold (input creep 0.0671, beyond ``creep_limit``
    0.06626) and the solve was refused; the branch's own equilibrium there has 0.0658.
    The step onto the torque is now tested (`ballcvt.solvers.held_creep.turned_back`)
    and taken again from closer. (At the limit itself the solve is still refused: left
    open, README.)"""
    v = _drive(*V2704_75, base="hub")
    kw = {"clamp_force": 769.6321876468879, "input_speed_rpm": 3753.412212451262}
    limit = v.limit_torque(2.0388210123713475, **kw)
    r = v.solve(2.0388210123713475, limit * 0.9999, **kw)
    assert max(abs(c.creep) for c in r.contacts.values()) <= v.design.creep_limit
