"""The fold of the branch from zero torque, located in a disc contact's held creep.

Where the traction can fall with the creep (the thermal law, docs/model.md §14), the
output torque along the branch of equilibria from zero torque, parametrised by the held
creep ``c`` of a disc contact (`ballcvt.solvers.newton.solve_pinned`, regular through the
fold), rises to a largest value and falls past it: the fold. `climb_to_fold` finds that
largest torque as a one-dimensional maximisation of ``T(c)``, each evaluation one pinned
solve started from the nearest point already solved:

* the held creep is stepped up from an equilibrium on the branch, the step doubled while
  the torque rises, until a step gives a lower torque (or fails, or takes a creep past the
  limit): the fold then lies between the last two rising points and that step;
* the bracket is then narrowed by successive parabolic interpolation of ``T(c)``, with a
  golden-section step wherever the parabola's vertex falls outside the bracket or next to
  its best point, and a bisection towards a failed end, until the vertex moves less than
  `FOLD_CREEP_RTOL` of the creep limit or the bracket is narrower than that (Brent 1973,
  *Algorithms for minimization without derivatives*, ch. 5).

Near a smooth maximum ``T(c)`` is a parabola to third order, so the vertex converges in a
few steps where the march of halving steps it replaces took some fifteen per contact.
The largest torque met is the fold; the climb also returns the highest point met below a
given share of it, on the rising side, from which the limit just below the fold is
reached (`ballcvt.solvers.peak`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .held_creep import FOLD_CREEP_RTOL, MAX_FOLD_STEPS, TURN_STEP, Pinned, held_of, pinned_step

__all__ = ["climb_to_fold", "Climb", "FIRST_CREEP_STEP", "GOLDEN"]

#: First step of the held creep, as a share of the creep limit [-].
FIRST_CREEP_STEP = 0.02
#: Share of the larger side of the bracket taken by a golden-section step [-].
GOLDEN = 0.381966
#: Width of a bracket, in `FOLD_CREEP_RTOL` creep limits, above which a parabolic step
#: that lands on the best point gives way to a golden-section one (`_Bracket.refine`) [-].
WIDE = 100.0


@dataclass
class Climb:
    """The result of `climb_to_fold` for a 1-D batch ``(n,)``.

    Attributes
    ----------
    torque : ndarray
        The largest torque met on each branch [N m].
    creep : ndarray
        The creeps there ``(n, n_c)`` [-].
    at_pin : ndarray of bool
        Whether that torque is at the held creep's bound (the creep limit), not at a fold.
    clean : ndarray of bool
        Whether the bracket's far end is a converged point with a lower torque and every
        creep within the bound (a fold), not a step that failed or took another creep
        past the bound (the other disc contact's climb may then go further).
    below : tuple of ndarray
        ``(creep of the contact (n,), torque (n,), creeps (n, n_c))`` of the highest point
        met on the rising side with a torque below ``share`` times the largest.
    """

    torque: np.ndarray
    creep: np.ndarray
    at_pin: np.ndarray
    clean: np.ndarray
    below: tuple

    @classmethod
    def empty(cls, n: int, nc: int) -> Climb:
        """``n`` points with nothing met yet (NaN torques)."""
        nan = np.full(n, np.nan)
        creeps = np.full((n, nc), np.nan)
        false = np.zeros(n, dtype=bool)
        return cls(nan, creeps, false, false.copy(), (nan.copy(), nan.copy(), creeps.copy()))

    def take(self, index) -> Climb:
        """The points ``index`` (integer or boolean array)."""
        return Climb(self.torque[index], self.creep[index], self.at_pin[index],
                     self.clean[index], tuple(v[index] for v in self.below))  # fmt: skip

    def put(self, index, other: Climb) -> None:
        """Set the points ``index`` to ``other``'s, in place."""
        self.torque[index], self.creep[index] = other.torque, other.creep
        self.at_pin[index], self.clean[index] = other.at_pin, other.clean
        for mine, theirs in zip(self.below, other.below, strict=True):
            mine[index] = theirs


def climb_to_fold(flat, pinned: Pinned, k, pin: float, tol: float, start, share: float):
    """The largest torque on each point's branch beyond the equilibria ``start``, found in
    the held creep of disc contact ``k`` (module docstring).

    Parameters
    ----------
    flat : EquilibriumProblem
        Operating points, 1-D batch ``(n,)``.
    pinned : callable
        `ballcvt.solvers.held_creep.Pinned`.
    k : int or ndarray of int
        The contact whose creep is held: one, or one per point ``(n,)`` (one batch of
        pinned solves a step, whichever contact each point holds).
    pin : float
        Creep bound [-] (the creep limit, a hair below).
    tol : float
        Solver tolerance [-].
    start : tuple of ndarray
        Equilibria on the branch: torques ``(n,)`` [N m] and creeps ``(n, n_c)`` [-];
        optionally a third entry, the walk's next two points ``((torque, creeps),
        (torque, creeps))`` (`ballcvt.solvers.branch_path.Walk`: its last rising point and
        the step past it), which seed the bracket where the held creep grows through them.
    share : float
        `Climb.below` is the highest point under ``share`` times the largest torque [-].

    Returns
    -------
    Climb
    """
    t0, x0 = start[0], start[1]
    k = np.broadcast_to(np.asarray(k, dtype=np.intp), (flat.size,))
    held = held_of(x0, k)
    br = _Bracket.start(t0, held, x0, FIRST_CREEP_STEP * pin)
    history = [(held.copy(), t0.copy(), x0.copy(), np.ones(flat.size, dtype=bool))]
    if len(start) > 2:
        history += br.seed(k, start[2])
    least = FOLD_CREEP_RTOL * pin
    done, probed = np.zeros(flat.size, dtype=bool), np.zeros(flat.size, dtype=bool)
    for _ in range(MAX_FOLD_STEPS):
        bracketed = np.isfinite(br.c_c)
        # the best point at the bound: a seeded bracket's far end may lie beyond it
        seeded_past = bracketed & (np.abs(br.c_c) > pin)
        bound = (~bracketed | seeded_past) & (np.abs(br.b_c) >= pin * (1.0 - 1e-12))
        check = np.flatnonzero(bound & ~probed & ~done)
        if check.size:  # the torque must still rise there (`_falls_at_pin`)
            probed[check] = True
            bound[check[_falls_at_pin(br, check, (flat, pinned, k, tol, pin), history)]] = False
            bracketed = np.isfinite(br.c_c)
        br.at_pin |= bound
        trial = np.where(bracketed, br.refine(least), br.b_c + br.step)
        trial = np.clip(trial, -pin, pin)
        narrow = (np.abs(trial - br.b_c) < least) | (np.abs(br.c_c - br.a_c) < least)
        done |= br.at_pin | (bracketed & narrow)
        active = np.flatnonzero(~done)
        if active.size == 0:
            break
        u = trial[active]
        got, xs = _held(br, active, u, (flat, pinned, k, tol, pin), history)
        br.update(active, u, got, xs, bracketed[active])
    clean = np.isfinite(br.c_t) & ~br.at_pin
    below = _below(history, br.b_t * share, br.b_c, br.direction)
    return Climb(br.b_t, br.b_x, br.at_pin, clean, below)


def _falls_at_pin(br, idx, climb, history) -> np.ndarray:
    """Whether the torque falls at the creep bound where the best point of the points
    ``idx`` stands there: a point held `TURN_STEP` of the bound lower carries more. The
    largest torque then lies inside, and the bracket becomes (the point before, that
    point, the bound); else the bound is the limit. A step onto the bound can pass the
    fold and still carry more than the point before it (harden task 3504:220 of a
    thermal-only campaign: 36.201 N m at the bound, 36.248 at the fold 6 % lower in the
    creep, where `solve` carried 36.24 N m past the limit). ``climb``: ``(flat, pinned, k,
    tol, pin)`` of `climb_to_fold`; updates ``br`` and ``history``, returns the mask over
    ``idx``."""
    u = br.b_c[idx] - br.direction[idx] * TURN_STEP * climb[-1]
    got, xs = _held(br, idx, u, climb, history)
    falls = got > br.b_t[idx]
    i = idx[falls]
    br.c_c[i], br.c_t[i] = br.b_c[i], br.b_t[i]
    br.b_c[i], br.b_t[i], br.b_x[i] = u[falls], got[falls], xs[falls]
    return falls


def _held(br, idx, u, climb, history):
    """The torques (-inf where the solve failed or another creep passed the bound) and
    creeps of the points ``idx`` at the held creeps ``u``, each from its best point;
    ``climb``: ``(flat, pinned, k, tol, pin)`` of `climb_to_fold`. Appends the step to
    ``history``."""
    flat, pinned, k, tol, pin = climb
    got, xs = pinned_step(pinned, flat.take(idx), k[idx], br.b_x[idx], u, tol)
    valid = np.isfinite(got) & (np.max(np.abs(xs), axis=-1) <= pin * (1.0 + 1e-9))
    got = np.where(valid, got, -np.inf)
    history.append(_record(flat.size, idx, (u, got, xs, valid), history[0][2]))
    return got, xs


@dataclass
class _Bracket:
    """The climb's points per contact: ``a`` before the best, ``b`` the best (creeps
    ``b_x``), ``c`` past it (NaN until a step falls; torque -inf where it failed), and the
    step of the held creep while no step has fallen."""

    a_c: np.ndarray
    a_t: np.ndarray
    b_c: np.ndarray
    b_t: np.ndarray
    b_x: np.ndarray
    c_c: np.ndarray
    c_t: np.ndarray
    step: np.ndarray
    direction: np.ndarray
    at_pin: np.ndarray
    #: The moves of the last two refinements (`refine`), the last first.
    moves: tuple = (np.inf, np.inf)

    @classmethod
    def start(cls, t0, c0, x0, step) -> _Bracket:
        n = t0.size
        direction = np.where(c0 < 0, -1.0, 1.0)
        nan = np.full(n, np.nan)
        return cls(c0.copy(), t0.copy(), c0.copy(), t0.copy(), x0.copy(), nan, nan.copy(),
                   direction * step, direction, np.zeros(n, dtype=bool))  # fmt: skip

    def seed(self, k, points) -> list:
        """The walk's last rising point ``points[0]`` as the best and its next step
        ``points[1]`` past it (torque -inf: beyond the creep bound), where the held creep
        of contact ``k`` grows from the start through both (the step then the distance
        from the start); returns the history entries of the points taken."""
        (t_b, x_b), (t_c, x_c) = points
        c_b, c_c = held_of(x_b, k), held_of(x_c, k)
        rise = np.isfinite(t_b) & (t_b > self.b_t) & ((c_b - self.b_c) * self.direction > 0)
        past = rise & ~(t_c >= t_b) & ((c_c - c_b) * self.direction > 0)  # NaN t_c: none
        self.a_c[rise], self.a_t[rise] = self.b_c[rise], self.b_t[rise]
        self.step[rise] = c_b[rise] - self.b_c[rise]
        self.b_c[rise], self.b_t[rise], self.b_x[rise] = c_b[rise], t_b[rise], x_b[rise]
        self.c_c[past], self.c_t[past] = c_c[past], t_c[past]
        valid = past & np.isfinite(t_c)
        return [(np.where(rise, c_b, np.nan), np.where(rise, t_b, -np.inf), x_b, rise),
                (np.where(valid, c_c, np.nan), np.where(valid, t_c, -np.inf), x_c, valid)]  # fmt: skip

    def refine(self, least) -> np.ndarray:
        """`_refine`, with Brent's safeguards (1973, ch. 5): where a parabolic step is not
        under half the one before last (a vertex creeping towards the fold from one side,
        the far end of the bracket never replaced), or is under ``least`` while the
        bracket is wider than `WIDE` times that (a parabola through distant points whose
        vertex falls on the best one: the walk's seed past a fold it stepped over), a
        golden-section step instead."""
        trial = _refine(self.ends(), self.torques())
        move = np.abs(trial - self.b_c)
        both = np.isfinite(self.c_t) & np.isfinite(self.a_t)
        wide = np.abs(self.c_c - self.a_c) > WIDE * least
        slow = both & ((move >= 0.5 * self.moves[1]) | ((move < least) & wide))
        trial = np.where(slow, _golden(*self.ends()), trial)
        self.moves = (np.abs(trial - self.b_c), self.moves[0])
        return trial

    def ends(self):
        return self.a_c, self.b_c, self.c_c

    def torques(self):
        return self.a_t, self.b_t, self.c_t

    def update(self, active, u, got, xs, bracketed) -> None:
        """The points ``active`` after a solve at the held creeps ``u`` (torques ``got``,
        -inf where it failed; creeps ``xs``): a higher point becomes the best, the old
        best bounding it on its side; a lower one bounds the bracket on its side."""
        up = got > self.b_t[active]
        beyond = ((u - self.b_c[active]) * self.direction[active] > 0.0) | ~bracketed
        i, left = active[up], beyond[up]  # the old best lies before the new one
        self.a_c[i[left]], self.a_t[i[left]] = self.b_c[i[left]], self.b_t[i[left]]
        self.c_c[i[~left]], self.c_t[i[~left]] = self.b_c[i[~left]], self.b_t[i[~left]]
        self.b_c[i], self.b_t[i], self.b_x[i] = u[up], got[up], xs[up]
        self.step[i[~bracketed[up]]] *= 2.0
        i, right, uu, gg = active[~up], beyond[~up], u[~up], got[~up]
        self.c_c[i[right]], self.c_t[i[right]] = uu[right], gg[right]
        self.a_c[i[~right]], self.a_t[i[~right]] = uu[~right], gg[~right]


def _record(n, active, step, x0):
    """One entry of the climb's history: the held creeps, torques, creeps and whether
    each converged within the bound, over all ``n`` points (NaN / -inf / False where not
    ``active``)."""
    u, got, xs, valid = step
    full_u, full_t, full_x = np.full(n, np.nan), np.full(n, -np.inf), np.full_like(x0, np.nan)
    record = np.zeros(n, dtype=bool)
    full_u[active], full_t[active], full_x[active], record[active] = u, got, xs, valid
    return full_u, full_t, full_x, record


def _refine(c, t) -> np.ndarray:
    """The next held creep inside the brackets ``c = (a, b, c)`` with torques ``t`` (``b``
    the best): the vertex of the parabola through the three points where it lies inside
    the bracket and not next to ``b``, else a golden-section step into the larger side;
    towards an end that failed (torque -inf), halfway to it."""
    (a, b, cc), (ta, tb, tc) = c, t
    with np.errstate(divide="ignore", invalid="ignore"):
        p = (b - a) ** 2 * (tb - tc) - (b - cc) ** 2 * (tb - ta)
        q = (b - a) * (tb - tc) - (b - cc) * (tb - ta)
        vertex = b - 0.5 * p / q
    lo, hi = np.minimum(a, cc), np.maximum(a, cc)
    usable = np.isfinite(vertex) & (vertex > lo) & (vertex < hi) & (a != b)
    out = np.where(usable, vertex, _golden(a, b, cc))
    failed = ~np.isfinite(tc)
    return np.where(failed, 0.5 * (b + cc), np.where(np.isfinite(ta), out, 0.5 * (a + b)))


def _golden(a, b, c) -> np.ndarray:
    """A golden-section step from the best point ``b`` into the larger side of the
    bracket ``(a, c)``."""
    return np.where(np.abs(c - b) >= np.abs(b - a), b + GOLDEN * (c - b), b + GOLDEN * (a - b))


def _below(history, limit, best_c, direction):
    """The highest recorded point with a torque below ``limit`` and a held creep before
    ``best_c`` (`Climb.below`); NaN where none was met."""
    cs, ts, xs, ok = (np.stack(v) for v in zip(*history, strict=True))
    fits = ok & (ts < limit) & ((cs - best_c) * direction <= 0.0)
    score = np.where(fits, ts, -np.inf)
    pick = np.argmax(score, axis=0)
    cols = np.arange(cs.shape[1])
    found = np.isfinite(score[pick, cols])
    nan = np.nan
    return (
        np.where(found, cs[pick, cols], nan),
        np.where(found, ts[pick, cols], nan),
        np.where(found[:, None], xs[pick, cols], nan),
    )
