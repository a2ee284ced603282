"""The planetary modes' batched path (issue 26): the fixed point on the actual ratio by
Wegstein's secant step, and the point solver kept for the points within the capacity."""

import numpy as np
import pytest

import ballcvt.solvers.newton as newton
from ballcvt import Variator
from ballcvt.model.modes import MEMBERS, OperatingMode, resolve_mode
from ballcvt.solvers.planetary import ModePoint, next_ratio, solve_mode
from ballcvt.solvers.planetary_batch import solve_mode_batch
from ballcvt.status import Status

F = 2000.0


@pytest.fixture(scope="module")
def v():
    return Variator()


def test_next_ratio_plain_then_secant():
    """The first step is the plain one; once a slope is measured, a linear map's fixed
    point is reached in one step."""

    def g(tau):
        return 0.3 * tau + 0.7  # fixed point 1, slope 0.3

    step, memory = next_ratio(1.5, g(1.5), None, 1e-13)
    assert step == pytest.approx(g(1.5), abs=0)
    step, _ = next_ratio(step, g(step), memory, 1e-13)
    assert step == pytest.approx(1.0, abs=1e-15)


def test_next_ratio_keeps_its_slope_within_the_noise():
    """Passes closer than `SLOPE_STEPS` tolerances keep the last slope: a change at the
    solves' noise does not give one."""
    memory = (np.array([1.0]), np.array([1.0 + 1e-12]), np.array([0.25]))
    step, (_, _, slope, secant) = next_ratio(np.array([1.0 + 1e-12]),
                                             np.array([1.0 + 5e-12]), memory, 1e-13)
    assert slope[0] == 0.25 and secant[0]
    assert step[0] == pytest.approx(1.0 + 1e-12 + 4e-12 / 0.75, abs=1e-15)


def test_next_ratio_plain_at_the_noise():
    """Within `SECANT_STEPS` tolerances the step is the plain one, and says so (the next
    pass may then be settled by the noise rule of `ratio_settles`)."""
    memory = (np.array([1.0]), np.array([1.0 + 1e-12]), np.array([0.25]))
    step, (*_, secant) = next_ratio(np.array([1.0 + 1e-12]), np.array([1.0 + 1.5e-12]),
                                    memory, 1e-13)
    assert step[0] == 1.0 + 1.5e-12 and not secant[0]


def test_next_ratio_bounds_its_slope():
    """A measured slope of 1 or more (no contraction) is clipped to 0.99."""
    memory = (np.array([1.0]), np.array([1.1]), np.array([0.0]))
    _, (_, _, slope, _) = next_ratio(np.array([1.1]), np.array([1.25]), memory, 1e-13)
    assert slope[0] == 0.99


@pytest.mark.parametrize("mode", ["disc0_held_disc2_drives", "carrier_held_disc2_drives"])
def test_few_passes_same_answer(v, mode):
    """The scalar path settles in a handful of passes (a dozen by the plain iteration) and
    the batch gives its answer."""
    point = ModePoint(1.2, 20.0, 30.0, F)
    one = solve_mode(v, mode, point, v.options)
    assert one.passes <= 7
    batch = solve_mode_batch(v, mode, ModePoint(np.array([1.2]), 20.0, 30.0, F), v.options)
    assert batch.status[0] == Status.CONVERGED
    assert batch.actual_ratio[0] == pytest.approx(
        float(one.solution.state.omega[-1] / one.solution.state.omega[0]), rel=1e-12)


def _counting(monkeypatch, module=newton, name="solve_robust"):
    """The calls of ``module.name`` from here on (a list that grows by one per call)."""
    calls = []
    real = getattr(module, name)

    def counted(*args, **kwargs):
        calls.append(1)
        return real(*args, **kwargs)

    monkeypatch.setattr(module, name, counted)
    return calls


