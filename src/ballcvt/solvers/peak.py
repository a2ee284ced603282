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
from .held_creep import FOLD_CREEP_RTOL, march_to_fold
from .newton import branch_pinned, branch_solver
from .options import at_residual_floor

__all__ = ["peak_limits", "PEAK_RTOL", "FOLD_MARGIN", "FOLD_CREEP_RTOL"]

#: Smallest torque step of the continuation to the limit, as a share of the problem's
#: ``torque_scale`` ``n F_N0 r_S`` (480 N m on Table I's drive at 2 kN) [-].
PEAK_RTOL = 1e-5
#: Relative margin below a fold at which its limit is reported [-]: a solve converges
#: there, and fails at ``1.001`` times it.
FOLD_MARGIN = 2e-4


def peak_limits(flat, creep_limit, options, x_zero=None):
    """Limiting torques of the 1-D batch ``flat`` under a law with more than one
    equilibrium (docs/model.md §8, §14): each point is followed from zero torque up
    (`continue_in_torque` to an open target) while its equilibrium converges with every
    ``|C| <= creep_limit``, then its fold is located in the creep (`ballcvt.solvers.held_creep.march_to_fold`).

    Returns the torques ``(n,)`` [N m] and the creeps there ``(n, n_c)``; NaN where even
    zero torque is inadmissible. ``x_zero`` (starting creeps of the other limit methods)
    is not used: the continuation starts from the cold start at zero torque.
    """
    options = at_residual_floor(options, flat.fluid)
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
        pinned = branch_pinned(options)
        top, fold = march_to_fold(sub, pinned[0], pin, options.tol, torque[keep], x[keep])
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
                xf, _, reached = continue_in_torque(
                    sub.take(idx[far]), solve, top[idx[far]], pinned=pinned
                )
                good[far], xr[far] = (reached == top[idx[far]]) & admissible(xf), xf
            torque[keep[idx[good]]], x[keep[idx[good]]] = top[idx[good]], xr[good]
    keep = np.isfinite(torque)
    return np.where(keep, torque, np.nan), np.where(keep[:, None], x, np.nan)
