"""What the batched Newton solver evaluates: the residual alone for the points near their
solutions, apart from the rest of the batch (`ballcvt.solvers.newton_eval`, session 34)."""

from dataclasses import replace

import numpy as np
import pytest

from ballcvt import Variator, load_builtin
from ballcvt.equilibrium.problem import build_problem
from ballcvt.solvers import newton_eval
from ballcvt.solvers.newton import solve_batch
from ballcvt.solvers.newton_eval import CONFIRM_NORM, confirm_norm
from ballcvt.solvers.secant import NEAR_NORM


def _batch(n=64):
    v = Variator()
    ratio = np.linspace(0.6, 1.8, n)
    pb = build_problem(v.design, v.fluid, v.architecture, ratio, np.full(n, 20.0),
                       np.full(n, 1500.0), np.full(n, 200.0))  # fmt: skip
    return v, pb, solve_batch(pb, v.options).state.creep


def _counted(mp):
    rows = {"jacobian": 0, "plain": 0}
    plain, jac = newton_eval.evaluate, newton_eval.evaluate_with_jacobian

    def with_jac(problem, x, *a, **k):
        rows["jacobian"] += x.shape[0]
        return jac(problem, x, *a, **k)

    def alone(problem, x, *a, **k):
        rows["plain"] += x.shape[0]
        return plain(problem, x, *a, **k)

    mp.setattr(newton_eval, "evaluate_with_jacobian", with_jac)
    mp.setattr(newton_eval, "evaluate", alone)
    return rows


def test_points_near_their_solution_skip_the_jacobian_and_keep_their_answers():
    """Half the batch starts 1e-6 off its solution, half 5 % off: the near half is
    evaluated without the Jacobian while the rest still needs one, and every point's answer
    is the one it gets solved with the whole batch evaluated with Jacobians."""
    v, pb, x = _batch()
    start = x * np.where(np.arange(x.shape[0]) % 2 == 0, 1 + 1e-6, 1.05)[:, None]
    with pytest.MonkeyPatch.context() as mp:
        whole = _counted(mp)  # never apart:
        ref = solve_batch(pb, replace(v.options, split_min=10**9), start, predict=False)
    with pytest.MonkeyPatch.context() as mp:
        split = _counted(mp)
        got = solve_batch(pb, v.options, start, predict=False)
    assert ref.converged.all() and got.converged.all()
    np.testing.assert_allclose(got.state.creep, ref.state.creep, rtol=1e-9, atol=1e-13)
    np.testing.assert_allclose(got.state.creep, x, rtol=1e-9, atol=1e-13)
    assert split["plain"] >= x.shape[0] // 2  # the near half at least once
    assert split["jacobian"] < whole["jacobian"]


def test_a_batch_with_few_points_near_is_evaluated_whole(monkeypatch):
    v, pb, x = _batch(8)
    start = x * np.where(np.arange(8) < 2, 1 + 1e-6, 1.05)[:, None]
    rows = _counted(monkeypatch)
    sol = solve_batch(pb, v.options, start, predict=False)
    assert sol.converged.all()
    assert rows["jacobian"] >= 8  # the first evaluation: all eight with the Jacobian
    assert rows["plain"] == 0  # never two near apart (they step with their last, unread)


def test_near_means_the_secant_range_except_under_a_law_with_folds():
    """Below NEAR_NORM a point steps with its last Jacobian, corrected; under the thermal law
    (more than one equilibrium, Newton's path near a fold turning on the last bit) only
    below CONFIRM_NORM, as before session 34."""
    d, f = load_builtin("table1")
    assert confirm_norm(f) == NEAR_NORM
    thermal = f.model_copy(update={"traction_law": "thermal"})
    assert confirm_norm(thermal) == CONFIRM_NORM < NEAR_NORM


def test_with_split_min_one_every_point_is_solved_as_alone():
    """With ``split_min`` 1 a point near its solution is evaluated without the Jacobian
    whatever its batch, so each point's answer is the one it gets alone, to the bit (the
    kernels with and without the derivatives round ``chi`` apart in its last bit, and with
    the default a point's evaluation depended on how many others were near)."""
    v, pb, x = _batch(8)
    start = x * np.where(np.arange(8) < 3, 1 + 1e-6, 1.05)[:, None]
    own = replace(v.options, split_min=1)
    got = solve_batch(pb, own, start, predict=False)
    for i in range(8):
        one = solve_batch(pb.take(np.array([i])), own, start[i : i + 1], predict=False)
        assert np.array_equal(one.state.creep[0], got.state.creep[i])
        assert np.array_equal(one.state.body_torque[0], got.state.body_torque[i])


def test_split_min_is_at_least_one():
    from ballcvt.solvers.options import SolverOptions

    with pytest.raises(ValueError, match="split_min"):
        SolverOptions(split_min=0)
