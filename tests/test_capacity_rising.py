"""The optimal clamp's capacity force where the limit still rises at the pressure bound
(session 25): two limits instead of the scan's ten, the same force."""

import numpy as np
import pytest

from ballcvt import Variator, load_builtin
from ballcvt.equilibrium.problem import build_problem
from ballcvt.solvers import optimal_capacity
from ballcvt.solvers.limit import LimitSearch
from ballcvt.solvers.optimal_capacity import capacity_force, force_range_top


def _problem(drive="table1", law="isothermal", rpm=2000.0):
    v = Variator(*load_builtin(drive), traction_law=law)
    ratio = np.array([0.5, 0.8, 1.0, 1.4, 2.0])
    pb = build_problem(v.design, v.fluid, v.architecture, ratio, 0.0, 1000.0, rpm * np.pi / 30)
    return v, pb


@pytest.mark.parametrize(("drive", "law", "rpm"), [("table1", "isothermal", 2000.0),
                                                   ("hub", "viscoelastic", 180.0)])
def test_the_same_force_as_the_scan(drive, law, rpm):
    v, pb = _problem(drive, law, rpm)
    d = v.design
    got = capacity_force(pb, d.max_pressure, d.creep_limit, 100.0, v.options)
    top = force_range_top(pb, d.max_pressure, 100.0)
    scanned = optimal_capacity._scan(pb, top, 100.0, d.creep_limit, v.options)
    assert np.array_equal(got, scanned)


def _stand_in(peak_share):
    """Limits rising to a peak at ``peak_share`` of each point's bound and falling beyond
    (the shape of the module docstring); records the forces asked for."""
    asked = []

    def limits(flat, forces, c_lim, options):
        asked.append(forces.shape)
        peak = peak_share * limits.top[: forces.shape[0], None]
        torque = (-((np.log(forces / peak)) ** 2)).ravel()
        nan = np.full((torque.size, 2), np.nan)
        return LimitSearch(torque, nan, nan)

    return limits, asked


def test_a_limit_rising_at_the_bound_takes_two_limits(monkeypatch):
    v, pb = _problem()
    d = v.design
    top = force_range_top(pb, d.max_pressure, 100.0)
    limits, asked = _stand_in(2.0)  # still rising at the bound: the bound
    limits.top = top
    monkeypatch.setattr(optimal_capacity, "_searches", limits)
    got = capacity_force(pb, d.max_pressure, d.creep_limit, 100.0, v.options)
    assert np.array_equal(got, top)
    assert asked == [(pb.size, 2)]


def test_a_limit_falling_at_the_bound_is_scanned_and_refined(monkeypatch):
    v, pb = _problem()
    d = v.design
    top = force_range_top(pb, d.max_pressure, 100.0)
    limits, asked = _stand_in(0.3)
    limits.top = top
    monkeypatch.setattr(optimal_capacity, "_searches", limits)
    got = capacity_force(pb, d.max_pressure, d.creep_limit, 100.0, v.options)
    assert got == pytest.approx(0.3 * top, rel=1e-2)
    assert asked[0] == (pb.size, 2) and asked[1] == (pb.size, optimal_capacity.GRID + 1)
