"""The last stage of the batched optimal-clamp search: a climb on one lattice of forces.

Why. The overall efficiency is not a smooth function of the clamping force below some
1e-5: where a contact spins hard, the pole quadrature of its traction (the paper's
Eqs. 20-23 integrated on the full rule) moves the efficiency in a saw tooth as the contact
grows with the force (harden task 30999:56, the hub-derived drive at 8,600 rpm: teeth of
1.6e-5 every 1 % of the force at its optimum). A parabola search certifies the vertex of
whichever tooth it starts on, so a duty cycle's second pass (started from its first pass's
forces, at a nearby ratio, on the coarse rule) and `Variator.solve` (started from a search
on the search rule) reported optima up to 7e-5 apart in efficiency. The optimum must be one
function of the point, whatever path asks for it.

Method. The forces ``u_k = k LATTICE`` (``u = ln F_N0``, ``k`` an integer) form one lattice
for every point and path. The climb starts on the stencil ``(k - 1, k, k + 1)`` around the
lattice point nearest the start and moves it until its centre is the best of its three
forces: a step toward the better end (one new force; the other two are kept), or, where the
parabola through the three is concave with its vertex more than one and a half steps away,
a jump to the lattice point nearest the vertex (at most `JUMP` steps; three new forces); a
stencil with no admissible force climbs by 3, 6, 12, ... steps. A centre better than both
neighbours is a local maximum of the efficiency on the lattice. With ``LATTICE = 0.02``,
lattice efficiencies next to each other differ, away from the top, by at least
``q LATTICE^2``, about 1e-4 (``q ~ 0.25``, the curvature of ``eta(ln F_N0)``), several
times the saw tooth, so every start in the maximum's basin ends on the same stencil; its
forces are computed from the integers ``k``, so the same stencil has the same bits. The
answer is the maximum of the cubic through that stencil and the lattice force two steps
from its centre on the side of its parabola's vertex (`_cubic`, one force more): a function
of those four lattice forces alone. The parabola's vertex alone misses a smooth optimum by
some ``2 LATTICE^2`` in ``ln F_N0`` (1.8e-6 in efficiency at one of Table I's points); the
cubic's is exact on a cubic efficiency (3e-7 at that point). Where the efficiency has a saw
tooth of height ``s``, the answer moves by up to some ``s / (2 q LATTICE)``, the same on
every path.

A stencil with a force below the creep bound (the bound within a step of the optimum), one
past the pressure bound or ``min_force``, and a climb not done in `ROUNDS`, are not
certified here: the caller searches on from the best lattice force found (a lattice point,
the same whichever start led there).
"""

from __future__ import annotations

import numpy as np

from .newton import initial_creep
from .optimal_stencil import _centred, _first_round, _interpolated, _parabola, _Scorer, _start

__all__ = ["LATTICE", "lattice_search"]

#: Spacing [-] of the lattice of ``ln F_N0`` the climb certifies a stencil on (2 % of the
#: force).
LATTICE = 0.02
#: Largest jump [lattice steps] of a stencil toward its parabola's vertex in one round.
JUMP = 16
#: Rounds (one batched solve each) of the climb before a point is searched on from its best
#: lattice force.
ROUNDS = 24
#: Largest batch [points] whose first round solves the five lattice forces around each start
#: (the stencil and the next force on either side, one of which the cubic uses) instead of
#: the stencil's three: one batched solve instead of two or three where a call's fixed
#: cost outweighs its forces' (`Variator.solve`: 3 calls -> 1).
PREFETCH = 8
_OFFSETS = np.array([-1.0, 0.0, 1.0])
_WINDOW = np.arange(-2.0, 3.0)  # the window's lattice steps from its centre


