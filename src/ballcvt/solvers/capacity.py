"""The traction capacity as intervals of output torque (docs/model.md §8, §11).

Under a constant clamping force the creeps grow with the torque, so the admissible torques
run from zero to the limiting torque. Under a law whose force follows the torque (a
loading cam) they need not: with a small preload the force at low torque may not carry
the drive's own drag while the force the cam adds at higher torque does, so the
admissible torques form a range that does not start at zero, or several ranges. Such
points are scanned (`interval_search`): every point is tried at about ``SCAN_POINTS``
torques from zero to an upper bound on its capacity, and every change between admissible
and inadmissible neighbours is bisected to ``rtol``. The result is a `Capacity` per point.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..errors import NoEquilibriumError
from ..model.traction.base import has_multiple_equilibria
from .clamped import at_ceiling, pressure_bound_force, solve_clamped
from .peak import FOLD_MARGIN
from .point import SolverOptions, solve_point

__all__ = ["Capacity", "interval_search", "no_equilibrium_error", "SCAN_POINTS"]

#: Torque steps of the scan of `interval_search` from zero to the capacity bound.
SCAN_POINTS = 48
#: Most bisection steps on one change between admissible and inadmissible torques.
MAX_STEPS = 60
#: Under a law with more than one equilibrium, the width of the first bracket [-] (relative to
#: the end) next to a bisection end the continuation from zero torque does not confirm
#: (`_confirmed_bisection`): the answer lies within some 1e-4 of it.
NEAR_BRACKET = 1e-3
#: Smallest nonzero scan torque, as a share of the bound [-].
SCAN_POINTS_FLOOR = 1e-4
#: Under a law with more than one equilibrium, the scan torques followed from zero torque:
#: every ``STRIDE``-th of a row; the others start from the one ``STRIDE`` below (`_march`).
STRIDE = 4


@dataclass(frozen=True)
class Capacity:
    """Admissible output torques of one operating point (docs/model.md §8, §11).

    Attributes
    ----------
    intervals : tuple of (float, float)
        Disjoint, increasing closed intervals ``(lo, hi)`` [N m] of output torque whose
        equilibria converge with every ``|C| <= creep_limit`` (and, under a
        torque-following law, every peak pressure within ``design.max_pressure``); empty
        when no torque is admissible.
    constraints : tuple of (str, str)
        Per interval, the constraint that sets its lower and its upper end, e.g.
        ``("zero torque", "creep (output contact)")`` or ``("creep (input contact)",
        "pressure (max_pressure 3 GPa)")`` (`ballcvt.solvers.constraints`); empty when not
        determined.
    """

    intervals: tuple[tuple[float, float], ...]
    constraints: tuple[tuple[str, str], ...] = ()

    @classmethod
    def from_array(cls, bounds) -> Capacity:
        """From a ``(k, 2)`` array of ``(lo, hi)`` rows [N m], NaN rows ignored."""
        rows = np.asarray(bounds, dtype=float).reshape(-1, 2)
        return cls(tuple((float(a), float(b)) for a, b in rows if np.isfinite(a)))

    @property
    def limit(self) -> float:
        """The limiting torque [N m] when the only interval starts at zero, else NaN."""
        if len(self.intervals) == 1 and self.intervals[0][0] == 0.0:
            return self.intervals[0][1]
        return float("nan")

    @property
    def largest(self) -> float:
        """The largest admissible output torque [N m] (NaN when there is none)."""
        return self.intervals[-1][1] if self.intervals else float("nan")

    @property
    def active_constraint(self) -> str | None:
        """The constraint that sets the largest admissible torque (``"no equilibrium"``
        when none is admissible; None when not determined)."""
        if not self.intervals:
            return "no equilibrium"
        return self.constraints[-1][1] if self.constraints else None

    def admits(self, torque: float, rtol: float = 0.0) -> bool:
        """Whether ``torque`` [N m] lies in an interval (each widened by ``rtol`` of its
        upper end)."""
        return any(lo - rtol * hi <= torque <= hi * (1 + rtol) for lo, hi in self.intervals)

    def describe(self) -> str:
        """The intervals as text, e.g. ``"0 to 41.2 N m"`` or ``"3.1 to 8 N m or 12 to
        40 N m"``; ``"none"`` when empty."""
        if not self.intervals:
            return "none"
        return " or ".join(f"{lo:.4g} to {hi:.4g} N m" for lo, hi in self.intervals)


