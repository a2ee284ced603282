"""The robust single-point path: MINPACK's hybrid method, then bracketing.

Used where the batched Newton method (`ballcvt.solvers.newton`) did not converge, and by
``SolverOptions(method="hybr")``. MINPACK's hybrid Powell method (`scipy.optimize.root`,
``hybr``) runs with a forward-difference Jacobian that has an absolute step floor (creeps
span 1e-15 to 0.4, docs/model.md §3); if that fails (typically near the traction limit from
a cold start), the bracketing solver of `ballcvt.solvers.bracketing`, which cannot wander
off. A result is reported converged only if the final residual, evaluated afresh, is below
the tolerance.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..equilibrium.residual import EquilibriumState, evaluate
from .bracketing import NoBracketError, solve_nested
from .options import CREEP_BOUNDS, SolverOptions
from .trials import quiet_trials

__all__ = ["PointSolution", "solve_robust"]


@dataclass(frozen=True)
class PointSolution:
    """Outcome of `solve_point`: never silently unconverged (check ``converged``)."""

    state: EquilibriumState
    converged: bool
    residual_norm: float
    evaluations: int
    message: str


def _attempt(problem, x0, options):
    count = [0]
    last: dict = {}

    def fun(x):
        if last and np.array_equal(x, last["x"]):
            return last["f"]  # hybr asks for f and the Jacobian at the same point
        count[0] += 1
        if np.any(x <= CREEP_BOUNDS[0]) or np.any(x >= CREEP_BOUNDS[1]):
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

    from scipy.optimize import root  # loaded when needed: scipy.optimize takes 0.4 s to import

    sol = root(
        fun, x0, jac=jac, method="hybr", options={"xtol": 1e-14, "maxfev": options.max_evaluations}
    )
    return sol, count[0]


@quiet_trials
def solve_robust(
    problem: EquilibriumProblem,
    options: SolverOptions,
    x0,
    state: EquilibriumState | None = None,
    evals: int = 0,
) -> PointSolution:
    """Finish one point (``problem.shape == ()``) by the hybrid method, then bracketing.

    Parameters
    ----------
    problem : EquilibriumProblem
        A single operating point.
    options : SolverOptions
        Numerical options; with ``method="newton"`` the hybrid method runs only if
        ``state`` (a Newton attempt) missed the tolerance.
    x0 : ndarray
        Starting creeps [-].
    state : EquilibriumState, optional
        The Newton attempt's state, if one was made.
    evals : int
        Evaluations spent so far.

    Returns
    -------
    PointSolution
        With ``converged`` False when no attempt met the tolerance.
    """
    if state is None:
        norm, detail = np.inf, ""
    else:
        norm, detail = float(np.max(np.abs(state.residual))), "Newton"
    if options.method == "hybr" or not norm <= options.tol:
        sol, n_ev = _attempt(problem, x0, options)
        evals = n_ev if options.method == "hybr" else evals + n_ev
        state = evaluate(problem, sol.x, options.quadrature)
        norm = float(np.max(np.abs(state.residual)))
        detail = "hybrid method"
    if not norm <= options.tol:
        try:
            x, n_ev = solve_nested(problem, options.quadrature)
            evals += n_ev
            state = evaluate(problem, x, options.quadrature)
            norm = float(np.max(np.abs(state.residual)))
            detail = "bracketing fallback"
        except NoBracketError as exc:
            detail = str(exc)
    assert state is not None  # the hybrid method ran when no Newton state was given
    converged = bool(norm <= options.tol and np.all(np.isfinite(state.residual)))
    message = (
        f"converged ({detail})"
        if converged
        else (f"no equilibrium found: max|residual| = {norm:.3g} > tol {options.tol:g} ({detail})")
    )
    return PointSolution(state, converged, norm, evals, message)
