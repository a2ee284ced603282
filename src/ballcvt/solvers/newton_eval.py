"""What the batched Newton solver evaluates at each iterate: the residual alone near the
solution, with its Jacobian elsewhere (`ballcvt.solvers.newton._newton`).

A point whose residual norm is at most `confirm_norm` before a Newton step and fell is
*near* its solution (`ballcvt.solvers.secant.SecantCorrection.near`): its next step keeps
its last Jacobian, corrected by Broyden's update, whether or not a fresh one is computed,
so its iterates do not depend on the other points of its batch. Its next evaluation then
needs the residual alone: `evaluate_split` evaluates the points near their solutions
without the Jacobian, apart from the rest of the batch. A residual without the traction
integrals' derivatives costs 0.5-0.6 of one with them (768 nodes per contact: 35 against
67 us per point under the hub's mixed lubrication, 16.5 against 27 on the paper's drive;
benchmarks, session 34).

How near is near. Below `NEAR_NORM` (1e-4, where the secant update is made: the residual
is close to linear over a step) the last Jacobian plus its correction steps as well as a
fresh analytic one, which is itself off by up to ~1 % (`ballcvt.solvers.secant`): a
quasi-Newton (Broyden) iteration from there (Dennis and Moré 1977, SIAM Rev. 19, 46-89,
§8). Under a law with more than one equilibrium (the thermal law) the residual turns
sharply near a fold of its branch, where Newton's path turns on the last bit (harden task
2125:54): a fresh Jacobian is kept down to `CONFIRM_NORM` there, as for every law before
session 34 (with `NEAR_NORM` a thermal planetary mode's capacity, a fold, came out 0.34
instead of above 1 N m: `tests/test_harden_regressions_modes.py`).
"""

from __future__ import annotations

import numpy as np

from ..equilibrium.residual import EquilibriumState, evaluate, evaluate_with_jacobian
from ..model.traction.base import has_multiple_equilibria
from .options import SPLIT_MIN
from .secant import NEAR_NORM

__all__ = ["CONFIRM_NORM", "SPLIT_MIN", "confirm_norm", "evaluate_split"]

#: Residual norm [-] below which a point steps with its last Jacobian (corrected) under a
#: law with more than one equilibrium (module docstring).
CONFIRM_NORM = 1e-6


def confirm_norm(fluid) -> float:
    """The residual norm [-] at most which a point of a batch under ``fluid``'s traction
    law is near its solution (module docstring): `NEAR_NORM`, or `CONFIRM_NORM` under a law
    with more than one equilibrium."""
    return CONFIRM_NORM if has_multiple_equilibria(fluid) else NEAR_NORM


def evaluate_split(problem, x, quadrature, near, split_min: int = SPLIT_MIN):
    """`evaluate_with_jacobian` of the points of the 1-D batch ``problem`` at creeps ``x``
    that are not ``near``, `evaluate` of the others (module docstring): the state of every
    point and the Jacobians, zero on the rows of the points near (not read: they step with
    their last). All together where fewer than ``split_min`` points are near; with
    ``split_min`` 1 a point is evaluated one way or the other whatever its batch, and its
    iterates are its own to the bit (the kernels with and without the derivatives round
    ``chi`` apart in its last bit: some 1e-14 in a thermal limit alone and in a batch)."""
    k = np.flatnonzero(near)
    if k.size < split_min:
        return evaluate_with_jacobian(problem, x, quadrature)
    if k.size == near.size:
        state = evaluate(problem, x, quadrature)
        return state, np.zeros(x.shape[:1] + (x.shape[1], x.shape[1]))
    f = np.flatnonzero(~near)
    far, jac_far = evaluate_with_jacobian(problem.take(f), x[f], quadrature)
    close = evaluate(problem.take(k), x[k], quadrature)
    jac = np.zeros((near.size,) + jac_far.shape[1:])
    jac[f] = jac_far
    return EquilibriumState.joined(near.size, ((f, far), (k, close))), jac
