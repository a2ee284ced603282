"""The thermal law's partials at the film temperature it returns (session 36).

The law converges the film temperature rise on a cheap rule, then takes one Newton step
on the requested rule, and returns the coefficients at the stepped rise. Its partials at
a fixed rise were those at the cheap rule's rise, one step behind: the total derivatives
(the rise's response included) were off by some 3e-3, and Newton converged linearly (by
about 1e-3 an iteration on Table I). They now carry the step's limiting-shear factor
``exp(-beta_L step)``, the whole of their dependence on the rise but the film's."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from ballcvt import Variator
from ballcvt.equilibrium.problem import build_problem
from ballcvt.equilibrium.residual import evaluate_with_jacobian
from ballcvt.model.traction.contact import ContactState
from ballcvt.model.traction.quadrature import Quadrature
from ballcvt.model.traction.thermal import thermal_law_film_coefficients
from ballcvt.solvers.newton import solve_batch
from ballcvt.solvers.options import at_residual_floor

THERMAL = Variator(traction_law="thermal")
# Table I-like contacts past the linear range (creeps 2-4 %: there the pole-centred rule's
# own derivative, moving with the pole, is exact to 1e-10 under the isothermal law)
CREEP = np.array([0.02, 0.03, 0.04])
STATE = ContactState(CREEP, np.full(3, -1.5), 1.6e-3, 2.2e-4, 1.6e9, 2000.0, 0.03, 15.0, 1.5e-7)
STEP = 1e-5


def _mu(engine, **change):
    return thermal_law_film_coefficients(STATE.replace(**change), THERMAL.fluid,
                                         Quadrature(engine=engine))[0]  # fmt: skip


@pytest.mark.parametrize("engine", ["auto", "numpy"])
def test_total_derivatives_against_central_differences(engine):
    """By the creep term and by ``log u``: within 1e-3 of central differences (3.1e-3 and
    2.8e-3 before, on both engines)."""
    _, _, dmu, _ = thermal_law_film_coefficients(STATE, THERMAL.fluid, Quadrature(engine=engine))
    fd_c = (_mu(engine, creep_term=CREEP * (1 + STEP)) - _mu(engine, creep_term=CREEP * (1 - STEP)))
    fd_c /= 2 * STEP * CREEP
    np.testing.assert_allclose(dmu[:, 0], fd_c, rtol=1e-3)
    up = _mu(engine, u_ref=np.full(3, 15.0 * math.exp(STEP)))
    down = _mu(engine, u_ref=np.full(3, 15.0 * math.exp(-STEP)))
    np.testing.assert_allclose(dmu[:, 2], (up - down) / (2 * STEP), rtol=1e-3)


def test_newton_converges_faster_than_linearly():
    """Table I at 2 kN, 2000 rpm, five points below their folds, from the coarse rule's
    solutions: Newton's residual falls from ~1e-4 to below 2e-10 in two iterations (to
    ~1e-9 before: a factor of ~1e-3 an iteration)."""
    ratio, torque = np.array([0.6, 0.9, 1.2, 1.5, 1.8]), np.array([10.0, 18.0, 26.0, 34.0, 40.0])
    pb = build_problem(THERMAL.design, THERMAL.fluid, THERMAL.architecture, ratio, torque,
                       2000.0, 2000.0 * math.pi / 30).flat()  # fmt: skip
    options = at_residual_floor(THERMAL.options, THERMAL.fluid)
    x = solve_batch(pb, replace(options, quadrature=options.predictor, tol=1e-13)).state.creep
    norms = []
    for _ in range(3):
        state, jac = evaluate_with_jacobian(pb, x, options.quadrature)
        norms.append(np.abs(state.residual).max(axis=-1))
        x = x + np.linalg.solve(jac, -state.residual[..., None])[..., 0]
    assert np.all(norms[0] > 1e-5)
    assert np.all(norms[2] < 2e-10), norms
