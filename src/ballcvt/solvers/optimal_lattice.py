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
_OFFSETS = np.array([-1.0, 0.0, 1.0])


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
        Per point: the vertex [-] where certified, else the best lattice ``ln F_N0`` seen
        (NaN where no lattice force was admissible or the lattice has no stencil within
        the bounds).
    certified : ndarray of bool
    creep : ndarray
        Creeps ``(k, n_c)`` [-] at ``exp(u)`` (interpolated from the last stencil).
    """
    lo, hi = bounds
    spacing = LATTICE
    k_lo, k_hi = np.ceil(lo / spacing) + 1, np.floor(hi / spacing) - 1
    k = np.clip(np.rint(start / spacing), k_lo, np.maximum(k_hi, k_lo))
    u = (k[:, None] + _OFFSETS) * spacing
    e, xs = _first_round(score, index, u, _centred(score, index, x_start, start, u))
    e, xs = e.reshape(-1, 3), xs.reshape(index.size, 3, -1)
    done = np.zeros(index.size, dtype=bool)
    climbs = np.zeros(index.size)  # stencils in a row with no admissible force
    floor = k_lo.copy()  # the lowest centre whose stencil may lie above the creep bound
    live = np.flatnonzero(k_lo <= k_hi)
    for _ in range(ROUNDS):
        step, top = _move(u[live], e[live], climbs[live], spacing)
        done[live[top]] = True
        finite = np.isfinite(e[live])
        climbs[live] = np.where(finite.any(axis=1), 0.0, climbs[live] + 1)
        # a stencil with no admissible force lies below the creep bound: no stencil
        # reaching down to it again (a jump back from above overshooting the bound)
        none = ~finite.any(axis=1)
        floor[live] = np.where(none, np.maximum(floor[live], k[live] + 3), floor[live])
        new = np.clip(k[live] + step, np.minimum(floor[live], k_hi[live]), k_hi[live])
        go = ~top & (new != k[live])
        live, new = live[go], new[go]
        if not live.size:
            break
        _shift(score, index, (u, e, xs), live, (k[live], new), spacing)
        k[live] = new
    vertex = _parabola(u, e)[0]
    ok = np.flatnonzero(done)
    ends = (k_lo[ok] - 1, k_hi[ok] + 1)  # the lattice steps within the bounds
    vertex[ok] = _cubic(score, index[ok], (u[ok], e[ok], xs[ok]), k[ok], ends)
    best = np.take_along_axis(u, np.argmax(e, axis=1)[:, None], axis=1)[:, 0]
    best = np.where(np.isfinite(e).any(axis=1), best, np.nan)
    out = np.where(done, vertex, best)
    return out, done, _interpolated(xs, u, e, out[:, None])


def _move(u, e, climbs, spacing):
    """``(step [lattice steps], top)`` of each stencil ``(u, e)``: ``top`` where its centre
    is the best of its three forces, all admissible; else a step toward the better end, a
    jump toward the concave parabola's vertex, or up by ``3 * 2**climbs`` where no force
    is admissible (below the creep bound); 0 where the centre is best but a neighbour is
    not admissible (module docstring)."""
    finite = np.isfinite(e)
    top = finite.all(axis=1) & (e[:, 1] > e[:, 0]) & (e[:, 1] >= e[:, 2])
    vertex, concave = _parabola(u, e)
    steps = (vertex - u[:, 1]) / spacing
    best = np.argmax(e, axis=1)
    toward = np.where(best == 2, 1.0, np.where(best == 0, -1.0, 0.0))
    far = concave & (np.abs(steps) > 1.5) & (np.sign(steps) == toward)
    step = np.where(far, np.clip(np.rint(np.where(far, steps, 0.0)), -JUMP, JUMP), toward)
    step = np.where(finite.any(axis=1), step, 3.0 * 2.0**climbs)
    return step, top


def _shift(score: _Scorer, index, stencils, live, centres, spacing) -> None:
    """Move the stencils ``live`` from their centres ``k`` to ``new`` in place
    (``centres`` = ``(k, new)`` in lattice steps; ``stencils`` =
    ``(u, e, xs)``): the forces the old stencil shares keep their efficiencies and creeps,
    the new ones are solved together (from creeps interpolated on the old stencil, or, after
    a jump or beside an inadmissible force, scaled from its best force's as ``1/F_N0``,
    `_start`)."""
    u, e, xs = stencils
    k, new = centres
    shift = new - k
    slots = np.arange(3)[None, :] + shift[:, None].astype(int)  # old slot of each new one
    kept = (slots >= 0) & (slots <= 2)
    old = np.clip(slots, 0, 2)
    u_new = (new[:, None] + _OFFSETS) * spacing  # from the integers: the same bits each time
    x0 = _interpolated(xs[live], u[live], e[live], u_new).reshape(live.size, 3, -1)
    # after a jump, or from a stencil with an inadmissible force (its creeps those of a
    # solve that failed): the best old force's creeps scaled to the new forces, or the
    # cold start where no old force was admissible
    far = (np.abs(shift) > 1) | ~np.isfinite(e[live]).all(axis=1)
    if far.any():
        rows = live[far]
        best = np.argmax(e[rows], axis=1)
        du = u_new[far] - u[rows, best][:, None]
        scaled = _start(xs[rows, best], du).reshape(-1, 3, x0.shape[-1])
        cold = initial_creep(score.problem)[index[rows]][:, None, :]
        none = ~np.isfinite(e[rows]).any(axis=1)
        x0[far] = np.where(none[:, None, None], cold, scaled)
    e_new = np.take_along_axis(e[live], old, axis=1)
    x_new = np.take_along_axis(xs[live], old[:, :, None], axis=1)
    rows, cols = np.nonzero(~kept)
    got, creep = score(index[live[rows]], u_new[rows, cols], x0[rows, cols])
    e_new[rows, cols], x_new[rows, cols] = got, creep
    u[live], e[live], xs[live] = u_new, e_new, x_new


#: Inverse Vandermonde matrices of the cubics through the lattice offsets ``(-1, 0, 1, 2)``
#: and ``(-2, -1, 0, 1)`` [steps]: their coefficients ``(c0, c1, c2, c3)`` from the values.
_UP = np.linalg.inv(np.vander([-1.0, 0.0, 1.0, 2.0], 4, increasing=True))
_DOWN = np.linalg.inv(np.vander([-2.0, -1.0, 0.0, 1.0], 4, increasing=True))


def _cubic(score: _Scorer, index, stencils, k, ends):
    """The maxima [-] (``ln F_N0``) of the cubics through the certified stencils
    ``(u, e, xs)`` (centres ``k``) and the lattice force two steps from the centre on the
    parabola's vertex's side, all those forces solved together; the parabola's vertex
    where that force lies outside the bounds (``ends``: the first and last lattice steps
    within them) or is not admissible, or the cubic has no maximum within the stencil. Against a
    smooth optimum the parabola's vertex on the 2 % lattice missed Table I's by up to
    1.8e-6 in efficiency (ratio 1.8, 40 N m), the cubic's by 3e-7."""
    u, e, xs = stencils
    vertex = _parabola(u, e)[0]
    up = vertex > u[:, 1]
    k4 = k + np.where(up, 2.0, -2.0)
    ok = (k4 >= ends[0]) & (k4 <= ends[1])
    u4 = k4 * LATTICE
    x0 = _interpolated(xs, u, e, u4[:, None])  # the stencil's parabola, two steps out
    e4 = np.full(k.size, -np.inf)
    if ok.any():
        e4[ok] = score(index[ok], u4[ok], x0[ok])[0]
    values = np.where(up[:, None], np.column_stack([e, e4]), np.column_stack([e4, e]))
    c = np.einsum("nij,nj->ni", np.where(up[:, None, None], _UP, _DOWN), values)
    with np.errstate(invalid="ignore", divide="ignore"):
        # the root of c1 + 2 c2 t + 3 c3 t^2 = 0 with a negative second derivative,
        # (-c2 - sqrt(D)) / (3 c3), written without cancellation (any c3, also 0)
        t = c[:, 1] / (np.sqrt(c[:, 2] ** 2 - 3.0 * c[:, 3] * c[:, 1]) - c[:, 2])
        curv = 2.0 * c[:, 2] + 6.0 * c[:, 3] * t
    good = np.isfinite(e4) & np.isfinite(t) & (np.abs(t) <= 1.0) & (curv < 0)
    return np.where(good, u[:, 1] + t * LATTICE, vertex)
