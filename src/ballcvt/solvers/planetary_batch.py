"""Planetary modes over many points, batched through the fast solver (docs/model.md §13).

`solve_mode_batch` is `ballcvt.solvers.planetary.solve_mode` on a batch: every pass of the
fixed point on the actual ratio is one batched solve. `limit_load_batch` finds the capacity
per mode by bisection on the load.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..equilibrium.problem import OperatingInputs, make_problem
from ..equilibrium.residual import balancing_output_torque
from ..model.architectures import contact_layout
from ..model.inertia import max_carrier_speed
from ..model.modes import MEMBERS, OperatingMode, member_torques, resolve_mode
from ..model.traction.base import has_multiple_equilibria
from ..params.drive import Drive
from ..performance.efficiency import LOSS_KINDS, loss_breakdown, power_losses
from ..status import Status
from .limit import traction_ceiling_torque
from .newton import initial_creep, solve_batch
from .options import SolverOptions
from .planetary import ModePoint, carrier_frame_problem, ratio_settles, ratio_tolerance

__all__ = ["ModeBatch", "solve_mode_batch", "limit_load_batch", "PROBE", "PROBES"]

#: Relative step above the bisection's end at a failed solve at which `limit_load_batch`
#: solves again [-] (twice its default ``rtol``), and how many times it goes on from there.
PROBE = 2e-3
PROBES = 2


@dataclass(frozen=True)
class ModeBatch:
    """Outcome of `solve_mode_batch`; arrays ``(n,)`` (speeds and torques ``(3, n)`` in
    the order of `ballcvt.model.modes.MEMBERS`), NaN where ``status`` (a
    `ballcvt.status.Status` code) is not ``CONVERGED``; ``losses`` [W] is ``(k, n)``, one
    row per kind of `ballcvt.performance.efficiency.LOSS_KINDS` (``loss`` is its total)."""

    status: np.ndarray
    speeds: np.ndarray
    torques: np.ndarray
    loss: np.ndarray
    actual_ratio: np.ndarray
    max_creep: np.ndarray
    circulating_power: np.ndarray
    losses: np.ndarray

    @property
    def powers(self) -> np.ndarray:
        """Power into the drive through each member [W], ``(3, n)``."""
        return self.torques * self.speeds

    @property
    def input_power(self) -> np.ndarray:
        """Power into the drive: the sum of the members' positive powers [W]."""
        return np.sum(np.maximum(self.powers, 0.0), axis=0)

    @property
    def eta(self) -> np.ndarray:
        """Power out over power in [-] (as `PlanetaryResult.eta`)."""
        p_in = self.input_power
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(p_in > 0, np.sum(np.maximum(-self.powers, 0.0), axis=0) / p_in, np.nan)

    def braking_direction(self, mode: OperatingMode) -> np.ndarray:
        """Sign of a load that brakes the driven member: that of its speed in this batch
        (solved at zero load), +1 where it is zero or unknown."""
        return np.where(np.nan_to_num(self.speeds[MEMBERS.index(mode.driven)]) < 0, -1.0, 1.0)


