"""Optimal clamping force: the paper's Fig. 8 remark as a feature.

For a ratio and output torque, find the clamping force ``F_N0`` that maximises the overall
efficiency subject to every ``|C| <= C_lim`` (traction capacity) and every Hertz peak
pressure ``<= p_lim`` (``design.max_pressure``).

`clamp_optimum` reports the optimum with the feasible range and the active constraint:
the optimum from the batched search (`ballcvt.solvers.optimal_batch.optimal_forces`, the
force `Variator.solve` uses under the optimal law), the range from the one-point search
(`ballcvt.solvers.optimal_search.search_optimum`, which also finds the optima the batched
search does not certify).
"""

from __future__ import annotations

from dataclasses import fields

import numpy as np

from .._compat import warn_renamed
from ..equilibrium.problem import build_problem
from ..model.clamping import OptimalClamp
from .optimal_batch import optimal_forces
from .optimal_search import SEARCH_SETTINGS, ClampCase, ClampOptimum, search_optimum
from .options import SolverOptions

__all__ = [
    "ClampCase",
    "ClampOptimum",
    "clamp_optimum",
    "optimal_force",
    "optimal_clamp_force",
    "optimal_start",
    "point_problem",
]


def optimal_clamp_force(*args, **kwargs) -> ClampOptimum:
    """Deprecated: ``optimal_clamp_force(design, fluid, architecture, ratio, output_torque,
    input_speed, options, creep_limit, max_pressure, min_force, grid, xtol)`` is
    `clamp_optimum` of a `ClampCase`, the limits and settings in an `OptimalClamp`."""
    warn_renamed(
        "optimal_clamp_force(design, fluid, ...)",
        "clamp_optimum(ClampCase(design, fluid, ...), OptimalClamp(...), options)",
    )
    names = tuple(f.name for f in fields(ClampCase)) + ("options",) + SEARCH_SETTINGS
    kw = {**dict(zip(names, args)), **kwargs}
    case = ClampCase(*(kw.pop(f.name) for f in fields(ClampCase)))
    options = kw.pop("options", SolverOptions())
    return clamp_optimum(case, OptimalClamp(**kw), options)


def clamp_optimum(
    case: ClampCase, law: OptimalClamp = OptimalClamp(), options: SolverOptions = SolverOptions()
) -> ClampOptimum:
    """Clamping force of maximum efficiency under the creep and pressure limits.

    At zero output torque the efficiency is zero at every force; the optimum there is the
    least force (from ``min_force``) that holds the no-load drag within the creep limit,
    the limit of the optimum as the torque falls to zero.

    Parameters
    ----------
    case : ClampCase
        The operating point (design, fluid, architecture, ratio [-], output torque
        [N m], input speed [rad/s]).
    law : OptimalClamp
        The limits (``creep_limit`` [-], ``max_pressure`` [Pa]: the design's when None;
        ``inf``: no pressure limit, the force then bounded only by the Roelands viscosity
        limit, docs/model.md §10, or by the efficiency) and the search settings
        (``min_force`` [N], ``grid``, ``xtol`` [N]).
    options : SolverOptions
        Solver options.

    Returns
    -------
    ClampOptimum

    Raises
    ------
    InputError
        Negative torque or non-positive limits.
    TractionLimitError
        If no clamping force up to the pressure bound carries the torque.
    """
    found = optimal_forces(point_problem(case), law, options, fallback=False)
    return search_optimum(case, law, options, float(found.force[0]) if found.fast[0] else None)


def optimal_force(
    case: ClampCase, law: OptimalClamp = OptimalClamp(), options: SolverOptions = SolverOptions()
) -> float:
    """The clamping force [N] of `clamp_optimum` without its feasible range: the batched
    search's where it certifies its optimum (a few batched solves of three forces), else
    the one-point search's.

    Raises
    ------
    InputError, TractionLimitError
        As `clamp_optimum`.
    """
    return optimal_start(case, law, options)[0]


def optimal_start(
    case: ClampCase, law: OptimalClamp = OptimalClamp(), options: SolverOptions = SolverOptions()
) -> tuple[float, np.ndarray | None]:
    """`optimal_force` and the creeps the batched search found there ``(n_c,)`` [-] (None
    where the one-point search gave the force), to start the solve at that force.

    Raises
    ------
    InputError, TractionLimitError
        As `clamp_optimum`.
    """
    found = optimal_forces(point_problem(case), law, options, fallback=False)
    if found.fast[0]:
        return float(found.force[0]), found.creep[0]
    return search_optimum(case, law, options).clamp_force, None


def point_problem(case: ClampCase):
    """The equilibrium problem of ``case`` as a batch of one point (any force)."""
    return build_problem(
        case.design,
        case.fluid,
        case.architecture,
        np.atleast_1d(float(case.ratio)),
        float(case.output_torque),
        1000.0,
        case.input_speed,
    )
