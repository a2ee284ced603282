"""Whether operating points lie within the traction capacity (docs/model.md §8, §11).

`solve_admissible` solves a batch under a constant force or a torque-following clamping
law and says which points converged with every creep within ``creep_limit`` (and, under
such a law, every peak pressure within ``design.max_pressure``); it is the test of the
limit search (`ballcvt.solvers.limit`) and of the sweeps' point status.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from .clamped import at_ceiling, pressure_bound_force, solve_clamped
from .newton import solve_batch
from .options import SolverOptions, at_residual_floor

__all__ = ["Admissibility", "solve_admissible", "follows_torque"]


@dataclass(frozen=True)
class Admissibility:
    """Outcome of `solve_admissible`; arrays have the batch shape ``(n,)``.

    Attributes
    ----------
    problem : EquilibriumProblem
        The points at the forces their clamping law set.
    ok : ndarray of bool
        Converged with every ``|C| <= creep_limit`` (and, under a torque-following law,
        every peak pressure within ``design.max_pressure``).
    converged : ndarray of bool
        The equilibrium (and clamping equation) converged.
    creep : ndarray
        Final creeps, ``(n, n_c)``.
    beyond : ndarray of bool
        Inadmissible for a known reason: converged beyond a limit, creeps past the creep
        limit, or (under a torque-following law) a force that asks for more than the force
        of ``design.max_pressure`` (`ballcvt.solvers.clamped.solve_clamped` stops it there);
        an inadmissible point that is none of these did not converge.
    """

    problem: EquilibriumProblem
    ok: np.ndarray
    converged: np.ndarray
    creep: np.ndarray
    beyond: np.ndarray


def solve_admissible(
    problem: EquilibriumProblem,
    creep_limit: float,
    options: SolverOptions = SolverOptions(),
    law=None,
    x0=None,
) -> Admissibility:
    """Solve a 1-D batch and say which points lie within the traction capacity.

    Newton alone first; the point solver only for the points whose Newton run failed
    without its creeps running past the limit (a failure of the method, not of the
    equilibrium). A point whose Newton run fails with its creeps beyond the limit is
    beyond the capacity at once. This is the admissibility test of the limiting torque
    (docs/model.md §8, §11), so a point is admissible exactly when its torque is at most
    the limit.

    Parameters
    ----------
    problem : EquilibriumProblem
        Operating points, 1-D batch.
    creep_limit : float
        ``C_lim`` [-].
    options : SolverOptions
        Solver options.
    law : clamping law, optional
        A torque-following law (`ballcvt.model.clamping`); by default the problem's forces.
    x0 : array_like, optional
        Starting creeps ``(n, n_c)``.

    Returns
    -------
    Admissibility
    """
    law = law if follows_torque(law) else None
    if law is not None:

        def solve(pb, x, fallback):
            return solve_clamped(
                pb,
                law,
                lambda p, y: solve_batch(p, options, y, fallback),
                x,
                pb.design.max_pressure,
            )
    else:

        def solve(pb, x, fallback):
            return pb, solve_batch(pb, options, x, fallback=fallback)

    pb, sol = solve(problem, x0, False)
    big = np.max(np.abs(sol.state.creep), axis=-1)
    conv, creep = sol.converged.copy(), sol.state.creep.copy()
    # a point whose creeps converged but whose clamping equation did not (a force that runs
    # away) gets nothing from the point solver, which only ever replaces failed creeps
    balanced = sol.residual_norm <= at_residual_floor(options, pb.fluid).tol
    unsure = np.flatnonzero(~conv & ~(big > creep_limit) & ~balanced)
    if unsure.size:
        _, again = solve(pb.take(unsure), None if x0 is None else np.asarray(x0)[unsure], True)
        conv[unsure], creep[unsure] = again.converged, again.state.creep
    big = np.max(np.abs(creep), axis=-1)
    ok = conv & (big <= creep_limit)
    beyond = conv | (big > creep_limit)
    if law is not None:
        bound = pressure_bound_force(pb, pb.design.max_pressure)
        ok &= pb.clamp_force <= bound * (1 + 1e-12)
        beyond |= at_ceiling(pb.clamp_force, bound)
    return Admissibility(pb, ok, conv, creep, beyond & ~ok)


def follows_torque(law) -> bool:
    """Whether ``law`` sets a torque-dependent force (else the problem's force is used)."""
    return law is not None and not law.fixed_force
