"""Following the branch of equilibria from zero torque in one disc contact's held creep.

Where the traction can fall with the creep (the thermal law, docs/model.md §14) the
branch of equilibria that starts at zero torque folds back at its largest torque. Next
to the fold Newton converges slowly in the torque (its Jacobian turns singular there),
and a torque continuation (`ballcvt.solvers.continuation`) can also stop short of it
where a step fails at the solver's noise floor (harden tasks 2026:2534, 2028:592: the
continuation stopped anywhere between 55 % and 99.5 % of the fold at forces 1e-6 apart).
Parametrised by the creep of a disc contact instead, the branch is regular through the
fold: with that creep held, one Newton solve gives the other creeps and the output torque
that goes with them (`ballcvt.solvers.newton.solve_pinned`, the ``Pinned`` callable
here). Two walks use it:

* `ballcvt.solvers.fold.climb_to_fold`: the largest torque on the branch (the limiting
  torque at a fold);
* `reach_torque` (here): the equilibrium on the branch at a given torque below the fold,
  where the continuation stopped short of it (`bracket_in_creep`, then the secant method
  in the held creep, `secant_in_creep`, then Newton at the torque itself).

Both step the held creep up from the last equilibrium on the branch, doubling the step
after a success and shrinking it where the torque does not rise (or the solve fails, or
a creep passes the limit), so they never leave the branch for the equilibrium past its
fold.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from ..equilibrium.problem import EquilibriumProblem

__all__ = [
    "reach_torque",
    "turned_back",
    "disc_to_climb",
    "TURN_STEP",
    "FOLD_CREEP_RTOL",
    "PINNED_SLACK",
    "MAX_FOLD_STEPS",
    "MAX_CREEP_STEP",
    "REACH_RTOL",
    "VERTEX_RTOL",
    "SECANT_STEPS",
    "secant_in_creep",
    "pinned_step",
    "held_of",
    "on_branch",
]

#: Smallest creep step of a walk, as a share of the creep scale (``C_lim`` for the
#: climb to the fold, the held creep where it starts for `reach_torque`) [-].
FOLD_CREEP_RTOL = 1e-4
#: Residual norm, in solver tolerances, up to which a held-creep step counts [-]: the
#: thermal residual has a noise floor near the tolerance at large loads, and only the
#: torque of the step is used (a solve at the torque itself decides convergence).
PINNED_SLACK = 100.0
#: Most steps of a walk.
MAX_FOLD_STEPS = 80
#: Largest creep step of `bracket_in_creep`, as a share of the held creep where it starts [-]:
#: a long step could pass the fold and still land above the last torque.
MAX_CREEP_STEP = 0.05
#: Relative torque error [-] at which the secant method hands over to Newton at the torque.
REACH_RTOL = 1e-7
#: Relative torque error [-] at which the secant below a fold (``vertex``) hands over to
#: Newton at the torque: 5 % of `ballcvt.solvers.peak.FOLD_MARGIN`, so Newton starts
#: within about 2.5 % of the distance in creep from that equilibrium to the fold.
VERTEX_RTOL = 1e-5
#: Most secant steps in the held creep.
SECANT_STEPS = 12

#: ``pinned(problem, contact, x0)`` -> ``(torque, BatchSolution)``: `solve_pinned` with
#: the solver options bound.
Pinned = Callable[[EquilibriumProblem, int, np.ndarray], tuple]
#: ``solve(problem, x0)`` -> ``(converged, creep)`` at the problems' own torques.
Solve = Callable[[EquilibriumProblem, np.ndarray], tuple]


def held_of(x, k) -> np.ndarray:
    """The creep ``(n,)`` of contact ``k`` (one, or one per point) of each row of ``x``
    ``(n, n_c)``."""
    return x[np.arange(x.shape[0]), k]


def pinned_step(pinned: Pinned, flat, k, x, creep, tol):
    """Held creep ``creep`` of contact ``k`` (one, or one per point) with the other creeps
    from ``x``: the torque (NaN where the solve failed) and the creeps."""
    x0 = x.copy()
    x0[np.arange(x0.shape[0]), k] = creep
    got, sol = pinned(flat, k, x0)
    ok = (sol.residual_norm <= PINNED_SLACK * tol) & np.isfinite(got)
    return np.where(ok, got, np.nan), sol.state.creep


def disc_to_climb(way) -> np.ndarray:
    """The disc contact, ``0`` or ``n_c - 1``, whose creep moves more along ``way``
    ``(n, n_c)`` (a walk's last chord, or the creeps themselves), per point: its held
    creep parametrises the branch best there."""
    return np.where(np.abs(way[:, 0]) >= np.abs(way[:, -1]), 0, way.shape[-1] - 1)


#: Relative step [-] down in the larger disc creep by which `turned_back` tells which way
#: the torque moves along the branch at an equilibrium. Next to a reported fold limit
#: (`ballcvt.solvers.peak.FOLD_MARGIN` below the fold) the torque then moves by ~3e-6 of
#: itself, thirty times the held-creep solves' noise (`PINNED_SLACK` x the law's 1e-9).
TURN_STEP = 1e-4


def turned_back(flat, pinned: Pinned, tol, x) -> np.ndarray:
    """Whether the equilibria ``x`` ``(n, n_c)`` at each point's own torque lie past a
    fold of its branch, where the torque falls as the creep grows.

    The larger disc creep is held `TURN_STEP` of itself lower: on the branch below its
    fold the torque falls with it, past the fold it rises. A step of the torque
    continuation that jumps the fold to the equilibrium past it (harden task 2704:75: to
    an input creep of 0.0671 where the branch's own is 0.0658; Table I's thermal cam
    sweep at ratio 1.83: its efficiency at the limit 0.91249 for the branch's 0.91274)
    is so told apart. False where the held solve fails.
    """
    goal, sign = _goal(flat)
    held = disc_to_climb(x)  # one batch, whichever contact each point holds
    got, _ = pinned_step(pinned, flat, held, x, held_of(x, held) * (1 - TURN_STEP), tol)
    return sign * got > goal


def reach_torque(flat, pinned: Pinned, solve: Solve, tol, torque, x):
    """The equilibrium at each point's own torque on its branch, from an equilibrium on
    the branch below it (``(torque, x)``, where a continuation stopped): the torque
    bracketed in a disc contact's held creep (`bracket_in_creep`, the input disc's
    contact first, then the output disc's for the points not bracketed), the secant
    method (Illinois) in that creep down to `REACH_RTOL`, then ``solve`` at the torque
    from there.

    Parameters
    ----------
    flat : EquilibriumProblem
        Operating points, 1-D batch ``(n,)``, each at its target ``output_torque``.
    pinned, solve : callable
        `Pinned`, `Solve`.
    tol : float
        Solver tolerance [-].
    torque, x : ndarray
        Equilibria below the targets on their branches: ``(n,)`` [N m], ``(n, n_c)``.

    Returns
    -------
    converged : ndarray of bool
        ``(n,)``: False where the torque lies past the fold (or the solve failed).
    creep : ndarray
        ``(n, n_c)``; the start ``x`` where not converged.
    """
    ok, out = np.zeros(flat.size, dtype=bool), np.array(x, dtype=float)
    past = np.zeros(flat.size, dtype=bool)  # the first contact's march passed the fold
    for k in (0, flat.layout.n_contacts - 1):
        todo = np.flatnonzero(~ok & ~past)
        if todo.size == 0:
            break
        sub = flat.take(todo)
        lo, hi = bracket_in_creep(sub, pinned, k, tol, torque[todo], x[todo])
        past[todo] = _past_fold(lo, hi)
        xs = secant_in_creep(sub, pinned, k, tol, lo, hi)
        found = np.flatnonzero(np.all(np.isfinite(xs), axis=-1))
        if found.size:
            good, xr = solve(sub.take(found), xs[found])
            good = np.asarray(good, dtype=bool)
            ok[todo[found[good]]], out[todo[found[good]]] = True, np.asarray(xr)[good]
    return ok, out


def _past_fold(lo, hi) -> np.ndarray:
    """The points `bracket_in_creep` left unbracketed at a fold of their branch: the torque
    fell at a converged step in the held creep (``lo``'s fourth entry), so the target lies
    above the branch's largest torque; the other disc's held creep would march to the same
    fold (it cost a thermal cam sweep a fifth of its time). Not so where only failed steps
    stopped the march: the other contact's march may get through."""
    return np.isnan(hi[1]) & lo[3]


def _goal(flat):
    """``|T_2|`` of each point's target and its sign (the direction the torque rises)."""
    t = np.broadcast_to(np.asarray(flat.output_torque, dtype=float), (flat.size,))
    return np.abs(t), np.where(t < 0, -1.0, 1.0)


def bracket_in_creep(flat, pinned: Pinned, k, tol, torque, x):
    """The held creep of contact ``k`` stepped up from the equilibria ``(torque, x)``
    until the torque passes each point's target: the step doubles while the torque rises
    short of it (to at most `MAX_CREEP_STEP` of the starting creep) and is quartered where
    the torque does not rise (the fold), down to `FOLD_CREEP_RTOL` of the starting creep.
    The step keeps the direction of the creep (the creeps grow along the branch), never
    reversed: a march turned back past the fold would bracket the equilibrium past it.

    Returns the brackets ``(lo, hi)``, each ``(creep (n,), |torque| (n,), creeps (n,
    n_c))``: ``lo`` below the target, ``hi`` past it (NaN where not bracketed); ``lo``
    has a fourth entry, whether the torque fell at a converged step (a fold) ``(n,)``.
    """
    goal, sign = _goal(flat)
    lo_x, lo_t = np.array(x, dtype=float), sign * np.asarray(torque, dtype=float)
    hi_t, hi_x = np.full(flat.size, np.nan), np.full_like(lo_x, np.nan)
    scale = np.maximum(np.abs(lo_x[:, k]), 1e-6)
    step = np.where(lo_x[:, k] < 0, -1.0, 1.0) * 0.01 * scale
    active = np.arange(flat.size)
    fell = np.zeros(flat.size, dtype=bool)
    for _ in range(MAX_FOLD_STEPS):
        active = active[np.abs(step[active]) >= FOLD_CREEP_RTOL * scale[active]]
        if active.size == 0:
            break
        trial = lo_x[active, k] + step[active]
        got, xs = pinned_step(pinned, flat.take(active), k, lo_x[active], trial, tol)
        got = sign[active] * got
        up = got > lo_t[active]
        fell[active[np.isfinite(got) & ~up]] = True
        past = up & (got >= goal[active])
        rise = up & ~past
        lo_t[active[rise]], lo_x[active[rise]] = got[rise], xs[rise]
        step[active[rise]] = np.clip(
            2.0 * step[active[rise]],
            -MAX_CREEP_STEP * scale[active[rise]],
            MAX_CREEP_STEP * scale[active[rise]],
        )
        step[active[~up]] *= 0.25
        hi_t[active[past]], hi_x[active[past]] = got[past], xs[past]
        active = active[~past]
    return (lo_x[:, k], lo_t, lo_x, fell), (hi_x[:, k], hi_t, hi_x)


def secant_in_creep(flat, pinned: Pinned, k, tol, lo, hi, vertex: bool = False):
    """The creeps at each point's target torque by the Illinois method in the held creep
    of contact ``k`` within the bracket ``(lo, hi)`` (`bracket_in_creep`), to a relative
    torque error `REACH_RTOL`; NaN rows where there is no bracket or a step failed.

    ``vertex``: ``hi`` is the largest torque of the branch (a fold), where the torque is
    a parabola in the creep: the method then runs on ``sqrt(T_hi - T)``, linear in the
    creep there (the secant of the torque itself, flat at ``hi``, crept towards it one
    side at a time), to `VERTEX_RTOL`.
    """
    goal, sign = _goal(flat)
    (c_lo, t_lo, x_lo, _), (c_hi, t_hi, x_hi) = lo, hi
    rtol = VERTEX_RTOL if vertex else REACH_RTOL

    def measure(t, top, target):
        if not vertex:
            return t - target
        return np.sqrt(np.maximum(top - target, 0.0)) - np.sqrt(np.maximum(top - t, 0.0))

    ends = [[c_lo.copy(), measure(t_lo, t_hi, goal), x_lo.copy()],
            [c_hi.copy(), measure(t_hi, t_hi, goal), x_hi.copy()]]  # fmt: skip
    out = np.full_like(x_lo, np.nan)
    close = np.abs(t_hi - goal) <= rtol * goal
    out[close] = x_hi[close]
    last = np.full(flat.size, -1)  # the side replaced last (Illinois)
    active = np.flatnonzero(np.isfinite(t_hi) & ~close)
    for _ in range(SECANT_STEPS):
        if active.size == 0:
            break
        (ca, fa, xa), (cb, fb, _) = ends
        a, b = fa[active], fb[active]
        c = ca[active] - a * (cb[active] - ca[active]) / (b - a)
        got, xs = pinned_step(pinned, flat.take(active), k, xa[active], c, tol)
        got = sign[active] * got
        err = measure(got, t_hi[active], goal[active])
        bad = ~np.isfinite(err)
        side = (err >= 0).astype(int)
        for s in (0, 1):
            j = ~bad & (side == s)
            i = active[j]
            ends[1 - s][1][i] *= np.where(last[i] == s, 0.5, 1.0)
            ends[s][0][i], ends[s][1][i], ends[s][2][i] = c[j], err[j], xs[j]
            last[i] = s
        done = ~bad & (np.abs(got - goal[active]) <= rtol * goal[active])
        out[active[done]] = xs[done]
        active = active[~bad & ~done]
    return out


def on_branch(creep, below, rtol: float = 1e-4) -> np.ndarray:
    """Whether equilibria with the creeps ``creep`` ``(n, n_c)`` lie on the branch from
    zero torque of a law with more than one equilibrium, given the creeps ``below`` of an
    equilibrium on that branch at a torque at least theirs: both disc creeps within
    ``below``'s (to ``rtol``). Along the branch the disc creeps grow with the torque, and
    the equilibrium past the fold has the creep of the contact whose traction peaks beyond
    its value at the fold (`ballcvt.solvers.fold`), which is beyond that of every torque of
    the branch below the fold. ``rtol`` lies between the creeps' noise and that gap: at a
    limit `ballcvt.solvers.peak.FOLD_MARGIN` below a fold (Table I, 2 kN, ratio 1.95)
    the equilibrium past the fold holds a disc creep 4.6 % larger, and the limit's
    creeps, converged at the thermal law's residual floor, were 1.9e-6 short of the
    solution to 5e-15 (at 1e-6 the efficiency at that limit was followed again from zero
    torque, a tenth of the sweep's traction evaluations; session 36)."""
    disc = [0, -1]
    return np.all(np.abs(creep[:, disc]) <= np.abs(below[:, disc]) * (1.0 + rtol), axis=-1)
