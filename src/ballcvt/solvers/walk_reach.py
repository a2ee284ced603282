"""The equilibrium at a torque on the branch from zero torque, reached by the walk along
the branch where the torque continuation stopped short of it.

Under a law with more than one equilibrium (the thermal law, docs/model.md §14) each
solve follows its point's branch from zero torque (`ballcvt.solvers.continuation`). A
torque beyond the branch's fold has no equilibrium on it, and a torque continuation
finds that out slowly: its steps next to the fold fail after Newton runs to their
patience, halved until they are a hundredth of the torque (a thermal cam sweep's
capacity scan spent three quarters of its Newton iterations on the quarter of its
torques that lay past their folds). From the continuation's first failed step,
`walk_to_torque` walks the branch instead (`ballcvt.solvers.branch_path.follow_branch`):

* a walk that passes the torque brackets it between its last two points: the secant
  method in the creep that moved most between them (`ballcvt.solvers.held_creep.
  secant_in_creep`), then Newton at the torque;
* a walk whose torque falls first has passed the fold: the climb seeded by its last
  points locates the fold (`ballcvt.solvers.fold.climb_to_fold`), and a torque above
  it lies past the fold (no equilibrium of the branch);
* the other points (a failed walk, a fold at the creep bound or not clean, a torque
  between the walk's best and the fold, a negative torque, a planetary mode's torque
  condition) are left to the march in a held creep (`ballcvt.solvers.held_creep.
  reach_torque`).
"""

from __future__ import annotations

import numpy as np

from .branch_path import follow_branch, walks
from .fold import climb_to_fold
from .held_creep import disc_to_climb, secant_in_creep

__all__ = ["walk_to_torque", "PAST_RTOL", "CLIMB_BOUND", "FAR_MARGIN"]

#: Relative margin by which a torque must exceed the largest one the climb met to count
#: as past the fold [-]: the climb stops within `ballcvt.solvers.held_creep.
#: FOLD_CREEP_RTOL` of its creep bound (`CLIMB_BOUND`) of the fold's creep, some 1e-7 of
#: its torque below it; a torque within the margin goes to `reach_torque`.
PAST_RTOL = 1e-5
#: Relative margin by which a torque must exceed `_concave_bound` of a walk's last points to
#: count as past the fold without the climb that locates the fold [-]: a capacity scan's
#: torques far past their folds (at 2000 rpm, Table I's thermal cam sweep's lie at up to 17
#: times theirs) spent a third of its time in that climb (session 39).
FAR_MARGIN = 0.05
#: Bound on the creeps of the climb to the fold, in creep limits [-]. A solve has no creep
#: bound, and the fold of a heavily clamped drive can lie beyond the creep limit: a climb
#: bounded there ended undecided at the limit, and the march in a held creep
#: (`reach_torque`) went on to the fold (17 of the 102 torques past their folds of Table
#: I's thermal cam sweep's capacity scan, ratios 1.83 and 2 near the pressure bound, 6 %
#: of the sweep's time; the same verdicts). The walk before it has no bound.
CLIMB_BOUND = 2.0


def walk_to_torque(flat, pinned, at_torque, start):
    """The equilibria at each point's own torque on its branch, from the equilibria
    ``start`` ``(torque (n,), creeps (n, n_c))`` on the branch below it (module
    docstring).

    Parameters
    ----------
    flat : EquilibriumProblem
        Operating points, 1-D batch ``(n,)``, each at its target ``output_torque``.
    pinned : tuple
        `ballcvt.solvers.held_creep.Pinned` and the solver tolerance [-].
    at_torque : callable
        ``(problem, x0) -> (converged, creeps)``: Newton at the problems' own torques.
    start : tuple of ndarray
        Equilibria on the branch below the targets.

    Returns
    -------
    decided : ndarray of bool
        ``(n,)``: whether the walk decided the point (reached it, or found it past the
        fold); the others go to `reach_torque`.
    converged : ndarray of bool
        ``(n,)``: reached (False where past the fold or not decided).
    creep : ndarray
        ``(n, n_c)``; the start's where not converged.
    """
    t0, x0 = (np.array(v, dtype=float) for v in start)
    n = flat.size
    goal = np.broadcast_to(np.asarray(flat.output_torque, dtype=float), (n,))
    decided, good, out = np.zeros(n, dtype=bool), np.zeros(n, dtype=bool), x0.copy()
    up = np.flatnonzero((goal > 0.0) & (t0 >= 0.0))
    if up.size == 0 or not walks(flat):
        return decided, good, out
    sub = flat.take(up)
    scale = float(flat.design.creep_limit)
    walk = follow_branch(sub, pinned, None, (scale, np.inf), (t0[up], x0[up]), goal[up])
    fell = walk.stopped & ~walk.passed & np.isfinite(walk.after[0])
    past = np.zeros(up.size, dtype=bool)
    if fell.any():
        past[fell] = _past_fold(sub.take(np.flatnonzero(fell)), pinned, walk, fell, scale)
    passed = np.flatnonzero(walk.passed)
    if passed.size:
        ok, xs = _bracketed(sub.take(passed), pinned, walk, passed, at_torque)
        decided[up[passed]] = True
        good[up[passed]], out[up[passed]] = ok, np.where(ok[:, None], xs, out[up[passed]])
    decided[up[past]] = True
    return decided, good, out