def lattice_search(score: _Scorer, index, bounds, start, x_start=None):
    """Climb of the points ``index`` on the lattice of forces (module docstring).

    Parameters
    ----------
    score : _Scorer
        Efficiencies of points at forces (one batched solve a call).
    index : ndarray of int
        The points of ``score.problem`` (positive torque).
    bounds : tuple of ndarray
        ``(lo, hi)``: the ``ln F_N0`` [-] range of each point (``min_force`` and the
        pressure bound).
    start : ndarray
        A first ``ln F_N0`` [-] per point (finite).
    x_start : ndarray, optional
        Creeps ``(k, n_c)`` [-] at the forces ``exp(start)`` (NaN rows: none).

    Returns
    -------
    u : ndarray
        Per point: the cubic's maximum [-] where certified, else the best lattice
        ``ln F_N0`` seen (NaN where no lattice force was admissible or the lattice has no
        stencil within the bounds).
    certified : ndarray of bool
    creep : ndarray
        Creeps ``(k, n_c)`` [-] at ``exp(u)`` (interpolated from the last stencil).
    """
    lo, hi = bounds
    k_lo, k_hi = np.ceil(lo / LATTICE) + 1, np.floor(hi / LATTICE) - 1
    k = np.clip(np.rint(start / LATTICE), k_lo, np.maximum(k_hi, k_lo))
    win = _Window(score, index, k, (k_lo - 1, k_hi + 1))
    win.first(x_start, start, prefetch=index.size <= PREFETCH)
    done = np.zeros(index.size, dtype=bool)
    climbs = np.zeros(index.size)  # stencils in a row with no admissible force
    runs = np.zeros(index.size)  # steps in a row the same way (signed)
    floor = k_lo.copy()  # the lowest centre whose stencil may lie above the creep bound
    ceiling = k_hi.copy()  # and the highest, below a stencil whose lower end was its best
    live = np.flatnonzero(k_lo <= k_hi)
    for _ in range(ROUNDS):
        u, e = win.stencil(live)
        step, top = _move(u, e, climbs[live])
        # a step the same way as the last doubles (at most JUMP): far above the optimum the
        # efficiency is convex in ln F_N0 and gives no vertex to jump to
        runs[live] = np.where(
            np.abs(step) == 1, np.where(step * runs[live] > 0, runs[live], 0) + step, 0
        )
        step = np.where(
            np.abs(step) == 1, step * np.minimum(2.0 ** (np.abs(runs[live]) - 1), JUMP), step
        )
        done[live[top]] = True
        none = ~np.isfinite(e).any(axis=1)
        climbs[live] = np.where(none, climbs[live] + 1, 0.0)
        # a stencil with no admissible force lies below the creep bound: no stencil
        # reaching down to it again (a jump back from above overshooting the bound)
        floor[live] = np.where(none, np.maximum(floor[live], win.k[live] + 3), floor[live])
        # a neighbour better than the centre: a local maximum on its side (never jump back
        # past it: two concave parabolas whose vertices overshoot each other's centres sent
        # a hub cycle's points back and forth for every round, session 33)
        up, down = (step > 0) & (e[:, 2] > e[:, 1]), (step < 0) & (e[:, 0] > e[:, 1])
        floor[live] = np.where(up, np.maximum(floor[live], win.k[live] + 1), floor[live])
        ceiling[live] = np.where(down, np.minimum(ceiling[live], win.k[live] - 1), ceiling[live])
        upper = np.clip(ceiling[live], k_lo[live], k_hi[live])  # (never below k_lo)
        new = np.clip(win.k[live] + step, np.minimum(floor[live], upper), upper)
        go = ~top & (new != win.k[live])
        live = live[go]
        if not live.size:
            break
        win.move(live, new[go])
    u, e = win.stencil(slice(None))
    xs = win.x[:, 1:4]
    vertex = _parabola(u, e)[0]
    ok = np.flatnonzero(done)
    vertex[ok], x_ok = win.cubic(ok, vertex[ok])
    best = np.take_along_axis(u, np.argmax(e, axis=1)[:, None], axis=1)[:, 0]
    best = np.where(np.isfinite(e).any(axis=1), best, np.nan)
    out = np.where(done, vertex, best)
    creep = _interpolated(xs, u, e, out[:, None])
    creep[ok] = np.where(np.isnan(x_ok), creep[ok], x_ok)
    return out, done, creep


def _move(u, e, climbs):
    """``(step [lattice steps], top)`` of each stencil ``(u, e)``: ``top`` where its centre
    is the best of its three forces, all admissible; else a step toward the better end, a
    jump toward the concave parabola's vertex, or up by ``3 * 2**climbs`` where no force
    is admissible (below the creep bound); 0 where the centre is best but a neighbour is
    not admissible (module docstring)."""
    finite = np.isfinite(e)
    top = finite.all(axis=1) & (e[:, 1] > e[:, 0]) & (e[:, 1] >= e[:, 2])
    vertex, concave = _parabola(u, e)
    steps = (vertex - u[:, 1]) / LATTICE
    best = np.argmax(e, axis=1)
    toward = np.where(best == 2, 1.0, np.where(best == 0, -1.0, 0.0))
    far = concave & (np.abs(steps) > 1.5) & (np.sign(steps) == toward)
    step = np.where(far, np.clip(np.rint(np.where(far, steps, 0.0)), -JUMP, JUMP), toward)
    step = np.where(finite.any(axis=1), step, 3.0 * 2.0**climbs)
    return step, top


