"""The secant correction of the analytic Jacobian (`ballcvt.solvers.secant`): Broyden's
good update (Broyden 1965, Eq. 4.5) meets the secant condition along the last move, and
Newton from a warm start converges superlinearly although the analytic Jacobian is ~1 %
off the discrete residual's."""

import math

import numpy as np
import pytest

from ballcvt import Variator
from ballcvt.equilibrium.problem import build_problem
from ballcvt.equilibrium.residual import evaluate, evaluate_with_jacobian
from ballcvt.solvers import newton_eval
from ballcvt.solvers.newton import solve_batch
from ballcvt.solvers.secant import NEAR_NORM, SecantCorrection


def test_broyden_update_meets_the_secant_condition():
    rng = np.random.default_rng(3)
    a = rng.normal(size=(2, 3, 3)) + 3 * np.eye(3)
    wrong = a * (1 + 0.01 * rng.normal(size=a.shape))  # an analytic Jacobian 1 % off
    x0 = rng.normal(size=(2, 3)) * 1e-6
    x1 = x0 + rng.normal(size=(2, 3)) * 1e-6
    sec = SecantCorrection.start(2, 3)
    idx = np.arange(2)
    first = sec.update(idx, x0, np.einsum("ijk,ik->ij", a, x0), wrong)
    assert np.array_equal(first, wrong)  # nothing learnt from one evaluation
    got = sec.update(idx, x1, np.einsum("ijk,ik->ij", a, x1), wrong)
    s = x1 - x0
    assert np.allclose(np.einsum("ijk,ik->ij", got, s), np.einsum("ijk,ik->ij", a, s),
                       rtol=1e-12, atol=1e-20)
    # far from the solution (a residual above NEAR_NORM) nothing is learnt
    far = SecantCorrection.start(1, 3)
    big = np.full((1, 3), 10 * NEAR_NORM)
    far.update(np.arange(1), x0[:1], big, wrong[:1])
    assert np.array_equal(far.update(np.arange(1), x1[:1], 2 * big, wrong[:1]), wrong[:1])


def test_the_analytic_jacobian_is_off_and_newton_still_converges_fast():
    v = Variator()
    w = 2000 * math.pi / 30
    pb = build_problem(v.design, v.fluid, v.architecture, np.array([1.6]), np.array([50.0]),
                       1300.0, w)
    q = v.options.quadrature
    x = solve_batch(pb, v.options).state.creep
    _, jac = evaluate_with_jacobian(pb, x, q)
    h = 1e-7 * abs(x[0, 0])
    xp, xm = x.copy(), x.copy()
    xp[0, 0] += h
    xm[0, 0] -= h
    fd = (evaluate(pb, xp, q).residual[0, 0] - evaluate(pb, xm, q).residual[0, 0]) / (2 * h)
    assert abs(jac[0, 0, 0] / fd - 1) > 1e-3  # the pole's node motion is not differentiated
    # from creeps 0.2 % off (a warm start): the Jacobian evaluated at most twice, the steps after
    # it taken with the secant-corrected one (without it three or four evaluations with the
    # Jacobian, its linear rate ~1/60 per iteration)
    calls = []

    def counted(*args, **kwargs):
        calls.append(1)
        return evaluate_with_jacobian(*args, **kwargs)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(newton_eval, "evaluate_with_jacobian", counted)
        sol = solve_batch(pb, v.options, x * 1.002, predict=False)
    assert sol.converged.all() and len(calls) <= 2
    assert np.allclose(sol.state.creep, x, rtol=1e-9, atol=1e-14)


def test_the_compiled_update_is_the_plain_pythons():
    """`update_points` runs compiled (numba) or as written (without numba): the same
    corrections and Jacobians, NaN residuals included (session 25)."""
    from ballcvt.solvers import secant

    if secant.update_compiled is None:  # pragma: no cover - numba is a dependency
        pytest.skip("numba missing")
    rng = np.random.default_rng(7)
    n, m = 6, 4
    states = []
    for _ in range(2):
        sec = SecantCorrection.start(n, m)
        states.append((sec.correction, sec.last_x, sec.last_res, sec.last_jac, sec.near))
    jac = rng.normal(size=(n, m, m)) + 3 * np.eye(m)
    active = np.array([0, 2, 3, 5])
    outs = []
    for state, step in zip(states, (secant.update_compiled, secant.update_points)):
        got = []
        for scale in (1e-3, 1e-6, 1e-7):  # far, then near: the second update learns
            x = rng.normal(size=(active.size, m)) * scale
            res = np.einsum("ijk,ik->ij", jac[active], x)
            res[1] = np.nan if scale == 1e-7 else res[1]  # a point gone NaN learns nothing
            got.append(step(active, x, res, 1.01 * jac[active], state, NEAR_NORM))  # 1 % off
        outs.append(got)
        rng = np.random.default_rng(7)
        jac = rng.normal(size=(n, m, m)) + 3 * np.eye(m)
    for a, b in zip(*outs):
        assert np.array_equal(a, b)
    for a, b in zip(*states):
        assert np.array_equal(a, b, equal_nan=True)
    assert np.abs(states[0][0][active[0]]).max() > 1e-3  # a correction was learnt
