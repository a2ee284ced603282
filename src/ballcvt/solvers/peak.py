"""Limiting torques where the drive can have more than one equilibrium (the thermal law).

Where a contact's traction falls past the peak of its curve, the branch of equilibria
that starts at zero torque folds back, and a second equilibrium can exist at the same
torque with every creep within the limit. The limiting torque is then the largest torque
the drive reaches on the branch from zero torque with every ``|C| <= C_lim``: the fold,
or the torque where a creep reaches ``C_lim`` if that comes first (docs/model.md §8,
§14). The branch is followed from zero torque by the torque continuation by which every
solve under such a law is made (`ballcvt.solvers.continuation`); next to the fold Newton
converges slowly in the torque (its Jacobian turns singular there) and the continuation
stops short of it, by a share that depends on its steps. So the fold is then located in
the creep: from where the continuation stopped, a disc contact's creep is held and
stepped (`ballcvt.solvers.newton.solve_pinned`, regular through the fold), the step
reversed and shrunk wherever the torque stops rising, until the step is below
`FOLD_CREEP_RTOL` of ``C_lim``: the largest torque met is the fold. A limit at a fold is
reported `FOLD_MARGIN` below it (a solve exactly at a fold does not converge), once a
solve converges there (Newton from where the continuation stopped, else the solve's own
continuation from zero torque). Used by `ballcvt.solvers.limit.limit_search`.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from .continuation import continue_in_torque, solve_twice
from .newton import branch_solver, solve_pinned

__all__ = ["peak_limits", "PEAK_RTOL", "FOLD_MARGIN", "FOLD_CREEP_RTOL"]

#: Smallest torque step of the continuation to the limit, as a share of the problem's
#: ``torque_scale`` ``n F_N0 r_S`` (480 N m on Table I's drive at 2 kN) [-].
PEAK_RTOL = 1e-5
#: Relative margin below a fold at which its limit is reported [-]: a solve converges
#: there, and fails at ``1.001`` times it.
FOLD_MARGIN = 2e-4
#: Smallest creep step of the march to the fold, as a share of ``C_lim`` [-].
FOLD_CREEP_RTOL = 1e-4
#: Residual norm, in solver tolerances, up to which a held-creep step counts [-]: the
#: thermal residual has a noise floor near the tolerance at large loads, and only the
#: torque of the step is used (exact far within the limit's 1e-3).
PINNED_SLACK = 100.0
#: Most steps of the march to the fold.
MAX_FOLD_STEPS = 80


def peak_limits(flat, creep_limit, options, x_zero=None):
    """Limiting torques of the 1-D batch ``flat`` under a law with more than one
    equilibrium (docs/model.md §8, §14): each point is followed from zero torque up
    (`continue_in_torque` to an open target) while its equilibrium converges with every
    ``|C| <= creep_limit``, then its fold is located in the creep (`_march_to_fold`).

    Returns the torques ``(n,)`` [N m] and the creeps there ``(n, n_c)``; NaN where even
    zero torque is inadmissible. ``x_zero`` (starting creeps of the other limit methods)
    is not used: the continuation starts from the cold start at zero torque.
    """
    pin = creep_limit * (1.0 - 1e-7)

    def admissible(x):
        return np.max(np.abs(x), axis=-1) <= pin

    solve = branch_solver(options)
    x, _, torque = continue_in_torque(
        flat, solve, np.full(flat.size, np.inf), PEAK_RTOL, admissible
    )
    keep = np.flatnonzero(np.isfinite(torque))
    if keep.size:
        sub = flat.take(keep)
        top, fold = _march_to_fold(sub, pin, options, torque[keep], x[keep])
        top = np.where(fold, top * (1.0 - FOLD_MARGIN), top)
        more = top > torque[keep]
        idx = np.flatnonzero(more)
        if idx.size:  # a solve must converge there: Newton from where the continuation
            # stopped, else the solve's own continuation from zero torque
            good, xr, _ = solve_twice(
                solve, replace(sub.take(idx), output_torque=top[idx]), x[keep[idx]]
            )
            good &= admissible(xr)
            far = np.flatnonzero(~good)
            if far.size:
                xf, _, reached = continue_in_torque(sub.take(idx[far]), solve, top[idx[far]])
                good[far], xr[far] = (reached == top[idx[far]]) & admissible(xf), xf
            torque[keep[idx[good]]], x[keep[idx[good]]] = top[idx[good]], xr[good]
    keep = np.isfinite(torque)
    return np.where(keep, torque, np.nan), np.where(keep[:, None], x, np.nan)


def _march_to_fold(flat, pin, options, torque, x):
    """The largest torque on each point's branch beyond ``(torque, x)``: each disc
    contact's creep held and stepped up from ``x`` (`solve_pinned`), the step reversed and
    quartered where the torque does not rise (or the step fails, or a creep passes
    ``pin``), until it is below `FOLD_CREEP_RTOL` of ``pin``.

    Returns the torques ``(n,)`` [N m] and whether each is that of a fold (not of a
    creep at ``pin``).
    """
    nc = flat.layout.n_contacts
    best_t = torque.copy()
    fold = np.zeros(flat.size, dtype=bool)
    for k in (0, nc - 1):
        t, xk = torque.copy(), x.copy()
        at_pin = np.zeros(flat.size, dtype=bool)
        step = np.where(xk[:, k] < 0, -1.0, 1.0) * 0.02 * pin
        active = np.arange(flat.size)
        for _ in range(MAX_FOLD_STEPS):
            active = active[np.abs(step[active]) >= FOLD_CREEP_RTOL * pin]
            if active.size == 0:
                break
            x0 = xk[active].copy()
            x0[:, k] = np.clip(x0[:, k] + step[active], -pin, pin)
            got, sol = solve_pinned(flat.take(active), k, x0, options)
            xs = sol.state.creep
            up = (
                (sol.residual_norm <= PINNED_SLACK * options.tol)
                & np.isfinite(got)
                & (got > t[active])
                & (np.max(np.abs(xs), axis=-1) <= pin * (1.0 + 1e-9))
            )
            acc, rej = active[up], active[~up]
            t[acc], xk[acc] = got[up], xs[up]
            at_pin[acc] = np.abs(xs[up, k]) >= pin * (1.0 - 1e-12)
            step[acc] *= 2.0
            step[rej] *= -0.25
        better = t > best_t
        best_t = np.where(better, t, best_t)
        fold = np.where(better, ~at_pin, fold)
    return best_t, fold