def interval_search(flat: EquilibriumProblem, admissible, top, rtol: float, screen=None):
    """Admissible torque intervals of a 1-D batch by a scan and bisections.

    Parameters
    ----------
    flat : EquilibriumProblem
        Operating points, 1-D batch ``(n,)`` (their ``output_torque`` is ignored).
    admissible : callable
        ``admissible(problem, x0) -> Admissibility`` (`ballcvt.solvers.limit.
        solve_admissible` with the creep limit, options and law bound).
    top : ndarray
        An upper bound on each point's admissible torques [N m], ``(n,)``.
    rtol : float
        Width of the final brackets relative to the ends they bracket [-].
    screen : callable, optional
        ``screen(problem) -> Admissibility`` deciding the scan's clear cases cheaply
        (`ballcvt.solvers.admissible.screen_admissible`): ``admissible`` then solves only
        the others (`_scan`).

    Returns
    -------
    intervals : ndarray
        ``(n, k, 2)`` rows ``(lo, hi)`` [N m], NaN-padded (``k >= 1``).
    creep : ndarray
        ``(n, n_c)`` creeps at the largest admissible torque (NaN where there is none).
    creep_zero : ndarray
        ``(n, n_c)`` creeps at zero torque (NaN where that did not converge).
    scan : (ndarray, ndarray)
        The scan's torques ``(n, S)`` [N m] and the creeps found there ``(n, S, n_c)``
        [-] (the screen's coarse ones where it decided; NaN where none converged): warm
        starts for points between them.
    """
    n, nc = flat.size, flat.layout.n_contacts
    grid = _scan_shares()[None, :] * top[:, None]
    rows = np.repeat(np.arange(n), grid.shape[1])
    ok, converged, creep = _scan(
        replace(flat.take(rows), output_torque=grid.ravel()), admissible, screen, grid
    )
    ok, creep = ok.reshape(grid.shape), creep.reshape(grid.shape + (nc,))
    # every change between neighbours: its admissible and its inadmissible end
    i, j = np.nonzero(ok[:, :-1] != ok[:, 1:])
    good = np.where(ok[i, j], j, j + 1)
    bad = np.where(ok[i, j], j + 1, j)
    ends = grid[i, good], grid[i, bad], creep[i, good]
    if has_multiple_equilibria(flat.fluid):
        a, b, x = _confirmed_bisection(flat, admissible, i, ends, rtol)
    else:
        a, b, x = _bisect(flat, lambda pb, x0: admissible(pb, x0, False), i, ends, rtol)
    edge = np.full(grid.shape, np.nan)
    edge[i, j] = a
    conv = converged.reshape(grid.shape)
    zero = np.where(conv[:, :1], creep[:, 0], np.nan)
    scan = (grid, np.where(conv[..., None], creep, np.nan))
    return _assemble(ok, grid, edge), _top_creep(ok, creep, (i, j, x)), zero, scan


def _bisect(flat: EquilibriumProblem, trial, rows, ends, rtol: float):
    """Bisect each change between an admissible and an inadmissible torque to ``rtol`` of
    the end itself (an end may lie near zero): ``rows`` ``(m,)`` the changes' points of
    ``flat``, ``ends`` = ``(a, b, x)`` their admissible and inadmissible torques [N m] and
    the creeps at ``a`` ``(m, n_c)``, ``trial(problem, x0) -> Admissibility`` from the
    creeps of the admissible end. Returns the final ``(a, b, x)`` (new arrays)."""
    a, b, x = (np.array(v, dtype=float) for v in ends)
    for _ in range(MAX_STEPS):
        act = np.flatnonzero(np.abs(b - a) > rtol * np.maximum(a, b))
        if act.size == 0:
            break
        mid = 0.5 * (a[act] + b[act])
        got = trial(replace(flat.take(rows[act]), output_torque=mid), x[act])
        a[act], b[act] = np.where(got.ok, mid, a[act]), np.where(got.ok, b[act], mid)
        x[act] = np.where(got.ok[:, None], got.creep, x[act])
    return a, b, x


