"""Limiting torques where the traction can fall with the creep (the thermal law).

The limit is then the peak of the branch that starts at no load, not the creep limit: each
disc contact's creep is pinned at rising values (continuation), and golden section
refines the largest output torque (docs/model.md §8, §14). Used by
`ballcvt.solvers.limit.limit_search`.
"""

from __future__ import annotations

import numpy as np

from .newton import initial_creep, solve_pinned

__all__ = ["peak_limits", "PEAK_SCAN", "PEAK_STEPS"]


#: Pinned creeps scanned per disc contact by `peak_limits`, then golden-section steps
#: about the best: the creep bracket shrinks to 2/12 x 0.618^20 = 1.5e-5 of the creep
#: limit, and the torque, flat at its peak, is exact to about 1e-9 relative.
PEAK_SCAN, PEAK_STEPS = 12, 20


def peak_limits(flat, creep_limit, options, x_zero):
    """Limits under a law whose traction can fall with the creep (docs/model.md §8, §14). For each disc contact,
    its creep is pinned at rising values up to ``creep_limit``, each solve started from
    the last (continuation on the branch that starts at no load), until ``T_2`` stops
    rising or a solve is inadmissible; golden section then refines the largest ``T_2``
    about the best pinned creep. The limit is the larger of the two contacts' (the branch
    folds where one contact passes the peak of its traction curve). NaN where no pinned
    solve is admissible."""
    nc = flat.layout.n_contacts
    n = flat.size
    torque = np.full(n, -np.inf)
    creep = np.full((n, nc), np.nan)
    start = np.where(np.isnan(x_zero), initial_creep(flat), x_zero)

    def pinned(rows, k, c, x_start):
        x0 = np.array(x_start, dtype=float)
        x0[:, k] = c
        t, sol = solve_pinned(flat.take(rows), k, x0, options)
        x = sol.state.creep
        ok = (
            sol.converged
            & np.isfinite(t)
            & (np.max(np.abs(x), axis=-1) <= creep_limit * (1.0 + 1e-9))
        )
        return np.where(ok, t, -np.inf), x

    grid = creep_limit * np.arange(1, PEAK_SCAN + 1) / PEAK_SCAN
    g = 0.5 * (np.sqrt(5.0) - 1.0)
    for k in (0, nc - 1):
        # continuation up the pinned creep, on the branch that starts at no load, until
        # the torque stops rising (the fold) or the solution is inadmissible
        best_t, best_x = np.full(n, -np.inf), start.copy()
        j = np.zeros(n, dtype=int)
        going = np.arange(n)
        for step, c in enumerate(grid):
            if going.size == 0:
                break
            t, x = pinned(going, k, np.full(going.size, c), best_x[going])
            up = t > best_t[going]
            rise = going[up]
            best_t[rise], best_x[rise], j[rise] = t[up], x[up], step
            going = rise
        live = np.flatnonzero(np.isfinite(best_t))
        a = grid[np.maximum(j[live] - 1, 0)] * (j[live] > 0)
        b = grid[np.minimum(j[live] + 1, PEAK_SCAN - 1)]
        seed = best_x[live]
        c1, c2 = b - g * (b - a), a + g * (b - a)
        (t1, x1), (t2, x2) = pinned(live, k, c1, seed), pinned(live, k, c2, seed)
        bt, bx = best_t[live], best_x[live]
        for _ in range(PEAK_STEPS):
            for t, x in ((t1, x1), (t2, x2)):
                better = t > bt
                bt, bx = np.where(better, t, bt), np.where(better[:, None], x, bx)
            left = t1 >= t2  # the peak lies in [a, c2]
            a, b = np.where(left, a, c1), np.where(left, c2, b)
            c1, c2 = b - g * (b - a), a + g * (b - a)
            c_new = np.where(left, c1, c2)
            t_new, x_new = pinned(live, k, c_new, bx)
            t1, x1, t2, x2 = (
                np.where(left, t_new, t2),
                np.where(left[:, None], x_new, x2),
                np.where(left, t1, t_new),
                np.where(left[:, None], x1, x_new),
            )
        better = bt > torque[live]
        torque[live[better]], creep[live[better]] = bt[better], bx[better]
    keep = np.isfinite(torque) & (torque >= 0.0)
    return np.where(keep, torque, np.nan), np.where(keep[:, None], creep, np.nan)
