"""Batched Newton solver: many operating points at once (the fast default path).

All points of a batch iterate together, first with a coarse quadrature (the predictor,
``SolverOptions.predictor``) to a loose tolerance, then with the requested one. Each
iteration evaluates the traction integrals once, with their analytic derivatives
(`evaluate_with_jacobian`; near the solution without them, the step then taken with the
last Jacobian corrected by Broyden's secant update, `ballcvt.solvers.secant`), and
updates every point in one compiled loop (`ballcvt.solvers.newton_step.advance`: the
small ``n_c x n_c`` Newton systems by Gaussian elimination, the caps, the back-offs).
Steps are capped so that no creep leaves its physical range, and a point whose residual
grew is sent back along half its previous step (a deferred backtracking line search that
costs nothing while Newton converges). Points
still unconverged after ``max_iterations`` go, one by one, to the robust point solver
(hybrid method, then bracketing). A point is reported converged only if its residual,
evaluated afresh on the final creeps, meets the tolerance; the others are flagged in
``converged``, never hidden.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..equilibrium.residual import (
    EquilibriumState,
    balancing_output_torque,
    evaluate,
)
from ..model.traction.base import has_multiple_equilibria
from .branch_path import walks
from .continuation import REACH_STEP, continue_in_torque
from .held_creep import on_branch, turned_back
from .newton_eval import confirm_norm, evaluate_split
from .newton_step import (
    MAX_STEP,
    Iterates,
    advance,
    at_free,
    free_creeps,
    reshape_state,
    residual_norm,
    scatter_state,
)
from .options import CREEP_BOUNDS, SolverOptions, at_residual_floor
from .robust import solve_robust
from .secant import SecantCorrection
from .trials import quiet_trials

__all__ = ["BatchSolution", "solve_batch", "solve_pinned", "initial_creep", "branch_solver"]
__all__ += ["on_branch", "solve_near", "solve_from", "CREEP_BOUNDS", "MAX_STEP", "PATIENCE"]

#: Consecutive Newton iterations without a lower residual after which a step of the
#: torque continuation gives up (`branch_solver`); the continuation then tries that
#: torque again from closer. A point past the fold of its branch never converges and
#: otherwise backs off for all ``max_iterations``. Session 23 measured 4 against 6 on
#: Table I's thermal sweeps (10 x 10 at 500, 2000 and 5000 rpm under a constant force; 4 x
#: 4 at 500 and 2000 rpm under the cam and the optimal clamp): the same efficiencies and
#: limits to the bit, with 25 %, 25 % and 16 % fewer Jacobian evaluations. 3 gave the same
#: on those sweeps but stopped a step that was still converging in a planetary mode
#: (harden task 2125:54: a capacity of 0.12 N m for a fold at 2.95; regression test).
PATIENCE = 4


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
        Residual evaluations of each point (with the Jacobian, or without it near the
        solution, `ballcvt.solvers.newton_eval.confirm_norm`); points that needed the point
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


@quiet_trials
def solve_batch(
    problem: EquilibriumProblem,
    options=None,
    x0=None,
    fallback: bool = True,
    predict: bool = True,
    below=None,
) -> BatchSolution:
    """Solve every operating point of ``problem`` for its creeps.

    Parameters
    ----------
    problem : EquilibriumProblem
        Operating points, batch shape ``(...)``.
    options : SolverOptions, optional
        Quadrature, tolerance and ``max_iterations`` (Newton iterations before a point goes
        to the point solver); ``ballcvt.solvers.point.SolverOptions()`` by default.
    x0 : array_like, optional
        Starting creeps, broadcastable to ``(..., n_c)`` (e.g. a neighbour's solution).
        Not used under a law with ``multiple_equilibria`` (the thermal law) without
        ``below``: every point is then followed from zero torque (`continue_in_torque`,
        docs/model.md §14).
    fallback : bool
        Whether unconverged points go to the point solver (otherwise they are flagged;
        under continuation only at zero torque).
    predict : bool
        Whether to run the predictor stage (``options.predictor``); False when ``x0`` is
        already close to the solution on the requested rule (e.g. a solution found by
        `solve_pinned` at the same torque), which the predictor would only move away.
    below : array_like, optional
        Under a law with ``multiple_equilibria`` only: the creeps ``(..., n_c)`` of an
        equilibrium on each point's branch from zero torque at a torque at least the
        point's own (e.g. its limiting torque). Newton from ``x0`` then comes first, and a
        point it solves keeps that solution where its disc creeps are within those
        (`on_branch`); the others are followed from zero torque.

    Returns
    -------
    BatchSolution
    """
    options = at_residual_floor(SolverOptions() if options is None else options, problem.fluid)
    shape, nc = problem.shape, problem.layout.n_contacts
    flat = problem.flat()
    x = (
        initial_creep(flat)
        if x0 is None
        else np.broadcast_to(np.asarray(x0, dtype=float), shape + (nc,)).reshape(-1, nc).copy()
    )
    if has_multiple_equilibria(problem.fluid):
        sol = _follow(flat, options, predict, x, None if below is None else _below(below))
    else:
        sol = _solve_flat(flat, x, options, fallback, predict)
    return BatchSolution(
        state=reshape_state(sol.state, shape),
        converged=sol.converged.reshape(shape),
        residual_norm=sol.residual_norm.reshape(shape),
        iterations=sol.iterations.reshape(shape),
    )


def solve_near(
    problem: EquilibriumProblem, options: SolverOptions, x0, follow: bool = True
) -> BatchSolution:
    """Solve a 1-D batch from the creeps ``x0`` ``(n, n_c)`` of nearby equilibria (the
    optimal clamp's stencils: the same torque at forces a few per cent apart), without
    the predictor stage or the point solver.

    Under a law with more than one equilibrium (under the torque condition on ``T_2``),
    Newton from ``x0`` comes first, and a point keeps its solution where it converged and
    does not lie past a fold of its branch (`ballcvt.solvers.held_creep.turned_back`, the
    test of the torque continuation's step onto its target); every other point is
    followed from zero torque, as `solve_batch` follows them all (before session 30 the
    thermal optimal sweep's stencils were each so followed). Otherwise `solve_batch` from
    ``x0``. Without ``follow`` the other points are left unconverged instead (a guess's
    scores, `ballcvt.solvers.optimal_stencil`).
    """
    options = at_residual_floor(options, problem.fluid)
    flat = problem.flat()
    x = np.array(x0, dtype=float).reshape(flat.size, flat.layout.n_contacts)
    turned = branch_turned(flat, options)  # None without the torque condition on T_2
    if not has_multiple_equilibria(flat.fluid) or turned is None:
        return solve_batch(flat, options, x, fallback=False, predict=False)

    def accept(direct: BatchSolution) -> np.ndarray:
        keep = np.array(direct.converged, dtype=bool)
        on = np.flatnonzero(keep)
        if on.size:
            keep[on] &= ~turned(flat.take(on), direct.state.creep[on])
        return keep

    return _follow(flat, options, False, x, accept, follow)


def solve_from(problem: EquilibriumProblem, options: SolverOptions, x0=None, fallback=True,
               predict=True, follow=True) -> BatchSolution:  # fmt: skip
    """`solve_batch`, except from starts ``x0`` near the solutions (``predict`` False) under
    a law with more than one equilibrium: `solve_near` there (Newton from them, kept where it
    lands on the branch from zero torque, not past a fold; only the other points followed
    from zero torque, as `solve_batch` follows every point). A capacity scan's torques from
    the one below and a sweep's points from its scan's creeps so cost a Newton run where
    each was followed from zero torque (Table I's thermal cam sweep, session 33). Not next
    to a fold: there Newton and the fold test accept torques the continuation does not
    reach (`ballcvt.solvers.capacity.interval_search` confirms its bisection's ends so).
    Without ``follow`` the points Newton leaves are left unconverged (`solve_near`)."""
    if x0 is not None and not predict and has_multiple_equilibria(problem.fluid):
        return solve_near(problem, options, x0, follow)
    return solve_batch(problem, options, x0, fallback, predict)


def _below(below):
    """The ``accept`` test of `_follow` given ``below`` (`solve_batch`): converged, and
    `on_branch` under those creeps."""

    def accept(direct: BatchSolution) -> np.ndarray:
        bound = np.broadcast_to(np.asarray(below, dtype=float), direct.state.creep.shape)
        return direct.converged & on_branch(direct.state.creep, bound)

    return accept


def _follow(flat, options, predict, x, accept, follow=True) -> BatchSolution:
    """`solve_batch` of the 1-D batch ``flat`` under a law with more than one
    equilibrium: Newton from ``x`` where ``accept`` is given (``BatchSolution -> bool
    (n,)``: `_below`'s `on_branch`, or `solve_near`'s fold test), kept where it holds;
    every other point followed from zero torque (`continue_in_torque`), or, without
    ``follow``, left unconverged.

    The direct Newton runs on towards `POLISH_SHARE` of the tolerance (and counts as
    converged at the tolerance): a solve stops anywhere below its tolerance, and the
    continuation from zero torque mostly ends well inside (its last step starts close
    by), so a point it solves and the same point solved directly could differ by tens of
    times the tolerance in efficiency (1.6e-8 against the thermal law's 1e-9 floor, Table
    I at ratio 1.2, 30 N m; docs/model.md §14)."""
    iterations = np.zeros(flat.size, dtype=int)
    todo = np.arange(flat.size)
    state = None
    if accept is not None:
        direct = _tight_solve(flat, x, options, predict)
        iterations += direct.iterations
        keep = accept(direct)
        state, todo = direct.state, np.flatnonzero(~keep)
        if not follow:
            return replace(direct, converged=keep)
    if todo.size:
        sub = flat.take(todo)
        xt, its, reached = continue_in_torque(
            sub,
            branch_solver(options, predict),
            min_step=REACH_STEP,
            pinned=branch_pinned(options),
            turned=branch_turned(flat, options),
        )
        count = np.array(its, dtype=int)
        ends = _tightened(sub, xt, reached == sub.output_torque, options, count)
        iterations[todo] += count
        state = ends if state is None else state.put(todo, ends)
    if state is None:  # no rows
        state = evaluate(flat, x, options.quadrature)
    return _flat_solution(state, iterations, options.tol)


def _tightened(flat, x, reached, options, iterations) -> EquilibriumState:
    """The state at the creeps ``x`` of the continuation's points ``flat``, taken on by
    Newton towards `POLISH_SHARE` of the tolerance where the continuation ``reached`` its
    torque (as `_follow`'s direct Newton runs: both paths then end near the residual's
    noise, and a sweep and `solve` agree to ~1e-10 in efficiency where they agreed to
    2.2e-8; at a limit 2e-4 below the fold the continuation's own end was 7.8e-8 off the
    solution to 1e-15, Table I at ratio 1.90). A step from an equilibrium converged to the
    tolerance moves the creeps by some 1e-7 even there, far from the other branch; the
    tighter solution is kept where it meets the tolerance, else the state at ``x``.
    ``iterations`` (of the points) gains the evaluations, in place."""
    done, parts = np.zeros(flat.size, dtype=bool), []
    idx = np.flatnonzero(reached)
    if idx.size:
        again = _tight_solve(flat.take(idx), x[idx].copy(), options, False)
        iterations[idx] += again.iterations
        parts.append((idx[again.converged], again.state.take(again.converged)))
        done[idx[again.converged]] = True
    rest = np.flatnonzero(~done)
    if rest.size:
        parts.append((rest, evaluate(flat.take(rest), x[rest], options.quadrature)))
        iterations[rest] += 1
    return EquilibriumState.joined(flat.size, parts)


def _tight_solve(flat, x, options, predict) -> BatchSolution:
    """`_solve_flat` from ``x`` without fallback, each point stopping after `PATIENCE`
    iterations without progress, run on towards `POLISH_SHARE` of ``options.tol`` and
    counted converged at ``options.tol`` (`_follow`)."""
    tight = replace(options, tol=options.tol * POLISH_SHARE)
    sol = _solve_flat(flat, x, tight, False, predict, PATIENCE)
    return replace(sol, converged=sol.residual_norm <= options.tol)


#: The share of the tolerance the direct Newton of `_follow` runs on towards [-].
POLISH_SHARE = 1e-2


def _solve_flat(flat, x, options, fallback, predict, patience=None) -> BatchSolution:
    """`solve_batch` of the 1-D batch ``flat`` from the creeps ``x`` (``(n, n_c)``);
    ``patience``: as in `_newton`."""
    iterations = np.zeros(flat.size, dtype=int)
    x, state = _staged_newton(flat, x, iterations, options, predict=predict, patience=patience)
    norm = residual_norm(state.residual)
    bad = np.flatnonzero(~(norm <= options.tol))
    if fallback and bad.size:
        robust = replace(options, method="hybr")
        for i in bad:
            one = flat.take(int(i))
            sol = solve_robust(one, robust, initial_creep(one))
            iterations[i] += sol.evaluations
            if sol.residual_norm < norm[i]:
                x[i] = sol.state.creep
        state = evaluate(flat, x, options.quadrature)
    return _flat_solution(state, iterations, options.tol)


def _flat_solution(state, iterations, tol) -> BatchSolution:
    """The `BatchSolution` of a 1-D batch at ``state`` (converged: norm <= ``tol``)."""
    norm = residual_norm(state.residual)
    return BatchSolution(state, norm <= tol, norm, iterations)


def branch_solver(options: SolverOptions, predict: bool = True):
    """The solver each step of `continue_in_torque` calls (its ``Solve``): Newton from
    the cold start (the output creep at 0) with the point solver at zero torque, Newton
    alone from the last step's creeps after it (a point giving up after `PATIENCE`
    iterations without progress) (``options``, ``predict`` as in
    `solve_batch`)."""

    def solve(flat, x0, cold):
        x = np.array(initial_creep(flat) if x0 is None else x0, dtype=float)
        x[:, -1] = 0.0 if x0 is None else x[:, -1]  # from 1e-3 it ran off at high ratios
        sol = _solve_flat(flat, x, options, cold, predict, None if cold else PATIENCE)
        return sol.converged, sol.state.creep, sol.iterations

    return solve


def branch_turned(flat, options: SolverOptions):
    """The ``turned`` test of `continue_in_torque` (`turned_back`, held creeps solved with
    ``options``) under the torque condition on ``T_2`` (`walks`); None under another."""
    if not walks(flat):
        return None
    pinned, tol = branch_pinned(options)
    return lambda pb, x: turned_back(pb, pinned, tol, x)


def branch_pinned(options: SolverOptions, patience: int | None = None):
    """`solve_pinned` with ``options`` (and ``patience``, as in `_newton`) bound and the
    tolerance: the ``pinned`` argument of `continue_in_torque`
    (`ballcvt.solvers.held_creep.Pinned`, tol)."""
    return (lambda pb, k, x0: solve_pinned(pb, k, x0, options, patience)), options.tol


@quiet_trials
def solve_pinned(problem: EquilibriumProblem, contact: int, x0, options=None, patience=None):
    """Solve with one contact's creep held, for the output torque that goes with it.

    The output torque enters only the output disc's balance, and linearly (the last
    residual, docs/model.md §5). With the creep of ``contact`` held at its value in
    ``x0``, the other balances fix the other creeps; the output torque is then the one
    that balances the output disc: ``T_2 = T_body,2 - T_drag,2``. This gives the torque
    at which a creep reaches a given value in one Newton solve (`ballcvt.solvers.limit`).
    The problem's own ``output_torque`` is not used.

    Parameters
    ----------
    problem : EquilibriumProblem
        Operating points, 1-D batch ``(n,)``, at a torque-independent clamping force.
    contact : int or ndarray of int
        The contact whose creep is held: one, or one per point ``(n,)``.
    x0 : array_like
        Starting creeps ``(n, n_c)``; column ``contact`` holds the prescribed creep [-].
    options : SolverOptions, optional
        As in `solve_batch` (no fallback: a point that fails is flagged).
    patience : int, optional
        A point stops (unconverged) after that many Newton iterations without a lower
        residual (`_newton`); None: after ``options.max_iterations``.

    Returns
    -------
    torque : ndarray
        Output torque ``T_2`` at the solution [N m], ``(n,)``.
    solution : BatchSolution
        Creeps and state; ``converged`` refers to the balances other than the output's.
    """
    options = at_residual_floor(SolverOptions() if options is None else options, problem.fluid)
    flat = problem.flat()
    nc = flat.layout.n_contacts
    x = np.array(x0, dtype=float).reshape(flat.size, nc)  # (0, n_c) too: no rows, no crash
    iterations = np.zeros(flat.size, dtype=int)
    _, state = _staged_newton(flat, x, iterations, options, pinned=contact, patience=patience)
    norm = residual_norm(state.residual[:, :-1])
    return balancing_output_torque(flat, state), BatchSolution(
        state=state, converged=norm <= options.tol, residual_norm=norm, iterations=iterations
    )


def _staged_newton(flat, x, iterations, options, pinned=None, predict=True, patience=None):
    """The predictor stage on the coarse rule (where it pays, `_predicts`), then Newton on
    the requested rule; a point whose coarse run went non-finite restarts from ``x``.
    Returns the final creeps (updated in place where possible) and state."""
    if predict and _predicts(options, flat.size):
        coarse = replace(options, quadrature=options.predictor, tol=options.predictor_tol)
        start = x.copy()
        _newton(flat, x, iterations, coarse, pinned, patience)
        x = np.where(np.all(np.isfinite(x), axis=-1, keepdims=True), x, start)
    return x, _newton(flat, x, iterations, options, pinned, patience)


def _predicts(options, n_points: int) -> bool:
    """Whether a batch of ``n_points`` runs the predictor stage first."""
    return (
        options.predictor is not None
        and options.predictor != options.quadrature
        and n_points >= options.predictor_min_points
    )


def _newton(flat, x, iterations, options, pinned=None, patience=None, refresh=None):
    """Damped Newton on the points of the 1-D batch ``flat``; updates ``x`` in place.

    ``pinned``: the contact whose creep stays at its value in ``x`` (one, or one per
    point); the output balance (the last residual) is then dropped, the output torque
    being the unknown it defines (`solve_pinned`). ``patience``: a point stops
    (unconverged) after that many iterations without a lower residual norm; None: never.
    ``refresh``: ``(rows, x) -> problem`` of the points ``rows`` rebuilt at their creeps
    ``x`` before each evaluation (`ballcvt.solvers.planetary.coupled_creeps`); None: ``flat``'s.

    Returns the state at the final ``x`` of every point: each point's last evaluation,
    or a fresh one for the points whose last move was not evaluated.
    """
    nc, n = x.shape[-1], flat.size
    free = free_creeps(nc, n, pinned)  # the same for all unless held per point (plain indexing)
    same = free[0] if n and (np.ndim(pinned) == 0 or (free == free[0]).all()) else None
    active = np.arange(n)
    final = None
    it = Iterates(
        x=x,
        best=np.full(n, np.inf),
        prev_x=x.copy(),
        prev_dx=np.zeros((n, free.shape[1])),
        fresh=np.zeros(n, dtype=bool),
    )
    fresh = it.fresh
    stall = np.zeros(n, dtype=int)  # iterations since each point's norm last fell
    confirm = False  # every active point is expected to converge: no Jacobian needed
    near_norm = confirm_norm(flat.fluid)
    m = free.shape[1]
    secant = SecantCorrection.start(n, m)
    for _ in range(options.max_iterations):
        if active.size == 0:
            break
        whole = active.size == n  # every point still iterates: no gathers or scatters
        at = slice(None) if whole else active  # (views of every point: no index arrays)
        xa = x if whole else x[active]
        sub = _problem(flat, None if whole else active, xa, refresh)
        jac = None
        if confirm:
            state = evaluate(sub, xa, options.quadrature)
        else:
            state, jac = evaluate_split(sub, xa, options.quadrature, secant.near[at],
                                        options.split_min)  # fmt: skip
            if pinned is not None:
                jac = at_free(jac[:, :m], free, at, same)
        iterations[at] += 1
        final = state if final is None or whole else scatter_state(final, state, active)
        fresh[at] = True
        res = np.ascontiguousarray(state.residual[:, :m])
        # near its solution a point steps with its last Jacobian, corrected
        jac = secant.update(active, at_free(xa, free, at, same), res, jac)
        before = it.best[at].copy()  # (`advance` updates the best norms in place)
        norm = residual_norm(res)
        secant.near[at] = (norm <= near_norm) & (norm < before)
        kept = advance(it, active, res, jac, free, options.tol)
        confirm = bool(secant.near[kept].all())  # no fresh Jacobian needed
        if patience is not None:
            stall[active] = np.where(it.best[active] < before, 0, stall[active] + 1)
            going = kept[stall[kept] < patience]
            kept, confirm = going, confirm and going.size == kept.size
        active = kept
    stale = np.flatnonzero(~fresh)
    if final is None or stale.size == n:
        return evaluate(_problem(flat, None, x, refresh), x, options.quadrature)
    if stale.size:
        again = evaluate(_problem(flat, stale, x[stale], refresh), x[stale], options.quadrature)
        final = scatter_state(final, again, stale)
    return final


def _problem(flat, rows, x, refresh):
    """The problem `_newton` evaluates at the creeps ``x`` of its points ``rows`` (None:
    all of them)."""
    if refresh is not None:
        return refresh(np.arange(flat.size) if rows is None else rows, x)
    return flat if rows is None else flat.take(rows)
