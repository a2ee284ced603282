"""The equilibrium at a torque reached by the walk along the branch
(`ballcvt.solvers.walk_reach`), and the fold found past a step that jumped over it, on
Table I's drive under the thermal law."""

import math

import numpy as np
import pytest

from ballcvt import Variator
from ballcvt.equilibrium.problem import build_problem
from ballcvt.solvers.continuation import solve_twice
from ballcvt.solvers.limit import limit_torque_batch
from ballcvt.solvers.newton import branch_pinned, branch_solver, solve_batch
from ballcvt.solvers.optimal_capacity import force_range_top
from ballcvt.solvers.options import SolverOptions, at_residual_floor
from ballcvt.solvers.walk_reach import walk_to_torque

THERMAL = Variator(traction_law="thermal")
OPTIONS = at_residual_floor(SolverOptions(), THERMAL.fluid)
W = 2000.0 * math.pi / 30


def _at(ratio, torque, force=2000.0):
    n = len(torque)
    return build_problem(THERMAL.design, THERMAL.fluid, THERMAL.architecture,
                         np.full(n, ratio), np.asarray(torque, dtype=float), force, W).flat()  # fmt: skip


def test_the_walk_reaches_torques_below_the_fold_and_refuses_those_past_it():
    """Ratio 1.0 at 2 kN (fold 114.78 N m), from zero torque: 60 and 114.5 N m reached,
    with the creeps of a solve (to 1e-8; the equilibrium on the branch at a torque is
    unique); 130 N m found past the fold (decided, not converged)."""
    pb = _at(1.0, [60.0, 114.5, 130.0])
    solve = branch_solver(OPTIONS)
    ok, x0, _ = solve(_at(1.0, [0.0, 0.0, 0.0]), None, True)
    assert np.all(ok)

    def at_torque(p, x):
        good, xt, _ = solve_twice(solve, p, x)
        return good, xt

    start = (np.zeros(3), np.asarray(x0))
    decided, good, x = walk_to_torque(pb, branch_pinned(OPTIONS), at_torque, start)
    assert decided.tolist() == [True, True, True]
    assert good.tolist() == [True, True, False]
    ref = solve_batch(pb.take([0, 1]), OPTIONS)
    assert ref.converged.all()
    np.testing.assert_allclose(x[:2], ref.state.creep, rtol=0, atol=1e-8)


def test_a_limit_at_the_pressure_bound_is_the_fold_past_a_step_over_it():
    """Ratio 0.833 at the force of the pressure limit `F_p`: the walk's step from 441 N m
    landed past the fold (562.2 N m) at 551.4 N m, still above the step before, and a
    parabola through the seed put its vertex on that point: the climb stopped there,
    and the limit read 551.3 N m against 561.8 at 0.999 `F_p`. A parabolic step onto the
    best point in a wide bracket is now a golden-section step: the limit rises with the
    force up to `F_p` (the optimal clamp's capacity there)."""
    ratio = np.linspace(0.5, 2.0, 10)[2]
    one = _at(ratio, [0.0])
    fp = float(force_range_top(one, THERMAL.design.max_pressure, 100.0)[0])
    limits = [float(limit_torque_batch(_at(ratio, [0.0], fp * s), THERMAL.design.creep_limit,
                                       OPTIONS)[0]) for s in (0.995, 0.999, 1.0)]  # fmt: skip
    assert limits[0] < limits[1] < limits[2]
    assert limits[2] == pytest.approx(562.23, abs=0.05)



