"""Torque continuation from no load, for traction laws with more than one equilibrium.

Where a contact's traction falls past the peak of its curve (the thermal law), the drive
can have two equilibria at one operating point: one on the branch that starts at zero
torque, and one past the fold of that branch, with more creep and a different efficiency
(docs/model.md §14). Newton's method lands on either, depending on where it starts. The
drive, loaded from rest at its speed, follows the first: each point is solved at zero
torque, then at rising shares of its torque, each solve started from the last accepted
one, the step doubled after a success and halved after a failure (a step that failed is
first resumed once from where its Newton run stopped: next to the fold Newton converges
slowly), never past a torque that failed other than the target, which is tried again from closer (batched over the
points). A point whose step or bracket narrows below `MIN_STEP` is past the fold of its
branch: no equilibrium of the drive carries its torque, and it is reported unconverged,
unless, given `solve_pinned`, the branch is then followed on in a held creep to the
torque: a step can fail well below the fold where the residual meets the solver's noise
floor (harden task 2028:592: between 55 % and 99.5 % of the fold at forces 1e-6 apart),
and the held creep is regular up to and through the fold. Under the torque condition on
``T_2`` (session 27) a point then stops at its first failed step, and the walk along the
branch takes over (`ballcvt.solvers.walk_reach.walk_to_torque`: it reaches the torque,
or finds it past the fold, where the halved steps each failed after a Newton run to its
patience); the march in a disc contact's held creep
(`ballcvt.solvers.held_creep.reach_torque`) takes the points it leaves. Used by
`ballcvt.solvers.newton.solve_batch` for a law with ``multiple_equilibria``.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from .branch_path import walks
from .held_creep import Pinned, reach_torque
from .walk_reach import walk_to_torque

__all__ = [
    "continue_in_torque",
    "solve_twice",
    "FIRST_STEP",
    "MIN_STEP",
    "OPEN_STEP",
    "REACH_STEP",
]

#: First torque step after zero torque, as a share of each point's torque [-].
FIRST_STEP = 0.25
#: Smallest step tried before a point is given up (past the fold), as a share of its
#: torque (or of ``torque_scale`` without one) [-].
MIN_STEP = 1e-5
#: First step towards an infinite target (as far as the branch goes), as a share of the
#: problem's ``torque_scale`` ``n F_N0 r_S`` [-].
OPEN_STEP = 0.05
#: Smallest step towards a finite target when the held creep follows on
#: (`reach_torque`, regular through the fold): halving the torque step further, each
#: failed step a Newton run to its patience near the fold, only comes closer to where the
#: held creep starts (a thermal cam sweep's capacity scan: 11.1 -> 8.5 s, the same
#: efficiencies to the bit) [-].
REACH_STEP = 1e-2

#: ``solve(problem, x0, cold)`` -> ``(converged, creep, iterations)`` of a 1-D batch;
#: ``x0`` None (and ``cold`` True) at zero torque, from the cold start with every fallback.
Solve = Callable[[EquilibriumProblem, np.ndarray | None, bool], tuple]


def continue_in_torque(flat: EquilibriumProblem, solve: Solve, target=None, min_step=MIN_STEP,
                       admissible=None, pinned: tuple[Pinned, float] | None = None,
                       turned=None):  # fmt: skip
    """Follow each point of the 1-D batch ``flat`` from zero torque up to its target.

    Parameters
    ----------
    flat : EquilibriumProblem
        Operating points, 1-D batch ``(n,)``.
    solve : callable
        The batched solver (`Solve`), without fallbacks beyond zero torque: a fallback
        from a cold start could land on the other equilibrium.
    target : array_like, optional
        Torque (of the torque condition, ``output_torque``) to reach per point [N m];
        ``+inf``: as far as the branch goes (its fold, the limiting torque). By default
        the problem's ``output_torque``.
    min_step : float
        Width of the bracket (last success, first failure) at which a point stops, as a
        share of ``|target|`` (of ``torque_scale`` for an infinite one) [-].
    admissible : callable, optional
        ``creep (m, n_c) -> bool (m,)``: a converged step counts only where it is true
        (the creep limit, for the limiting torque).
    pinned : callable, optional
        `ballcvt.solvers.held_creep.Pinned` with the solver's options and tolerance
        ``(pinned, tol)``: a point that stops short of a finite target is followed on in a
        held creep (`walk_to_torque`, then `reach_torque`; under the torque condition on
        ``T_2`` from its first failed step); None: it stops there.
    turned : callable, optional
        ``turned(problem, x) -> bool (m,)``: whether the equilibria ``x`` of a step onto
        the points' targets lie past a fold (`ballcvt.solvers.held_creep.turned_back`);
        such a step counts as failed. Only the step onto the target is tested (one
        held-creep solve per point).

    Returns
    -------
    creep : ndarray
        ``(n, n_c)``: at the highest torque reached (the target where it was) [-].
    iterations : ndarray of int
        Residual evaluations of each point over all steps, ``(n,)``.
    torque : ndarray
        The highest torque reached, ``(n,)`` [N m]; NaN where zero torque failed (or was
        not admissible).
    """
    n = flat.size
    given = flat.output_torque if target is None else target
    target = np.broadcast_to(np.asarray(given, dtype=float), (n,))
    scale = np.broadcast_to(flat.torque_scale, (n,))
    open_ = np.isinf(target)
    step = np.where(open_, OPEN_STEP * scale, FIRST_STEP * np.abs(target))
    least = min_step * np.where(open_, scale, np.abs(target))
    ok, x, iterations = solve(replace(flat, output_torque=np.zeros(n)), None, True)
    x, iterations = np.array(x, dtype=float), np.array(iterations, dtype=int)
    if admissible is not None:
        ok = ok & admissible(x)
    torque = np.where(ok, 0.0, np.nan)
    failed = np.full(n, np.nan)  # the lowest torque tried in vain (a bracket of the fold)
    active = np.flatnonzero(ok & (target != 0.0))
    while active.size:
        t, goal, bad = torque[active], target[active], failed[active]
        trial = np.where(np.abs(goal - t) <= step[active], goal, t + np.sign(goal) * step[active])
        beyond = (np.abs(trial) >= np.abs(bad)) & (trial != goal)  # the goal: from closer
        trial = np.where(beyond, 0.5 * (t + bad), trial)
        good, xt, its = solve_twice(solve, replace(flat.take(active), output_torque=trial),
                                     x[active])  # fmt: skip
        if admissible is not None:
            good = good & admissible(xt)
        onto = np.flatnonzero(good & (trial == goal)) if turned is not None else ()
        if len(onto):  # the step onto the target jumped a fold?
            sub = replace(flat.take(active[onto]), output_torque=trial[onto])
            good[onto] &= ~turned(sub, xt[onto])
        iterations[active] += its
        acc, rej = active[good], active[~good]
        torque[acc], x[acc] = trial[good], xt[good]
        step[acc] *= 2.0
        step[rej] *= 0.5
        failed[rej] = trial[~good]
        width = np.where(np.isnan(failed[active]), step[active], failed[active] - torque[active])
        going = (np.abs(width) >= least[active]) & (step[active] >= least[active])
        if pinned is not None and walks(flat):  # the walk along the branch takes over
            going &= np.isnan(failed[active]) | np.isinf(target[active])
        active = active[(torque[active] != target[active]) & going]
    if pinned is not None:
        _reach(flat, solve, pinned, (target, torque, x), admissible)
    return x, iterations, torque


def _reach(flat, solve: Solve, pinned, reached, admissible) -> None:
    """The points stopped short of a finite target followed on in a held creep
    (`reach_torque`); updates ``reached`` = ``(target, torque, x)`` in place."""
    target, torque, x = reached
    short = np.flatnonzero(np.isfinite(target) & np.isfinite(torque) & (torque != target))
    if short.size == 0:
        return
    pin_solve, tol = pinned
    sub = replace(flat.take(short), output_torque=target[short])

    def at_torque(pb, x0):
        good, xt, _ = solve_twice(solve, pb, x0)
        return good, xt

    decided, good, xr = walk_to_torque(sub, pinned, at_torque, (torque[short], x[short]))
    rest = np.flatnonzero(~decided)
    if rest.size:
        sub_t, sub_x = torque[short[rest]], x[short[rest]]
        good[rest], xr[rest] = reach_torque(
            sub.take(rest), pin_solve, at_torque, tol, sub_t, sub_x
        )
    if admissible is not None:
        good &= admissible(xr)
    torque[short[good]], x[short[good]] = target[short[good]], xr[good]


def solve_twice(solve: Solve, flat: EquilibriumProblem, x0: np.ndarray):
    """``solve`` from ``x0``, then once more from where it stopped for the points that
    did not converge: next to a fold Newton converges only linearly (its Jacobian turns
    singular there) and runs out of iterations short of the tolerance, but on its way."""
    good, xt, its = solve(flat, x0, False)
    good, xt, its = np.array(good, dtype=bool), np.array(xt, dtype=float), np.array(its)
    again = np.flatnonzero(~good & np.all(np.isfinite(xt), axis=-1))
    if again.size:
        ok, xa, ia = solve(flat.take(again), xt[again], False)
        its[again] += ia
        good[again], xt[again] = ok, np.where(np.asarray(ok)[:, None], xa, xt[again])
    return good, xt, its
