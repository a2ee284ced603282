"""Traction capacity of a drive: the traction ceiling of its output contact and the limiting
torques of a set of curves (docs/model.md §8)."""

from __future__ import annotations

import numpy as np

from ..equilibrium.problem import build_problem
from ..params.drive import Drive
from ..solvers.limit import LimitSearch, saturated_traction
from ..solvers.options import SolverOptions
from .sweeps.curves import OperatingRows, limit_search_curves

__all__ = ["traction_ceiling", "limit_curves"]


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


def limit_curves(
    drive, ratio, *, clamp_force: float, input_speed: float, creep_limit: float | None = None
) -> LimitSearch:
    """Limiting torques of the curves at ``ratio`` under a constant clamping force.

    The search's outcome also holds the creeps at the limits, which a sweep over the same
    curves takes as its ``limit_torque`` (`ballcvt.analysis.sweeps.sweep`) to start every
    point in one batch.

    Parameters
    ----------
    drive : Drive or Variator
        Design, fluid, idler architecture and (optionally) solver ``options``.
    ratio : array_like
        Ideal ratios ``tau_ID`` [-], shape ``(m,)``.
    clamp_force : float
        ``F_N0`` [N].
    input_speed : float
        ``omega_0`` [rad/s].
    creep_limit : float, optional
        ``C_lim`` [-]; ``design.creep_limit`` by default.

    Returns
    -------
    LimitSearch
        ``torque`` [N m] (NaN where even zero torque is not admissible), ``(m,)``.
    """
    ratio = np.asarray(ratio, dtype=float)
    n = ratio.size
    options = getattr(drive, "options", None) or SolverOptions()
    c_lim = drive.design.creep_limit if creep_limit is None else float(creep_limit)
    rows = OperatingRows.of(
        Drive(drive.design, drive.fluid, drive.architecture),
        ratio,
        np.full(n, float(input_speed)),
        float(clamp_force),
        None,
        options,
        c_lim,
    )
    _, search = limit_search_curves(rows)
    return search