def _bracketed(flat, pinned, walk, idx, at_torque):
    """The points ``idx`` of ``walk`` whose last step passed their torque: the secant in
    the creep that moved most over that step, then ``at_torque``. Returns
    ``(converged, creeps)``."""
    pin_solve, tol = pinned
    lo_x, hi_x = walk.creep[idx], walk.after[1][idx]
    lo_t, hi_t = walk.torque[idx], walk.after[0][idx]
    held = np.argmax(np.abs(hi_x - lo_x), axis=-1)
    xs = np.full_like(lo_x, np.nan)
    for k in np.unique(held):
        j = np.flatnonzero(held == k)
        lo = (lo_x[j, k], lo_t[j], lo_x[j], np.zeros(j.size, dtype=bool))
        hi = (hi_x[j, k], hi_t[j], hi_x[j])
        xs[j] = secant_in_creep(flat.take(j), pin_solve, int(k), tol, lo, hi)
    good = np.zeros(idx.size, dtype=bool)
    ready = np.flatnonzero(np.all(np.isfinite(xs), axis=-1))
    if ready.size:
        ok, xr = at_torque(flat.take(ready), xs[ready])
        ok = np.asarray(ok, dtype=bool)
        good[ready], xs[ready] = ok, np.where(ok[:, None], np.asarray(xr), xs[ready])
    return good, xs


def _past_fold(flat, pinned, walk, fell, scale) -> np.ndarray:
    """Whether the points ``fell`` of ``walk`` (their torque fell before their target)
    lie past their fold: the target above `FAR_MARGIN` over `_concave_bound`, or else the
    climb from the walk's last points to the fold (in the disc creep that moved more over
    its last step, within `CLIMB_BOUND` creep limits ``scale``), clean, below the target
    by more than `PAST_RTOL`."""
    pin_solve, tol = pinned
    nc = flat.layout.n_contacts
    first = disc_to_climb(walk.direction[fell])
    goal = np.broadcast_to(np.asarray(flat.output_torque, dtype=float), (flat.size,))
    past = goal > (1.0 + FAR_MARGIN) * _concave_bound(walk, fell)
    for k in (0, nc - 1):
        j = np.flatnonzero((first == k) & ~past)
        if j.size == 0:
            continue
        pick = np.flatnonzero(fell)[j]
        start = (walk.before[0][pick], walk.before[1][pick],
                 ((walk.torque[pick], walk.creep[pick]), tuple(v[pick] for v in walk.after)))  # fmt: skip
        climb = climb_to_fold(flat.take(j), pin_solve, k, CLIMB_BOUND * scale, tol, start, 1.0)
        past[j] = climb.clean & ~climb.at_pin & (goal[j] > climb.torque * (1.0 + PAST_RTOL))
    return past


def _concave_bound(walk, fell) -> np.ndarray:
    """An upper bound [N m] on the fold's torque of the points ``fell`` of ``walk``, from
    its last three points, ``(s, T)`` in the distance ``s`` along the creeps: the point
    before the last on the rising side, that one, and the fallen one. Where the torque is
    concave in ``s`` between them (as next to the top of a traction curve), the chord of
    each pair extended over the other pair's interval lies above it, so no torque there
    exceeds the larger of the two chords' values at the far ends."""
    idx = np.flatnonzero(fell)
    t_b, x_b = walk.before[0][idx], walk.before[1][idx]
    t_m, x_m = walk.torque[idx], walk.creep[idx]
    t_a, x_a = walk.after[0][idx], walk.after[1][idx]
    s_1 = np.linalg.norm(x_m - x_b, axis=-1)
    s_2 = np.linalg.norm(x_a - x_m, axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        rise = t_m + (t_m - t_b) / s_1 * s_2  # the first chord, at the fallen point
        back = t_m + (t_m - t_a) / s_2 * s_1  # the second chord, at the point before
    bound = np.fmax(np.fmax(rise, back), t_m)
    return np.where(np.isfinite(bound) & (s_1 > 0) & (s_2 > 0), bound, np.inf)
