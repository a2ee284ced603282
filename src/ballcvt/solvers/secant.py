"""Secant correction of the analytic Jacobian near the solution (Broyden's good update).

The traction integrals' analytic derivatives (`ballcvt.model.traction.isothermal`) leave
out the motion of the pole-centred rule's nodes with the pole and the derivative of the
blend weight between the two rules: they change the sums only by the discretisation
error, but the Newton method zeroes the *discrete* residual, whose Jacobian they are then
off by up to about 1 % (measured on the Table I drive: the first balance's derivative
with respect to the input creep, 0.9 %). Newton's convergence is then linear near the
solution, by a factor of about 1/60 per iteration: from a warm start at a residual of
3e-6 it took five evaluations to reach 1e-11.

`SecantCorrection` keeps, per point, a correction ``E`` to the analytic Jacobian ``J_a``,
updated after every evaluation near the solution by Broyden's good update of the matrix
``J_a + E`` (Broyden 1965, Math. Comp. 19, 577-593, Eq. 4.5; Dennis and Moré 1977, SIAM
Rev. 19, 46-89, §8): with ``s`` the move of the creeps since the last evaluation and ``y``
the change of the residual,

    E <- E + (y - (J_a + E) s) s^T / (s^T s),

so that ``J_a + E`` satisfies the secant condition ``(J_a + E) s = y`` along the last
move. ``E`` captures the slowly varying part of the discretisation's derivative that the
analytic Jacobian lacks, and the convergence near the solution becomes superlinear.
Updates are made only while both residual norms are below `NEAR_NORM`, where the
residual is close to linear over a step (a secant through a far point would teach the
correction the residual's curvature instead). The converged answer is the same: only the
path to the tolerance changes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

njit: Any
try:
    from numba import njit
except ImportError:  # pragma: no cover - numba is a declared dependency
    njit = None

__all__ = ["SecantCorrection", "NEAR_NORM", "update_points"]

#: Largest residual norm [-] of both evaluations of a secant update.
NEAR_NORM = 1e-4


@dataclass
class SecantCorrection:
    """Per-point Jacobian corrections of one Newton run (mutable working state).

    Attributes
    ----------
    correction : ndarray
        ``E`` per point ``(n, m, m)`` on the free creeps [-].
    last_x : ndarray
        Free creeps of each point's last evaluation ``(n, m)`` [-] (NaN: none yet).
    last_res : ndarray
        Residuals there ``(n, m)`` [-].
    last_jac : ndarray
        The analytic Jacobian each point steps with ``(n, m, m)`` (plus its correction).
    near : ndarray of bool
        Whether each point's last evaluation was a step from a residual norm at most the
        solver's ``CONFIRM_NORM`` (`ballcvt.solvers.newton`): its next step then keeps its
        Jacobian, corrected, whether or not the batch evaluates a fresh one, so that a
        point's iterates do not depend on the other points of its batch.
    """

    correction: np.ndarray
    last_x: np.ndarray
    last_res: np.ndarray
    last_jac: np.ndarray
    near: np.ndarray

    @classmethod
    def start(cls, n: int, m: int) -> SecantCorrection:
        """No correction yet for ``n`` points of ``m`` free creeps."""
        nan = np.full((n, m), np.nan)
        return cls(np.zeros((n, m, m)), nan, nan.copy(), np.zeros((n, m, m)), np.zeros(n, bool))

    def update(self, active, x, res, jac=None):
        """Record the evaluation of the points ``active`` at free creeps ``x`` ``(k, m)``
        with residuals ``res`` ``(k, m)`` and analytic Jacobians ``jac`` ``(k, m, m)`` (None
        for a value-only evaluation, which only points ``near`` may have); returns the
        Jacobians to step with, ``J_a + E`` ``(k, m, m)``: the fresh one where the point is
        not ``near``, its last one otherwise (`update_points`).
        """
        active = np.asarray(active)
        if jac is None:
            if not self.near[active].all():
                raise ValueError("a point far from its solution needs a fresh Jacobian")
            jac = self.last_jac[active]  # (not read: every point keeps its last)
        state = (self.correction, self.last_x, self.last_res, self.last_jac, self.near)
        step = update_compiled if update_compiled is not None else update_points
        return step(active, x, res, jac, state, NEAR_NORM)


def update_points(active, x, res, jac, state, near_norm):
    """The loop of `SecantCorrection.update` over the points ``active`` (compiled where
    numba is installed: `update_compiled`); ``state``: the correction's ``(correction,
    last_x, last_res, last_jac, near)``, updated in place. A point whose residual norms,
    this evaluation's and its last, are both below ``near_norm`` (NaN: not) updates its
    correction by Broyden's good update along its move; every point keeps these creeps
    and residuals, and a point not ``near`` this Jacobian."""
    correction, last_x, last_res, last_jac, near = state
    k, m = x.shape
    out = np.empty((k, m, m))
    y = np.empty(m)
    s = np.empty(m)
    for p in range(k):
        a = active[p]
        if _small(res[p], near_norm) and _small(last_res[a], near_norm):
            finite = True
            for i in range(m):
                s[i] = x[p, i] - last_x[a, i]
                y[i] = res[p, i] - last_res[a, i]
                finite = finite and math.isfinite(y[i])
            ss = _dot(s, s)
            if ss > 0.0 and finite and math.isfinite(ss):
                for i in range(m):
                    miss = y[i] - _dot(last_jac[a, i] + correction[a, i], s)
                    for j in range(m):
                        correction[a, i, j] += miss * s[j] / ss
        last_x[a] = x[p]
        last_res[a] = res[p]
        if not near[a]:
            last_jac[a] = jac[p]
        out[p] = last_jac[a] + correction[a]
    return out


def _dot(u, v) -> float:
    """``u . v`` summed as NumPy's ``einsum`` sums a few terms (two running sums, of the
    even and of the odd terms; the same bits up to six terms): Newton's path near a fold
    of the thermal law turns on the last bit (harden task 2125:54)."""
    even = odd = 0.0
    for j in range(u.shape[0]):
        if j % 2 == 0:
            even += u[j] * v[j]
        else:
            odd += u[j] * v[j]
    return even + odd


def _small(values, bound) -> bool:
    """Whether every one of ``values`` is finite and its largest magnitude below ``bound``."""
    for v in values:
        if not abs(v) < bound:  # NaN too
            return False
    return True


#: `update_points`, `_dot` and `_small` compiled (None without numba).
_small = njit(cache=True)(_small) if njit is not None else _small
_dot = njit(cache=True)(_dot) if njit is not None else _dot
update_compiled: Any = njit(cache=True)(update_points) if njit is not None else None
