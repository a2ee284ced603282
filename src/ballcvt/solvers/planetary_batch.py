"""Planetary modes over many points, batched through the fast solver (docs/model.md §13).

`solve_mode_batch` is `ballcvt.solvers.planetary.solve_mode` on a batch: every pass of the
fixed point on the actual ratio is one batched solve. `limit_load_batch` finds the capacity
per mode by bisection on the load.
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace

import numpy as np

from ..equilibrium.problem import EquilibriumProblem, OperatingInputs, make_problem
from ..equilibrium.residual import balancing_output_torque
from ..model.architectures import contact_layout
from ..model.modes import MEMBERS, OperatingMode, member_torques, resolve_mode
from ..model.traction.base import has_multiple_equilibria, traction_rises_with_creep
from ..params.drive import Drive
from ..performance.efficiency import LOSS_KINDS, loss_breakdown, power_losses
from ..status import Status
from .limit import PIN_MARGIN, traction_ceiling_torque
from .mode_batch import ModeBatch
from .newton import BatchSolution, initial_creep, solve_batch
from .options import SolverOptions
from .planetary import ModePoint, RatioPasses, carrier_frame_problem, coupled_creeps, couples
from .planetary_pinned import carrier_speed_bound, held_creep_loads, member_speeds

__all__ = [
    "ModeBatch",
    "solve_mode_batch",
    "limit_load_batch",
    "limit_load_search",
    "PROBE",
    "PROBES",
    "START_SHARES",
    "START_ITERATIONS",
    "START_RTOL",
    "HELD_MATCH",
    "PassPlan",
    "LoadSearch",
]

#: Relative step above the bisection's end at a failed solve at which `limit_load_batch`
#: solves again [-] (twice its default ``rtol``), and how many times it goes on from there.
PROBE = 2e-3
PROBES = 2


@dataclass(frozen=True)
class PassPlan:
    """How `solve_mode_batch` runs the fixed point on the actual ratio: at most
    ``max_passes`` passes (int), to a tolerance.

    Attributes
    ----------
    ratio_rtol : float or None
        Its relative tolerance [-] where looser than `ballcvt.solvers.planetary.
        ratio_tolerance` (points solved only as a start for another search); None: that
        tolerance.
    """

    max_passes: int = 30
    ratio_rtol: float | None = None


def solve_mode_batch(
    drive: Drive,
    mode: OperatingMode | str,
    point: ModePoint,
    options: SolverOptions = SolverOptions(),
    plan: PassPlan = PassPlan(),
    rescue=True,
    start=None,
) -> ModeBatch:
    """`solve_mode` on a batch of points, batched through the fast solver.

    ``point.ratio``, ``point.load_torque`` and ``point.driver_speed`` broadcast to
    ``(n,)``; ``mode`` is an `OperatingMode` or a name of
    `ballcvt.registry.OPERATING_MODES`. The points first go through
    `ballcvt.solvers.planetary.coupled_creeps` (the fixed point on the actual ratio
    inside one Newton run; not in a rough ``plan``, nor where `couples` says no); then
    every pass of the fixed point is one `solve_batch` of the points not yet settled (one
    evaluation where the coupled run converged); a point's figures are taken from the pass
    in which it settles. Points whose speeds are
    out of range are flagged (``Status.OUT_OF_RANGE``), not raised; points whose creeps exceed
    ``design.creep_limit`` are flagged 1.

    ``rescue`` says which points whose Newton run fails go on to the point solver
    (`ballcvt.solvers.robust`, MINPACK's hybrid method then bracketing, about ten
    milliseconds a point): every one (True, as `solve`), a mask ``(n,)`` of them, or none
    (False: the capacity search's first loads, which are only starts). ``plan``: the
    passes' number and tolerance (`PassPlan`). ``start``:
    ``(ratio (n,), creeps (n_c, n))``, a guess of each point's actual (relative) ratio and
    carrier-frame creeps (e.g. interpolated between solved loads; NaN: the ideal ratio and
    the cold start). The fixed point has one solution: a start saves passes, and moves the
    answer only within the tolerances.
    """
    mode = resolve_mode(mode)
    design, clamp_force = drive.design, point.clamp_force
    ratio, load, w = (
        np.ravel(v)
        for v in np.broadcast_arrays(
            *(
                np.asarray(v, dtype=float)
                for v in (point.ratio, point.load_torque, point.driver_speed)
            )
        )
    )
    n = ratio.size
    layout = contact_layout(design, drive.architecture)
    w_max = carrier_speed_bound(drive, mode, clamp_force)
    status = np.full(n, int(Status.NOT_CONVERGED))
    tau, x = _started(ratio, start, layout.n_contacts)
    speeds, torques = np.full((3, n), np.nan), np.full((3, n), np.nan)
    loss, circ, big = (np.full(n, np.nan) for _ in range(3))
    kinds = np.full((len(LOSS_KINDS), n), np.nan)
    settled = np.zeros(n, dtype=bool)
    passes = RatioPasses(n, options, drive.fluid, plan.ratio_rtol)
    if plan.ratio_rtol is None and couples(drive.fluid, mode):  # on to the fixed point at once
        rows = np.flatnonzero(member_speeds(mode, w, tau, w_max)[1])
        at = ModePoint(ratio, load, w, clamp_force)
        _couple(drive, mode, (at, rows), (tau, x), options)
    for _ in range(plan.max_passes):
        sp, ok = member_speeds(mode, w, tau, w_max)
        status[~ok & ~settled] = Status.OUT_OF_RANGE
        todo = np.flatnonzero(ok & ~settled)
        if todo.size == 0:
            break
        pb, sign = carrier_frame_problem(
            drive,
            mode,
            ModePoint(ratio[todo], load[todo], w[todo], clamp_force),
            {m: v[todo] for m, v in sp.items()},
        )
        cold = np.isnan(x[todo])
        start = np.where(cold, initial_creep(pb), x[todo])
        sol = _solve_pass(pb, options, start, _rescued(rescue, todo), bool(cold.any()))
        st = sol.state
        x[todo] = st.creep
        new = st.omega[:, -1] / st.omega[:, 0]
        done = ~sol.converged | passes.settles(tau, new, todo)
        settled[todo[done]] = True
        fin = done & sol.converged
        j = todo[fin]
        status[j] = Status.CONVERGED
        members = member_torques(sign * st.input_torque, sign * balancing_output_torque(pb, st))
        for row, m in enumerate(MEMBERS):
            speeds[row, j] = sp[m][todo][fin]
            torques[row, j] = members[m][fin]
        by_kind = loss_breakdown(power_losses(pb, st))
        loss[j] = by_kind["total"][fin]
        for row, kind in enumerate(LOSS_KINDS):
            kinds[row, j] = by_kind[kind][fin]
        circ[j] = np.abs(st.input_torque * pb.input_speed)[fin]
        big[j] = np.max(np.abs(st.creep[fin]), axis=-1)
        step = passes.step(tau, new, todo)
        tau[todo] = np.where(sol.converged, np.where(done, new, step), tau[todo])
    status[(status == Status.CONVERGED) & (big > design.creep_limit)] = Status.BEYOND_LIMIT
    keep = status == Status.CONVERGED
    return ModeBatch(
        status,
        np.where(keep, speeds, np.nan),
        np.where(keep, torques, np.nan),
        np.where(keep, loss, np.nan),
        np.where(keep, tau, np.nan),
        np.where(keep, big, np.nan),
        np.where(keep, circ, np.nan),
        np.where(keep, kinds, np.nan),
        np.where(keep, x.T, np.nan),
    )


def _couple(drive, mode, point_rows, state, options) -> None:
    """`coupled_creeps` of the points ``rows`` of ``point_rows = (point, rows)`` (their
    speeds in range) before the passes of `solve_mode_batch`: where it converges, their
    ratios and creeps in ``state = (tau, x)`` (updated in place; NaN creeps: the cold
    start) are its, and the passes confirm them; elsewhere the passes run from ``state``
    as it was."""
    point, rows = point_rows
    if rows.size == 0:
        return
    tau, x = state
    here = replace(point, ratio=point.ratio[rows], load_torque=point.load_torque[rows],
                   driver_speed=point.driver_speed[rows])  # fmt: skip
    got, creep, done = coupled_creeps(drive, mode, here, (tau[rows], x[rows]), options)
    j = rows[done]
    tau[j], x[j] = got[done], creep[done]


def _started(ratio, start, nc: int):
    """The first pass's ratios ``(n,)`` and creeps ``(n, n_c)`` of `solve_mode_batch`
    (``start`` where finite; else the ideal ratio, and NaN creeps for the cold start)."""
    if start is None:
        return ratio.copy(), np.full((ratio.size, nc), np.nan)
    guess = np.broadcast_to(np.asarray(start[0], dtype=float), ratio.shape)
    creeps = np.broadcast_to(np.asarray(start[1], dtype=float), (nc, ratio.size)).T
    return np.where(np.isfinite(guess), guess, ratio), np.array(creeps)


def _rescued(rescue, todo):
    """``rescue`` of `solve_mode_batch` for its points ``todo``."""
    if np.ndim(rescue) == 0:
        return bool(rescue)
    return np.asarray(rescue, dtype=bool)[todo]


def _solve_pass(pb: EquilibriumProblem, options: SolverOptions, x0, rescue, predict: bool):
    """One pass of `solve_mode_batch`: `solve_batch` from ``x0`` (with its predictor stage
    where ``predict``: not from the last pass's creeps, which it would only move away, five
    iterations a point and a pass), the points whose Newton run failed rescued by the point
    solver as ``rescue`` says (True: all of them; a mask; False: none)."""
    if rescue is True or has_multiple_equilibria(pb.fluid):
        return solve_batch(pb, options, x0, predict=predict)
    sol = solve_batch(pb, options, x0, fallback=False, predict=predict)
    idx = np.flatnonzero(~sol.converged & rescue)
    if idx.size == 0:
        return sol
    again = solve_batch(pb.take(idx), options, np.asarray(x0)[idx])
    return BatchSolution(
        sol.state.put(idx, again.state),
        _put(sol.converged, idx, again.converged),
        _put(sol.residual_norm, idx, again.residual_norm),
        _put(sol.iterations, idx, again.iterations),
    )


def _put(values, idx, new) -> np.ndarray:
    out = np.array(values)
    out[idx] = new
    return out


@dataclass(frozen=True)
class LoadSearch:
    """What `limit_load_search` found; unpacks as ``(limit, at_limit)``.

    Attributes
    ----------
    limit : ndarray
        ``|L|`` at the limit [N m], ``(n,)``; NaN where even zero load is not admissible or
        the speeds are out of range.
    at_limit : ModeBatch
        The points solved at that load (in the load's direction).
    probe : tuple of ndarray
        ``(load (n,), creep (n_c, n))``: the admissible load [N m] (magnitude) below the
        limit that the held-creep search started from (`START_SHARES`), and its creeps
        [-] (to `START_RTOL` in the ratio); NaN where there is none (the bisection's
        points). A third solved load of each curve, between zero load and the limit.
    """

    limit: np.ndarray
    at_limit: ModeBatch
    probe: tuple

    def __iter__(self):
        return iter((self.limit, self.at_limit))

    def __getitem__(self, k):
        return (self.limit, self.at_limit)[k]


def limit_load_batch(
    drive: Drive,
    mode: OperatingMode | str,
    point: ModePoint,
    options: SolverOptions = SolverOptions(),
    rtol: float = 1e-3,
    max_steps: int = 40,
    zero: ModeBatch | None = None,
) -> np.ndarray:
    """Largest load torque of the driven member with every ``|C| <= creep_limit``
    (``drive.design.creep_limit``): `limit_load_search`'s first return."""
    return limit_load_search(drive, mode, point, options, (rtol, max_steps), zero)[0]


def limit_load_search(
    drive: Drive,
    mode: OperatingMode | str,
    point: ModePoint,
    options: SolverOptions = SolverOptions(),
    bisection: tuple[float, int] = (1e-3, 40),
    zero: ModeBatch | None = None,
) -> LoadSearch:
    """Largest load torque of the driven member with every ``|C| <= creep_limit``
    (``drive.design.creep_limit``), and the points solved there.

    ``point.ratio`` and ``point.driver_speed`` are the batch; ``point.load_torque`` only
    gives the direction of the load searched, by its sign where it is finite and non-zero
    (an overhauling load, negative to the driven member's speed, has its own capacity).
    Elsewhere the load brakes the driven member: its sign is that of the driven speed at
    zero load (positive at geared neutral).

    Under a traction law whose traction never falls with the creep, the load at which a
    disc contact's creep reaches the limit is found at a held creep
    (`ballcvt.solvers.planetary_pinned.held_creep_loads`, from an admissible load of
    `START_SHARES` of the traction ceiling) and kept where a solve there from the cold
    start, as `solve` makes it, is admissible (issue 26: a handful of batched solves for
    the bisection's dozen). The other points are bracketed by doubling from the
    carrier-frame traction ceiling, then bisected on all ratios at once to ``bisection``
    = ``(rtol, max_steps)`` (`solve_mode_batch`). Where the bisection ends at a load whose
    solve failed (not one beyond the creep limit), the load `PROBE` above it is solved:
    where that one is admissible, the failure was the solver's, not the capacity's edge,
    and the bisection goes on above it (up to `PROBES` times; not under a law with more
    than one equilibrium, where a failed solve is the continuation's verdict: the load
    lies past the fold of the branch from zero). ``zero``: the points solved at zero
    load, where the caller has them (`solve_mode_batch` of the same points).

    Returns
    -------
    LoadSearch
        The limits and the points solved there (it unpacks as ``(limit, at_limit)``), and
        the held search's first loads.
    """
    mode = resolve_mode(mode)
    ratio, given, w = (
        np.ravel(v)
        for v in np.broadcast_arrays(
            *(
                np.asarray(v, dtype=float)
                for v in (point.ratio, point.load_torque, point.driver_speed)
            )
        )
    )
    at = replace(point, ratio=ratio, driver_speed=w)
    if zero is None:
        zero = solve_mode_batch(drive, mode, replace(at, load_torque=0.0), options)
    chosen = np.isfinite(given) & (given != 0.0)
    direction = np.where(
        chosen, np.sign(np.where(chosen, given, 1.0)), zero.braking_direction(mode)
    )
    at = replace(at, load_torque=direction)
    ok0 = zero.status == Status.CONVERGED
    hi = traction_ceiling_torque(
        make_problem(drive, OperatingInputs(ratio, 0.0, point.clamp_force, 1.0))
    )

    def solved(size, rows, start=None, first=False):  # the points ``rows`` at ``size``
        here = _rows(at, direction[rows] * size, rows)
        if first:  # a start for the held creep: not converging soon, it is tried lower
            brief = replace(options, max_iterations=START_ITERATIONS)
            rough = PassPlan(ratio_rtol=START_RTOL)
            return solve_mode_batch(drive, mode, here, brief, rough, False, start)
        return solve_mode_batch(drive, mode, here, options, start=start)

    limit, found = np.full(ratio.size, np.nan), None
    probe = (np.full(ratio.size, np.nan), np.full(zero.creep.shape, np.nan))
    if traction_rises_with_creep(drive.fluid):
        limit, found, probe = _held_limits(drive, mode, (at, solved), (zero, hi), options)
    rest = np.flatnonzero(ok0 & np.isnan(limit))
    if rest.size:
        limit[rest] = _bisected(lambda size, rows: solved(size, rest[rows]).status, hi[rest],
                                has_multiple_equilibria(drive.fluid), bisection)  # fmt: skip
    limit = np.where(ok0, limit, np.nan)
    fill = np.flatnonzero(np.isfinite(limit)) if found is None else rest[np.isfinite(limit[rest])]
    if found is not None and fill.size == 0:  # every limit held and confirmed
        return LoadSearch(limit, found, probe)
    again = solved(limit[fill], fill).expand(fill, ratio.size, Status.NOT_CONVERGED)
    return LoadSearch(limit, again if found is None else _merged(found, again, fill), probe)


#: Loads of the first solve of `limit_load_search`'s held-creep path, as shares of the
#: traction ceiling, each tried where the one before was not admissible [-]: its creeps
#: and actual ratio start the search, and their change from zero load tells the sign in
#: which each creep grows.
START_SHARES = (0.1, 0.02, 0.004)
#: Newton iterations a pass of that first solve may take [-]: from zero load's creeps it
#: converges in some five where the load is admissible; one beyond the capacity ran to
#: ``max_iterations`` (40) and took most of the capacity search's time (issue 26). It is
#: not left to the point solver either: where it fails, the next share is tried.
START_ITERATIONS = 12
#: Relative tolerance of that first solve's fixed point on the actual ratio [-]: only its
#: creeps are used, scaled to the creep limit (`ballcvt.solvers.planetary_pinned`), and
#: whether it is admissible. Two passes where 1e-13 took five: the held search then
#: found the same loads to 1e-14 (a map of each mode at 300 rpm, session 39).
START_RTOL = 1e-4


#: Relative distance [-] within which the confirming solve of a held-creep load must find
#: the held disc creep (the larger disc creep at the held value): the same equilibrium as
#: the held search's. Along a mode's branch from zero load the load can pass a maximum (a
#: fold) before a creep reaches the limit, even under a traction law whose traction rises
#: with the creep; the held search then lands on the branch beyond the fold, at a lower
#: load, and the solve there finds the branch from zero load with its creeps far below the
#: limit (harden task 3904:25888: 0.072 against 0.152, a capacity 0.2 % short of the
#: fold). Such a load goes to the bisection.
HELD_MATCH = 1e-4


def _held_limits(drive, mode, at_solved, zero_hi, options):
    """`limit_load_search`'s loads at a held creep (NaN where none is confirmed by an
    admissible solve), the points solved there and `LoadSearch.probe` (``at_solved``: the
    points and their ``solved(size, rows)``; ``zero_hi``: the zero-load batch and the
    traction ceilings)."""
    at, solved = at_solved
    zero, hi = zero_hi
    n = hi.size
    first = np.full(n, np.nan)
    tau, x = np.full(n, np.nan), np.full((n, zero.creep.shape[0]), np.nan)
    for share in START_SHARES:
        idx = np.flatnonzero((zero.status == Status.CONVERGED) & np.isnan(first))
        if idx.size == 0:
            break
        probe = solved(share * hi[idx], idx, (zero.actual_ratio[idx], zero.creep[:, idx]), True)
        keep = probe.status == Status.CONVERGED
        j = idx[keep]
        first[j], tau[j], x[j] = share * hi[j], probe.actual_ratio[keep], probe.creep[:, keep].T
    idx = np.flatnonzero(np.isfinite(first))
    change = x[idx] - zero.creep[:, idx].T
    load = held_creep_loads(drive, mode, _rows(at, at.load_torque[idx], idx),
                            (tau[idx], x[idx], change), options)  # fmt: skip
    above = load > first[idx]  # (NaN: none)
    idx, load = idx[above], load[above]
    limit = np.full(n, np.nan)
    # confirmed from the cold start, as `solve` reaches it: started from the held search's
    # solution, a confirming solve kept a load with a creep at the limit, 0.288, where
    # `solve` found no equilibrium (harden task 3804:471, a disc held, visco-elastic law)
    found = solved(load, idx).expand(idx, n, Status.NOT_CONVERGED)
    disc = np.max(np.abs(found.creep[[0, -1]][:, idx]), axis=0)  # NaN where it failed
    pin = float(drive.design.creep_limit) * (1.0 - PIN_MARGIN)
    ok = (found.status[idx] == Status.CONVERGED) & (disc >= pin * (1.0 - HELD_MATCH))
    limit[idx[ok]] = load[ok]
    return limit, found, (first, x.T)


def _merged(first: ModeBatch, second: ModeBatch, rows) -> ModeBatch:
    """``first`` with the points ``rows`` replaced by ``second``'s (batches of one size)."""
    values = []
    for f in fields(first):
        mine, theirs = np.array(getattr(first, f.name)), getattr(second, f.name)
        mine[..., rows] = theirs[..., rows]
        values.append(mine)
    return ModeBatch(*values)


def _bisected(status, hi, multiple: bool, bisection) -> np.ndarray:
    """The doubling from the traction ceilings ``hi`` [N m] and the bisection of
    `limit_load_search` (``status(size, rows)``: the statuses of the points ``rows`` at the
    loads ``size``; ``multiple``: a law with more than one equilibrium; ``bisection``: its
    ``(rtol, max_steps)``), for points admissible at zero load; returns ``lo`` [N m]."""
    rtol, max_steps = bisection
    everyone = np.arange(hi.size)
    lo = np.zeros(hi.size)
    for _ in range(12):  # double until beyond the capacity
        up = status(hi, everyone) == Status.CONVERGED
        if not up.any():
            break
        lo, hi = np.where(up, hi, lo), np.where(up, 2.0 * hi, hi)
    top = hi.copy()
    probes = PROBES if not multiple else 0
    for attempt in range(probes + 1):
        lo, hi, failed = _bisect(lambda size: status(size, everyone), (lo, hi), rtol, max_steps)
        again = np.flatnonzero(failed & (hi * (1.0 + PROBE) < top))
        if attempt == probes or again.size == 0:
            break
        above = hi[again] * (1.0 + PROBE)
        good = status(above, again) == Status.CONVERGED
        lo[again[good]], hi[again[good]] = above[good], top[again[good]]
        if not good.any():
            break
    return lo


def _bisect(status, bracket, rtol, max_steps):
    """Bisect each point's bracket ``(lo, hi)`` [N m] on ``status(load) == CONVERGED`` to
    ``rtol``; returns ``lo``, ``hi`` and whether each ``hi`` was last set by a failed solve
    (``NOT_CONVERGED``)."""
    lo, hi = (np.array(b, dtype=float) for b in bracket)
    failed = np.zeros(lo.size, dtype=bool)
    for _ in range(max_steps):
        if np.all(hi - lo <= rtol * hi):
            break
        mid = 0.5 * (lo + hi)
        got = status(mid)
        up = got == Status.CONVERGED
        lo, hi = np.where(up, mid, lo), np.where(up, hi, mid)
        failed = np.where(up, failed, got == Status.NOT_CONVERGED)
    return lo, hi, failed


def _rows(point: ModePoint, load: np.ndarray, rows: np.ndarray) -> ModePoint:
    """The points ``rows`` of a batch ``point`` (ratio and driver speed ``(n,)``) at the
    loads ``load`` [N m] (of those points)."""
    return replace(
        point,
        ratio=point.ratio[rows],
        load_torque=load,
        driver_speed=point.driver_speed[rows],
    )
