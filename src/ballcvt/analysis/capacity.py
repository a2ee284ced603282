"""Traction capacity of a drive: the traction ceiling of its output contact and the
admissible output torques at an operating point (docs/model.md §8, §11)."""

from __future__ import annotations

import numpy as np

from ..equilibrium.problem import build_problem
from ..solvers.capacity import Capacity
from ..solvers.constraints import with_constraints
from ..solvers.limit import limit_search, saturated_traction
from ..solvers.optimal_capacity import capacity_search
from ..solvers.options import SolverOptions

__all__ = ["traction_ceiling", "torque_capacity", "Capacity"]


def torque_capacity(
    drive,
    ratio: float,
    law,
    input_speed: float,
    creep_limit: float | None = None,
    options: SolverOptions = SolverOptions(),
) -> Capacity:
    """Admissible output torques of an operating point, as intervals.

    The torques whose equilibrium converges with every ``|C| <= creep_limit`` (and, under
    a torque-following law, every peak pressure within ``design.max_pressure``;
    docs/model.md §8, §11). Under a constant force they run from zero to the limiting
    torque; under a loading cam with a small preload they may start above zero, or form
    two ranges (`ballcvt.solvers.capacity`).

    Parameters
    ----------
    drive : Drive or Variator
        Design, fluid and idler architecture.
    ratio : float
        Ideal ratio ``tau_ID`` [-].
    law : clamping law
        `ballcvt.model.clamping` law object (constant, cam, optimal).
    input_speed : float
        ``omega_0`` [rad/s].
    creep_limit : float, optional
        ``C_lim`` [-]; ``design.creep_limit`` by default.
    options : SolverOptions
        Solver options.

    Returns
    -------
    Capacity
        Empty when no torque is admissible; ``constraints`` names what sets each end
        (`ballcvt.solvers.constraints`).
    """
    design = drive.design
    c_lim = design.creep_limit if creep_limit is None else float(creep_limit)
    start = 1.0 if law.optimises else law.clamp_force(design, 0.0, 0.0)
    zero = build_problem(
        design, drive.fluid, drive.architecture, float(ratio), 0.0, start, float(input_speed)
    )
    problem, follows, c_lim, search = capacity_search(zero, law, c_lim, options)
    if search is None:  # (the optimal law's search for its force may have made it)
        search = limit_search(problem, c_lim, options, law=follows)
    cap = Capacity.from_array(search.spans())
    return with_constraints(problem, cap, c_lim, options, follows)


def traction_ceiling(drive, ratio: float, *, clamp_force: float, input_speed: float) -> dict:
    """Traction ceiling of the output contact and the torque its tangential forces carry.

    ``mu_max = a + tau_L0 pi a_x a_y / F_N`` (Eqs. 53-54, 57) at zero output torque, and
    the bound ``n F_N r_2 mu_max`` of the balls' saturated tangential forces.

    Parameters
    ----------
    drive : Drive or Variator
        Design, fluid and idler architecture.
    ratio : float
        Ideal ratio ``tau_ID`` [-].
    clamp_force : float
        ``F_N0`` [N] (constant clamping).
    input_speed : float
        ``omega_0`` [rad/s].

    Returns
    -------
    dict
        ``mu_max`` [-] and ``force_bound`` [N m].
    """
    problem = build_problem(
        drive.design, drive.fluid, drive.architecture, ratio, 0.0, clamp_force, input_speed
    )
    mu_max = float(np.asarray(saturated_traction(problem))[..., -1])
    force = problem.design.n_rollers * problem.load[..., -1] * problem.radius[-1] * mu_max
    return {"mu_max": mu_max, "force_bound": float(force)}
