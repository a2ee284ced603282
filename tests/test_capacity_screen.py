"""The capacity scan under a cam screens its points on the coarse rule (issue 26): the
screen decides only what the full rule decides alike, the intervals are those of the scan
on the full rule, and a Newton run stopped just short of the tolerance is finished from
where it stopped, not handed to the point solver."""

import math

import numpy as np
import pytest

import ballcvt.solvers.limit as limit_module
import ballcvt.solvers.newton as newton_module
from ballcvt import Variator
from ballcvt.equilibrium.problem import build_problem
from ballcvt.model.clamping.cam import CamClamp
from ballcvt.solvers.admissible import screen_admissible, screens, solve_admissible
from ballcvt.solvers.limit import limit_search
from ballcvt.solvers.options import SolverOptions

RPM = 2000.0
SMALL_PRELOAD = CamClamp(200.0, math.radians(8.0), 0.05, 0.005)


@pytest.fixture(scope="module")
def v():
    return Variator()


def _points(v, ratio, torque, speed_rpm=RPM):
    n = torque.size
    return build_problem(
        v.design,
        v.fluid,
        v.architecture,
        np.full(n, ratio),
        torque,
        np.ones(n),
        np.full(n, speed_rpm * math.pi / 30),
    )


@pytest.mark.parametrize("law", ["design", "small"])
def test_screen_decides_as_the_full_rule(v, law):
    law = CamClamp.from_design(v.design) if law == "design" else SMALL_PRELOAD
    pb = _points(v, 1.3, np.concatenate([np.linspace(0.0, 30.0, 31), np.linspace(40, 400, 10)]))
    c_lim = v.design.creep_limit
    fast = screen_admissible(pb, c_lim, SolverOptions(), law)
    full = solve_admissible(pb, c_lim, SolverOptions(), law)
    assert np.all(full.ok[fast.ok])
    assert not np.any(full.ok[fast.beyond])
    assert np.any(fast.ok | fast.beyond)  # it decides something


@pytest.mark.parametrize("law", ["design", "small"])
@pytest.mark.parametrize("fluid_law", ["isothermal", "viscoelastic"])
def test_screen_at_its_tolerance_decides_as_at_the_predictors(law, fluid_law, monkeypatch):
    """The screen's Newton runs stop at SCREEN_TOL (1e-4), not the predictor's 1e-6: the
    verdicts are the same, and where both runs converged the largest creeps differ by
    under 5 % of the creep limit, a tenth of the verdicts' margin (50 %; 2.5 % here, with
    the small preload near the limit, where the traction curve is flat)."""
    import ballcvt.solvers.admissible as admissible_module

    w = Variator(traction_law=fluid_law)
    law = CamClamp.from_design(w.design) if law == "design" else SMALL_PRELOAD
    pb = _points(w, 0.8, np.concatenate([np.geomspace(1e-2, 30.0, 25), np.linspace(40, 400, 10)]))
    c_lim = w.design.creep_limit
    loose = screen_admissible(pb, c_lim, SolverOptions(), law)
    monkeypatch.setattr(admissible_module, "SCREEN_TOL", 1e-6)
    tight = screen_admissible(pb, c_lim, SolverOptions(), law)
    both = loose.converged & tight.converged
    assert np.count_nonzero(both) >= 20
    assert np.array_equal(loose.ok[both], tight.ok[both])
    assert np.array_equal(loose.beyond[both], tight.beyond[both])
    big = [np.max(np.abs(a.creep[both]), axis=-1) for a in (loose, tight)]
    assert np.max(np.abs(big[0] - big[1])) < 0.05 * c_lim


def test_screen_only_where_the_rules_can_agree(v):
    cam = CamClamp.from_design(v.design)
    assert screens(SolverOptions(), cam, v.fluid)
    assert not screens(SolverOptions(predictor=None), cam, v.fluid)
    assert not screens(SolverOptions(), CamClamp(1e3, 0.1, 0.05, 0.0, disc="input"), v.fluid)
    thermal = Variator(traction_law="thermal").fluid
    assert not screens(SolverOptions(), cam, thermal)


