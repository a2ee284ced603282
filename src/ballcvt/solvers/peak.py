"""Limiting torques where the drive can have more than one equilibrium (the thermal law).

Where a contact's traction falls past the peak of its curve, the branch of equilibria
that starts at zero torque folds back, and a second equilibrium can exist at the same
torque with every creep within the limit. The limiting torque is then the largest torque
the drive reaches on the branch from zero torque with every ``|C| <= C_lim``: the fold,
or the torque where a creep reaches ``C_lim`` if that comes first. It is found by the
same torque continuation by which every solve under such a law is made
(`ballcvt.solvers.continuation`), so that the limit is the largest torque at which a
solve succeeds (docs/model.md §8, §14). Used by `ballcvt.solvers.limit.limit_search`.
"""

from __future__ import annotations

import numpy as np

from .continuation import continue_in_torque
from .newton import branch_solver

__all__ = ["peak_limits", "PEAK_RTOL"]

#: Smallest torque step of the continuation to the limit, as a share of the problem's
#: ``torque_scale`` ``n F_N0 r_S`` (480 N m on Table I's drive at 2 kN): the limit is
#: exact to twice this (1e-2 N m there, 1e-4 relative) [-].
PEAK_RTOL = 1e-5


def peak_limits(flat, creep_limit, options, x_zero=None):
    """Limiting torques of the 1-D batch ``flat`` under a law with more than one
    equilibrium (docs/model.md §8, §14): each point is followed from zero torque up
    (`continue_in_torque` to an open target) while its equilibrium converges with every
    ``|C| <= creep_limit``.

    Returns the torques ``(n,)`` [N m] and the creeps there ``(n, n_c)``; NaN where even
    zero torque is inadmissible. ``x_zero`` (starting creeps of the other limit methods)
    is not used: the continuation starts from the cold start at zero torque.
    """

    def admissible(x):
        return np.max(np.abs(x), axis=-1) <= creep_limit * (1.0 + 1e-9)

    x, _, torque = continue_in_torque(
        flat,
        branch_solver(options),
        np.full(flat.size, np.inf),
        PEAK_RTOL,
        admissible,
    )
    keep = np.isfinite(torque)
    return np.where(keep, torque, np.nan), np.where(keep[:, None], x, np.nan)
