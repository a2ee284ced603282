"""Which constraint sets each end of the traction capacity (docs/model.md §8, §11).

An end of an admissible interval of output torque (`ballcvt.solvers.capacity.Capacity`)
is where a torque just past it is inadmissible. That torque is solved once
(`ballcvt.solvers.limit.solve_admissible`) and the first constraint it breaks names the
end:

- ``"no equilibrium"``: its equilibrium (or clamping equation) does not converge;
- ``"creep (<name> contact)"``: a contact's ``|C|`` exceeds the creep limit (the contact
  with the largest ``|C|`` is named, from the architecture's contact names);
- ``"pressure (max_pressure <p> GPa)"``: under a torque-following law, its clamping force
  puts a peak pressure above ``design.max_pressure``;
- ``"zero torque"``: the lower end of an interval that starts at zero (no constraint).

A torque just past an end that is still admissible (an end on the scan's upper bound that
the scan could not pass, or an end within the solver's tolerance) is named by the
constraint closest to binding at the end itself: the creep of the contact nearest the
limit, or the pressure when the force is within 0.1 % of its bound.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..registry import ARCHITECTURES
from .admissible import solve_admissible
from .capacity import Capacity
from .clamped import pressure_bound_force
from .limit import LIMIT_RTOL
from .options import SolverOptions

__all__ = ["with_constraints", "ZERO_TORQUE", "NO_EQUILIBRIUM", "PAST_END"]

#: The lower end of an interval starting at zero torque.
ZERO_TORQUE = "zero torque"
#: The name of a torque (or an empty capacity) without a converged equilibrium.
NO_EQUILIBRIUM = "no equilibrium"
#: Relative step past an end at which the broken constraint is read [-] (ten times the
#: limit search's bracket width, so the step leaves the bracket).
PAST_END = 10.0 * LIMIT_RTOL


def with_constraints(
    problem: EquilibriumProblem,
    capacity: Capacity,
    creep_limit: float,
    options: SolverOptions = SolverOptions(),
    law=None,
) -> Capacity:
    """``capacity`` with the constraint that sets each end of each interval.

    Parameters
    ----------
    problem : EquilibriumProblem
        The operating point the capacity was found for (its ``output_torque`` is ignored).
    capacity : Capacity
        Its admissible intervals (`ballcvt.solvers.refusal.point_capacity`).
    creep_limit : float
        ``C_lim`` [-].
    options : SolverOptions
        Solver options.
    law : clamping law, optional
        The torque-following law of the search; by default the problem's constant force.

    Returns
    -------
    Capacity
        With ``constraints``: one ``(lower, upper)`` pair of names per interval (module
        docstring). An empty capacity is returned as it is (its ``active_constraint`` is
        ``"no equilibrium"``).
    """
    ends = np.array([t for span in capacity.intervals for t in span], dtype=float)
    if ends.size == 0:
        return capacity
    side = np.tile([-1.0, 1.0], len(capacity.intervals))
    past = ends * (1.0 + side * PAST_END)
    rows = np.zeros(ends.size, dtype=int)
    both = np.concatenate([ends, past])
    got = solve_admissible(
        replace(problem.flat().take(np.concatenate([rows, rows])), output_torque=both),
        creep_limit,
        options,
        law,
    )
    names = [
        ZERO_TORQUE if (k % 2 == 0 and ends[k] == 0.0) else _name(got, k, ends.size, creep_limit)
        for k in range(ends.size)
    ]
    pairs = tuple((names[2 * i], names[2 * i + 1]) for i in range(len(capacity.intervals)))
    return replace(capacity, constraints=pairs)


def _name(got, k: int, n: int, creep_limit: float) -> str:
    """The constraint broken just past end ``k`` (solved at ``n + k``; the end itself at
    ``k``)."""
    pb = got.problem
    contacts = ARCHITECTURES.get(pb.layout.architecture).contacts
    p_max = pb.design.max_pressure
    bound = np.asarray(pressure_bound_force(pb, p_max), dtype=float).reshape(-1)
    force = np.asarray(pb.clamp_force, dtype=float).reshape(-1)
    pressure = f"pressure (max_pressure {p_max / 1e9:g} GPa)"
    j = n + k
    if not got.ok[j]:
        if not got.converged[j]:
            return NO_EQUILIBRIUM
        creep = np.abs(got.creep[j])
        if np.max(creep) > creep_limit:
            return f"creep ({contacts[int(np.argmax(creep))]} contact)"
        return pressure
    # still admissible past the end: the constraint nearest to binding at the end
    if force[k] >= bound[k] * (1.0 - 1e-3):
        return pressure
    return f"creep ({contacts[int(np.argmax(np.abs(got.creep[k])))]} contact)"
