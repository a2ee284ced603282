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

from dataclasses import dataclass

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..equilibrium.residual import EquilibriumState, evaluate
from ..model.traction.quadrature import Quadrature
from .bracketing import NoBracketError, solve_nested
from .newton import CREEP_BOUNDS, initial_creep, solve_batch

__all__ = ["SolverOptions", "PointSolution", "solve_point", "initial_creep"]

METHODS = ("newton", "hybr")


@dataclass(frozen=True)
class SolverOptions:
    """Numerical options of the equilibrium solvers.

    Attributes
    ----------
    quadrature : Quadrature
        Traction-integral rule.
    tol : float
        Largest accepted ``max |residual|`` (residuals are torques over ``F_N0 r_S``) [-].
    method : {"newton", "hybr"}
        ``newton``: the batched Newton method with analytic traction derivatives (fast,
        default); ``hybr``: SciPy's hybrid method with a finite-difference Jacobian (the
        straightforward path, kept as a baseline). Both fall back to bracketing.
    max_iterations : int
        Newton iterations allowed (per stage) before the fallback.
    predictor : Quadrature or None
        Coarse rule on which the Newton method first converges to ``predictor_tol``
        (a cheap starting point for the iterations on ``quadrature``); None to skip.
    predictor_tol : float
        Tolerance of the predictor stage [-].
    predictor_min_points : int
        Smallest batch that runs the predictor stage. On a few points an iteration
        costs the same on either rule (Python, not the integrals, dominates), and Newton
        on the requested rule alone needs 3-5 iterations where the two stages need 7;
        the predictor pays from a few tens of points up (benchmarks/bench_paths.py).
    max_evaluations : int
        Residual evaluations allowed to the hybrid method before the fallback.
    """

    quadrature: Quadrature = Quadrature()
    tol: float = 1e-11
    method: str = "newton"
    max_iterations: int = 40
    max_evaluations: int = 400
    predictor: Quadrature | None = Quadrature("pole", 12, 8, 12)
    predictor_tol: float = 1e-6
    predictor_min_points: int = 32

    def __post_init__(self):
        if self.method not in METHODS:
            raise ValueError(f"solver method must be one of {METHODS}, got {self.method!r}")


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
    if options.method == "newton":
        batch = solve_batch(problem, options, x0, fallback=False)
        state, norm, evals = batch.state, float(batch.residual_norm), int(batch.iterations)
        detail = "Newton"
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
    converged = bool(norm <= options.tol and np.all(np.isfinite(state.residual)))
    message = (
        f"converged ({detail})"
        if converged
        else (f"no equilibrium found: max|residual| = {norm:.3g} > tol {options.tol:g} ({detail})")
    )
    return PointSolution(state, converged, norm, evals, message)
