"""Batched Newton solver: many operating points at once (the fast default path).

All points of a batch iterate together, first with a coarse quadrature (the predictor,
``SolverOptions.predictor``) to a loose tolerance, then with the requested one. Each
iteration evaluates the traction integrals once, with their analytic derivatives
(`evaluate_with_jacobian`; the last one, which only confirms convergence, without them),
and solves the small ``n_c x n_c`` Newton systems of every
point in one `numpy.linalg.solve` call. Steps are capped so that no creep leaves its
physical range, and a point whose residual grew is sent back along half its previous step
(a deferred backtracking line search that costs nothing while Newton converges). Points
still unconverged after ``max_iterations`` go, one by one, to the robust point solver
(hybrid method, then bracketing). A point is reported converged only if its residual,
evaluated afresh on the final creeps, meets the tolerance; the others are flagged in
``converged``, never hidden.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..equilibrium.residual import (
    EquilibriumState,
    balancing_output_torque,
    evaluate,
    evaluate_with_jacobian,
)

njit: Any
try:
    from numba import njit
except ImportError:  # pragma: no cover - numba is a declared dependency
    njit = None

__all__ = ["BatchSolution", "solve_batch", "solve_pinned", "initial_creep", "CREEP_BOUNDS"]

#: Creeps outside this open interval are unphysical (speeds reverse).
CREEP_BOUNDS = (-0.5, 0.98)
#: Largest change of any creep in one Newton step [-].
MAX_STEP = 0.05


@dataclass(frozen=True)
class BatchSolution:
    """Outcome of `solve_batch`; arrays have the batch shape ``(...)``.

    Attributes
    ----------
    state : EquilibriumState
        Every quantity at the final creeps (also for unconverged points: check
        ``converged``).
    converged : ndarray of bool
        Residual at most the tolerance and finite.
    residual_norm : ndarray
        ``max |residual|`` at the final creeps [-].
    iterations : ndarray of int
        Residual evaluations of each point (with the Jacobian, or without it where only
        convergence was left to confirm, `CONFIRM_NORM`); points that needed the point
        solver add its residual evaluations.
    """

    state: EquilibriumState
    converged: np.ndarray
    residual_norm: np.ndarray
    iterations: np.ndarray


def initial_creep(problem: EquilibriumProblem) -> np.ndarray:
    """A starting creep vector per point: small positive disc creeps, zero idler creeps."""
    x0 = np.where(problem.layout.is_idler, 0.0, 1e-3)
    return np.broadcast_to(x0, problem.shape + x0.shape).copy()


def solve_batch(
    problem: EquilibriumProblem, options=None, x0=None, fallback: bool = True, predict: bool = True
) -> BatchSolution:
    """Solve every operating point of ``problem`` for its creeps.

    Parameters
    ----------
    problem : EquilibriumProblem
        Operating points, batch shape ``(...)``.
    options : SolverOptions, optional
        Quadrature, tolerance and ``max_iterations`` (Newton iterations before a point goes
        to the point solver); ``ballcvt.solver.point.SolverOptions()`` by default.
    x0 : array_like, optional
        Starting creeps, broadcastable to ``(..., n_c)`` (e.g. a neighbour's solution).
    fallback : bool
        Whether unconverged points go to the point solver (otherwise they are flagged).
    predict : bool
        Whether to run the predictor stage (``options.predictor``); False when ``x0`` is
        already close to the solution on the requested rule (e.g. a solution found by
        `solve_pinned` at the same torque), which the predictor would only move away.

    Returns
    -------
    BatchSolution
    """
    from .point import SolverOptions, solve_point  # the point solver builds on this module

    options = SolverOptions() if options is None else options
    shape, nc = problem.shape, problem.layout.n_contacts
    flat = problem.flat()
    x = (
        initial_creep(flat)
        if x0 is None
        else np.broadcast_to(np.asarray(x0, dtype=float), shape + (nc,)).reshape(-1, nc).copy()
    )
    iterations = np.zeros(flat.size, dtype=int)
    x, state = _staged_newton(flat, x, iterations, options, predict=predict)
    norm = _norm(state.residual)
    bad = np.flatnonzero(~(norm <= options.tol))
    if fallback and bad.size:
        robust = replace(options, method="hybr")
        for i in bad:
            sol = solve_point(flat.take(int(i)), robust)
            iterations[i] += sol.evaluations
            if sol.residual_norm < norm[i]:
                x[i] = sol.state.creep
        state = evaluate(flat, x, options.quadrature)
        norm = _norm(state.residual)
    converged = norm <= options.tol
    return BatchSolution(
        state=_reshape(state, shape),
        converged=converged.reshape(shape),
        residual_norm=norm.reshape(shape),
        iterations=iterations.reshape(shape),
    )


def solve_pinned(problem: EquilibriumProblem, contact: int, x0, options=None):
    """Solve with one contact's creep held, for the output torque that goes with it.

    The output torque enters only the output disc's balance, and linearly (the last
    residual, docs/model.md §5). With the creep of ``contact`` held at its value in
    ``x0``, the other balances fix the other creeps; the output torque is then the one
    that balances the output disc: ``T_2 = T_body,2 - T_drag,2``. This gives the torque
    at which a creep reaches a given value in one Newton solve (`ballcvt.solver.limit`).
    The problem's own ``output_torque`` is not used.

    Parameters
    ----------
    problem : EquilibriumProblem
        Operating points, 1-D batch ``(n,)``, at a torque-independent clamping force.
    contact : int
        Index of the contact whose creep is held.
    x0 : array_like
        Starting creeps ``(n, n_c)``; column ``contact`` holds the prescribed creep [-].
    options : SolverOptions, optional
        As in `solve_batch` (no fallback: a point that fails is flagged).

    Returns
    -------
    torque : ndarray
        Output torque ``T_2`` at the solution [N m], ``(n,)``.
    solution : BatchSolution
        Creeps and state; ``converged`` refers to the balances other than the output's.
    """
    from .point import SolverOptions

    options = SolverOptions() if options is None else options
    flat = problem.flat()
    x = np.array(x0, dtype=float).reshape(flat.size, -1)
    iterations = np.zeros(flat.size, dtype=int)
    _, state = _staged_newton(flat, x, iterations, options, pinned=contact)
    norm = _norm(state.residual[:, :-1])
    return balancing_output_torque(flat, state), BatchSolution(
        state=state, converged=norm <= options.tol, residual_norm=norm, iterations=iterations
    )


def _staged_newton(flat, x, iterations, options, pinned=None, predict=True):
    """The predictor stage on the coarse rule (where it pays, `_predicts`), then Newton on
    the requested rule; a point whose coarse run went non-finite restarts from ``x``.
    Returns the final creeps (updated in place where possible) and state."""
    if predict and _predicts(options, flat.size):
        coarse = replace(options, quadrature=options.predictor, tol=options.predictor_tol)
        start = x.copy()
        _newton(flat, x, iterations, coarse, pinned=pinned)
        x = np.where(np.all(np.isfinite(x), axis=-1, keepdims=True), x, start)
    return x, _newton(flat, x, iterations, options, pinned=pinned)


def _predicts(options, n_points: int) -> bool:
    """Whether a batch of ``n_points`` runs the predictor stage first."""
    return (
        options.predictor is not None
        and options.predictor != options.quadrature
        and n_points >= options.predictor_min_points
    )


#: A point whose residual norm is at most this before a Newton step is expected to meet
#: the tolerance after it (Newton's convergence is quadratic down to the Jacobian's
#: accuracy, about 1e-5 relative here): when every point still iterating is, the next
#: evaluation skips the Jacobian; a point that then misses the tolerance is evaluated
#: again, with it, at the same creeps.
CONFIRM_NORM = 1e-6


def _newton(flat, x, iterations, options, pinned=None):
    """Damped Newton on the points of the 1-D batch ``flat``; updates ``x`` in place.

    ``pinned``: the index of a contact whose creep stays at its value in ``x``; the
    output balance (the last residual) is then dropped, the output torque being the
    unknown it defines (`solve_pinned`).

    Returns the state at the final ``x`` of every point: each point's last evaluation,
    or a fresh one for the points whose last move was not evaluated.
    """
    nc, n = x.shape[-1], flat.size
    free = np.arange(nc) if pinned is None else np.delete(np.arange(nc), pinned)
    rows = slice(None) if pinned is None else slice(0, nc - 1)
    active = np.arange(n)
    final = None
    fresh = np.zeros(n, dtype=bool)  # last evaluation was at the current x
    best = np.full(n, np.inf)  # residual norm at the last accepted creeps
    prev_x = x.copy()
    prev_dx = np.zeros((n, free.size))
    confirm = False  # every active point is expected to converge: no Jacobian needed
    for _ in range(options.max_iterations):
        if active.size == 0:
            break
        whole = active.size == n  # every point still iterates: no gathers or scatters
        sub, xa = (flat, x) if whole else (flat.take(active), x[active])
        if confirm:
            state, jac = evaluate(sub, xa, options.quadrature), None
        else:
            state, jac = evaluate_with_jacobian(sub, xa, options.quadrature)
        iterations[active] += 1
        final = state if final is None or whole else _scatter(final, state, active)
        fresh[active] = True
        res = state.residual[:, rows]
        norm = _norm(res)
        done = norm <= options.tol
        if confirm:  # the others go round again, with the Jacobian, at the same creeps
            active, confirm = active[~done], False
            continue
        worse = ~done & ~(norm < best[active])  # includes NaN residuals
        # Points that got worse go back along half their last step; the others step.
        ok = ~done & ~worse
        idx = active
        if ok.any():
            step = idx[ok]
            every = ok.all()
            xs = x[step][:, free]
            dx = _newton_step(
                (jac if every else jac[ok])[:, rows][:, :, free], res if every else res[ok], xs
            )
            best[step] = norm[ok]
            prev_x[step] = x[step]
            prev_dx[step] = dx
            x[step[:, None], free] = xs + dx
            fresh[step] = False
        if worse.any():
            back = idx[worse]
            prev_dx[back] *= 0.5
            x[back[:, None], free] = prev_x[back][:, free] + prev_dx[back]
            fresh[back] = False
            stuck = worse & ~(np.abs(prev_dx[idx]).max(axis=-1) > 1e-14)
            active = idx[~done & ~stuck]
        else:
            active = idx[ok]
            confirm = bool((norm[ok] <= CONFIRM_NORM).all())
    stale = np.flatnonzero(~fresh)
    if final is None or stale.size == n:
        return evaluate(flat, x, options.quadrature)
    if stale.size:
        final = _scatter(final, evaluate(flat.take(stale), x[stale], options.quadrature), stale)
    return final


def _scatter(full: EquilibriumState, part: EquilibriumState, index) -> EquilibriumState:
    """``full`` with the points ``index`` replaced by ``part`` (copies, 1-D batches)."""
    if part.creep.shape[0] == full.creep.shape[0] and np.array_equal(
        index, np.arange(full.creep.shape[0])
    ):
        return part
    fields = {}
    for name, value in vars(full).items():
        value = np.array(value, copy=True)
        value[index] = getattr(part, name)
        fields[name] = value
    return EquilibriumState(**fields)


def _newton_step(jac, res, x):
    """Newton steps, capped in size and kept inside `CREEP_BOUNDS`.

    Compiled (`_capped_steps`: Gaussian elimination with partial pivoting and the caps in
    one call; on one point it costs a tenth of `numpy.linalg.solve` and the NumPy caps);
    a point whose matrix is singular takes the least-squares step instead.
    """
    if not COMPILED:  # pragma: no cover - numba is a declared dependency
        try:
            dx = np.linalg.solve(jac, -res[..., None])[..., 0]
        except np.linalg.LinAlgError:
            dx = np.stack([_lstsq(j, r) for j, r in zip(jac, res)])
        return _cap(dx, x)
    jac = np.ascontiguousarray(jac, dtype=float)
    res = np.ascontiguousarray(res, dtype=float)
    x = np.ascontiguousarray(x, dtype=float)
    dx = np.empty_like(res)
    singular = np.zeros(res.shape[0], dtype=np.bool_)
    lo, hi = CREEP_BOUNDS
    _capped_steps(jac, res, x, MAX_STEP, lo, hi, dx, singular)
    if singular.any():
        idx = np.flatnonzero(singular)
        dx[idx] = _cap(np.stack([_lstsq(jac[i], res[i]) for i in idx]), x[idx])
    return dx


def _cap(dx, x):
    """The caps of `_capped_steps` on steps ``(n, m)`` (NumPy)."""
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


def _capped_steps(jac, res, x, max_step, lo, hi, dx, singular):  # pragma: no cover - compiled
    """Solve ``jac[i] dx[i] = -res[i]`` for every point, then cap each step: non-finite
    components to 0, the largest ``|dx|`` to ``max_step``, and no component more than
    half-way to a bound of ``(lo, hi)``. ``singular[i]`` marks a zero pivot."""
    n, m = res.shape
    a = np.empty((m, m))
    b = np.empty(m)
    for i in range(n):
        for r in range(m):
            b[r] = -res[i, r]
            for c in range(m):
                a[r, c] = jac[i, r, c]
        ok = True
        for k in range(m):  # elimination with partial pivoting
            p = k
            for r in range(k + 1, m):
                if abs(a[r, k]) > abs(a[p, k]):
                    p = r
            if a[p, k] == 0.0:
                ok = False
                break
            if p != k:
                for c in range(m):
                    a[k, c], a[p, c] = a[p, c], a[k, c]
                b[k], b[p] = b[p], b[k]
            for r in range(k + 1, m):
                f = a[r, k] / a[k, k]
                for c in range(k, m):
                    a[r, c] -= f * a[k, c]
                b[r] -= f * b[k]
        if not ok:
            singular[i] = True
            continue
        for r in range(m - 1, -1, -1):
            v = b[r]
            for c in range(r + 1, m):
                v -= a[r, c] * dx[i, c]
            dx[i, r] = v / a[r, r]
        big = 0.0
        for r in range(m):
            if not math.isfinite(dx[i, r]):
                dx[i, r] = 0.0
            big = max(big, abs(dx[i, r]))
        scale = min(1.0, max_step / max(big, 1e-300))
        for r in range(m):
            dx[i, r] *= scale
        scale = 1.0
        for r in range(m):  # never more than half-way to a bound
            room = 0.5 * (hi - x[i, r]) if dx[i, r] > 0 else 0.5 * (x[i, r] - lo)
            if abs(dx[i, r]) > room:
                scale = min(scale, room / max(abs(dx[i, r]), 1e-300))
        for r in range(m):
            dx[i, r] *= scale


COMPILED = njit is not None
if COMPILED:
    _capped_steps = njit(cache=True)(_capped_steps)


def _lstsq(jac, res):
    return np.linalg.lstsq(jac, -res, rcond=None)[0]


def _norm(res):
    norm = np.abs(res).max(axis=-1)
    norm[~np.isfinite(norm)] = np.inf
    return norm


def _reshape(state: EquilibriumState, shape) -> EquilibriumState:
    fields = {}
    for name, value in vars(state).items():
        value = np.asarray(value)
        fields[name] = value.reshape(shape + value.shape[1:])
    return EquilibriumState(**fields)
