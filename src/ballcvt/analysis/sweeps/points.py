"""Scattered operating points, batched: what duty cycles and lookup tables evaluate.

A sweep solves a grid with continuation along the torque axis. Here every point has its
own ratio, torque and speed (a time series), so the points are solved together, from the
kinematic start, in chunks; each is classified by the admissibility test of the limiting
torque (`ballcvt.solvers.limit.solve_admissible`), so ``status`` 1 here means exactly
"above the limiting torque" (no limit search is needed to say so).
"""

from __future__ import annotations

import numpy as np

from ...solvers.admissible import solve_admissible
from ...solvers.newton import solve_batch
from ...status import Status
from .curves import OperatingRows, derived, optimal_start

__all__ = ["evaluate_points", "CHUNK"]

#: Points solved together (bounds memory; one progress-bar step each).
CHUNK = 1024


def evaluate_points(
    points: OperatingRows,
    output_torque,
    callback=None,
    executor=None,
    beyond: bool = False,
    start=None,
) -> dict:
    """Solve scattered operating points and report every quantity of a sweep at each.

    Parameters
    ----------
    points : OperatingRows
        The points' drive, ratios [-], input speeds > 0 [rad/s] and constant clamping
        forces [N] (or clamping law), one row per point (`OperatingRows.of` builds them from
        array-likes).
    output_torque : array_like
        Output torque >= 0 [N m] of each point, 1-D, as long as ``points``.
    callback : callable, optional
        Called with the number of points done after each chunk (progress bars).
    executor : concurrent.futures.Executor, optional
        Solve the chunks in its worker processes (the same results, to round-off).
    beyond : bool
        Whether the points converged beyond the capacity (``status`` 1) are reported too
        (else NaN): the oil's heat balance takes their losses, as `Variator.solve` with
        ``check_capacity=False`` gives them (`ballcvt.analysis.oil_sweep.balanced_tops`).
    start : array_like, optional
        Creeps ``(n, n_c)`` [-] near each point's solution (a duty cycle's first pass's,
        on the coarse rule, at nearby conditions; NaN rows: none): the solves start there
        without the predictor stage (`_solve_chunk`).

    Returns
    -------
    dict of ndarray
        ``status`` (`ballcvt.status.Status`: converged within the capacity, beyond it,
        not converged), ``clamp_force`` [N], and the point, contact and loss variables of a
        sweep (`ballcvt.analysis.sweeps.variables`) with a leading axis of length ``n``
        (NaN where ``status`` is not converged, or not 0 unless ``beyond``).
    """
    torque = np.atleast_1d(np.asarray(output_torque, dtype=float))
    n, law = points.size, points.law
    given = points.clamp_force
    force = np.ones(n) if law is not None or given is None else given
    points.problem(slice(None), torque, force)  # validate all
    # the same chunks with or without worker processes: the same results to round-off
    parts = np.array_split(np.arange(n), -(-n // CHUNK))
    x0 = None if start is None else np.asarray(start, dtype=float)

    def starts(i):
        return None if x0 is None else x0[i]

    if executor is not None and len(parts) > 1:
        futures = [
            executor.submit(
                evaluate_points, points.take(i), torque[i], None, None, beyond, starts(i)
            )
            for i in parts
        ]
        chunks = ((i, f.result()) for i, f in zip(parts, futures))
    else:
        chunks = (
            (i, _solve_chunk(points, i, torque[i], force[i], beyond, starts(i))) for i in parts
        )
    out: dict = {}
    for idx, got in chunks:  # each chunk into the output arrays, then dropped
        if not out:  # allocated once: every point is written by its chunk
            out = {k: np.empty((n,) + v.shape[1:], dtype=v.dtype) for k, v in got.items()}
        for k, v in got.items():
            out[k][idx] = v
        if callback is not None:
            callback(idx.size)
    return out


def _solve_chunk(points: OperatingRows, idx, torque, force, beyond=False, start=None) -> dict:
    """Solve and report the points ``idx`` (one chunk; see `evaluate_points`; ``start``:
    the chunk's starting creeps, or None)."""
    law, c_lim = points.law, points.creep_limit
    follows = law if law is not None and not points.optimal else None
    pb = points.problem(idx, torque, force)
    # given starting creeps (near the solutions), Newton on the full rule at once
    x0, predict = start, start is None
    if points.optimal:  # the optimiser's force (from the rows' forces if given), then constant
        guess = None if points.clamp_force is None else points.clamp_force[idx]
        pb, x0 = optimal_start(pb, law, points.options, guess, start)
        # from the search's creeps, near the solutions: no predictor stage, which would
        # only move them to its coarse rule's solutions (as a sweep's `solve_column`)
        predict = bool(np.isnan(x0).any())
    # rows with no start are cold (NaN: the kinematic start, `solve_admissible`)
    x0 = np.full((idx.size, pb.layout.n_contacts), np.nan) if x0 is None else x0
    got = solve_admissible(pb, c_lim, points.options, follows, x0, predict)
    used = np.array(got.problem.clamp_force, dtype=float)
    # converged but inadmissible (creep or, under a cam, pressure), or running away
    status = np.where(
        got.ok,
        Status.CONVERGED,
        np.where(got.beyond, Status.BEYOND_LIMIT, Status.NOT_CONVERGED),
    ).astype(np.int8)
    shown, solved = (got.ok, got.creep) if not beyond else _beyond(got, follows, points.options)
    creep = np.where(shown[:, None], solved, np.nan)[:, None]
    listed = np.where(shown, Status.CONVERGED, status)[:, None]  # the points derived
    out = derived(points.take(idx), used[:, None], torque[:, None], creep, listed)
    out = {k: v[:, 0] for k, v in out.items()}
    out["status"] = status
    out["clamp_force"] = np.where(status == Status.CONVERGED, used, np.nan)
    return out


def _beyond(got, law, options) -> tuple[np.ndarray, np.ndarray]:
    """``(converged, creeps)`` of every point of ``got`` (`Admissibility`) with the points
    whose run stopped as soon as a creep passed the limit (beyond the capacity at once)
    solved on to convergence, as `Variator.solve` with ``check_capacity=False`` solves
    them (a law's force fixed before the solve; a law that senses the input torque keeps
    the shortcut)."""
    conv, creep = got.converged.copy(), np.array(got.creep, dtype=float)
    if law is not None and law.implicit:
        return conv, creep
    redo = np.flatnonzero(got.beyond & ~conv & np.all(np.isfinite(creep), axis=-1))
    if redo.size:
        sol = solve_batch(got.problem.take(redo), options, creep[redo])
        conv[redo], creep[redo] = sol.converged, sol.state.creep
    return conv, creep
