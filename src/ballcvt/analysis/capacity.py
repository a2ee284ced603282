"""Traction capacity of a drive: the traction ceiling of its output contact and the limiting
torques of a set of curves (docs/model.md §8)."""

from __future__ import annotations

import numpy as np

from ..equilibrium.problem import build_problem
from ..solvers.limit import saturated_traction

__all__ = ["traction_ceiling"]


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