def test_rescue_false_skips_the_point_solver(v, monkeypatch):
    """A load far beyond the capacity goes to the point solver by default (as `solve`),
    not with ``rescue=False`` (the capacity search's first loads, only starts): both say
    it is not admissible, and the admissible load is the same in both."""
    mode = OperatingMode("disc0", "carrier")
    point = ModePoint(np.array([1.0, 1.0]), np.array([20.0, 2000.0]), 30.0, F)
    calls = _counting(monkeypatch)
    every = solve_mode_batch(v, mode, point, v.options)
    rescued = len(calls)
    none = solve_mode_batch(v, mode, point, v.options, rescue=False)
    assert rescued > 0 and len(calls) == rescued
    assert every.status[0] == none.status[0] == Status.CONVERGED
    assert every.status[1] != Status.CONVERGED and none.status[1] != Status.CONVERGED
    assert none.eta[0] == pytest.approx(every.eta[0], abs=1e-12)


def test_rescue_mask(v, monkeypatch):
    """A mask rescues only the points it names."""
    mode = OperatingMode("disc0", "carrier")
    point = ModePoint(np.array([1.0, 1.0]), np.array([2000.0, 2000.0]), 30.0, F)
    calls = _counting(monkeypatch)
    solve_mode_batch(v, mode, point, v.options, rescue=np.array([True, False]))
    one = len(calls)
    calls.clear()
    solve_mode_batch(v, mode, point, v.options, rescue=np.array([False, False]))
    assert one > 0 and len(calls) == 0


@pytest.mark.parametrize("mode", ["disc0_held_disc2_drives", "disc0_held_carrier_drives",
                                  "carrier_held_disc2_drives"])
def test_held_creep_capacity_is_the_load_at_the_creep_limit(v, mode):
    """The capacity found at a held creep: at it the largest creep is the creep limit (held
    1e-7 below it), a load 1e-4 above is beyond it, and the bisection's answer (the
    thermal-law path, forced here) lies within its bracket below."""
    from ballcvt.solvers import planetary_batch as pbm

    ratios = np.array([0.7, 1.35, 1.6])
    point = ModePoint(ratios, np.nan, 30.0, F)
    limit, at = pbm.limit_load_search(v, mode, point, v.options)
    assert np.isfinite(limit).all() and (at.status == Status.CONVERGED).all()
    assert at.max_creep == pytest.approx(v.design.creep_limit, rel=1e-6)
    direction = np.sign(at.torques[MEMBERS.index(resolve_mode(mode).driven)]) * -1.0
    above = solve_mode_batch(v, mode, ModePoint(ratios, direction * limit * (1 + 1e-4), 30.0, F),
                             v.options)
    assert (above.status != Status.CONVERGED).all()
    bisected = pbm._bisected(
        lambda size, rows: solve_mode_batch(
            v, mode, ModePoint(ratios[rows], direction[rows] * size, 30.0, F), v.options,
            rescue="within").status,
        pbm.traction_ceiling_torque(pbm.make_problem(v, pbm.OperatingInputs(ratios, 0.0, F, 1.0))),
        False, (1e-3, 40))
    assert (bisected <= limit * (1 + 1e-9)).all() and (bisected >= limit * (1 - 1.1e-3)).all()


def test_held_creep_capacity_takes_few_solves(v, monkeypatch):
    """Zero load, one first load, the held search and one confirming solve: not the
    dozen batches of a bisection."""
    from ballcvt.solvers import planetary_batch as pbm

    calls = _counting(monkeypatch, pbm, "solve_mode_batch")
    limit = pbm.limit_load_batch(v, "carrier_held_disc2_drives",
                                 ModePoint(np.array([0.8, 1.4]), np.nan, 30.0, F), v.options)
    assert np.isfinite(limit).all() and len(calls) <= 4


def test_map_grid_start_moves_nothing(v, monkeypatch):
    """The map's grid solved from the ratios and creeps interpolated between zero load and
    the limit gives the cold start's answers."""
    import ballcvt.analysis.planetary as ap

    mode = resolve_mode("disc2_held_carrier_drives")
    kw = {"driver_speed": 30.0, "clamp_force": F}
    warm = ap.mode_map(v, mode, np.array([0.7, 1.3]), 5, **kw)
    real = ap.solve_mode_batch
    monkeypatch.setattr(ap, "solve_mode_batch",
                        lambda *a, start=None, **k: real(*a, **k))
    cold = ap.mode_map(v, mode, np.array([0.7, 1.3]), 5, **kw)
    assert (warm["status"].values == cold["status"].values).all()
    assert np.nanmax(np.abs(warm["eta"].values - cold["eta"].values)) < 1e-9
