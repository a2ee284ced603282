"""Why an operating point is refused: beyond the traction capacity, and the capacity there
(docs/model.md §8, §11)."""

from __future__ import annotations

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..registry import ARCHITECTURES
from .admissible import CREEP_RTOL
from .capacity import Capacity
from .clamped import pressure_bound_force
from .limit import limit_search
from .options import SolverOptions

__all__ = ["beyond_capacity", "point_capacity", "CREEP_RTOL"]


def beyond_capacity(problem: EquilibriumProblem, solution, follows: bool) -> str:
    """Why a converged point lies beyond the traction capacity, in one line ("" if not).

    Parameters
    ----------
    problem : EquilibriumProblem
        One operating point, at the force its clamping law set.
    solution : PointSolution
        Its equilibrium; a point that did not converge is not judged here.
    follows : bool
        Whether the force follows the torque (then the peak pressure is bounded by
        ``design.max_pressure``, docs/model.md §11).

    Returns
    -------
    str
        The contact whose ``|C|`` exceeds ``design.creep_limit`` and its creep, or the
        clamping force whose peak pressure exceeds ``design.max_pressure``.
    """
    if not solution.converged:
        return ""
    design = problem.design
    creep = np.abs(np.asarray(solution.state.creep, dtype=float)).reshape(-1)
    k = int(np.argmax(creep))
    if creep[k] > design.creep_limit * (1.0 + CREEP_RTOL):
        name = ARCHITECTURES.get(problem.layout.architecture).contacts[k]
        return (
            f"the {name} contact's creep {creep[k]:.3g} exceeds creep_limit {design.creep_limit:g}"
        )
    bound = float(pressure_bound_force(problem, design.max_pressure))
    if follows and float(problem.clamp_force) > bound * (1 + 1e-12):
        return (
            f"its clamping force {float(problem.clamp_force):.4g} N exceeds {bound:.4g} N, "
            f"the force of peak pressure max_pressure {design.max_pressure:g} Pa"
        )
    return ""


def point_capacity(
    problem: EquilibriumProblem,
    creep_limit: float,
    options: SolverOptions = SolverOptions(),
    law=None,
) -> Capacity:
    """The admissible output torques of one operating point (`limit_search`).

    Parameters
    ----------
    problem : EquilibriumProblem
        One operating point (its ``output_torque`` is ignored; under a torque-following
        ``law`` its ``clamp_force`` too).
    creep_limit : float
        ``C_lim`` [-].
    options : SolverOptions
        Solver options.
    law : clamping law, optional
        As in `limit_search`; by default the problem's constant ``clamp_force``.

    Returns
    -------
    Capacity
    """
    return Capacity.from_array(limit_search(problem, creep_limit, options, law=law).spans())
