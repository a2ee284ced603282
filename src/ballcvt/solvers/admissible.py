"""Whether operating points lie within the traction capacity (docs/model.md §8, §11).

`solve_admissible` solves a batch under a constant force or a torque-following clamping
law and says which points converged with every creep within ``creep_limit`` (and, under
such a law, every peak pressure within ``design.max_pressure``); it is the test of the
limit search (`ballcvt.solvers.limit`) and of the sweeps' point status.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..model.traction.base import has_multiple_equilibria, traction_rises_with_creep
from .clamped import at_ceiling, pressure_bound_force, solve_clamped, with_clamp
from .newton import initial_creep, solve_batch, solve_from
from .options import SolverOptions, at_residual_floor, coarse_options

__all__ = [
    "Admissibility",
    "solve_admissible",
    "screen_admissible",
    "screens",
    "follows_torque",
    "CREEP_RTOL",
]

#: Relative margin on ``creep_limit`` of a solved point [-]: the limit search pins a creep
#: at the limit to the solver's tolerance, so a point at the limit solves to within it.
#: Every admissibility test of a solved creep takes it (`solve_admissible`, `solve`'s
#: refusal, the optimal clamp's searches): before session 31 `solve_admissible` took
#: none, and a study refused an optimal force 1.8e-9 over the creep limit that `solve`
#: carried (harden task 3005:3406).
CREEP_RTOL = 1e-8

#: Relative margin [-] by which the largest creep of a point solved on the predictor's
#: coarse rule must clear the creep limit, below or above it, for `screen_admissible` to
#: decide the point there. Between 0.3 and 3 times the limit the two rules' largest creeps
#: were seen to differ by up to 0.5 % (Table I drive and the hub, 150-2000 rpm) and 10 %
#: where the limit lies on the flat of the traction curve (a 200 N cam preload; the hub
#: at 40 rpm), five times less than this margin (issue 26).
SCREEN_MARGIN = 0.5
#: Tolerance [-] of the screen's Newton runs on the coarse rule (`screen_admissible`; the
#: predictor's is 1e-6): its verdicts need the largest creep to within a fraction of
#: `SCREEN_MARGIN`, not to round-off. Against runs to 1e-6 on harden's draws (seeds 2601
#: and 2602, session 26: 47,187 screened points) the largest creeps differed by at most
#: 4 % of the creep limit between 0.3 and 2 times it (up to 33 % far beyond it, where the
#: traction curve is flat). Verdicts changed on 81 points: 78 decided within and one
#: beyond that were not at 1e-6 (the 74 recorded had not converged there; their creeps
#: within 0.2 %), two beyond at 1e-6 left to the full rule. The scan's screen takes about
#: a quarter fewer iterations (issue 26).
SCREEN_TOL = 1e-4
#: Residual norm [-] at or below which a point that `solve_admissible`'s first Newton run
#: left unconverged is solved again from where that run ended (`_restart`): Newton's
#: steps from there meet the tolerance where a slow run stopped short of it.
RESTART_NORM = 1e-6


@dataclass(frozen=True)
class Admissibility:
    """Outcome of `solve_admissible`; arrays have the batch shape ``(n,)``.

    Attributes
    ----------
    problem : EquilibriumProblem
        The points at the forces their clamping law set.
    ok : ndarray of bool
        Converged with every ``|C| <= creep_limit`` (and, under a torque-following law,
        every peak pressure within ``design.max_pressure``).
    converged : ndarray of bool
        The equilibrium (and clamping equation) converged.
    creep : ndarray
        Final creeps, ``(n, n_c)``.
    beyond : ndarray of bool
        Inadmissible for a known reason: converged beyond a limit, creeps past the creep
        limit, or (under a torque-following law) a force that asks for more than the force
        of ``design.max_pressure`` (`ballcvt.solvers.clamped.solve_clamped` stops it there);
        an inadmissible point that is none of these did not converge.
    """

    problem: EquilibriumProblem
    ok: np.ndarray
    converged: np.ndarray
    creep: np.ndarray
    beyond: np.ndarray


def solve_admissible(
    problem: EquilibriumProblem,
    creep_limit: float,
    options: SolverOptions = SolverOptions(),
    law=None,
    x0=None,
    predict: bool = True,
    follow: bool = True,
) -> Admissibility:
    """Solve a 1-D batch and say which points lie within the traction capacity.

    Newton alone first; the point solver only for the points whose Newton run failed
    without its creeps running past the limit (a failure of the method, not of the
    equilibrium). A point whose Newton run fails with its creeps beyond the limit is
    beyond the capacity at once, unless it started cold (a NaN row of ``x0``). This is the
    admissibility test of the limiting torque (docs/model.md §8, §11), so a point is
    admissible exactly when its torque is at most the limit.

    Parameters
    ----------
    problem : EquilibriumProblem
        Operating points, 1-D batch.
    creep_limit : float
        ``C_lim`` [-].
    options : SolverOptions
        Solver options.
    law : clamping law, optional
        A torque-following law (`ballcvt.model.clamping`); by default the problem's forces.
    x0 : array_like, optional
        Starting creeps ``(n, n_c)``. A NaN row starts cold: from the kinematic start
        (`ballcvt.solvers.newton.initial_creep`), with no solved neighbour, and its failed
        run goes to the point solver whatever its creeps, as `solve`'s does. The rule
        "beyond at once" holds for a run started next to an equilibrium (a bisection's, a
        scan's, a continuation's), not for one from the kinematic start: there Newton can
        run the creeps past the limit at a point whose equilibrium lies within it (harden
        task 3903:1810, a cam-clamped drive at 6,364 rpm, the visco-elastic law: a study
        called 6.42 N m beyond the capacity, where `solve` converged at a creep of 0.098
        against the limit of 0.106). None: every point from the kinematic start, the rule
        kept (a capacity scan's first torques).
    predict : bool
        Whether the Newton runs start with the predictor stage (`ballcvt.solvers.newton.
        solve_batch`); False when ``x0`` is already close to the solutions (under a law
        with more than one equilibrium the points then start from ``x0``,
        `ballcvt.solvers.newton.solve_from`, where otherwise each is followed from zero
        torque).
    follow : bool
        Under such a law, from ``x0`` without the predictor stage: whether a point that
        Newton does not solve on its branch is followed from zero torque (else it is
        inadmissible: a bisection's trial, whose ends are then confirmed so,
        `ballcvt.solvers.capacity.interval_search`).
    Returns
    -------
    Admissibility
    """
    law = law if follows_torque(law) else None
    cold = np.zeros(problem.size, dtype=bool)
    if x0 is not None:
        cold = np.isnan(np.asarray(x0, dtype=float)).any(axis=-1)
        x0 = np.where(cold[:, None], initial_creep(problem), x0)
    if law is not None:

        def solve(pb, x, fallback):
            return solve_clamped(
                pb,
                law,
                lambda p, y: solve_from(p, options, y, fallback, predict, follow),
                x,
                pb.design.max_pressure,
                lambda p, y: solve_batch(p, options, y, fallback, False),
            )
    else:

        def solve(pb, x, fallback):
            return pb, solve_from(pb, options, x, fallback, predict, follow)

    pb, sol = solve(problem, x0, False)
    big = np.max(np.abs(sol.state.creep), axis=-1)
    conv, creep = sol.converged.copy(), sol.state.creep.copy()
    # a point whose creeps converged but whose clamping equation did not (a force that runs
    # away) gets nothing from the point solver, which only ever replaces failed creeps
    balanced = sol.residual_norm <= at_residual_floor(options, pb.fluid).tol
    within = creep_limit * (1.0 + CREEP_RTOL)
    unsure = np.flatnonzero(~conv & (~(big > within) | cold) & ~balanced)
    # under a law with more than one equilibrium every point was followed from zero torque
    # with the point solver there (`solve_batch` ignores ``x0`` and ``fallback``): the
    # same run again gives the same answer (it cost a quarter of a thermal cam sweep)
    if unsure.size and not has_multiple_equilibria(pb.fluid):
        got, again = solve(pb.take(unsure), _restart(problem, x0, sol, unsure), True)
        conv[unsure], creep[unsure] = again.converged, again.state.creep
        if law is not None and law.implicit:  # the rescue's own forces (its fixed point's)
            force = np.array(np.broadcast_to(pb.clamp_force, conv.shape), dtype=float)
            force[unsure] = got.clamp_force
            pb = with_clamp(pb, force)
    big = np.max(np.abs(creep), axis=-1)
    ok = conv & (big <= within)
    beyond = conv | (big > within)
    if law is not None:
        bound = pressure_bound_force(pb, pb.design.max_pressure)
        ok &= ~_over_pressure(pb, bound)
        beyond |= at_ceiling(pb.clamp_force, bound)
    return Admissibility(pb, ok, conv, creep, beyond & ~ok)


def _over_pressure(pb: EquilibriumProblem, bound) -> np.ndarray:
    """Whether each point's clamping force [N] exceeds ``bound`` [N], the force of peak
    pressure ``design.max_pressure`` (`pressure_bound_force`), beyond round-off."""
    return pb.clamp_force > bound * (1 + 1e-12)


def _restart(problem: EquilibriumProblem, x0, sol, unsure) -> np.ndarray:
    """Starting creeps ``(len(unsure), n_c)`` of the second run of `solve_admissible` on
    its points ``unsure``: the first run's final creeps where their residual norm came
    within `RESTART_NORM` (a Newton run that converged slowly, e.g. linearly at a point
    near the traction peak of the coarse rule, and ran out of iterations a step or two
    short of the tolerance: it ends there instead of in the point solver, issue 26), the
    first run's start ``x0`` (or the cold start) elsewhere."""
    start = initial_creep(problem.take(unsure)) if x0 is None else np.asarray(x0)[unsure]
    near = sol.residual_norm[unsure] <= RESTART_NORM
    return np.where(near[:, None], sol.state.creep[unsure], start)


def screens(options: SolverOptions, law, fluid) -> bool:
    """Whether `screen_admissible` can decide points under ``options``, ``law`` and
    ``fluid``: the options have a predictor rule other than their own, the law's force
    does not depend on the solution (a constant force, or a law that senses the output
    torque), and the fluid's traction never falls with the creep (no fold of the
    equilibrium below the creep limit, where the two rules could disagree on whether a
    point has an equilibrium at all)."""
    law = law if follows_torque(law) else None
    coarse = options.predictor is not None and options.predictor != options.quadrature
    return coarse and (law is None or not law.implicit) and traction_rises_with_creep(fluid)


def screen_admissible(
    problem: EquilibriumProblem, creep_limit: float, options: SolverOptions, law=None, x0=None
) -> Admissibility:
    """Which points of a 1-D batch lie clearly within or clearly beyond the traction
    capacity, from one Newton run on the predictor's coarse rule (``options.predictor``,
    to `SCREEN_TOL`; only where `screens`).

    A point is decided only where its creeps converged on that rule and every ``|C|`` lies
    `SCREEN_MARGIN` below ``creep_limit`` (``ok``), or some ``|C|`` lies that far above it
    (``beyond``), as `solve_admissible` would find on the full rule; a force beyond the
    pressure bound (``design.max_pressure``) is beyond on any rule (the force of such a
    law and the Hertz pressure do not depend on the creeps). Every other point (neither
    ``ok`` nor ``beyond``) is left to `solve_admissible`. The capacity scan of
    `ballcvt.solvers.capacity.interval_search` decides most of its points so, at about a
    third of the cost of a solve on the full rule (issue 26).

    Parameters and returns as in `solve_admissible` (``converged`` and ``creep``: the
    coarse rule's).
    """
    law = law if follows_torque(law) else None
    coarse = coarse_options(options)  # to SCREEN_TOL (or the options' own, if looser)
    coarse = replace(coarse, tol=max(coarse.tol, SCREEN_TOL))
    if law is not None:
        pb, sol = solve_clamped(problem, law, lambda p, y: solve_batch(p, coarse, y, False), x0)
    else:
        pb, sol = problem, solve_batch(problem, coarse, x0, False)
    big = np.max(np.abs(sol.state.creep), axis=-1)
    conv = np.asarray(sol.converged)
    ok = conv & (big <= creep_limit * (1.0 - SCREEN_MARGIN))
    beyond = conv & (big > creep_limit * (1.0 + SCREEN_MARGIN))
    if law is not None:
        over = _over_pressure(pb, pressure_bound_force(pb, pb.design.max_pressure))
        ok, beyond = ok & ~over, beyond | over
    return Admissibility(pb, ok, conv, sol.state.creep, beyond & ~ok)


def follows_torque(law) -> bool:
    """Whether ``law`` sets a torque-dependent force (else the problem's force is used)."""
    return law is not None and not law.fixed_force