def _confirmed_bisection(flat: EquilibriumProblem, admissible, rows, ends, rtol: float):
    """`_bisect` under a law with more than one equilibrium, where each point is followed
    from zero torque, as `solve` follows it: the trials by Newton from the admissible
    end's creeps alone, kept where they lie on their branch below its fold
    (`ballcvt.solvers.newton.solve_near` without its continuation), and the two final
    ends then followed from zero torque. Next to a fold Newton and the fold test accept
    torques up to the fold, which the continuation stops short of by 1e-5 to 3e-5 of it
    (Table I's thermal cam, session 38): an admissible end it does not reach is stepped
    down by `ballcvt.solvers.peak.FOLD_MARGIN`, the margin below a fold at which the
    limit under a constant force is reported. Where that fails too, or the
    inadmissible end is reached, the bisection runs again between the unconfirmed end and
    the scan's, each trial followed from zero torque (session 33: from the admissible
    end's creeps Table I's single-idler thermal cam capacity at 5000 rpm and ratio 1.56
    came out 10.785 N m, where `solve` found no equilibrium above 10.783). Each trial
    costs a Newton run instead of a continuation to next to the fold (a thermal cam
    sweep's capacity search, session 39)."""
    a0, b0, x0 = (np.array(v, dtype=float) for v in ends)
    near_trial = lambda pb, xs: admissible(pb, xs, predict=False, follow=False)  # noqa: E731
    a, b, x = _bisect(flat, near_trial, rows, ends, rtol)
    m = a.size
    both = replace(flat.take(np.concatenate([rows, rows])), output_torque=np.concatenate([a, b]))
    got = admissible(both, None, False)
    ok_a, ok_b = got.ok[:m], got.ok[m:]
    x = np.where(ok_a[:, None], got.creep[:m], x)
    # the admissible end in the fold's sliver: stepped down (an upper end only)
    down = np.flatnonzero(~ok_a & ~ok_b & (a < b))
    if down.size:
        lower = a[down] * (1.0 - FOLD_MARGIN)
        again = admissible(replace(flat.take(rows[down]), output_torque=lower), None, False)
        fine = again.ok & (lower > a0[down])
        a[down[fine]], b[down[fine]] = lower[fine], a[down[fine]]
        x[down[fine]] = again.creep[fine]
        ok_a[down[fine]] = True
    # the rest: between the unconfirmed end and the scan's, followed from zero torque,
    # first within `NEAR_BRACKET` of the unconfirmed end (the answer lies next to it)
    redo = np.flatnonzero(~ok_a | ok_b)
    if redo.size:
        yes = np.where(ok_b[redo], b[redo], a0[redo])  # the admissible end
        no = np.where(ok_b[redo], b0[redo], a[redo])
        start = np.where(ok_b[redo, None], got.creep[m:][redo], x0[redo])
        near = np.where(ok_b[redo], b[redo], a[redo])  # the unconfirmed end
        gap = np.where(ok_b[redo], no, yes) - near  # to the other one
        near = near + np.clip(NEAR_BRACKET * near * np.sign(gap), -np.abs(gap), np.abs(gap))
        probe = admissible(replace(flat.take(rows[redo]), output_torque=near), None, False)
        yes, no = np.where(probe.ok, near, yes), np.where(probe.ok, no, near)
        start = np.where(probe.ok[:, None], probe.creep, start)
        followed = lambda pb, xs: admissible(pb, None, False)  # noqa: E731 - one line
        a[redo], b[redo], x[redo] = _bisect(flat, followed, rows[redo], (yes, no, start), rtol)
    return a, b, x


