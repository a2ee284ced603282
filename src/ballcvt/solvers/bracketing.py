"""A bracketing solver that exploits the structure of the residual (robust fallback).

For a fixed input creep ``C_0`` (hence ball speed), each idler balance and the output
balance depend on their own creep only and are monotone in it, so they are solved together
by a vectorised Illinois (regula falsi) iteration on brackets. What remains is the ball's
moment balance as a scalar function of ``C_0``, solved by `scipy.optimize.brentq`.
Slower than the hybrid method but it cannot wander off: every root is bracketed.
"""

from __future__ import annotations

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..equilibrium.residual import evaluate
from ..model.traction.quadrature import Quadrature

__all__ = ["solve_nested", "NoBracketError"]

#: Brackets of the creeps: disc creeps may approach 1 under overload; idlers stay small.
DISC_BRACKET = (-0.5, 0.97)
IDLER_BRACKET = (-0.5, 0.5)


class NoBracketError(RuntimeError):
    """A balance has no sign change over its creep bracket: no equilibrium exists there."""


def _inner(problem, c0, quadrature, xtol):
    """Solve the decoupled balances (idlers, output) for a given input creep.

    Returns the creep vector, its residual vector and the evaluations used.
    """
    n_c = problem.layout.n_contacts
    lo = np.array([c0] + [IDLER_BRACKET[0]] * (n_c - 2) + [DISC_BRACKET[0]])
    hi = np.array([c0] + [IDLER_BRACKET[1]] * (n_c - 2) + [DISC_BRACKET[1]])
    f_lo = evaluate(problem, lo, quadrature).residual
    f_hi = evaluate(problem, hi, quadrature).residual
    k = slice(1, None)
    if np.any(np.sign(f_lo[k]) == np.sign(f_hi[k])):
        raise NoBracketError("an idler or output balance has no root in its creep bracket")
    x = hi.copy()
    count = 2
    for _ in range(200):
        denom = np.where(f_hi != f_lo, f_hi - f_lo, 1.0)
        x = np.where(f_hi != f_lo, hi - f_hi * (hi - lo) / denom, 0.5 * (lo + hi))
        x[0] = c0
        f = evaluate(problem, x, quadrature).residual
        count += 1
        crossed = np.sign(f) != np.sign(f_hi)
        # Illinois: the kept end's value is halved so that it does not stay stale.
        lo, f_lo = np.where(crossed, hi, lo), np.where(crossed, f_hi, 0.5 * f_lo)
        hi, f_hi = x, f
        if np.all((np.abs(hi - lo) <= xtol * (1e-3 + np.abs(x)))[k] | (f[k] == 0)):
            break
    return x, f_hi, count


def solve_nested(problem: EquilibriumProblem, quadrature: Quadrature, xtol: float = 1e-13):
    """Solve a single operating point by nested bracketing.

    Returns
    -------
    creep : ndarray
        Creep vector at equilibrium.
    evaluations : int
        Residual evaluations used.

    Raises
    ------
    NoBracketError
        If a balance has no sign change over its bracket (e.g. torque beyond capacity).
    """
    total = [0]
    cache: dict[float, np.ndarray] = {}

    def outer(c0):
        x, f, n = _inner(problem, c0, quadrature, xtol)
        total[0] += n
        cache[c0] = x
        if not np.isfinite(f[0]):  # beyond the model's range (e.g. the Roelands limit)
            raise NoBracketError(f"the ball moment balance is not finite at input creep {c0:g}")
        return f[0]

    a, b = DISC_BRACKET
    fa, fb = outer(a), outer(b)
    if np.sign(fa) == np.sign(fb):
        raise NoBracketError("the ball moment balance has no root in the input-creep bracket")
    from scipy.optimize import brentq  # loaded when needed: scipy.optimize takes 0.4 s to import

    c0 = brentq(outer, a, b, xtol=1e-16, rtol=4 * np.finfo(float).eps, maxiter=200)
    x = cache.get(c0)
    if x is None:
        outer(c0)
        x = cache[c0]
    return x, total[0]
