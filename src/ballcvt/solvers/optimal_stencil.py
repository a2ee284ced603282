"""The stencils of the batched optimal-clamp searches (`ballcvt.solvers.optimal_batch`,
`ballcvt.solvers.optimal_lattice`): the efficiency of points at given clamping forces in one
batched solve (`_Scorer`), the parabola through three of them, and the starting creeps of
a stencil's solves from the last stencil's."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..model.traction.base import has_multiple_equilibria
from ..performance.efficiency import efficiency
from .clamped import with_clamp
from .newton import initial_creep, solve_batch, solve_near
from .options import SolverOptions
from .refusal import CREEP_RTOL

#: Newton iterations (per stage) of a solve in the search (the coarse rule a duty cycle
#: searches on needs 20 or more at some points): a force below the creep bound
#: has no equilibrium, and the batch would iterate on it up to ``max_iterations``.
ITERATIONS = 30
#: Residual tolerance [-] of the search's solves (the solve at the optimum keeps the
#: options' own, 1e-11 by default). Stopping at 1e-9 instead moved the efficiency of
#: Table I's points (10 x 10, 1-4 kN, both laws) by at most 6e-8; a stencil of half-width
#: ``h = NEAR`` (`ballcvt.solvers.optimal_batch`) compares efficiencies some ``q h^2``
#: apart (``q ~ 0.25``, the curvature of ``eta(ln F_N0)``): 6e-6, so its vertex moves by
#: at most some ``6e-8 / (q h)``, 5e-5, the size of the vertex's own cubic bias
#: (``2 NEAR^2``), the efficiency by under 1e-9.
#: The full rule's first round takes 3.5 Newton evaluations per force instead of 4.2
#: (issue 26, session 28).
SCORE_TOL = 1e-9


@dataclass(frozen=True)
class _Scorer:
    """Solves points of the batch at given clamping forces (one batched solve a call)."""

    problem: EquilibriumProblem
    c_lim: float
    options: SolverOptions

    def __call__(self, index, u, x0=None, follow=True):
        """``(score, creeps)`` of points ``index`` at ``F_N0 = exp(u)``: the score is the
        overall efficiency where the point converges within the creep limit, ``-inf``
        elsewhere (as in `search_optimum`). From the starting creeps ``x0`` (a last
        stencil's, a coarse search's, a duty cycle's first pass's), `solve_near`: under a
        law with more than one equilibrium Newton's answer is kept unless it lies past a
        fold, where each solve was followed from zero torque before session 30 (a third
        of the thermal optimal sweep's traction evaluations); without ``follow``, a point
        Newton does not keep so scores ``-inf`` (a guess's round, `_first_round`)."""
        pb = with_clamp(self.problem.take(index), np.exp(u))
        options = replace(
            self.options,
            max_iterations=min(self.options.max_iterations, ITERATIONS),
            tol=max(self.options.tol, SCORE_TOL),
        )
        if x0 is None:
            sol = solve_batch(pb, options, None, fallback=False)
        else:  # near their solutions (under the thermal law: kept unless past a fold)
            sol = solve_near(pb, options, x0, follow)
        creep = np.max(np.abs(sol.state.creep), axis=-1)
        ok = sol.converged & (creep <= self.c_lim * (1.0 + CREEP_RTOL))
        eta = efficiency(pb, sol.state).overall
        return np.where(ok, eta, -np.inf), sol.state.creep


def _parabola(u, e):
    """Vertex ``u*`` and concavity of the parabola through the three sorted points
    ``(u[:, k], e[:, k])`` (Newton's divided differences)."""
    a, b, c = u.T
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        s1 = (e[:, 1] - e[:, 0]) / (b - a)
        s2 = (e[:, 2] - e[:, 1]) / (c - b)
        q = (s2 - s1) / (c - a)
        vertex = b - (s1 + q * (b - a)) / (2.0 * q)
    concave = np.isfinite(e).all(axis=1) & (q < 0) & np.isfinite(vertex)
    return vertex, concave


def _start(x, du):
    """Starting creeps at forces ``exp(du)`` times those of the creeps ``x`` (one row per
    point, ``du`` one row of stencil offsets per point): the traction coefficient a
    torque needs falls as ``1/F_N0``, and with it, near the origin of the traction
    curve, the creep."""
    return (x[:, None, :] * np.exp(-du)[:, :, None]).reshape(-1, x.shape[-1])


def _interpolated(xs, us, es, u):
    """Starting creeps ``(k * m, n_c)`` at the forces ``exp(u)`` ``(k, m)`` from the last
    stencil's solutions (creeps ``xs`` ``(k, 3, n_c)`` at ``us`` ``(k, 3)``, scores ``es``):
    the parabola in ``ln F_N0`` through ``F_N0`` times the creeps (nearly constant, as in
    `_start`) where all three were admissible, else `_start` from the centre. The next
    stencil lies within or next to the last, so Newton starts within the interpolation's
    error (~ h^3) instead of the scaling's."""
    out = _start(xs[:, 1], u - us[:, 1:2]).reshape(u.shape + xs.shape[-1:])
    ok = np.isfinite(es).all(axis=1)
    if ok.any():
        a, b, c = (us[ok, j][:, None] for j in range(3))
        t = u[ok]
        lag = np.stack(  # Lagrange weights (k, 3 new, 3 old)
            [(t - b) * (t - c) / ((a - b) * (a - c)),
             (t - a) * (t - c) / ((b - a) * (b - c)),
             (t - a) * (t - b) / ((c - a) * (c - b))], axis=-1,
        )  # fmt: skip
        scaled = xs[ok] * np.exp(us[ok])[:, :, None]
        out[ok] = np.einsum("knj,kjc->knc", lag, scaled) * np.exp(-t)[:, :, None]
    return out.reshape(-1, xs.shape[-1])


def _first_round(score: _Scorer, index, u, x0=None, guess=False):
    """``(scores, creeps)`` of the first stencils ``u`` ``(k, 3)``, as one flat batch.

    Given ``x0``, creeps near each centre (a coarse search's, a duty cycle's first
    pass's), all three forces start from them scaled to their forces (`_start`), without
    the predictor stage. Otherwise, on a rule with a predictor and in a batch of at least
    ``predictor_min_points`` forces, the centres come first from the cold start through
    the predictor stage and their neighbours from the centres' creeps, about half the
    iterations of all three from the cold start; else all three start cold together.
    Given ``x0`` or on a rule without a predictor (the search rule, whose solves stop at
    the predictor's tolerance, 1e-6), a point's Newton iterates depend on its own start
    only, never on its batch: a table, a sweep and `solve` then certify the same force
    even where the efficiency has a kink near its optimum (harden task 0:28). Under a law
    with more than one equilibrium (the thermal law) the centres come first on any rule,
    each followed from zero torque, and their neighbours start from their creeps
    (`solve_near`: kept unless past a fold), each point's still from its own start only:
    before session 37 all three were followed from zero torque (the wide start of
    `ballcvt.solvers.optimal_batch`, a quarter of Table I's thermal optimal sweep). With
    ``guess`` (that wide start: its scores only pick where the lattice's climb starts) a
    neighbour Newton does not keep scores ``-inf`` without being followed from zero
    torque."""
    options = score.options
    x = None if x0 is None else _start(x0, u - u[:, 1:2])
    staged = options.predictor is not None and 3 * index.size >= options.predictor_min_points
    if x is not None or not (staged or has_multiple_equilibria(score.problem.fluid)):
        return score(np.repeat(index, 3), u.reshape(-1), x)
    mid, x_mid = score(index, u[:, 1])
    sides = u[:, [0, 2]]
    x_sides = _start(x_mid, sides - u[:, 1:2])
    got, x_sides = score(np.repeat(index, 2), sides.reshape(-1), x_sides, not guess)
    got, x_sides = got.reshape(-1, 2), x_sides.reshape(index.size, 2, -1)
    scores = np.column_stack([got[:, 0], mid, got[:, 1]]).reshape(-1)
    creeps = np.stack([x_sides[:, 0], x_mid, x_sides[:, 1]], axis=1)
    return scores, creeps.reshape(-1, x_mid.shape[-1])


def _centred(score: _Scorer, index, x_start, start, u):
    """Starting creeps at the first centres ``u[:, 1]`` of the points ``index``: from the
    creeps ``x_start`` at the forces ``exp(start)`` (`_start`), the cold start
    (`initial_creep`) where a point has none; None without ``x_start``."""
    if x_start is None or start is None:
        return None
    known = np.all(np.isfinite(x_start), axis=1) & np.isfinite(start)
    scaled = _start(x_start, (u[:, 1] - start)[:, None])  # NaN rows where not known
    return np.where(known[:, None], scaled, initial_creep(score.problem)[index])
