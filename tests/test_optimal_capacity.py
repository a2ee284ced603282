"""The optimal law's capacity: the largest limiting torque over the forces it may pick
(issue 23: a solve at the reported limit must converge, 1.001 x it must be refused)."""

import json

import pytest

from ballcvt import TractionLimitError, Variator, load_builtin

# harden.py --task 4:372: the optimiser refused the limit it reported (creep pinned at
# the limit, no margin in the optimiser's creep test)
FIELDS_4_372 = json.loads(
    '{"aspect_ratio": 2.483198952943732, "roller_radius": 0.05223603939770971, '
    '"theta0_deg": 42.42749829556891, "theta2_deg": 39.150112410624644, '
    '"alpha_deg": 11.336853968262627, "n_rollers": 4, '
    '"roller_bearing_diameter": 0.013689966635101835, '
    '"idler_bearing_diameter": 0.018132469374323237, "disc_groove_ratio": 5.148448698273314, '
    '"idler_groove_ratio": 1.6598857125730493, "single_idler_groove_ratio": 27.876384239988603, '
    '"tilt_safety_factor": 0.5852248040565238, "creep_limit": 0.17633288783090018, '
    '"min_roller_gap": 0.0028275810898156263}'
)


def test_optimal_solve_holds_at_its_reported_limit():
    d, f = load_builtin("table1")
    v = Variator(d.replace(name="random", **FIELDS_4_372), f, "double",
                 traction_law="viscoelastic")
    ratio, rpm = 0.8154838011200438, 33.640902166151385
    lim = v.limit_torque(ratio, clamp_law="optimal", input_speed_rpm=rpm)
    r = v.solve(ratio, lim, clamp_law="optimal", input_speed_rpm=rpm)
    assert r.converged


def test_optimal_capacity_without_pressure_limit_is_the_best_force():
    d, f = load_builtin("table1")
    v = Variator(d.replace(max_pressure=float("inf")), f, "double")
    lim = v.limit_torque(1.0, clamp_law="optimal", input_speed_rpm=2000)
    # the limit at the Roelands force is none; the best force (about 1.5 MN) carries more
    # than the force of 1 MN does
    assert lim > v.limit_torque(1.0, clamp_force=1e6, input_speed_rpm=2000)
    r = v.solve(1.0, lim, clamp_law="optimal", input_speed_rpm=2000)
    assert max(abs(c.creep) for c in r.contacts.values()) <= d.creep_limit * (1 + 1e-8)
    with pytest.raises(TractionLimitError):
        v.solve(1.0, 1.001 * lim, clamp_law="optimal", input_speed_rpm=2000)
    curve = v.limit_curve([1.0], clamp_law="optimal", input_speed_rpm=2000, progress=False)
    assert float(curve.torque[0]) == pytest.approx(lim, rel=1e-6)


class _Stand:
    """A stand-in `LimitSearch` of limiting torques only."""

    def __init__(self, torque):
        self.torque = torque

    def take(self, index):
        return _Stand(self.torque[index])


@pytest.mark.parametrize("peak, kept", [(0.05, True), (-5e-4, False)])
def test_thermal_capacity_keeps_f_p_where_its_limit_still_rises(monkeypatch, peak, kept):
    """Under the thermal law (more than one equilibrium) the optimal law's capacity force
    is ``F_p`` from the limits at ``F_p (1 - EDGE)`` and ``F_p`` alone where the limit
    rises there by more than `RISE` (a stand-in limit peaking at ``ln(F / F_p) = 0.05``);
    a limit peaking just below ``F_p`` (at -5e-4, flat across the last ``EDGE``) is
    scanned and refined to its peak, below ``F_p``."""
    import numpy as np

    from ballcvt.equilibrium.problem import build_problem
    from ballcvt.solvers import optimal_capacity as oc

    d, f = load_builtin("table1")
    v = Variator(d, f, traction_law="thermal")
    pb = build_problem(v.design, v.fluid, v.architecture, np.array([1.0]), 0.0,
                       np.ones(1), np.array([200.0]))  # fmt: skip
    p_lim, c_lim = v.design.max_pressure, v.design.creep_limit
    top = float(oc.force_range_top(pb, p_lim, 100.0)[0])
    calls = []

    def searches(flat, forces, c, o):
        calls.append(forces.shape[1])
        return _Stand((100.0 * (1.0 - (np.log(forces / top) - peak) ** 2)).ravel())

    monkeypatch.setattr(oc, "_searches", searches)
    force = float(oc.capacity_force(pb, p_lim, c_lim, 100.0, v.options)[0])
    if kept:
        assert force == top and calls == [2]
    else:
        assert force < top and np.log(force / top) == pytest.approx(peak, abs=1e-4)
        assert calls[0] == 2 and len(calls) == 2 + oc.ZOOM
