"""Solve the equilibrium of one operating point for its creep coefficients.

Strategy: the batched Newton method of `ballcvt.solvers.newton` on the single point
(``method="newton"``, the default); if it fails, or with ``method="hybr"``, MINPACK's
hybrid Powell method (`scipy.optimize.root`, ``hybr``) with a
forward-difference Jacobian that has an absolute step floor (creeps span 1e-15 to 0.4,
docs/model.md §3). If that fails (typically near the traction limit from a cold start),
the bracketing solver of `ballcvt.solvers.bracketing`, which cannot wander off. A result is
reported converged only if the final residual, evaluated afresh, is below the tolerance.
Under a traction law with more than one equilibrium (``multiple_equilibria``, the
thermal law) the point is instead followed from zero torque (`ballcvt.solvers.continuation`),
with either ``method``, so that it gets the equilibrium a sweep or a map gets.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..model.traction.base import has_multiple_equilibria
from .newton import initial_creep, solve_batch, solve_near
from .options import METHODS, SolverOptions, at_residual_floor
from .robust import PointSolution, solve_robust

__all__ = ["SolverOptions", "PointSolution", "solve_point", "initial_creep", "METHODS"]


def solve_point(
    problem: EquilibriumProblem, options: SolverOptions = SolverOptions(), x0=None, near=False
) -> PointSolution:
    """Solve one operating point (``problem.shape == ()``).

    Parameters
    ----------
    problem : EquilibriumProblem
        A single operating point.
    options : SolverOptions
        Numerical options.
    x0 : array_like, optional
        Starting creeps (e.g. a neighbouring point's solution).
    near : bool
        Whether ``x0`` lies next to the solution on the branch from zero torque (the
        optimal clamp's search found it there): under a law with more than one
        equilibrium Newton from it is then kept unless it lands past a fold, as a sweep
        keeps it (`ballcvt.solvers.newton.solve_near`); otherwise such a point is
        followed from zero torque whatever ``x0``.

    Returns
    -------
    PointSolution
        With ``converged`` False when no attempt met the tolerance.
    """
    if problem.shape != ():
        raise ValueError("solve_point takes a single operating point")
    start = None if x0 is None or not near else np.asarray(x0, dtype=float)
    x0 = initial_creep(problem) if x0 is None else np.asarray(x0, dtype=float)
    if has_multiple_equilibria(problem.fluid):
        return _on_branch(problem, at_residual_floor(options, problem.fluid), start)
    if options.method == "hybr":
        return solve_robust(problem, options, x0)
    batch = solve_batch(problem, options, x0, fallback=False)
    return solve_robust(problem, options, x0, batch.state, int(batch.iterations))


def _on_branch(problem: EquilibriumProblem, options: SolverOptions, x0=None) -> PointSolution:
    """The equilibrium reached from zero torque (a law with ``multiple_equilibria``,
    `ballcvt.solvers.continuation`), or from ``x0`` where Newton's answer from there does
    not lie past a fold (`solve_near`); no fallback from a cold start, which could land on
    another equilibrium."""
    if x0 is not None:
        batch = solve_near(problem.flat(), options, x0.reshape(1, -1))
        batch = replace(batch, state=batch.state.take(0), converged=batch.converged[0],
                        residual_norm=batch.residual_norm[0], iterations=batch.iterations[0])  # fmt: skip
    else:
        batch = solve_batch(problem, options)
    norm = float(batch.residual_norm)
    converged = bool(batch.converged)
    message = (
        "converged (continuation from zero torque)"
        if converged
        else (
            f"no equilibrium on the branch from zero torque: max|residual| = {norm:.3g} > "
            f"tol {options.tol:g} (the torque lies past the branch's fold, or the "
            "drive has no equilibrium at zero torque)"
        )
    )
    return PointSolution(batch.state, converged, norm, int(batch.iterations), message)
