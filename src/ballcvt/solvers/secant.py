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

from dataclasses import dataclass

import numpy as np

__all__ = ["SecantCorrection", "NEAR_NORM"]

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
        not ``near``, its last one otherwise.
        """
        if active.size == self.near.size:  # every point (``active`` is sorted, unique)
            active = slice(None)  # views, not copies
        last_res = self.last_res[active]
        # (NaN norms, before a point's first evaluation, compare False)
        linear = (np.abs(res).max(axis=1) < NEAR_NORM) & (np.abs(last_res).max(axis=1) < NEAR_NORM)
        if linear.any():  # (most evaluations are far from the solution: no update)
            s = x - self.last_x[active]
            y = res - last_res
            ss = np.einsum("ij,ij->i", s, s)
            use = linear & (ss > 0) & np.isfinite(y).all(axis=1) & np.isfinite(ss)
        else:
            use = linear
        if use.any():
            k = np.arange(self.near.size)[active][use]
            s_u = s[use]
            jac_s = np.einsum("ijk,ik->ij", self.last_jac[k] + self.correction[k], s_u)
            miss = y[use] - jac_s
            self.correction[k] += miss[:, :, None] * s_u[:, None, :] / ss[use][:, None, None]
        self.last_x[active] = x
        self.last_res[active] = res
        far = ~self.near[active]
        if far.any():
            if jac is None:
                raise ValueError("a point far from its solution needs a fresh Jacobian")
            if far.all():
                self.last_jac[active] = jac
            else:
                self.last_jac[np.arange(self.near.size)[active][far]] = jac[far]
        return self.last_jac[active] + self.correction[active]  # (a new contiguous array)