def solve_mode_batch(
    drive: Drive,
    mode: OperatingMode | str,
    point: ModePoint,
    options: SolverOptions = SolverOptions(),
    max_passes: int = 30,
) -> ModeBatch:
    """`solve_mode` on a batch of points, batched through the fast solver.

    ``point.ratio``, ``point.load_torque`` and ``point.driver_speed`` broadcast to
    ``(n,)``; ``mode`` is an `OperatingMode` or a name of
    `ballcvt.registry.OPERATING_MODES`. Every pass of the
    fixed point on the actual ratio is one `solve_batch` of the points not yet settled;
    a point's figures are taken from the pass in which it settles. Points whose speeds are
    out of range are flagged (``Status.OUT_OF_RANGE``), not raised; points whose creeps exceed
    ``design.creep_limit`` are flagged 1.
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
    w_max = float(max_carrier_speed(design, layout, clamp_force)) if mode.centrifugal else np.inf
    status = np.full(n, int(Status.NOT_CONVERGED))
    tau = ratio.copy()
    x = np.full((n, layout.n_contacts), np.nan)
    speeds, torques = np.full((3, n), np.nan), np.full((3, n), np.nan)
    loss, circ, big = (np.full(n, np.nan) for _ in range(3))
    kinds = np.full((len(LOSS_KINDS), n), np.nan)
    settled = np.zeros(n, dtype=bool)
    ratio_tol = ratio_tolerance(options, drive.fluid)
    last = np.full(n, np.inf)  # each point's last change of the ratio
    for _ in range(max_passes):
        sp = mode.speeds(w, tau, check=False)
        rel = sp["disc0"] - sp["carrier"]
        ok = (
            np.isfinite(rel)
            & (np.abs(rel) > 0)
            & np.isfinite(sp["carrier"])
            & (np.abs(sp["carrier"]) < w_max)
        )
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
        sol = solve_batch(pb, options, np.where(np.isnan(x[todo]), initial_creep(pb), x[todo]))
        st = sol.state
        x[todo] = st.creep
        new = st.omega[:, -1] / st.omega[:, 0]
        change = np.abs(new - tau[todo])
        done = ~sol.converged | ratio_settles(change, last[todo], tau[todo], ratio_tol)
        last[todo] = change
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
        tau[todo] = np.where(sol.converged, new, tau[todo])
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
    )


def limit_load_batch(
    drive: Drive,
    mode: OperatingMode | str,
    point: ModePoint,
    options: SolverOptions = SolverOptions(),
    rtol: float = 1e-3,
    max_steps: int = 40,
) -> np.ndarray:
    """Largest load torque of the driven member with every ``|C| <= creep_limit``
    (``drive.design.creep_limit``).

    ``point.ratio`` and ``point.driver_speed`` are the batch; ``point.load_torque`` only
    gives the direction of the load searched, by its sign where it is finite and non-zero
    (an overhauling load, negative to the driven member's speed, has its own capacity).

    Elsewhere the load brakes the driven member: its sign is that of the driven speed at
    zero load (positive at geared neutral). Bracketed by doubling from the carrier-frame
    traction ceiling, then bisected to ``rtol`` on all ratios at once (`solve_mode_batch`).
    Where the bisection ends at a load whose solve failed (not one beyond the creep
    limit), the load `PROBE` above it is solved: where that one is admissible, the failure
    was the solver's, not the capacity's edge, and the bisection goes on above it (up to
    `PROBES` times; not under a law with more than one equilibrium, where a failed solve
    is the continuation's verdict: the load lies past the fold of the branch from zero).

    Returns
    -------
    ndarray
        ``|L|`` at the limit [N m], ``(n,)``; NaN where even zero load is not admissible or
        the speeds are out of range.
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
    zero = solve_mode_batch(drive, mode, replace(at, load_torque=0.0), options)
    chosen = np.isfinite(given) & (given != 0.0)
    direction = np.where(
        chosen, np.sign(np.where(chosen, given, 1.0)), zero.braking_direction(mode)
    )
    ok0 = zero.status == Status.CONVERGED

    def status(size, rows=None):  # of the loads ``size`` [N m] of the points ``rows`` (all)
        here = (
            replace(at, load_torque=direction * size)
            if rows is None
            else _rows(at, direction[rows] * size, rows)
        )
        return solve_mode_batch(drive, mode, here, options).status

    hi = traction_ceiling_torque(
        make_problem(drive, OperatingInputs(ratio, 0.0, point.clamp_force, 1.0))
    )
    lo = np.zeros(ratio.size)
    for _ in range(12):  # double until beyond the capacity
        up = (status(hi) == Status.CONVERGED) & ok0
        if not up.any():
            break
        lo, hi = np.where(up, hi, lo), np.where(up, 2.0 * hi, hi)
    top = hi.copy()
    probes = PROBES if not has_multiple_equilibria(drive.fluid) else 0
    for attempt in range(probes + 1):
        lo, hi, failed = _bisect(status, (lo, hi), ok0, rtol, max_steps)
        again = np.flatnonzero(failed & ok0 & (hi * (1.0 + PROBE) < top))
        if attempt == probes or again.size == 0:
            break
        above = hi[again] * (1.0 + PROBE)
        good = status(above, again) == Status.CONVERGED
        lo[again[good]], hi[again[good]] = above[good], top[again[good]]
        if not good.any():
            break
    return np.where(ok0, lo, np.nan)


def _bisect(status, bracket, ok0, rtol, max_steps):
    """Bisect each point's bracket ``(lo, hi)`` [N m] on ``status(load) == CONVERGED`` to
    ``rtol`` (the points not ``ok0`` left as they are); returns ``lo``, ``hi`` and whether
    each ``hi`` was last set by a failed solve (``NOT_CONVERGED``)."""
    lo, hi = (np.array(b, dtype=float) for b in bracket)
    failed = np.zeros(lo.size, dtype=bool)
    for _ in range(max_steps):
        if np.all(~ok0 | (hi - lo <= rtol * hi)):
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