@pytest.mark.parametrize("law", ["design", "small"])
def test_intervals_as_without_the_screen(v, law, monkeypatch):
    law = CamClamp.from_design(v.design) if law == "design" else SMALL_PRELOAD
    pb = _points(v, 1.0, np.zeros(6))
    pb = build_problem(
        v.design,
        v.fluid,
        v.architecture,
        np.array([0.5, 0.8, 1.0, 1.3, 1.7, 2.0]),
        np.zeros(6),
        np.ones(6),
        pb.input_speed,
    )
    c_lim = v.design.creep_limit
    fast = limit_search(pb, c_lim, law=law)
    monkeypatch.setattr(limit_module, "screens", lambda *a: False)
    slow = limit_search(pb, c_lim, law=law)
    np.testing.assert_array_equal(fast.spans(), slow.spans())
    np.testing.assert_allclose(fast.creep, slow.creep, rtol=1e-7, atol=1e-12)


def test_slow_newton_is_finished_from_where_it_stopped(v, monkeypatch):
    pb = build_problem(
        v.design,
        v.fluid,
        v.architecture,
        np.array([1.0, 1.5]),
        np.array([30.0, 40.0]),
        np.array([2000.0, 2000.0]),
        np.full(2, RPM * math.pi / 30),
    )
    short = SolverOptions(max_iterations=2)  # stops some 1e-7 short of the tolerance
    first = newton_module.solve_batch(pb, short, None, fallback=False)
    assert not np.any(first.converged) and np.all(first.residual_norm <= 1e-6)

    def refuse(*args, **kwargs):
        raise AssertionError("the point solver was not needed")

    monkeypatch.setattr(newton_module, "solve_robust", refuse)
    got = solve_admissible(pb, v.design.creep_limit, short)
    assert np.all(got.converged) and np.all(got.ok)
    ref = newton_module.solve_batch(pb, SolverOptions())
    np.testing.assert_allclose(got.creep, ref.state.creep, rtol=1e-8, atol=1e-13)


def test_the_scan_creeps_start_a_cam_sweeps_points(v):
    """A cam's limit search keeps its scan (torques and creeps, `LimitSearch.scan_torque`,
    ``scan_creep``), through `flat` and `take`; its creeps interpolated to a torque between
    two scan torques start that point near its solution on the full rule (within the
    coarse rule's error and the interpolation's), so a cam sweep solves its points without
    the predictor stage: the same efficiencies as a sweep whose points start cold."""
    from ballcvt.solvers.clamped import solve_clamped
    from ballcvt.solvers.newton import solve_batch

    law = CamClamp.from_design(v.design)
    ratio = np.array([[0.6, 1.0], [1.4, 1.9]])
    pb = build_problem(v.design, v.fluid, v.architecture, ratio, 0.0, 1.0,
                       RPM * math.pi / 30)
    search = limit_search(pb, v.design.creep_limit, law=law)
    assert search.scan_torque.shape[:2] == (2, 2) and search.scan_creep.shape[:2] == (2, 2)
    flat = search.flat()
    assert flat.take(np.array([3])).scan_torque.shape == (1, search.scan_torque.shape[-1])
    torque = 0.37 * flat.torque  # between scan torques, within the capacity
    x0 = flat.start_between(np.arange(4), torque)
    pts = build_problem(v.design, v.fluid, v.architecture, ratio.ravel(), torque, 1.0,
                        RPM * math.pi / 30)
    _, sol = solve_clamped(pts, law, lambda p, x: solve_batch(p, v.options, x))
    assert sol.converged.all()
    np.testing.assert_allclose(x0, sol.state.creep, rtol=0.02, atol=2e-6)
    # the sweep: the same answers as from the cold start
    grid = {"ratio": [0.6, 1.4], "output_torque": np.linspace(0.0, 60.0, 7)}
    swept = v.sweep(**grid, clamp_law="cam", input_speed_rpm=RPM, progress=False)
    assert np.isfinite(swept.eta.values).sum() >= 10
    for r in grid["ratio"]:
        for t in grid["output_torque"]:
            e = float(swept.eta.sel(ratio=r, output_torque=t).squeeze())
            if np.isfinite(e):
                got = v.solve(r, t, clamp_law="cam", input_speed_rpm=RPM)
                assert abs(got.eta - e) <= 1e-9
