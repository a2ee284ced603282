"""Scattered operating points, batched: what duty cycles and lookup tables evaluate.

A sweep solves a grid with continuation along the torque axis. Here every point has its
own ratio, torque and speed (a time series), so the points are solved together, from the
kinematic start, in chunks; each is classified by the admissibility test of the limiting
torque (`ballcvt.solvers.limit.solve_admissible`), so ``status`` 1 here means exactly
"above the limiting torque" (no limit search is needed to say so).
"""

from __future__ import annotations

import numpy as np

from ...equilibrium.problem import build_problem
from ...model.architectures import CONTACT_NAMES
from ...solvers.limit import solve_admissible
from ...solvers.point import SolverOptions
from .curves import at_optimal_forces, derived
from .variables import STATUS

__all__ = ["evaluate_points", "CHUNK"]

#: Points solved together (bounds memory; one progress-bar step each).
CHUNK = 1024


def evaluate_points(
    design,
    fluid,
    architecture,
    ratio,
    output_torque,
    input_speed,
    *,
    clamp_force=None,
    law=None,
    options: SolverOptions = SolverOptions(),
    creep_limit: float | None = None,
    callback=None,
    executor=None,
) -> dict:
    """Solve scattered operating points and report every quantity of a sweep at each.

    Parameters
    ----------
    design, fluid : Design, Fluid
        The drive.
    architecture : {"double", "single"}
        Idler architecture.
    ratio, output_torque, input_speed : array_like
        Ideal ratios [-], output torques >= 0 [N m] and input speeds > 0 [rad/s] of the
        points, 1-D and of equal length.
    clamp_force : array_like, optional
        ``F_N0`` [N] of the constant law (a number or one per point).
    law : clamping law, optional
        ``cam``, ``optimal`` or any law of `ballcvt.model.clamping` instead of ``clamp_force``.
    options : SolverOptions
        Solver options.
    creep_limit : float, optional
        ``C_lim`` [-]; the design's by default.
    callback : callable, optional
        Called with the number of points done after each chunk (progress bars).
    executor : concurrent.futures.Executor, optional
        Solve the chunks in its worker processes (the same results, to round-off).

    Returns
    -------
    dict of ndarray
        ``status`` (0 converged within the capacity, 1 beyond it, 2 not converged),
        ``clamp_force`` [N], and the point, contact and loss variables of a sweep
        (`ballcvt.analysis.sweeps.variables`) with a leading axis of length ``n`` (NaN where
        ``status`` is not 0).
    """
    ratio, torque, speed = (
        np.atleast_1d(np.asarray(a, dtype=float)) for a in (ratio, output_torque, input_speed)
    )
    n = ratio.size
    c_lim = design.creep_limit if creep_limit is None else float(creep_limit)
    optimal = law is not None and law.optimises
    follows = law if law is not None and not optimal else None
    force = (
        np.ones(n)
        if law is not None
        else np.broadcast_to(np.asarray(clamp_force, dtype=float), (n,)).astype(float)
    )
    build_problem(design, fluid, architecture, ratio, torque, force, speed)  # validate all
    # the same chunks with or without worker processes: the same results to round-off
    parts = np.array_split(np.arange(n), -(-n // CHUNK))
    if executor is not None and len(parts) > 1:
        futures = [
            executor.submit(
                evaluate_points,
                design,
                fluid,
                architecture,
                ratio[i],
                torque[i],
                speed[i],
                clamp_force=None if law is not None else force[i],
                law=law,
                options=options,
                creep_limit=c_lim,
            )
            for i in parts
        ]
        done = []
        for i, f in zip(parts, futures):
            done.append(f.result())
            if callback is not None:
                callback(i.size)
        return {k: np.concatenate([d[k] for d in done]) for k in done[0]}
    status = np.full(n, STATUS["not_converged"], dtype=np.int8)
    creep = np.full((n, 1, len(CONTACT_NAMES[architecture])), np.nan)
    used = force.copy()
    for idx in parts:
        pb = build_problem(
            design, fluid, architecture, ratio[idx], torque[idx], force[idx], speed[idx]
        )
        if optimal:  # the optimiser's force, then the constant law
            pb = at_optimal_forces(pb, law, options)
        got = solve_admissible(pb, c_lim, options, follows)
        used[idx] = got.problem.clamp_force
        # converged but inadmissible (creep or, under a cam, pressure), or running away
        beyond = got.converged | (np.max(np.abs(got.creep), axis=-1) > c_lim)
        status[idx] = np.where(
            got.ok,
            STATUS["converged"],
            np.where(beyond, STATUS["beyond_limit"], STATUS["not_converged"]),
        )
        creep[idx, 0] = np.where(got.ok[:, None], got.creep, np.nan)
        if callback is not None:
            callback(idx.size)
    out = derived(
        design,
        fluid,
        architecture,
        used[:, None],
        speed,
        ratio,
        torque[:, None],
        creep,
        status[:, None],
        options,
    )
    out = {k: v[:, 0] for k, v in out.items()}
    out["status"] = status
    out["clamp_force"] = np.where(status == 0, used, np.nan)
    return out