def _scan(points: EquilibriumProblem, admissible, screen, grid):
    """The admissibility of the scan's ``points`` (a 1-D batch, the torques ``grid``
    ``(rows, S)`` [N m] in C order): ``(ok, converged, creep)``, flat.

    Without a ``screen``, one ``admissible`` batch from the cold start. With one, the
    points it decides keep its answer (and its coarse creeps, later only a start); the
    others, the zero and the top torques, and the points on either side of every change between admissible and
    inadmissible neighbours (again after each round, until every such point has been
    solved), are solved by ``admissible`` (`_solve_scan_points`). Every end the bisections
    start from is then the full rule's, and the screen's decision stands only where the
    full rule would take the same (its creeps `ballcvt.solvers.admissible.SCREEN_MARGIN`
    clear of the creep limit) or inside a run of its own decisions.
    """
    if points.size and has_multiple_equilibria(points.fluid):
        return _march(points, admissible, grid.shape)
    if screen is None or points.size == 0:
        got = admissible(points, None)
        return got.ok, got.converged, got.creep
    got = screen(points)
    ok, conv, creep = got.ok.copy(), got.converged.copy(), got.creep.copy()
    ends = np.zeros(grid.shape, dtype=bool)
    ends[:, [0, -1]] = True  # their creeps are the search's (the sweeps' starts)
    todo = ~(got.ok | got.beyond) | ends.ravel() | _next_to_change(ok, grid.shape)
    done = np.zeros(points.size, dtype=bool)
    while np.any(todo & ~done):
        idx = np.flatnonzero(todo & ~done)
        _solve_scan_points(points, admissible, idx, (ok, conv, creep))
        done[idx] = True
        todo |= _next_to_change(ok, grid.shape)
    return ok, conv, creep


def _march(points: EquilibriumProblem, admissible, shape):
    """`_scan` under a law with more than one equilibrium (the thermal law): every
    `STRIDE`-th torque of each row followed from zero torque, as `solve_admissible` follows
    a point without a start; every other torque from the creeps of the one `STRIDE` below
    it where those converged (near it: Newton, kept where it lands on the branch from zero
    torque, not past a fold; `ballcvt.solvers.newton.solve_from`), from zero torque
    elsewhere. Two batches where every point was followed from zero torque: on Table I's
    30 x 30 thermal cam sweep every scan decision the same, with the sweep's own starts
    33 % fewer traction evaluations (session 33)."""
    ok = np.zeros(points.size, dtype=bool)
    conv, creep = ok.copy(), np.full((points.size, points.layout.n_contacts), np.nan)
    step = np.arange(points.size) % shape[1] % STRIDE  # torques above the anchor
    _solve_scan_points(points, admissible, np.flatnonzero(step == 0), (ok, conv, creep))
    rest = np.flatnonzero(step)
    conv[rest], creep[rest] = conv[rest - step[rest]], creep[rest - step[rest]]
    _solve_scan_points(points, admissible, rest, (ok, conv, creep))
    return ok, conv, creep


def _next_to_change(ok, shape) -> np.ndarray:
    """Flat mask of the scan points (``ok`` flat, ``shape`` (rows, S)) on either side of a
    change between admissible and inadmissible neighbours along a row."""
    grid_ok = ok.reshape(shape)
    change = grid_ok[:, :-1] != grid_ok[:, 1:]
    near = np.zeros(shape, dtype=bool)
    near[:, :-1] |= change
    near[:, 1:] |= change
    return near.ravel()


def _solve_scan_points(points, admissible, idx, scan) -> None:
    """Solve the scan's points ``idx`` with ``admissible``, from the creeps in ``scan``
    (``ok``, ``converged``, ``creep``, updated in place) where they converged (without
    the predictor stage: they are already near), from the cold start elsewhere."""
    ok, conv, creep = scan
    for warm in (True, False):
        at = idx[conv[idx] == warm]
        if at.size:
            again = admissible(points.take(at), creep[at] if warm else None, not warm)
            ok[at], conv[at], creep[at] = again.ok, again.converged, again.creep


