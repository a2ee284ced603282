"""Why `Variator.solve` refuses a point beyond the traction capacity, in one line.

The refusals name the contact and its creep (or the pressure bound) and give the admissible
output torques (`ballcvt.solvers.capacity.Capacity`, docs/model.md §8, §11).
"""

from __future__ import annotations

from ..equilibrium.problem import EquilibriumProblem
from ..errors import TractionLimitError
from ..solvers.admissible import follows_torque
from ..solvers.capacity import Capacity, no_equilibrium_error
from ..solvers.options import SolverOptions
from ..solvers.refusal import beyond_capacity, point_capacity

__all__ = ["optimal_refusal", "refuse_beyond_capacity"]


def optimal_refusal(output_torque: float, ratio: float, cap: Capacity) -> TractionLimitError:
    """The refusal of a torque for which the optimal law finds no clamping force.

    Parameters
    ----------
    output_torque : float
        The torque asked for [N m].
    ratio : float
        Ideal speed ratio ``tau_ID`` [-].
    cap : Capacity
        The admissible torques at that point under the optimal law.
    """
    return TractionLimitError(
        output_torque,
        cap.largest,
        f" at ratio {ratio:g}, optimal clamping law: no clamping force up to the "
        "pressure limit keeps every creep within creep_limit",
        "" if cap.limit == cap.largest else cap.describe(),
    )


def refuse_beyond_capacity(
    problem: EquilibriumProblem, sol, law, name: str, options: SolverOptions
) -> None:
    """Raise `TractionLimitError` if the solved point lies beyond the traction capacity.

    A converged point whose creep exceeds ``design.creep_limit`` (or, under a
    torque-following law, whose pressure exceeds ``design.max_pressure``) is refused, as is
    an unconverged point outside every admissible interval; where no torque at all is
    admissible, `NoEquilibriumError` says why (`ballcvt.solvers.capacity.no_equilibrium_error`).

    Parameters
    ----------
    problem : EquilibriumProblem
        The point as solved (under a torque-following law, at its clamping force).
    sol : PointSolution
        Its solution.
    law : ClampLaw
        The clamping law.
    name : str
        The law's name, for the message.
    options : SolverOptions
        Solver options of the capacity search.
    """
    follows = follows_torque(law)
    why = beyond_capacity(problem, sol, follows)
    if not (why or not sol.converged):
        return
    c_lim = problem.design.creep_limit
    cap = point_capacity(problem, c_lim, options, law)
    if not cap.intervals:  # none at all: NoEquilibriumError says why
        raise no_equilibrium_error(problem, c_lim, options, law if follows else None)
    torque = float(problem.output_torque)
    if why or not cap.admits(torque):
        where = (
            f"clamp {float(problem.clamp_force):g} N" if not follows else f"{name} clamping law"
        )
        raise TractionLimitError(
            torque,
            cap.largest,
            f" at ratio {float(problem.ratio):g}, {where}: {why or 'no equilibrium within it'}",
            "" if cap.intervals and cap.limit == cap.largest else cap.describe(),
        )
