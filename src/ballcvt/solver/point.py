"""Solve the equilibrium of one operating point for its creep coefficients.

Strategy: MINPACK's hybrid Powell method (`scipy.optimize.root`, ``hybr``) with a
forward-difference Jacobian that has an absolute step floor (creeps span 1e-15 to 0.4,
MODEL.md section 8). If that fails (typically near the traction limit from a cold start),
the bracketing solver of `ballcvt.solver.nested`, which cannot wander off. A result is
reported converged only if the final residual, evaluated afresh, is below the tolerance.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import root

from ..contact.quadrature import Quadrature
from ..equilibrium.problem import EquilibriumProblem
from ..equilibrium.residual import EquilibriumState, evaluate
from .nested import NoBracketError, solve_nested

__all__ = ["SolverOptions", "PointSolution", "solve_point", "initial_creep"]

#: Creeps outside this open interval are unphysical (speeds reverse); the residual
#: there is replaced by a large value so that the root finder backs off.
_CREEP_BOUNDS = (-0.5, 0.98)


@dataclass(frozen=True)
class SolverOptions:
    """Numerical options of the equilibrium solver.

    Attributes
    ----------
    quadrature : Quadrature
        Traction-integral rule.
    tol : float
        Largest accepted ``max |residual|`` (residuals are torques over ``F_N0 r_S``) [-].
    max_evaluations : int
        Residual evaluations allowed to the hybrid method before the fallback.
    """

    quadrature: Quadrature = Quadrature()
    tol: float = 1e-11
    max_evaluations: int = 400


@dataclass(frozen=True)
class PointSolution:
    """Outcome of `solve_point`: never silently unconverged (check ``converged``)."""

    state: EquilibriumState
    converged: bool
    residual_norm: float
    evaluations: int
    message: str


def initial_creep(problem: EquilibriumProblem) -> np.ndarray:
    """A starting creep vector: small positive disc creeps, zero idler creeps."""
    x0 = np.full(problem.layout.n_contacts, 1e-3)
    x0[problem.layout.is_idler] = 0.0
    return x0


def _attempt(problem, x0, options):
    count = [0]
    last: dict = {}

    def fun(x):
        if last and np.array_equal(x, last["x"]):
            return last["f"]  # hybr asks for f and the Jacobian at the same point
        count[0] += 1
        if np.any(x <= _CREEP_BOUNDS[0]) or np.any(x >= _CREEP_BOUNDS[1]):
            f = np.full_like(x, 1e3)
        else:
            f = evaluate(problem, x, options.quadrature).residual
        last.update(x=x.copy(), f=f)
        return f

    def jac(x):
        f0 = fun(x)
        h = 1e-7 * np.maximum(np.abs(x), 1e-4)
        cols = [(fun(x + np.eye(x.size)[j] * h[j]) - f0) / h[j] for j in range(x.size)]
        return np.column_stack(cols)

    sol = root(fun, x0, jac=jac, method="hybr",
               options={"xtol": 1e-14, "maxfev": options.max_evaluations})
    return sol, count[0]


def solve_point(problem: EquilibriumProblem, options: SolverOptions = SolverOptions(),
                x0=None) -> PointSolution:
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
    sol, evals = _attempt(problem, x0, options)
    x = sol.x
    state = evaluate(problem, x, options.quadrature)
    norm = float(np.max(np.abs(state.residual)))
    if not norm <= options.tol:
        try:
            x, n_ev = solve_nested(problem, options.quadrature)
            evals += n_ev
            state = evaluate(problem, x, options.quadrature)
            norm = float(np.max(np.abs(state.residual)))
            detail = "bracketing fallback"
        except NoBracketError as exc:
            detail = str(exc)
    else:
        detail = "hybrid method"
    converged = bool(norm <= options.tol and np.all(np.isfinite(state.residual)))
    message = f"converged ({detail})" if converged else (
        f"no equilibrium found: max|residual| = {norm:.3g} > tol {options.tol:g} ({detail})")
    return PointSolution(state, converged, norm, evals, message)

