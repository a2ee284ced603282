"""Solve the equilibrium of one operating point for its creep coefficients.

Strategy: the batched Newton method of `ballcvt.solvers.newton` on the single point
(``method="newton"``, the default); if it fails, or with ``method="hybr"``, MINPACK's
hybrid Powell method (`scipy.optimize.root`, ``hybr``) with a
forward-difference Jacobian that has an absolute step floor (creeps span 1e-15 to 0.4,
docs/model.md §3). If that fails (typically near the traction limit from a cold start),
the bracketing solver of `ballcvt.solvers.bracketing`, which cannot wander off. A result is
reported converged only if the final residual, evaluated afresh, is below the tolerance.
"""

from __future__ import annotations

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from .newton import initial_creep, solve_batch
from .options import METHODS, SolverOptions
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
    if options.method == "hybr":
        return solve_robust(problem, options, x0)
    batch = solve_batch(problem, options, x0, fallback=False)
    return solve_robust(problem, options, x0, batch.state, int(batch.iterations))