def _scan_shares() -> np.ndarray:
    """Scan torques as shares of the bound: ``SCAN_POINTS // 2`` steps of equal width, and
    as many in geometric progression from ``1e-4`` (a range beyond the capacity at low
    torque, where the preload still sets the force, is narrow)."""
    even = np.linspace(0.0, 1.0, SCAN_POINTS // 2 + 1)
    return np.union1d(even, np.geomspace(SCAN_POINTS_FLOOR, 1.0, SCAN_POINTS // 2 + 1))


def _assemble(ok, grid, edge):
    """Intervals ``(n, k, 2)`` from the scan (``ok``, ``grid``) and the refined ends
    ``edge[i, j]`` of the change between scan points ``j`` and ``j + 1``."""
    n = ok.shape[0]
    found: list[list[tuple[float, float]]] = [[] for _ in range(n)]
    for r in range(n):
        start = 0.0 if ok[r, 0] else None
        for j in range(ok.shape[1] - 1):
            if ok[r, j] and not ok[r, j + 1]:
                found[r].append((start, edge[r, j]))
            elif not ok[r, j] and ok[r, j + 1]:
                start = edge[r, j]
        if ok[r, -1]:
            found[r].append((start, grid[r, -1]))
    out = np.full((n, max([1, *map(len, found)]), 2), np.nan)
    for r, spans in enumerate(found):
        if spans:
            out[r, : len(spans)] = spans
    return out


def _top_creep(ok, creep, ends):
    """Creeps at each point's largest admissible torque: the refined end of its last
    admissible-to-inadmissible change, or its top scan point when admissible there."""
    out = np.where(ok[:, -1, None], creep[:, -1], np.nan)
    i, j, x = ends
    for k in np.argsort(j, kind="stable"):  # later changes overwrite earlier ones
        if ok[i[k], j[k]] and not ok[i[k], -1]:
            out[i[k]] = x[k]
    return out


def no_equilibrium_error(
    problem: EquilibriumProblem, creep_limit: float, options: SolverOptions, law=None
) -> NoEquilibriumError:
    """Why no output torque of ``problem`` is admissible, as the error to raise.

    Parameters
    ----------
    problem : EquilibriumProblem
        One operating point (its ``output_torque`` is ignored).
    creep_limit : float
        ``C_lim`` [-].
    options : SolverOptions
        Solver options.
    law : clamping law, optional
        A torque-following law; by default the problem's constant ``clamp_force``.

    Returns
    -------
    NoEquilibriumError
        Naming the point, its force at zero torque and what failed there.
    """
    zero = replace(problem, output_torque=np.asarray(0.0))
    bound = float(pressure_bound_force(zero, zero.design.max_pressure))
    if law is not None:
        zero, best = solve_clamped(
            zero, law, lambda p, x: solve_point(p, options, x), None, zero.design.max_pressure
        )
    else:
        best = solve_point(zero, options)
    force = float(zero.clamp_force)
    said = {
        "input_speed": f"input speed {float(problem.input_speed):g} rad/s",
        "clamp_force": f"clamp_force {force:g} N",
    }
    where = (
        f"ratio {float(problem.ratio):g}, {said['clamp_force']}"
        f"{f' by the {law.name} law at zero torque' if law is not None else ''}, "
        f"{said['input_speed']}"
    )
    if law is not None and law.implicit and not best.converged and at_ceiling(force, bound):
        why = (
            f"the {law.name} law's clamping force finds no balance up to {bound:.4g} N, the "
            f"force of peak pressure max_pressure = {zero.design.max_pressure:g} Pa: the "
            "drag the force causes asks for still more force"
        )
    elif law is not None and force > bound:
        why = (
            f"the {law.name} law's clamping force {force:.4g} N already exceeds the "
            f"pressure limit max_pressure = {zero.design.max_pressure:g} Pa"
        )
    elif best.converged and law is None:
        why = (
            f"its creep {float(np.max(np.abs(best.state.creep))):.3g} already exceeds "
            f"creep_limit {creep_limit:g}: the drive's own spin and bearing drag use up "
            "its traction"
        )
    elif law is None:
        why = (
            "the traction this clamping force can transmit at this speed does not carry "
            f"the drive's own drag; raise clamp_force ({best.message})"
        )
    else:
        at_zero = (
            f"at zero torque its creep is {float(np.max(np.abs(best.state.creep))):.3g}"
            if best.converged
            else f"at zero torque: {best.message}"
        )
        return NoEquilibriumError(
            f"no admissible equilibrium at any output torque ({where}): the {law.name} "
            f"law's force does not carry the torque within creep_limit {creep_limit:g} "
            f"({at_zero}); a law that clamps harder (a cam: a larger preload or a smaller "
            "ramp angle) would",
            said,
        )
    return NoEquilibriumError(
        f"no admissible equilibrium even at zero output torque ({where}): {why}", said
    )