def test_a_fold_beyond_the_creep_limit_is_located_by_the_climb(monkeypatch):
    """Ratio 2 at 9396 N (the cam's force at 287 N m in Table I's thermal cam scan): the
    fold lies at 161.79 N m, an input creep of 0.081, within the creep limit (0.1). The
    torque continuation towards 287 N m stops at its first failed step and the walk from
    there jumps the fold to a creep of 0.1006, still above the step before. The climb
    seeded there, bounded at the creep limit, ended at its bound undecided, and the march
    in a held creep (`reach_torque`) went on to the fold; bounded at `CLIMB_BOUND` limits
    it brackets the fold, and 287 N m is found past it without the march (the climb run
    even though 287 N m lies far above the walk's concave bound)."""
    import ballcvt.solvers.continuation as continuation
    import ballcvt.solvers.walk_reach as walk_reach

    monkeypatch.setattr(walk_reach, "FAR_MARGIN", np.inf)

    force = 9395.82198308934
    fold = float(limit_torque_batch(_at(2.0, [0.0], force), THERMAL.design.creep_limit, OPTIONS)[0])
    assert fold == pytest.approx(161.79, abs=0.01)
    marches = []
    reach = continuation.reach_torque
    monkeypatch.setattr(continuation, "reach_torque",
                        lambda p, *a: (marches.append(p.size), reach(p, *a))[1])  # fmt: skip
    pb = _at(2.0, [287.252129997354], force)
    _, _, torque = continuation.continue_in_torque(
        pb, branch_solver(OPTIONS), pinned=branch_pinned(OPTIONS)
    )
    assert torque[0] < fold  # not reached: past the fold
    assert marches == []


def test_the_concave_bound_lies_above_a_concave_top():
    """`_concave_bound` of three points on ``T = 10 - (s - 1)^2`` along a straight line in
    the creeps (the top at ``s = 1`` between the second and the third): above 10, and
    infinite where two points coincide."""
    from ballcvt.solvers.branch_path import Walk
    from ballcvt.solvers.walk_reach import _concave_bound

    line = np.array([0.6, 0.0, 0.0, 0.8])  # unit direction in the creeps
    s = np.array([[0.2, 0.9, 1.6], [0.5, 0.5, 1.2]])
    t = 10.0 - (s - 1.0) ** 2
    x = s[..., None] * line
    walk = Walk(t[:, 1], x[:, 1], (t[:, 0], x[:, 0]), (t[:, 2], x[:, 2]), x[:, 1],
                np.ones(2, dtype=bool), np.zeros(2, dtype=bool))  # fmt: skip
    bound = _concave_bound(walk, np.ones(2, dtype=bool))
    assert 10.0 <= bound[0] < 11.0  # 10.62: the first chord at the third point
    assert np.isinf(bound[1])


def test_far_past_the_fold_the_concave_bound_decides_as_the_climb(monkeypatch):
    """Ratio 2 at 9396 N (fold 161.79 N m): torques from 1.02 to 3 times the fold are
    found past it with and without the climb skipped above `FAR_MARGIN` over the walk's
    concave bound, and the climb runs only for the nearer ones (session 39: a thermal
    cam sweep's capacity scan spent a third of its time in climbs to folds far below its
    torques)."""
    import ballcvt.solvers.continuation as continuation
    import ballcvt.solvers.walk_reach as walk_reach

    force, fold = 9395.82198308934, 161.79
    torques = fold * np.array([0.9, 1.02, 1.1, 1.5, 3.0])
    climbs = []
    real = walk_reach.climb_to_fold
    monkeypatch.setattr(walk_reach, "climb_to_fold",
                        lambda p, *a: (climbs.append(p.size), real(p, *a))[1])  # fmt: skip

    def reached(margin):
        monkeypatch.setattr(walk_reach, "FAR_MARGIN", margin)
        climbs.clear()
        _, _, torque = continuation.continue_in_torque(
            _at(2.0, torques, force), branch_solver(OPTIONS), pinned=branch_pinned(OPTIONS)
        )
        return torque == torques, sum(climbs)

    (skipped, few), (climbed, many) = reached(walk_reach.FAR_MARGIN), reached(np.inf)
    np.testing.assert_array_equal(skipped, [True, False, False, False, False])
    np.testing.assert_array_equal(skipped, climbed)
    assert few < many
