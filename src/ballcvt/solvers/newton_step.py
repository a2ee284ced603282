"""The update of the batched Newton solver (`advance`, compiled where numba is installed):
per point, the ``n_c x n_c`` Newton system by Gaussian elimination with partial pivoting,
the caps of the step and the back-off of a step whose residual grew. A plain-Python form
runs where numba is missing."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..equilibrium.residual import EquilibriumState
from .options import CREEP_BOUNDS

njit: Any
try:
    from numba import njit
except ImportError:  # pragma: no cover - numba is a declared dependency
    njit = None

__all__ = [
    "COMPILED",
    "MAX_STEP",
    "Iterates",
    "advance",
    "advance_compiled",
    "advance_python",
    "cap",
    "free_creeps",
    "at_free",
    "residual_norm",
    "reshape_state",
    "scatter_state",
]

#: Largest change of any creep in one Newton step [-].
MAX_STEP = 0.05


def _gauss_python(a, b, dx):
    """Solve ``a dx = b`` (``m x m``) by Gaussian elimination with partial pivoting, in
    place (``a`` and ``b`` are overwritten); False, with ``dx`` untouched, if singular."""
    m = b.size
    for c in range(m):
        p = c
        for r in range(c + 1, m):
            if abs(a[r, c]) > abs(a[p, c]):
                p = r
        if a[p, c] == 0.0:
            return False
        if p != c:
            for q in range(m):
                a[c, q], a[p, q] = a[p, q], a[c, q]
            b[c], b[p] = b[p], b[c]
        for r in range(c + 1, m):
            f = a[r, c] / a[c, c]
            for q in range(c, m):
                a[r, q] -= f * a[c, q]
            b[r] -= f * b[c]
    for r in range(m - 1, -1, -1):
        v = b[r]
        for q in range(r + 1, m):
            v -= a[r, q] * dx[q]
        dx[r] = v / a[r, r]
    return True


_gauss = njit(cache=True)(_gauss_python) if njit is not None else _gauss_python


# many parameters: compiled by numba, which takes arrays and scalars (an object would not
# compile); `advance` is the typed entry point.
def advance_python(
    active, res, jac, x, free, best, prev_x, prev_dx, fresh, tol, max_step, lo, hi, keep,
    singular,
):  # fmt: skip
    """`advance`'s loop: Gaussian elimination with partial pivoting for the steps, then
    the caps of `cap`; writes ``keep`` and ``singular`` per point. Compiled by numba
    (`advance_compiled`); this plain-Python form runs only without numba."""
    m = free.shape[1]
    a = np.empty((m, m))
    b = np.empty(m)
    dx = np.empty(m)
    for k in range(active.size):
        i = active[k]
        norm = 0.0
        for r in range(m):
            norm = max(norm, abs(res[k, r]))
        if not math.isfinite(norm):
            norm = math.inf
        if norm <= tol:
            continue  # done
        if not norm < best[i]:  # worse (or NaN): half the previous step back
            big = 0.0
            for r in range(m):
                prev_dx[i, r] *= 0.5
                x[i, free[i, r]] = prev_x[i, free[i, r]] + prev_dx[i, r]
                big = max(big, abs(prev_dx[i, r]))
            fresh[i] = False
            keep[k] = big > 1e-14
            continue
        keep[k] = True
        best[i] = norm
        for r in range(m):
            b[r] = -res[k, r]
            for c in range(m):
                a[r, c] = jac[k, r, c]
        if not _gauss(a, b, dx):
            singular[k] = True
            continue
        big = 0.0  # the caps of `cap`
        for r in range(m):
            if not math.isfinite(dx[r]):
                dx[r] = 0.0
            big = max(big, abs(dx[r]))
        scale = min(1.0, max_step / max(big, 1e-300))
        for r in range(m):
            dx[r] *= scale
        scale = 1.0
        for r in range(m):
            xr = x[i, free[i, r]]
            room = 0.5 * (hi - xr) if dx[r] > 0 else 0.5 * (xr - lo)
            if abs(dx[r]) > room:
                scale = min(scale, room / max(abs(dx[r]), 1e-300))
        for r in range(m):
            prev_dx[i, r] = dx[r] * scale
        for q in range(x.shape[1]):
            prev_x[i, q] = x[i, q]
        for r in range(m):
            x[i, free[i, r]] += prev_dx[i, r]
        fresh[i] = False


def free_creeps(nc: int, n: int, pinned=None) -> np.ndarray:
    """The free creeps of each of ``n`` points, ``(n, m)`` contact indices in increasing
    order: all ``nc`` (``pinned`` None), or all but the held one (``pinned``: one contact
    for every point, or one per point ``(n,)``; `ballcvt.solvers.newton.solve_pinned`)."""
    if pinned is None:  # (a few microseconds a Newton run: a one-point solve's 1 %)
        out = np.empty((n, nc), dtype=np.intp)
        out[:] = np.arange(nc)
        return out
    every = np.broadcast_to(np.arange(nc), (n, nc))
    held = np.broadcast_to(np.asarray(pinned, dtype=np.intp), (n,))
    return np.ascontiguousarray(every[every != held[:, None]].reshape(n, nc - 1))


def at_free(a, free, rows, same=None):
    """``a`` ``(k, ..., n_c)`` on its last axis at the free creeps of the batch's points
    ``rows`` (``free``: every point's, `free_creeps`), or at ``same`` ``(m,)`` where every
    point's are those (plain indexing: `numpy.take_along_axis` costs some 20 us a call)."""
    if same is not None:
        return a[..., same]
    free = free[rows]
    index = free.reshape(free.shape[:1] + (1,) * (a.ndim - 2) + free.shape[1:])
    return np.take_along_axis(a, index, axis=-1)


def cap(dx, x):
    """Steps ``(n, m)`` with non-finite components set to 0, the largest ``|dx|`` capped at
    `MAX_STEP`, and no component more than half-way to a bound of `CREEP_BOUNDS` (NumPy)."""
    dx = np.where(np.isfinite(dx), dx, 0.0)
    big = np.max(np.abs(dx), axis=-1, keepdims=True)
    dx = dx * np.minimum(1.0, MAX_STEP / np.maximum(big, 1e-300))
    lo, hi = CREEP_BOUNDS
    # Never step more than half-way to a bound.
    room = np.where(dx > 0, 0.5 * (hi - x), 0.5 * (x - lo))
    scale = np.min(
        np.where(np.abs(dx) > room, room / np.maximum(np.abs(dx), 1e-300), 1.0),
        axis=-1,
        keepdims=True,
    )
    return dx * scale


COMPILED = njit is not None
advance_compiled: Any = njit(cache=True)(advance_python) if COMPILED else None


@dataclass(frozen=True)
class Iterates:
    """The Newton iterates of a batch, updated in place by `advance`.

    Attributes
    ----------
    x : ndarray
        Creeps ``(n, n_c)`` [-].
    best : ndarray
        Residual norm at each point's last accepted creeps ``(n,)`` [-].
    prev_x, prev_dx : ndarray
        Creeps before the last step ``(n, n_c)`` and that step on the free creeps.
    fresh : ndarray of bool
        Whether each point's last evaluation was at its current creeps ``(n,)``.
    """

    x: np.ndarray
    best: np.ndarray
    prev_x: np.ndarray
    prev_dx: np.ndarray
    fresh: np.ndarray


def advance(it: Iterates, active, res, jac, free, tol):
    """One Newton update of the points ``active`` after their evaluation (``res``,
    ``jac``: their residuals and the Jacobians to step with on the free creeps,
    `ballcvt.solvers.secant.SecantCorrection`); ``free``: the free creeps of every point
    of the batch ``(n, m)`` (`free_creeps`); updates ``it`` in place.

    A point whose residual norm meets ``tol`` is done. Otherwise a point whose norm did
    not fall below its best goes back along half its previous step (and stops if that
    step is below 1e-14), and the others take the Newton step, capped in size and kept
    inside `CREEP_BOUNDS` (`cap`; least squares where the matrix is singular).

    Returns the points still iterating.
    """
    lo, hi = CREEP_BOUNDS
    keep = np.zeros(active.size, dtype=np.bool_)
    singular = np.zeros(active.size, dtype=np.bool_)
    step = advance_compiled if COMPILED else advance_python
    x, prev_x, prev_dx, fresh = it.x, it.prev_x, it.prev_dx, it.fresh
    step(
        active, res, jac, x, free, it.best, prev_x, prev_dx, fresh, tol,
        MAX_STEP, lo, hi, keep, singular,
    )  # fmt: skip
    for k in np.flatnonzero(singular):  # rare: a least-squares step, capped
        i = active[k]
        dx = cap(_lstsq(jac[k], res[k])[None, :], x[i, free[i]][None, :])[0]
        prev_x[i] = x[i]
        prev_dx[i] = dx
        x[i, free[i]] += dx
        fresh[i] = False
    return active[keep]


def _lstsq(jac, res):
    return np.linalg.lstsq(jac, -res, rcond=None)[0]


def scatter_state(full: EquilibriumState, part: EquilibriumState, index) -> EquilibriumState:
    """``full`` with the points ``index`` replaced by ``part`` (copies, 1-D batches)."""
    if part.creep.shape[0] == full.creep.shape[0] and np.array_equal(
        index, np.arange(full.creep.shape[0])
    ):
        return part
    return full.put(index, part)


def residual_norm(res) -> np.ndarray:
    """``max |res|`` over the last axis, ``inf`` where it is not finite."""
    norm = np.abs(res).max(axis=-1)
    norm[~np.isfinite(norm)] = np.inf
    return norm


def reshape_state(state: EquilibriumState, shape) -> EquilibriumState:
    """``state`` of a 1-D batch with its batch axis reshaped to ``shape``."""
    fields = {}
    for name, value in vars(state).items():
        value = np.asarray(value)
        fields[name] = value.reshape(shape + value.shape[1:])
    return EquilibriumState(**fields)