#: Inverse Vandermonde matrices of the cubics through the lattice offsets ``(-1, 0, 1, 2)``
#: and ``(-2, -1, 0, 1)`` [steps]: their coefficients ``(c0, c1, c2, c3)`` from the values.
_UP = np.linalg.inv(np.vander([-1.0, 0.0, 1.0, 2.0], 4, increasing=True))
_DOWN = np.linalg.inv(np.vander([-2.0, -1.0, 0.0, 1.0], 4, increasing=True))


class _Window:
    """The lattice forces ``k - 2 .. k + 2`` around each point's centre ``k``: their
    efficiencies ``e`` (NaN: not solved yet; ``-inf``: no admissible equilibrium) and
    creeps ``x``; the stencil is the middle three, the cubic's fourth force one of the
    ends. A force is solved once, when first needed, and kept while the window covers it;
    its value does not depend on when (from creeps near its solution, to `SCORE_TOL`)."""

    def __init__(self, score: _Scorer, index, k, ends):
        self.score, self.index, self.k, self.ends = score, index, k.copy(), ends
        self.e = np.full((index.size, 5), np.nan)
        self.x = np.full((index.size, 5, score.problem.layout.is_idler.size), np.nan)

    def u(self, rows):
        """Lattice ``ln F_N0`` [-] of the windows ``rows``, from the integers."""
        return (self.k[rows, None] + _WINDOW) * LATTICE

    def stencil(self, rows):
        """``(u, e)`` of the stencils ``rows``."""
        return self.u(rows)[:, 1:4], self.e[rows, 1:4]

    def first(self, x_start, start, prefetch):
        """Solve the first stencils (the whole windows where ``prefetch``) from the creeps
        ``x_start`` at ``start`` (`_centred`), or as `_first_round` does."""
        rows = np.arange(self.k.size)
        u = self.u(rows)
        x0 = _centred(self.score, self.index, x_start, start, u[:, 1:4])
        if not prefetch:
            e, x = _first_round(self.score, self.index, u[:, 1:4], x0)
            self.e[:, 1:4], self.x[:, 1:4] = e.reshape(-1, 3), x.reshape(rows.size, 3, -1)
            return
        x0 = None if x0 is None else _start(x0, u - u[:, 2:3])
        e, x = self.score(np.repeat(self.index, 5), u.reshape(-1), x0)
        self.e[:], self.x[:] = e.reshape(-1, 5), x.reshape(rows.size, 5, -1)
        self.e[(u < self.ends[0][:, None] * LATTICE) | (u > self.ends[1][:, None] * LATTICE)] = (
            np.nan
        )

    def move(self, rows, new):
        """Centre the windows ``rows`` on ``new``: the forces they still cover are kept,
        the new stencil's others solved together."""
        shift = (new - self.k[rows]).astype(int)
        old = np.arange(5)[None, :] + shift[:, None]
        kept = (old >= 0) & (old <= 4)
        at = np.clip(old, 0, 4)
        u_old, e_old, x_old = self.u(rows)[:, 1:4], self.e[rows, 1:4], self.x[rows, 1:4]
        self.e[rows] = np.where(kept, np.take_along_axis(self.e[rows], at, axis=1), np.nan)
        self.x[rows] = np.take_along_axis(self.x[rows], at[:, :, None], axis=1)
        self.k[rows] = new
        need = np.zeros((rows.size, 5), dtype=bool)
        need[:, 1:4] = np.isnan(self.e[rows, 1:4])
        self._solve(rows, need, (u_old, e_old, x_old), shift)

    def cubic(self, rows, vertex):
        """The maxima [-] of the cubics through the certified stencils ``rows`` and the
        lattice force two steps from the centre on the side of the parabola's vertex
        ``vertex``; the vertex where that force lies outside the bounds or is not
        admissible, or the cubic has no maximum within the stencil. Against a smooth
        optimum the parabola's vertex on the 2 % lattice missed Table I's by up to 1.8e-6
        in efficiency (ratio 1.8, 40 N m), the cubic's by 3e-7."""
        u = self.u(rows)
        up = vertex > u[:, 2]
        slot = np.where(up, 4, 0)
        k4 = self.k[rows] + slot - 2
        inside = (k4 >= self.ends[0][rows]) & (k4 <= self.ends[1][rows])
        need = np.zeros((rows.size, 5), dtype=bool)
        need[np.arange(rows.size), slot] = inside & np.isnan(self.e[rows, slot])
        stencil = (u[:, 1:4], self.e[rows, 1:4], self.x[rows, 1:4])
        self._solve(rows, need, stencil, np.zeros(rows.size, dtype=int))
        e = np.where(inside[:, None] | (np.arange(5) != slot[:, None]), self.e[rows], np.nan)
        four = np.where(up[:, None], np.arange(1, 5), np.arange(4))  # the cubic's slots
        values = np.take_along_axis(e, four, axis=1)
        inverse = np.where(up[:, None, None], _UP, _DOWN)
        c = np.einsum("nij,nj->ni", inverse, values)
        with np.errstate(invalid="ignore", divide="ignore"):
            # the root of c1 + 2 c2 t + 3 c3 t^2 = 0 with a negative second derivative,
            # (-c2 - sqrt(D)) / (3 c3), written without cancellation (any c3, also 0)
            t = c[:, 1] / (np.sqrt(c[:, 2] ** 2 - 3.0 * c[:, 3] * c[:, 1]) - c[:, 2])
            curv = 2.0 * c[:, 2] + 6.0 * c[:, 3] * t
        good = np.isfinite(values).all(axis=1) & np.isfinite(t) & (np.abs(t) <= 1.0)
        good &= curv < 0
        t = np.where(good, t, np.nan)
        return np.where(good, u[:, 2] + t * LATTICE, vertex), self._creep(
            rows, u, four, inverse, t
        )

    def _creep(self, rows, u, four, inverse, t):
        """Creeps ``(rows, n_c)`` at the cubics' maxima ``u_k + t LATTICE`` (``u``: the
        windows' forces; NaN rows where ``t`` is): the cubic through the four forces'
        ``F_N0`` times their creeps (nearly constant, as in `_start`): its error ~ h^4, the
        stencil's parabola's ~ h^3 (the final solve there 3.09 -> 2.81 Newton evaluations
        per point on Table I's 30 x 30 sweeps; the analytic Jacobian's 1 % error sets most
        of the rest, session 33)."""
        at4 = np.take_along_axis(u, four, axis=1)
        x = np.take_along_axis(self.x[rows], four[:, :, None], axis=1) * np.exp(at4)[:, :, None]
        c = np.einsum("nij,njc->nic", inverse, x)
        powers = t[:, None] ** np.arange(4.0)
        at = u[:, 2] + t * LATTICE  # t: lattice steps from the centre
        return np.einsum("ni,nic->nc", powers, c) * np.exp(-at)[:, None]

    def _solve(self, rows, need, stencil, shift) -> None:
        """Solve the forces ``need`` ``(rows, 5)`` of the windows ``rows`` together, from
        creeps interpolated on the old ``stencil`` ``(u, e, x)`` (its parabola through
        ``F_N0`` times the creeps) or, after a jump (``|shift| > 1``) or beside an
        inadmissible force, its best force's creeps scaled as ``1/F_N0`` (`_start`), or
        the cold start where it has no admissible force."""
        r, c = np.nonzero(need)
        if not r.size:
            return
        u_old, e_old, x_old = stencil
        u = self.u(rows)
        x0 = _interpolated(x_old, u_old, e_old, u).reshape(rows.size, 5, -1)
        far = (np.abs(shift) > 1) | ~np.isfinite(e_old).all(axis=1)
        if far.any():
            best = np.argmax(e_old[far], axis=1)
            at = np.arange(best.size)
            du = u[far] - u_old[far][at, best][:, None]
            scaled = _start(x_old[far][at, best], du).reshape(-1, 5, x0.shape[-1])
            cold = initial_creep(self.score.problem)[self.index[rows[far]]][:, None, :]
            none = ~np.isfinite(e_old[far]).any(axis=1)
            x0[far] = np.where(none[:, None, None], cold, scaled)
        got, creep = self.score(self.index[rows[r]], u[r, c], x0[r, c])
        e, x = self.e[rows], self.x[rows]
        e[r, c], x[r, c] = got, creep
        self.e[rows], self.x[rows] = e, x
