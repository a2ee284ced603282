"""Limiting output torque (docs/model.md §8).

The traction law saturates (``mu -> a + tau_L0 A / F_N``), so creep runs away over a
narrow torque band instead of stopping at a sharp maximum. The limiting torque is the
largest ``T_2`` with a converged equilibrium and every ``|C| <= C_lim``. Under a constant
clamping force it is found directly, by holding a disc creep at ``C_lim`` and solving for
the output torque (`limit_search`, `ballcvt.solvers.newton.solve_pinned`); as the
fallback, by bisection on ``T_2``, each trial started from the solution at the highest
torque known to be admissible (continuation). Under a torque-following clamping law the
admissible torques are found as intervals (`ballcvt.solvers.capacity`), and the limit is
the largest of them.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..model.traction.base import traction_rises_with_creep
from .admissible import (  # noqa: F401 - Admissibility: its old path keeps working
    Admissibility,
    follows_torque,
    screen_admissible,
    screens,
    solve_admissible,
)
from .capacity import interval_search, no_equilibrium_error
from .clamped import pressure_bound_force, with_clamp
from .newton import initial_creep, solve_pinned
from .peak import peak_limits
from .point import SolverOptions

__all__ = [
    "limit_torque",
    "limit_torque_batch",
    "limit_search",
    "LimitSearch",
    "limit_torque_bisection",
    "traction_ceiling_torque",
    "saturated_traction",
    "bisection_steps",
    "LIMIT_RTOL",
]


#: Default relative width of the final torque bracket of the limit bisections.
LIMIT_RTOL = 1e-4
#: Most bisection steps of `limit_torque_batch` (a bracket of 2^-60 of the ceiling).
MAX_BISECTIONS = 60
#: Relative margin below ``C_lim`` at which the limit search pins a disc creep [-]: a
#: solve at the torque found meets its creeps only to its tolerance (some 1e-9
#: relative), so the limit is taken on the admissible side of ``C_lim``, where a solve
#: at it keeps every ``|C| <= C_lim`` (the torque lower by about as much, relative).
PIN_MARGIN = 1e-7


def bisection_steps(rtol: float = LIMIT_RTOL) -> int:
    """Bisection steps of `limit_torque_batch` for a relative bracket ``rtol``."""
    return int(np.ceil(np.log2(1.0 / rtol))) + 1


def saturated_traction(problem: EquilibriumProblem) -> np.ndarray:
    """Traction ceiling ``mu_max = a + tau_L0 pi a_x a_y / F_N`` of every contact [-].

    ``|tau| <= tau_L = tau_L0 + a p`` and the pressure integrates to ``F_N`` over the
    ellipse, so ``|mu| <= mu_max`` (Eqs. 53-54, 57).
    """
    fl = problem.fluid
    area = np.pi * problem.ax * problem.ay
    return fl.limiting_shear_slope + fl.limiting_shear_stress * area / problem.load


def traction_ceiling_torque(problem: EquilibriumProblem) -> np.ndarray:
    """Upper bound on ``T_2`` from the saturated traction of the disc contacts [N m].

    With the spin moment bounded like the traction (`saturated_traction`), the output
    torque cannot exceed ``n F_N r_c (1 + sin(theta)) mu_max`` at the output contact, nor
    that of the input contact over ``tau_ID`` (power cannot grow: ``T_2 <= T_0 / tau_ID``).
    Shape ``(...)``, the batch shape of ``problem``.
    """
    cap = (
        problem.design.n_rollers
        * problem.load
        * problem.radius
        * saturated_traction(problem)
        * (1 + np.abs(problem.layout.z_j))
    )
    return np.minimum(cap[..., -1], cap[..., 0] / problem.ratio)


def limit_torque(
    problem: EquilibriumProblem,
    creep_limit: float,
    options: SolverOptions = SolverOptions(),
    rtol: float = LIMIT_RTOL,
    law=None,
) -> float:
    """Largest admissible output torque of a single operating point [N m].

    `limit_torque_batch` on one point, so that a point, a sweep and a map give the same
    limit; when there is none, the cause is diagnosed and raised.

    Parameters
    ----------
    problem : EquilibriumProblem
        Operating point (its ``output_torque`` is ignored).
    creep_limit : float
        ``C_lim``, the largest admissible ``|C|`` [-].
    options : SolverOptions
        Solver options.
    rtol : float
        Relative width of the final torque bracket [-].
    law : clamping law, optional
        A law whose force follows the torque (`ballcvt.model.clamping`); by default the
        problem's constant ``clamp_force``.

    Returns
    -------
    float
        The largest admissible torque. Under a torque-following law the admissible
        torques need not start at zero (`ballcvt.solvers.capacity.Capacity`).

    Raises
    ------
    NoEquilibriumError
        If no admissible equilibrium exists (even at zero output torque).
    """
    torque = float(limit_torque_batch(problem, creep_limit, options, rtol, law=law))
    if not np.isnan(torque):
        return torque
    raise no_equilibrium_error(problem, creep_limit, options, law if follows_torque(law) else None)


@dataclass(frozen=True)
class LimitSearch:
    """Outcome of `limit_search`; arrays have the batch shape ``(...)`` of the problem.

    Attributes
    ----------
    torque : ndarray
        Limiting output torques [N m]; NaN where even ``T_2 = 0`` is inadmissible.
    creep : ndarray
        Creeps at the limit, ``(..., n_c)`` (NaN where there is none) [-]: a warm start
        for the points at or near the limit.
    creep_zero : ndarray
        Creeps at zero output torque, ``(..., n_c)`` [-], where they were solved for
        (points that needed the bisection or have no limit; NaN elsewhere).
    intervals : ndarray, optional
        The admissible torques, ``(..., k, 2)`` rows ``(lo, hi)`` [N m], NaN-padded
        (`ballcvt.solvers.capacity.Capacity`); None: ``(0, torque)`` where ``torque`` is
        finite. ``torque`` is the largest ``hi``.
    scan_torque, scan_creep : ndarray, optional
        The torques ``(..., S)`` [N m] of a capacity scan (a torque-following law,
        `ballcvt.solvers.capacity.interval_search`), or of the walk up each branch and its
        limit (a law with more than one equilibrium at a constant force,
        `ballcvt.solvers.peak.peak_limits`; ``+inf`` after a point's last), and the creeps
        found there ``(..., S, n_c)`` [-] (NaN where none): warm starts for the points
        between them (`start_between`). None without a scan.
    """

    torque: np.ndarray
    creep: np.ndarray
    creep_zero: np.ndarray
    intervals: np.ndarray | None = None
    scan_torque: np.ndarray | None = None
    scan_creep: np.ndarray | None = None

    def spans(self) -> np.ndarray:
        """``intervals``, or ``(0, torque)`` rows where it is None: ``(..., k, 2)``."""
        if self.intervals is not None:
            return self.intervals
        lo = np.where(np.isnan(self.torque), np.nan, 0.0)
        return np.stack([lo, self.torque], axis=-1)[..., None, :]

    def admits(self, torque) -> np.ndarray:
        """Whether each torque of ``torque`` ``(n_T,)`` [N m] lies in an admissible
        interval of each point: ``(..., n_T)``."""
        s = self.spans()[..., None, :, :]
        t = np.asarray(torque, dtype=float)[:, None]
        with np.errstate(invalid="ignore"):
            return np.any((s[..., 0] <= t) & (t <= s[..., 1]), axis=-1)

    def flat(self) -> LimitSearch:
        """The same points as a 1-D batch (C order)."""
        nc, k = self.creep.shape[-1], self.spans().shape[-2]
        return LimitSearch(
            self.torque.reshape(-1),
            self.creep.reshape(-1, nc),
            self.creep_zero.reshape(-1, nc),
            self.spans().reshape(-1, k, 2),
            *self._scan(lambda a, tail: a.reshape((-1,) + a.shape[a.ndim - tail :])),
        )

    def take(self, index) -> LimitSearch:
        """The points ``index`` of a 1-D batch."""
        return LimitSearch(
            self.torque[index],
            self.creep[index],
            self.creep_zero[index],
            self.spans()[index],
            *self._scan(lambda a, tail: a[index]),
        )

    def _scan(self, fn):
        """``(fn(scan_torque, 1), fn(scan_creep, 2))`` (the trailing axes per point), or
        ``(None, None)`` without a scan."""
        if self.scan_torque is None or self.scan_creep is None:
            return None, None
        return fn(self.scan_torque, 1), fn(self.scan_creep, 2)

    def start_between(self, index, torque):
        """Starting creeps ``(m, n_c)`` [-] of points ``index`` (of a 1-D batch) at
        ``torque`` ``(m,)`` [N m] within their limits, or None without a scan: the creeps
        of the scan's two torques around each one, interpolated linearly in torque (the one
        that converged where only one did; NaN where neither)."""
        grid, creep = self._scan(lambda a, tail: a[index])
        if grid is None or creep is None:
            return None
        t = np.asarray(torque, dtype=float)
        hi = np.clip((grid < t[:, None]).sum(axis=1), 1, grid.shape[1] - 1)
        lo = hi - 1
        rows = np.arange(t.size)
        a, b = grid[rows, lo], grid[rows, hi]
        share = np.clip(np.divide(t - a, b - a, out=np.zeros(t.size), where=b > a), 0, 1)
        xa, xb = creep[rows, lo], creep[rows, hi]
        x = xa + share[:, None] * (xb - xa)
        return np.where(np.isnan(x), np.where(np.isnan(xa), xb, xa), x)


def limit_torque_batch(
    problem: EquilibriumProblem,
    creep_limit: float,
    options: SolverOptions = SolverOptions(),
    rtol: float = LIMIT_RTOL,
    callback=None,
    law=None,
) -> np.ndarray:
    """Limiting output torque of every point of a batch (its ``output_torque`` is ignored).

    `limit_search` returning the torques only: shape ``(...)`` [N m], NaN where even
    ``T_2 = 0`` is inadmissible. Parameters as in `limit_search`.
    """
    return limit_search(problem, creep_limit, options, rtol, callback, law).torque


def limit_search(
    problem: EquilibriumProblem,
    creep_limit: float,
    options: SolverOptions = SolverOptions(),
    rtol: float = LIMIT_RTOL,
    callback=None,
    law=None,
) -> LimitSearch:
    """Limiting output torque of every point of a batch, and the creeps there.

    Under a constant clamping force the limit is found directly: the creep of a disc
    contact is held at ``creep_limit`` (`PIN_MARGIN` below it) and the output torque
    that goes with it solved for (`solve_pinned`), first at the disc contact with the
    lower traction ceiling, then at the other one for the points where that answer is
    inadmissible (the other disc's creep beyond the limit). The creeps grow with the
    torque, so a non-negative torque found so, with every creep within the limit, is the
    largest admissible one, exact to the solver tolerance. Under a torque-following law
    the admissible torques need not start at zero nor be one range (a cam with a small
    preload): they are scanned and their ends bisected
    (`ballcvt.solvers.capacity.interval_search`), ``torque`` is the largest and
    ``intervals`` holds them all. The other points of a constant force are solved at
    ``T_2 = 0``: inadmissible there, they have no limit (NaN); otherwise the pinned
    solve is tried again from those creeps and, failing that (a non-monotone creep, a
    failed solve), the bisection on ``T_2`` of `limit_torque_bisection` decides. The two
    methods agree within ``rtol`` (tests/test_fast_solver.py). Under a traction law
    whose traction can fall with the creep (the thermal law), the torque at the creep
    limit may lie past the peak of the curve ``T_2(C)``: there the limit is the fold of
    the branch followed from zero torque, or where a creep reaches the limit first (a
    torque continuation, then a climb in a disc's held creep to the fold;
    `ballcvt.solvers.peak.peak_limits`, docs/model.md §8, §14). A creep is held
    `PIN_MARGIN` below ``creep_limit``, on the admissible side.

    Parameters
    ----------
    problem : EquilibriumProblem
        Operating points, batch shape ``(...)``.
    creep_limit : float
        ``C_lim`` [-].
    options : SolverOptions
        Solver options.
    rtol : float
        Relative width of the final torque brackets of the bisection [-].
    callback : callable, optional
        Called with no argument `bisection_steps` times in all (progress bars).
    law : clamping law, optional
        A law whose force follows the torque (`ballcvt.model.clamping`). Its force grows with
        the torque, so the capacity is also bounded by the peak pressure: a trial counts as
        admissible only if its force keeps every contact at or below
        ``design.max_pressure`` (docs/model.md §11). By default the problem's constant
        ``clamp_force``.

    Returns
    -------
    LimitSearch
    """
    flat = problem.flat()
    law = law if follows_torque(law) else None
    nc = flat.layout.n_contacts
    calls = [0]

    def tick(n=1):
        for _ in range(n if callback is not None else 0):
            if calls[0] < bisection_steps(rtol):
                calls[0] += 1
                callback()

    torque = np.full(flat.size, np.nan)
    creep = np.full((flat.size, nc), np.nan)
    x_zero = np.full((flat.size, nc), np.nan)
    shape = problem.shape
    if law is not None:
        spans, creep, x_zero, (scan_t, scan_x) = interval_search(
            flat,
            lambda pb, x, predict=True, follow=True: solve_admissible(
                pb, creep_limit, options, law, x, predict, follow
            ),
            _law_bound(flat, law),
            rtol,
            screen=(
                (lambda pb: screen_admissible(pb, creep_limit, options, law))
                if screens(options, law, flat.fluid)
                else None
            ),
        )
        tick(bisection_steps(rtol))
        return LimitSearch(
            np.fmax.reduce(spans[..., 1], axis=-1).reshape(shape),
            creep.reshape(shape + (nc,)),
            x_zero.reshape(shape + (nc,)),
            spans.reshape(shape + spans.shape[-2:]),
            scan_t.reshape(shape + scan_t.shape[-1:]),
            scan_x.reshape(shape + scan_x.shape[-2:]),
        )
    torque, creep, scan = _pinned_limits(flat, creep_limit, options, initial_creep(flat))
    tick()
    rest = np.flatnonzero(np.isnan(torque))
    if rest.size:
        zero = solve_admissible(
            replace(flat.take(rest), output_torque=np.zeros(rest.size)), creep_limit, options, law
        )
        tick()
        x_zero[rest] = np.where(zero.converged[:, None], zero.creep, np.nan)
        todo = rest[zero.ok]
        if todo.size:  # once more, from the T_2 = 0 creeps
            torque[todo], creep[todo] = _pinned_limits(
                flat.take(todo), creep_limit, options, x_zero[todo]
            )[:2]
            if scan is not None:  # (its walk's points are not these limits')
                scan[0][todo], scan[1][todo] = np.inf, np.nan
        todo = todo[np.isnan(torque[todo])]
        if todo.size:
            torque[todo], creep[todo] = limit_torque_bisection(
                flat.take(todo), creep_limit, options, rtol, tick, law, x_zero[todo]
            )
    tick(bisection_steps(rtol))
    walked = () if scan is None else (scan[0].reshape(shape + scan[0].shape[-1:]),
                                      scan[1].reshape(shape + scan[1].shape[-2:]))  # fmt: skip
    return LimitSearch(
        torque.reshape(shape), creep.reshape(shape + (nc,)), x_zero.reshape(shape + (nc,)),
        None, *walked,
    )  # fmt: skip


def _pinned_limits(flat, creep_limit, options, x_zero):
    """Torques at which a disc creep reaches ``creep_limit`` with every creep admissible
    (`limit_search`); NaN where neither disc contact gives one. Also the equilibria met on
    the way up each branch under a law with more than one equilibrium (the walk's,
    `ballcvt.solvers.peak.peak_limits`), else None."""
    if not traction_rises_with_creep(flat.fluid):
        return peak_limits(flat, creep_limit, options, x_zero, path=True)
    nc = flat.layout.n_contacts
    torque = np.full(flat.size, np.nan)
    creep = np.full((flat.size, nc), np.nan)
    # the disc contact with the lower traction ceiling usually limits: try it first
    cap = (flat.load * flat.radius * saturated_traction(flat))[:, [0, -1]]
    cap[:, 0] /= flat.ratio
    first = np.where(cap[:, 0] <= cap[:, 1], 0, nc - 1)
    pin = creep_limit * (1.0 - PIN_MARGIN)
    for attempt in range(2):
        for k in (0, nc - 1):
            idx = np.flatnonzero(np.isnan(torque) & ((first == k) == (attempt == 0)))
            if idx.size == 0:
                continue
            x0 = x_zero[idx].copy()
            x0[:, [0, -1]] = pin
            t, sol = solve_pinned(flat.take(idx), k, x0, options)
            x = sol.state.creep
            good = (
                sol.converged
                & np.isfinite(t)
                & (t >= 0.0)
                & (np.max(np.abs(x), axis=-1) <= pin * (1.0 + 1e-9))
            )
            torque[idx[good]], creep[idx[good]] = t[good], x[good]
    return torque, creep, None


def _law_bound(flat: EquilibriumProblem, law) -> np.ndarray:
    """Upper bound on the admissible ``T_2`` under a torque-following ``law`` [N m]: the
    torque whose force reaches the pressure limit, and the traction ceiling at that
    force."""
    f_cap = pressure_bound_force(flat, flat.design.max_pressure)
    return np.minimum(
        law.output_torque_bound(flat.design, f_cap, flat.ratio),
        traction_ceiling_torque(with_clamp(flat, f_cap)),
    )


def limit_torque_bisection(
    flat: EquilibriumProblem,
    creep_limit: float,
    options: SolverOptions,
    rtol: float,
    callback,
    law,
    x_zero,
):
    """Bisection on ``T_2`` for the limits of a 1-D batch admissible at ``T_2 = 0``.

    Each trial is started from the point's last admissible creeps (continuation) and
    counts as admissible only if it converges with every ``|C| <= creep_limit`` (and,
    under a torque-following ``law``, within the pressure limit; `solve_admissible`).

    Returns
    -------
    torque : ndarray
        The highest admissible torque found, within ``rtol`` of the limit [N m].
    creep : ndarray
        The creeps there.
    """
    hi = traction_ceiling_torque(flat) if law is None else _law_bound(flat, law)
    best = np.array(x_zero, dtype=float)
    lo = np.zeros(flat.size)
    # bisect until every bracket is narrow: a loose ceiling (extreme designs) needs more
    # than the bisection_steps() of a typical one
    steps = bisection_steps(rtol)
    for step in range(MAX_BISECTIONS):
        active = np.flatnonzero((step < steps) | (hi - lo > rtol * hi))
        if active.size == 0:
            break
        mid = 0.5 * (lo[active] + hi[active])
        got = solve_admissible(
            replace(flat.take(active), output_torque=mid), creep_limit, options, law, best[active]
        )
        lo[active] = np.where(got.ok, mid, lo[active])
        hi[active] = np.where(got.ok, hi[active], mid)
        best[active] = np.where(got.ok[:, None], got.creep, best[active])
        callback()
    return lo, best
