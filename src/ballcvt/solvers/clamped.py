"""Equilibrium under a clamping law (docs/model.md §11).

A law whose force follows the output torque (a cam on the output disc) fixes ``F_N0``
before the equilibrium is solved. A law whose force follows the input torque (a cam on
the input disc) makes ``F_N0`` an unknown of the equilibrium: it is found by a fixed-point
iteration ``F_N0 <- law(T_0(F_N0))`` around the creep solver, warm-started from the last
creeps, each step accelerated by the map's measured slope (Wegstein 1958, a secant step
on ``law(T_0(F)) - F``). The map is a contraction (``T_0`` changes with ``F_N0`` only
through the losses), though it can be a slow one (a factor of 0.5 per step, issue 23),
and a point counts as converged only when its equilibrium residual meets the
solver's tolerance *and* the clamping equation holds to ``CLAMP_RTOL`` (or its fixed point
has reached the noise floor of ``T_0``, within ``CLAMP_NOISE_RTOL``).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..equilibrium.problem import EquilibriumProblem, with_clamp_force
from ..model.rheology import roelands_pressure_limit

__all__ = [
    "with_clamp",
    "solve_clamped",
    "pressure_bound_force",
    "at_ceiling",
    "CLAMP_RTOL",
    "MAX_CLAMP_ITERATIONS",
]

#: Relative tolerance of the clamping equation ``F_N0 = law(T_0, T_2)`` [-]. The creep
#: solver meets its residual tolerance (``SolverOptions.tol``, 1e-11 on dimensionless
#: torques), which leaves ``T_0`` uncertain to some 1e-10 of itself: a tighter tolerance
#: let the fixed point wander in that noise and fail points that had converged.
CLAMP_RTOL = 1e-10
#: Relative step of the clamping force below which a fixed point whose step stops
#: shrinking has reached that noise floor [-]: the steps of a contraction shrink every
#: iteration, and the noise floor (2e-10 to 6e-10 of the force, seen as a two-cycle of
#: the steps) lies far below it, so every path that solves a point settles it, wherever
#: in the noise its sequence happens to be (issue 23, harden 3:444 and 2026:4129).
CLAMP_NOISE_RTOL = 1e-8
#: Fixed-point iterations allowed for a law that senses the input torque.
MAX_CLAMP_ITERATIONS = 30
#: Relative margin kept below the Roelands overflow pressure by `pressure_bound_force` [-].
#: The peak pressure of a problem rebuilt at ``F_N0 (p_lim / p_max)^3`` lands on ``p_lim``
#: only to a few units of round-off (1e-16), either side; at the limit itself
#: `ballcvt.equilibrium.build_problem` would refuse the force that came out a hair above
#: it, so a fixed point clipped there raised instead of being flagged (issue 23).
ROELANDS_ROUND_OFF = 1e-12
#: Largest slope ``s`` of the map ``F -> law(T_0(F))`` a Wegstein step trusts [-]: the step
#: is ``1 / (1 - s)`` times the plain one, so this caps that gain at 10 (noise of the
#: force at its floor, some 5e-10 of it, stays below `CLAMP_NOISE_RTOL` when amplified).
MAX_SLOPE = 0.9
#: Smallest change of the force, relative to it, from which the map's slope is measured
#: [-]: smaller changes come too close to the noise floor of ``T_0`` to give a slope, and
#: the last slope measured is kept.
SLOPE_RTOL = 1e-7
#: Largest gain on the step of a fixed point whose force runs away (`_wegstein`) [-].
MAX_RUNAWAY_GAIN = 16.0
#: Relative margin [-] within which a force counts as at its ceiling (`at_ceiling`): a
#: problem rebuilt at the ceiling gives back its bound only to round-off.
CEILING_RTOL = 1e-9


def at_ceiling(force, bound) -> np.ndarray:
    """Whether each clamping force [N] stands at its ceiling ``bound`` [N]
    (`pressure_bound_force`), to `CEILING_RTOL`."""
    return np.asarray(force) >= np.asarray(bound) * (1.0 - CEILING_RTOL)


def _settles(step, last, force) -> np.ndarray:
    """Whether a fixed point's force ``force`` [N] is settled, from its step ``step``
    (``|law(T_0(F)) - F|``) and the previous step ``last`` [N]: within `CLAMP_RTOL`, or
    within `CLAMP_NOISE_RTOL` and no smaller than the step before (the noise floor)."""
    return (step <= CLAMP_RTOL * force) | ((step <= CLAMP_NOISE_RTOL * force) & (step >= last))


def _wegstein(force, new, memory):
    """The next force [N] of the fixed point ``F <- g(F)`` from ``force`` ``F`` and
    ``new`` ``g(F)`` [N] (Wegstein 1958): ``F + (g(F) - F) / (1 - s)``, with ``s`` the
    slope of ``g`` measured against the previous pair in ``memory`` (a dict it updates;
    ``s = 0``, the plain step, until a slope is measured), clipped to ``[-1, MAX_SLOPE]``.
    A contraction of slope ``s`` then converges in a step or two instead of some
    ``log(1e-10) / log(s)`` plain ones (issue 23, harden 2029:5846).

    A measured slope of 1 or more is no contraction: the force runs away from any fixed
    point below it (a loading cam whose drag grows faster with the force than the cam's
    force does, issue 23, harden 2032:2993). The plain iteration would creep towards the
    next fixed point above, or the model's pressure ceiling, by ever larger steps; its step
    is instead multiplied by a gain that doubles at every such iteration (up to
    `MAX_RUNAWAY_GAIN`), and falls back to 1 once a slope below 1 is measured again (the
    fixed point is then bracketed and the secant step above takes over).

    A step that would leave the positive forces (a slope measured on a curved ``g`` far
    from the fixed point: from 1,192 N with ``g = 137 N`` and a slope of 0.18, -93 N; harden
    task 3103:847) is replaced by the plain step ``g(F)``, or half the force where that is
    not positive either."""
    slope = memory.get("slope", np.zeros(np.shape(force)))
    gain = memory.get("gain", np.ones(np.shape(force)))
    if "force" in memory:
        df = force - memory["force"]
        with np.errstate(divide="ignore", invalid="ignore"):
            measured = (new - memory["new"]) / df
        fresh = np.isfinite(measured) & (np.abs(df) > SLOPE_RTOL * np.abs(force))
        trusted = np.where(measured < 1.0, np.clip(measured, -1.0, MAX_SLOPE), 0.0)
        slope = np.where(fresh, trusted, slope)
        away = fresh & (measured >= 1.0) & ((new - force) * (memory["new"] - memory["force"]) > 0)
        gain = np.where(away, np.minimum(2.0 * gain, MAX_RUNAWAY_GAIN), 1.0)
    memory.update(force=force, new=new, slope=slope, gain=gain)
    step = force + gain * (new - force) / (1.0 - slope)
    return np.where(step > 0.0, step, np.where(new > 0.0, new, 0.5 * force))


def with_clamp(problem: EquilibriumProblem, clamp_force) -> EquilibriumProblem:
    """The same operating points at other clamping forces ``F_N0`` [N]
    (`ballcvt.equilibrium.problem.with_clamp_force`)."""
    return with_clamp_force(problem, clamp_force)


def pressure_bound_force(problem: EquilibriumProblem, max_pressure: float) -> np.ndarray:
    """Largest ``F_N0`` [N] whose peak pressure stays at or below ``max_pressure`` [Pa].

    Every contact load is proportional to ``F_N0`` and the Hertz peak pressure grows as
    ``F^(1/3)`` (Eqs. 48-50), so ``F = F_N0 (p_lim / p_max)^3``. The bound never exceeds the
    pressure at which the Roelands viscosity overflows (docs/model.md §10), less
    `ROELANDS_ROUND_OFF` of it, so that a problem built at the bound is never refused for a
    peak pressure one round-off above that limit (issue 23, harden 2029:2727).
    """
    fl = problem.fluid
    roelands = roelands_pressure_limit(
        fl.viscosity, fl.pole_viscosity, fl.pole_pressure, fl.roelands_index
    )
    p_lim = min(float(max_pressure), roelands * (1.0 - ROELANDS_ROUND_OFF))
    return problem.clamp_force * (p_lim / np.max(problem.p_max, axis=-1)) ** 3


def _from_ceiling(problem, first, solve, x0, max_pressure):
    """The first pass of the fixed point of a law that senses the input torque, with the
    points it failed solved again at the force of ``max_pressure`` or the design's
    ``max_pressure``, the lower (`pressure_bound_force`), from ``x0``.

    The first force is the law's at the lossless input torque ``T_2 tau``, below its fixed
    point by the losses; where that force does not carry the torque the creeps run off,
    though the law's own force would carry it (harden task 2701:139: a hub cam at 40 %
    efficiency, whose capacity scan called every torque above 1.88 N m beyond the creep
    limit where loads to 7.05 N m settle within it). At the ceiling a torque within the
    capacity has an equilibrium, from which the fixed point descends to the law's force (a
    contraction); a torque that fails there too keeps that failure: with its creeps past the
    limit it is beyond the capacity, within them a failure of the solver, which
    `ballcvt.solvers.admissible.solve_admissible` hands to the point solver."""
    pb, sol = first
    failed = ~np.asarray(sol.converged, dtype=bool)
    if not failed.any():
        return pb, sol
    # (the design's pressure limit also bounds the restart of a solve that has none: the
    # Roelands range's force is a poor start, and the fixed point rises from there if the
    # law asks for more)
    top = min(max_pressure, pb.design.max_pressure)
    ceiling = np.broadcast_to(pressure_bound_force(pb, top), failed.shape)
    if failed.ndim == 0:  # the point solver
        again = solve(up := with_clamp(problem, ceiling), x0)
        return (up, again) if again.converged else (pb, sol)
    idx = np.flatnonzero(failed & np.isfinite(ceiling))
    if idx.size == 0:
        return pb, sol
    up = with_clamp(problem.take(idx), ceiling[idx])
    again = solve(up, None if x0 is None else np.asarray(x0)[idx])
    # every retried point keeps the retry's outcome, converged or not: the first pass's
    # failure at a force below the law's own tells nothing, and a retry that failed with
    # its creeps within the limit is the solver's failure, not the capacity's (harden
    # task 3902:3522: a hub cam on the input disc at 39,000 rpm and 26 % efficiency; its
    # first pass ran the creeps off at 1,866 N, and `solve_admissible` called the point
    # beyond the capacity at once where its point solver, from the ceiling's 8,305 N,
    # settles at 6,580 N within it)
    force = np.array(pb.clamp_force, dtype=float)
    force[idx] = ceiling[idx]
    return with_clamp(problem, force), _put(sol, idx, again, np.arange(idx.size))


def _put(sol, index, part, rows):
    """``sol`` (a batch solution) with its points ``index`` replaced by ``part``'s
    points ``rows``."""
    fields = {"state": sol.state.put(index, part.state.take(rows))}
    for name in ("converged", "residual_norm", "iterations"):
        value = np.array(getattr(sol, name), copy=True)
        value[index] = np.asarray(getattr(part, name))[rows]
        fields[name] = value
    return replace(sol, **fields)


def solve_clamped(
    problem: EquilibriumProblem, law, solve, x0=None, max_pressure=np.inf, again=None
):
    """Solve ``problem`` with its clamping force set by ``law``.

    Parameters
    ----------
    problem : EquilibriumProblem
        Operating points; their ``clamp_force`` is a starting value only (any positive
        force).
    law : clamping law
        See `ballcvt.model.clamping`.
    solve : callable
        ``solve(problem, x0) -> solution`` with ``state`` and ``converged`` (the batched
        or the point solver).
    x0 : array_like, optional
        Starting creeps.
    max_pressure : float
        The fixed point of a law that senses the input torque is sought up to the force
        of this peak pressure [Pa] (and never past the model's own pressure range): a point
        whose force asks for more there is left unconverged (the admissibility test of
        `ballcvt.solvers.admissible.solve_admissible` refuses it anyway, and a force that runs
        away would otherwise be followed to the Roelands ceiling, issue 23); `at_ceiling`
        says whether a force was stopped there.
    again : callable, optional
        The solver of the fixed point's later passes, each from the last pass's creeps
        (``solve`` by default): e.g. the batched solver without its predictor stage, which
        would only move a start that close away from the solution (issue 26).

    Returns
    -------
    (EquilibriumProblem, solution)
        The problem at the law's force and its solution, whose ``converged`` also requires
        the clamping equation to hold.
    """
    t2 = problem.output_torque
    force = law.clamp_force(problem.design, t2 * problem.ratio, t2)
    pb = with_clamp(problem, force)
    sol = solve(pb, x0)
    if not law.implicit:
        return pb, sol
    settled = np.zeros(np.shape(sol.converged), dtype=bool)
    last = np.full(np.shape(sol.converged), np.inf)
    memory: dict = {}
    pb, sol = _from_ceiling(problem, (pb, sol), solve, x0, max_pressure)
    for _ in range(MAX_CLAMP_ITERATIONS):
        new = law.clamp_force(pb.design, sol.state.input_torque, t2)
        # a point whose clamping equation holds, or whose fixed point has reached the
        # noise floor of its input torque, is settled: its force moves no more, so a point
        # of a batch gets the answer it gets alone, however long the others take
        step = np.abs(new - pb.clamp_force)
        settled |= np.asarray(sol.converged) & _settles(step, last, pb.clamp_force)
        last = step
        # points whose creeps did not converge keep their force (their torque means
        # nothing); no force beyond the ceiling is tried, and a force already there that
        # asks for more has no fixed point below it: it moves no more (such a point then
        # fails the clamping equation below and is flagged, never clipped silently)
        ceiling = pressure_bound_force(pb, max_pressure)
        stuck = at_ceiling(pb.clamp_force, ceiling) & (new > pb.clamp_force)
        move = np.asarray(sol.converged) & np.isfinite(new) & ~settled & ~stuck
        if not np.any(move):
            break
        target = np.minimum(_wegstein(pb.clamp_force, new, memory), ceiling)
        pb = with_clamp(problem, np.where(move, target, pb.clamp_force))
        sol = (solve if again is None else again)(pb, sol.state.creep)
    new = law.clamp_force(pb.design, sol.state.input_torque, t2)
    held = settled | (np.abs(new - pb.clamp_force) <= CLAMP_RTOL * pb.clamp_force)
    converged = np.asarray(sol.converged) & held
    if np.ndim(sol.converged) == 0:
        converged = bool(converged)
        if sol.converged and not converged:
            return pb, replace(
                sol,
                converged=False,
                message=sol.message.replace(
                    "converged", "equilibrium converged, clamping force did not", 1
                ),
            )
    return pb, replace(sol, converged=converged)
