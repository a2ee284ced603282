"""Limiting torques where the drive can have more than one equilibrium (the thermal law).

Where a contact's traction falls past the peak of its curve, the branch of equilibria
that starts at zero torque folds back, and a second equilibrium can exist at the same
torque with every creep within the limit. The limiting torque is then the largest torque
the drive reaches on the branch from zero torque with every ``|C| <= C_lim``: the fold,
or the torque where a creep reaches ``C_lim`` if that comes first (docs/model.md §8,
§14). The branch is walked from zero torque in a moving held creep to next to its fold
(`ballcvt.solvers.branch_path.follow_branch`); where the walk's solves fail, and under a
planetary mode's torque condition, it is followed instead by the torque continuation by
which every solve under such a law is made (`ballcvt.solvers.continuation`) to within
`PEAK_RTOL` of where it stops. Next to the fold Newton converges slowly in the torque (its
Jacobian turns singular there), so the fold is then located in the creep: from there, a
disc contact's creep is held (`ballcvt.solvers.newton.solve_pinned`, regular through the
fold) and the largest torque of the branch found by a one-dimensional maximisation in it
(`ballcvt.solvers.fold.climb_to_fold`). A limit at a
fold is reported `FOLD_MARGIN` below it (a solve exactly at a fold does not converge),
once a solve converges there: Newton from the held creep's secant to that torque, else
the solve's own continuation from zero torque. Used by `ballcvt.solvers.limit.
limit_search`.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from .branch_path import by_torque, follow_branch, walks
from .continuation import continue_in_torque, solve_twice
from .fold import Climb, climb_to_fold
from .held_creep import FOLD_CREEP_RTOL, disc_to_climb, on_branch, secant_in_creep
from .newton import PATIENCE, branch_pinned, branch_solver, branch_turned
from .options import at_residual_floor

__all__ = ["peak_limits", "PEAK_RTOL", "FOLD_MARGIN", "PEAK_PIN_MARGIN", "FOLD_CREEP_RTOL"]

#: Smallest torque step of the continuation to the limit, as a share of the problem's
#: ``torque_scale`` ``n F_N0 r_S`` (480 N m on Table I's drive at 2 kN) [-]: the climb in
#: the creep does the rest (at 1e-5, as before the climb, the continuation's failed steps
#: next to the fold were two thirds of a thermal sweep's limit search).
PEAK_RTOL = 1e-2
#: Relative margin below a fold at which its limit is reported [-]: a solve converges
#: there, and fails at ``1.001`` times it.
FOLD_MARGIN = 2e-4
#: Relative margin below ``C_lim`` at which a creep is held for a limit there [-]:
#: next to a fold the torque is flat in the creep, and a solve at the held creep's torque
#: meets the creep only to its noise over that slope (harden task 2703:530 of a
#: thermal-only campaign: 3.5 N m per unit creep, a solve 2e-8 over ``C_lim`` held
#: `ballcvt.solvers.limit.PIN_MARGIN` = 1e-7 below it). Ten times that margin.
PEAK_PIN_MARGIN = 1e-6


def peak_limits(flat, creep_limit, options, x_zero=None, path=False):
    """Limiting torques of the 1-D batch ``flat`` under a law with more than one
    equilibrium (docs/model.md §8, §14): each point is followed from zero torque up while
    its equilibrium converges with every ``|C| <= creep_limit``, by the walk along its
    branch (or to within `PEAK_RTOL` of where the torque continuation stops;
    `_rise_to_fold`), then its fold is located in a disc contact's held creep
    (`ballcvt.solvers.fold.climb_to_fold`).

    Returns the torques ``(n,)`` [N m] and the creeps there ``(n, n_c)``; NaN where even
    zero torque is inadmissible. ``x_zero`` (starting creeps of the other limit methods)
    is not used: the continuation starts from the cold start at zero torque. With
    ``path``, also the equilibria met on the way (`_scan`), or None without a walk.
    """
    options = at_residual_floor(options, flat.fluid)
    pin = creep_limit * (1.0 - PEAK_PIN_MARGIN)

    def admissible(x):
        return np.max(np.abs(x), axis=-1) <= pin

    solve = branch_solver(options)
    pinned = branch_pinned(options)
    turned = branch_turned(flat, options)  # a step onto a torque that jumped a fold
    walk = (solve, branch_pinned(options, PATIENCE))
    torque, x, seed, walked = _rise_to_fold(flat, walk, options.quadrature, pin, admissible)
    keep = np.flatnonzero(np.isfinite(torque))
    if keep.size:
        sub = flat.take(keep)
        seed = tuple((t[keep], xx[keep]) for t, xx in seed[:2]) + (seed[2][keep],)
        climb, k = _climb(sub, pinned, pin, (torque[keep], x[keep], seed))
        top = np.where(climb.at_pin, climb.torque, climb.torque * (1.0 - FOLD_MARGIN))
        idx = np.flatnonzero(top > torque[keep])
        if idx.size:  # a solve must converge there
            good, xr = _reach_top(sub.take(idx), (solve, pinned, turned), climb.take(idx),
                                  k[idx], top[idx])  # fmt: skip
            # within the creep limit itself: the top was held at `pin`, PEAK_PIN_MARGIN
            # below it, and a solve at its torque meets that creep to round-off, on
            # either side (harden task 2803:367: 1.4e-16 above `pin`, and the limit fell
            # to the walk's point before its last, 78.5 N m for 171.6)
            good &= np.max(np.abs(xr), axis=-1) <= creep_limit
            torque[keep[idx[good]]], x[keep[idx[good]]] = top[idx[good]], xr[good]
            _below_later_fold(sub, (solve, turned), (idx[~good], top[idx[~good]]), admissible,
                              (keep, torque, x))  # fmt: skip
    keep = np.isfinite(torque)
    out = np.where(keep, torque, np.nan), np.where(keep[:, None], x, np.nan)
    return out + (_scan(walked, *out),) if path else out


def _scan(walked, torque, x):
    """The walk's points (`ballcvt.solvers.branch_path.Walk.path`) and the limit, in
    increasing torque per point (``+inf`` and NaN after the last), or None without a
    walk: the `ballcvt.solvers.limit.LimitSearch` scan, whose creeps start a sweep's
    points between them (session 36: Table I's thermal sweep's predictor stage 30 % fewer
    traction rows than from between the creeps at zero torque and at the limit)."""
    if walked is None:
        return None
    t, creep = walked
    n, s, nc = creep.shape
    # a walk's step can land past the fold and still rise (the climb then starts before
    # it): only the points on the branch below the limit, as `on_branch` tells them
    below = (t <= torque[:, None]) & on_branch(
        creep.reshape(-1, nc), np.repeat(x, s, axis=0)).reshape(n, s)  # fmt: skip
    end = np.where(np.isfinite(torque), torque, np.inf)[:, None]
    return by_torque(
        np.concatenate([np.where(below, t, np.inf), end], axis=1),
        np.concatenate([np.where(below[..., None], creep, np.nan), x[:, None]], 1),
    )


def _below_later_fold(flat, solvers, tops, admissible, found) -> None:
    """The limits of the points ``idx`` of ``flat`` whose climb's top ``top`` (``tops`` =
    ``(idx, top)``) no solve reached: the torque continuation from zero torque towards
    it in steps down to `FOLD_MARGIN` of it, which stops at the branch's first fold.

    A walk's step can pass a fold and land past a later one, higher, where the branch
    turns more than once, and the climb then finds that later fold: the branch from zero
    torque does not reach it (harden task 2803:167: a fold at 11.58 N m in the input
    creep, the climb's at 11.66 N m in the output creep, and the limit fell back to the
    walk's point before its last, 10.64 N m). The continuation's highest torque replaces
    the limit where it is larger. ``found`` = ``(keep, torque, x)``: the indices of
    ``flat``'s points in the batch and the batch's limits and creeps (updated in place);
    ``solvers``: the continuation's solver and its ``turned`` test.
    """
    solve, turned = solvers
    idx, top = tops
    keep, torque, x = found
    if idx.size == 0:
        return
    xc, _, tc = continue_in_torque(flat.take(idx), solve, top, FOLD_MARGIN, admissible,
                                   turned=turned)  # fmt: skip
    better = np.isfinite(tc) & (tc > torque[keep[idx]])
    torque[keep[idx[better]]], x[keep[idx[better]]] = tc[better], xc[better]


def _rise_to_fold(flat, solvers, quadrature, pin, admissible):
    """Equilibria on each point's branch from zero torque below its fold or its creep
    limit, from which the climb in a held creep starts, and the two points that seed its
    bracket: the walk along the branch (`ballcvt.solvers.branch_path.follow_branch`), the
    climb starting from the point before its last rising one (the fold lies beyond it),
    seeded with that point and the step past it; the torque continuation
    (`continue_in_torque` to an open target, to within `PEAK_RTOL` of where it stops) for
    the points whose walk failed and under a planetary mode's torque condition (no seed).
    Returns the torques ``(n,)`` [N m] (NaN where zero torque is inadmissible), creeps
    ``(n, n_c)``, seeds ``((torque, creeps), (torque, creeps))`` (NaN: none) and the
    walk's `Walk.path` (None without a walk)."""
    solve, (pinned, tol) = solvers
    n, nc = flat.size, flat.layout.n_contacts
    rest = np.arange(n)
    torque, x = np.full(n, np.nan), np.full((n, nc), np.nan)
    none = (np.full(n, np.nan), np.full((n, nc), np.nan))
    seed, walked = (none, none, none[1]), None
    if walks(flat):
        ok, x0, _ = solve(replace(flat, output_torque=np.zeros(n)), None, True)
        x0 = np.array(x0, dtype=float)
        ok = np.asarray(ok, dtype=bool) & admissible(x0)
        start = (np.where(ok, 0.0, np.nan), x0)
        walk = follow_branch(flat, (pinned, tol), quadrature, (pin, pin), start)
        on = walk.stopped
        torque, x = (
            np.where(on, walk.before[0], np.nan),
            np.where(on[:, None], walk.before[1], np.nan),
        )
        seed = ((np.where(on, walk.torque, np.nan), walk.creep), walk.after, walk.direction)
        rest, walked = np.flatnonzero(ok & ~on), walk.path
    if rest.size:
        xr, _, tr = continue_in_torque(
            flat.take(rest), solve, np.full(rest.size, np.inf), PEAK_RTOL, admissible
        )
        torque[rest], x[rest] = tr, xr
    return torque, x, seed, walked


def _climb(flat, pinned, pin, start):
    """The largest torque of each point's branch (`climb_to_fold`) beyond ``start``
    ``(torque, x, seed)`` (the seed of `_rise_to_fold`): in the held creep of the disc
    contact that moved more along the walk's last step (at the start, the one with the
    larger creep, without a walk) first, then in the other's where that climb ended short
    of a clean fold (a failed step, or another creep at the bound). Returns the better
    `Climb` per point and its contact."""
    pinned_solve, tol = pinned
    nc = flat.layout.n_contacts
    t0, x0, (seed_b, seed_c, way) = start
    seed = (seed_b, seed_c)
    # along the walk's last chord where there is one, else at the start
    first = disc_to_climb(np.where(np.all(np.isfinite(way), axis=-1, keepdims=True), way, x0))
    best, contact = Climb.empty(flat.size, nc), first.copy()
    other = np.where(first == 0, nc - 1, 0)
    for k, on in ((first, np.ones(flat.size, dtype=bool)), (other, None)):
        idx = np.flatnonzero(~best.clean if on is None else on)  # both contacts in a batch
        if idx.size == 0:
            continue
        got = climb_to_fold(flat.take(idx), pinned_solve, k[idx], pin, tol,
                            (t0[idx], x0[idx], tuple((t[idx], xx[idx]) for t, xx in seed)),
                            1.0 - FOLD_MARGIN)  # fmt: skip
        better = ~np.isfinite(best.torque[idx]) | (got.torque > best.torque[idx])
        best.put(idx[better], got.take(better))
        contact[idx[better]] = k[idx[better]]
    return best, contact


def _reach_top(flat, solvers, climb, k, top):
    """The equilibria at the torques ``top`` just below each climb's fold (or at its
    creep bound): the held creep's secant between the climb's highest point below ``top``
    and its largest torque (`ballcvt.solvers.held_creep`, on the square root of the
    torque's fall below the fold), then Newton at the torque from there (`solve_twice`),
    else the solve's own continuation from zero torque.
    Returns ``(converged (n,), creeps (n, n_c))``."""
    solve, branch, turned = solvers  # the continuation's solver, (`Pinned`, tol), its test
    pinned, tol = branch
    at = replace(flat, output_torque=top)
    start = np.where(climb.at_pin[:, None], climb.creep, np.nan)
    for kk in np.unique(k):
        idx = np.flatnonzero((k == kk) & ~climb.at_pin)
        if idx.size == 0:
            continue
        c_lo, t_lo, x_lo = (v[idx] for v in climb.below)
        hi = (climb.creep[idx, kk], climb.torque[idx], climb.creep[idx])
        lo = (c_lo, t_lo, x_lo, np.zeros(idx.size, dtype=bool))
        start[idx] = secant_in_creep(at.take(idx), pinned, kk, tol, lo, hi, vertex=True)
    good = np.zeros(flat.size, dtype=bool)
    xr = np.array(start)
    ready = np.flatnonzero(np.all(np.isfinite(start), axis=-1))
    if ready.size:
        ok, xs, _ = solve_twice(solve, at.take(ready), start[ready])
        good[ready], xr[ready] = ok, xs
    far = np.flatnonzero(~good)
    if far.size:
        xf, _, reached = continue_in_torque(at.take(far), solve, top[far], pinned=branch,
                                            turned=turned)  # fmt: skip
        good[far], xr[far] = reached == top[far], xf
    return good, xr
