"""Efficiency-optimal clamping forces of many points in a few batched solves (issue 26).

`ballcvt.solvers.optimal_search.search_optimum` searches one point at a time (a geometric
grid of forces, a bisection for the creep bound, a bounded Brent search): some 15 batched
solves per point. Here every point of a batch is advanced together, so a sweep or a duty
cycle of ``N`` points costs a few batched solves of ``N`` points each.

Method. Over the Table I drive and the ``hub`` (ratios 0.5-2, torques up to 90 N m, 500 to
5000 rpm, the isothermal and the viscoelastic laws) the optimum sits inside the feasible
range, away from the creep and pressure limits: it is the maximum of a smooth efficiency
``eta(u)``, ``u = ln F_N0``, where ``d eta / du = 0``. Each point runs Newton's method on
that condition with finite-difference derivatives: three forces ``u_c - h, u_c, u_c + h``
per round, solved together in one batched solve (`solve_batch`, warm from the creeps of
the last round's centre, scaled as ``1/F_N0``), the next centre the vertex of their
parabola and the next half-width the vertex's error (some ``2 h^2``, the cubic term's
bias) where the vertex lies within the stencil, else the step taken, at most half the
last (quadratic convergence). Where the parabola is not
concave or its vertex lies far outside the stencil, the stencil moves to its best force
(doubling its width), or halves around it when a neighbour has no admissible
equilibrium (below the creep bound); a stencil with no admissible force at all lies wholly
below the creep bound (the guess too low for the torque), and the next starts a
half-width above its top. A point is certified when the parabola of a stencil
of half-width at most `NEAR` is concave with its vertex within the stencil: the vertex
then misses the optimum by some ``2 NEAR^2`` at most, the efficiency by under 1e-7
(`STEP` bounds the smallest stencil).

The answer on the options' own rule comes from a climb on a fixed lattice of forces
(`ballcvt.solvers.optimal_lattice`, since session 32): from its start to the stencil of
the lattice ``ln F_N0 = 0.02 k`` whose centre is better than both neighbours, the answer
the maximum of the cubic through it and one more lattice force. Where the efficiency has a
saw tooth in the force (a hard-spinning contact's quadrature), a parabola search certifies
the tooth it starts on; the lattice's stencils are the same whichever start led there, so a
duty cycle's second pass, a sweep and `solve` give one optimum per point. The parabola
search above runs only where the climb does not certify (an optimum within a lattice step
of the creep bound), from the best lattice force found.

Given a force near each point's optimum (``guess``: a duty cycle's first pass hands its
forces to its second), the climb starts there (one round mostly, and the cubic's force); the creeps
found at the optimum (``OptimalForces.creep``) start the solve that follows. A sweep
searches all its points in one batch. Without a guess (and with a predictor rule in the
options) one round on the options' ``search_rule`` to the predictor's tolerance, on the
forces ``exp(+-WIDTH)`` times the guess ``F = 200 + 14 T`` (`_wide_start`, since session
32; from session 24 a whole stencil search there, two rounds mostly), gives the vertex and
creeps the climb on the full rule starts from as from a guess; without a guess or
predictor, that round runs on the options' own rule.

A large batch without starts on a rule without a predictor (a duty cycle's first pass)
searches every `SEED_STRIDE`-th point so and starts the others' climbs from the optimum of
the seed nearest them (`_seeded`, since session 34): `_guess` is 30-50 % low on the hub.

At zero torque the answer is ``min_force`` when it holds the no-load drag within the
creep limit (the old search's first grid point). Every point not certified (an optimum
on the creep or pressure limit or at ``min_force``, a torque no force carries, invalid
input) is handed to `search_optimum`, which also raises its errors unchanged.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..errors import TractionLimitError
from ..model.clamping import OptimalClamp
from .clamped import pressure_bound_force
from .optimal_lattice import lattice_search
from .optimal_search import ClampCase, search_optimum
from .optimal_stencil import _centred, _first_round, _interpolated, _parabola, _Scorer
from .options import SolverOptions, coarse_options

__all__ = ["OptimalForces", "optimal_forces", "STEP", "NEAR"]

#: Largest distance in ``ln F_N0`` [-] of the parabola's vertex from the best force of a
#: certified point (0.01 % of the force).
STEP = 1e-4
#: Largest distance in ``ln F_N0`` [-] of the best force's nearest neighbour at
#: certification (the parabola is then local).
NEAR = 5e-3
#: Half-width in ``ln F_N0`` [-] of the first three forces around the guess.
WIDTH = 0.1
#: Rounds (one batched solve each) before a point is handed to `search_optimum`.
ROUNDS = 12
#: Stencils in a row with no admissible force (each a half-width above the last: up to
#: ``0.9`` in ``ln F_N0`` from the first at `WIDTH`) before a point is handed to
#: `search_optimum` (as a torque no force carries does, after them).
CLIMBS = 3
#: Smallest batch of points without starts whose climbs start from the optima of a sample
#: of its own points, on a rule without a predictor (`_seeded`).
SEED_MIN = 256
#: One point of such a batch in this many is a seed.
SEED_STRIDE = 16


@dataclass(frozen=True)
class OptimalForces:
    """Result of `optimal_forces`, one entry per point of the batch.

    Attributes
    ----------
    force : ndarray
        Optimal ``F_N0`` [N]; NaN where no force carries the torque.
    fast : ndarray of bool
        Found by the batched search (else by `search_optimum`).
    refused : ndarray of bool
        No clamping force up to the pressure bound carries the torque.
    creep : ndarray
        Starting creeps ``(n, n_c)`` [-] at ``force`` where ``fast`` (interpolated to it
        from the search's last stencil, `_interpolated`; NaN elsewhere), for the solve
        that follows.
    """

    force: np.ndarray
    fast: np.ndarray
    refused: np.ndarray
    creep: np.ndarray


def _limits(problem: EquilibriumProblem, law: OptimalClamp):
    """``(C_lim [-], F_p [N] per point)``, or None where the limits are invalid (left to
    `search_optimum` to refuse)."""
    d = problem.design
    c_lim = d.creep_limit if law.creep_limit is None else float(law.creep_limit)
    p_lim = d.max_pressure if law.max_pressure is None else float(law.max_pressure)
    if not (0 < c_lim < 1 and p_lim > 0):
        return None
    return c_lim, pressure_bound_force(problem, p_lim)


def _torque(problem: EquilibriumProblem) -> np.ndarray:
    """The larger of each point's input and output torques [N m] (ideal ratio)."""
    return np.abs(problem.output_torque) * np.maximum(1.0, np.abs(problem.ratio))


def _guess(problem: EquilibriumProblem, lo=-np.inf, hi=np.inf) -> np.ndarray:
    """First guess of ``ln F_N0`` [-]: the optimum of the drives studied grows about
    linearly with the larger of the input and output torques, ``F ~ 200 + 14 T`` [N];
    kept ``WIDTH`` inside ``(lo, hi)`` so that the first three forces are admissible."""
    return np.clip(np.log(200.0 + 14.0 * _torque(problem)), lo + WIDTH, hi - WIDTH)


def _next(u, e, bounds):
    """The next stencil of each point, ``(centre, half-width)`` in ``ln F_N0``, and whether
    it is certified (module docstring; on stencils of half-width at most `NEAR`);
    ``bounds`` = ``(lo, hi)``; NaN centre: the point leaves for `search_optimum`."""
    lo, hi = bounds
    best = np.argmax(e, axis=1)
    vertex, concave = _parabola(u, e)
    a, b, c = u.T
    h = 0.5 * (c - a)
    step = np.abs(vertex - b)
    newton = concave & (step <= 2 * h)
    done = newton & (step <= h) & (h <= NEAR * (1 + 1e-9))
    # Newton: the vertex, the next stencil as wide as the vertex's error (some 2 h^2:
    # quadratic convergence) where it lies within the stencil, else as the step taken,
    # at most half the last
    centre = np.where(newton, vertex, b)
    error = np.where(step <= h, 2 * h * h, np.maximum(step, 2 * h * h))
    width = np.where(newton, np.clip(error, STEP, 0.5 * h), 0.5 * h)
    # otherwise (an infeasible neighbour, below the creep bound) the best force with the
    # width halved; or the best force at an end: move the stencil there
    up, down = ~newton & (best == 2), ~newton & (best == 0)
    centre = np.where(up, np.where(c < hi, c, np.nan), centre)
    centre = np.where(down, np.where(a > lo, a, np.nan), centre)
    width = np.where(up | down, np.minimum(2 * h, WIDTH), width)
    # no admissible force at all: the stencil lies below the creep bound (the guess too
    # low for the torque); the next one starts a half-width above its top
    none = ~np.isfinite(e).any(axis=1)
    centre = np.where(none, c + 2 * h, centre)
    width = np.where(none, h, width)
    centre = np.clip(centre, lo + width, hi - width)
    moves = ~none | (c + h <= hi)
    centre = np.where(moves & (hi - lo > 2 * width), centre, np.nan)
    return centre, width, done


def _coarse(score: _Scorer) -> _Scorer:
    """``score`` on the options' search rule, to the predictor's tolerance
    (`coarse_options`)."""
    return replace(score, options=coarse_options(score.options, search=True))


def _search(score: _Scorer, index, bounds, start=None, x_start=None):
    """The stencil search of the points ``index`` (positive torque) -> ``(u, certified,
    creeps)`` per point: ``u`` the vertex of the last stencil's parabola, the creeps there
    (`_interpolated`). ``start``: a first ``ln F_N0`` [-] per point (NaN: `_guess`),
    searched from a half-width of `NEAR` (certified in one round when it is within it of
    the optimum); ``x_start``: creeps at those forces, which start the first round
    (`_centred`)."""
    lo, hi = bounds
    centre = _guess(score.problem.take(index), lo, hi)
    width = np.full(index.size, WIDTH)
    if start is not None:
        known = np.isfinite(start)
        width[known] = NEAR
        centre[known] = np.clip(start[known], lo[known] + NEAR, hi[known] - NEAR)
    u = np.empty((index.size, 3))
    e = np.full((index.size, 3), -np.inf)
    xs = None
    done = np.zeros(index.size, dtype=bool)
    climbs = np.zeros(index.size, dtype=int)  # stencils in a row with no admissible force
    live = np.arange(index.size)
    for _ in range(ROUNDS):
        last = u[live].copy() if xs is not None else None
        u[live] = centre[live, None] + width[live, None] * np.array([-1.0, 0.0, 1.0])
        if xs is None:
            x0 = _centred(score, index, x_start, start, u)
            got, creep = _first_round(score, index, u, x0)
        else:
            x0 = _interpolated(xs[live], last, e[live], u[live])
            got, creep = score(np.repeat(index[live], 3), u[live].reshape(-1), x0)
        e[live] = got.reshape(-1, 3)
        if xs is None:
            xs = np.empty((index.size, 3, creep.shape[-1]))
        xs[live] = creep.reshape(live.size, 3, -1)
        nxt, w, certified = _next(u[live], e[live], (lo[live], hi[live]))
        done[live[certified]] = True
        climbs[live] = np.where(np.isfinite(e[live]).any(axis=1), 0, climbs[live] + 1)
        go = ~certified & np.isfinite(nxt) & (climbs[live] <= CLIMBS)
        centre[live], width[live] = nxt, w
        live = live[go]
        if not live.size:
            break
    vertex = _parabola(u, e)[0]
    return vertex, done, _interpolated(xs, u, e, vertex[:, None])


def optimal_forces(
    problem: EquilibriumProblem,
    law: OptimalClamp = OptimalClamp(),
    options: SolverOptions = SolverOptions(),
    fallback: bool = True,
    guess=None,
    creep=None,
) -> OptimalForces:
    """Efficiency-optimal clamping forces of a 1-D batch of points (module docstring).

    Parameters
    ----------
    problem : EquilibriumProblem
        The points (their ``clamp_force`` is not used), a 1-D batch.
    law : OptimalClamp
        The limits and the fallback search's settings (as in `search_optimum`).
    options : SolverOptions
        Solver options.
    fallback : bool
        Whether the points the batched search does not certify go to the one-point
        search (`search_optimum`); otherwise their force is NaN (``fast`` False).
    guess : array_like, optional
        A force near each point's optimum [N] (NaN where none), e.g. the optimum of a pass
        on the solver's coarse rule: the lattice's climb then starts there.
    creep : array_like, optional
        Creeps ``(n, n_c)`` [-] at the guessed forces (e.g. that pass's; NaN rows: none):
        the first stencils start from them (or from the cold start) without the
        predictor stage.

    Returns
    -------
    OptimalForces

    Raises
    ------
    InputError
        From `search_optimum` (negative torque, invalid limits).
    """
    n = problem.size
    force = np.full(n, np.nan)
    fast = np.zeros(n, dtype=bool)
    creep_guess = None if creep is None else np.asarray(creep, dtype=float)
    creep = np.full((n, problem.layout.n_contacts), np.nan)
    limits = _limits(problem, law)
    if limits is not None:
        c_lim, f_p = limits
        score = _Scorer(problem, c_lim, options)
        torque = problem.output_torque
        lo, hi = np.log(law.min_force), np.log(f_p)
        zero = np.flatnonzero((torque == 0) & (hi > lo))
        if zero.size:  # min_force when it holds the drag
            got, creep[zero] = score(zero, np.full(zero.size, lo))
            fast[zero] = np.isfinite(got)
            force[zero] = law.min_force
        pos = np.flatnonzero((torque > 0) & (hi > lo + 2 * WIDTH))
        if pos.size:
            bounds = (np.full(pos.size, lo), hi[pos])
            start = None if guess is None else _log_guess(guess, n)[pos]
            x_start = None if creep_guess is None else creep_guess[pos]
            u, done, creep[pos] = _final(score, pos, bounds, start, x_start)
            fast[pos] = done
            force[pos] = np.exp(u)
    force = np.where(fast, force, np.nan)
    creep[~fast] = np.nan
    refused = np.zeros(n, dtype=bool)
    for j in np.flatnonzero(~fast) if fallback else ():
        force[j], refused[j] = _fallback(problem, int(j), law, options)
    return OptimalForces(force, fast, refused, creep)


def _final(score: _Scorer, index, bounds, start=None, x_start=None):
    """``(u, certified, creeps)`` of the points ``index``: the lattice climb
    (`lattice_search`) from ``start`` (None: from one round on a wide stencil about
    `_guess`, on the search rule where the options have a predictor, `_wide_start`; NaN:
    from `_guess`), and from the best lattice force of each point it does not certify (an
    optimum within a lattice step of the creep bound), the stencil search (`_search`)."""
    if start is None and score.options.predictor is None and index.size >= SEED_MIN:
        return _seeded(score, index, bounds)
    lo, hi = bounds
    first = _guess(score.problem.take(index), lo, hi)
    if start is None:  # nothing but the guess: one round on a wide stencil about it first
        wide = _coarse(score) if score.options.predictor is not None else score
        start, x_start = _wide_start(wide, index, first)
    known = np.isfinite(start)
    first = np.where(known, start, first)
    if x_start is not None:  # creeps at the starts only where they are known
        x_start = np.where(known[:, None], x_start, np.nan)
    u, done, x = lattice_search(score, index, bounds, first, x_start)
    rest = np.flatnonzero(~done)
    if rest.size:
        got = _search(score, index[rest], (lo[rest], hi[rest]), u[rest], x[rest])
        u[rest], done[rest], x[rest] = got
    return u, done, x


def _seeded(score: _Scorer, index, bounds):
    """`_final` of a large batch of the points ``index`` without starts, on a rule without
    a predictor (a duty cycle's first pass): every `SEED_STRIDE`-th point as `_final`
    searches it (from `_guess`, its wide round first), the others' climbs from the optimum
    of the seed nearest them (`_nearest`), without the wide round. The lattice's answer does
    not depend on where its climb starts (`ballcvt.solvers.optimal_lattice`); from their
    own optima the hub's first pass took 0.21 s per 1,000 steps instead of 0.57 (session
    34)."""
    lo, hi = bounds
    seed = np.zeros(index.size, dtype=bool)
    seed[::SEED_STRIDE] = True
    s, r = np.flatnonzero(seed), np.flatnonzero(~seed)
    u = np.full(index.size, np.nan)
    done = np.zeros(index.size, dtype=bool)
    x = np.full((index.size, score.problem.layout.n_contacts), np.nan)
    u[s], done[s], x[s] = _final(score, index[s], (lo[s], hi[s]))
    start = _nearest(score.problem, index[s[done[s]]], u[s[done[s]]], index[r])
    start = np.clip(start, lo[r], hi[r])
    u[r], done[r], x[r] = _final(score, index[r], (lo[r], hi[r]), start)
    return u, done, x


def _nearest(problem: EquilibriumProblem, seeds, u_seeds, rest) -> np.ndarray:
    """Starts ``ln F_N0`` [-] of the points ``rest`` from the optima ``u_seeds`` of the
    points ``seeds``: the nearest seed's in ``(ln ratio, torque, ln speed)`` (each scaled by
    its spread over the points), moved by `_guess`'s change between the two; NaN without
    seeds."""
    from scipy.spatial import cKDTree  # (here: not on every import of the package)

    if not seeds.size:
        return np.full(rest.size, np.nan)
    pb = problem.take(np.concatenate([seeds, rest]))  # the seeds first
    feats = np.column_stack(
        [np.log(np.abs(pb.ratio)), _torque(pb), np.log(np.abs(pb.input_speed))]
    )
    spread = np.ptp(feats, axis=0)
    feats = feats / np.where(spread > 0, spread, 1.0)
    k = cKDTree(feats[: seeds.size]).query(feats[seeds.size :])[1]
    g = _guess(pb)  # (unbounded)
    return u_seeds[k] + g[seeds.size :] - g[k]


def _wide_start(score: _Scorer, index, centre):
    """``(ln F_N0, creeps)`` to start the climb of the points ``index`` from, after one
    round on the forces ``centre +- WIDTH``: the vertex of their parabola where it is
    concave and within ``2 WIDTH`` of the centre, else the best of them, else (none
    admissible: below the creep bound) ``2 WIDTH`` above the centre without creeps. From
    `_guess` on the hub's duty cycle the climb's parabolas through stencils 0.02 apart
    jumped twice before they reached the optimum (session 32)."""
    u = centre[:, None] + WIDTH * np.array([-1.0, 0.0, 1.0])
    e, x = _first_round(score, index, u, guess=True)
    e, x = e.reshape(-1, 3), x.reshape(index.size, 3, -1)
    vertex, concave = _parabola(u, e)
    best = np.take_along_axis(u, np.argmax(e, axis=1)[:, None], axis=1)[:, 0]
    some = np.isfinite(e).any(axis=1)
    near = concave & (np.abs(vertex - centre) <= 2 * WIDTH)
    start = np.where(near, vertex, np.where(some, best, centre + 2 * WIDTH))
    creep = _interpolated(x, u, e, start[:, None])
    return start, np.where(some[:, None], creep, np.nan)


def _log_guess(guess, n) -> np.ndarray:
    """``ln`` of the guessed forces [N] broadcast to ``n`` points (NaN where none)."""
    g = np.broadcast_to(np.asarray(guess, dtype=float), (n,))
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(np.isfinite(g) & (g > 0), np.log(np.where(g > 0, g, 1.0)), np.nan)


def _fallback(problem: EquilibriumProblem, j: int, law: OptimalClamp, options):
    """``(force [N], refused)`` of point ``j`` by `search_optimum`."""
    case = ClampCase(
        problem.design,
        problem.fluid,
        problem.layout.architecture,
        float(problem.ratio[j]),
        float(problem.output_torque[j]),
        float(problem.input_speed[j]),
    )
    try:
        opt = search_optimum(case, law, options)
    except TractionLimitError:
        return np.nan, True
    return opt.clamp_force, False
