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

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..model.traction.base import has_multiple_equilibria
from .newton import initial_creep, solve_batch
from .options import METHODS, SolverOptions, at_residual_floor
from .robust import PointSolution, solve_robust

__all__ = ["SolverOptions", "PointSolution", "solve_point", "initial_creep", "METHODS"]


def solve_point(
    problem: EquilibriumProblem, options: SolverOptions = SolverOptions(), x0=None
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

    Returns
    -------
    PointSolution
        With ``converged`` False when no attempt met the tolerance.
    """
    if problem.shape != ():
        raise ValueError("solve_point takes a single operating point")
    x0 = initial_creep(problem) if x0 is None else np.asarray(x0, dtype=float)
    if has_multiple_equilibria(problem.fluid):
        return _on_branch(problem, at_residual_floor(options, problem.fluid))
    if options.method == "hybr":
        return solve_robust(problem, options, x0)
    batch = solve_batch(problem, options, x0, fallback=False)
    return solve_robust(problem, options, x0, batch.state, int(batch.iterations))


def _on_branch(problem: EquilibriumProblem, options: SolverOptions) -> PointSolution:
    """The equilibrium reached from zero torque (a law with ``multiple_equilibria``,
    `ballcvt.solvers.continuation`); no fallback from a cold start, which could land on
    another equilibrium."""
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
