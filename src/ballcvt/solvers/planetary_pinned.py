"""The capacity of a planetary mode at a held creep (docs/model.md §8, §13; issue 26).

A mode's capacity is the largest load of its driven member with every ``|C| <=
creep_limit``. Under a traction law whose traction never falls with the creep the creeps
grow with the load, so it is the load at which a disc contact's creep reaches the limit
first. As for the carrier-held drive (`ballcvt.solvers.limit`), that creep is held
`PIN_MARGIN` below the limit and the balances other than the torque condition are solved
(`ballcvt.solvers.newton.solve_pinned`): the torque condition's value at that solution
gives the load. The carrier-frame speeds depend on the actual ratio, so each held solve
is one pass of the fixed point of `ballcvt.solvers.planetary_batch.solve_mode_batch` on
it (`ballcvt.solvers.planetary.next_ratio`). One such search replaces the dozen batches
of solves of a bisection on the load; `ballcvt.solvers.planetary_batch.limit_load_batch`
confirms its answers by a solve there and bisects where one fails.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..model.modes import OperatingMode
from .limit import PIN_MARGIN
from .newton import solve_pinned
from .planetary import ModePoint, RatioPasses, carrier_frame_problem
from .planetary_speeds import (
    carrier_speed_bound,
    member_speeds,
    relative_ratio,
)

__all__ = ["held_creep_loads", "carrier_speed_bound", "member_speeds", "relative_ratio"]


def held_creep_loads(drive, mode: OperatingMode, point: ModePoint, start, options):
    """The loads of the driven member [N m] at which a disc contact's creep reaches the
    creep limit (module docstring), magnitudes ``(n,)``; NaN where neither disc contact
    gives one with every creep within the limit.

    Parameters
    ----------
    drive : Drive
        Design (its ``creep_limit``), fluid and architecture.
    mode : OperatingMode
        Held and driving members.
    point : ModePoint
        ``ratio`` and ``driver_speed`` ``(n,)``; ``load_torque`` the direction of the load
        (its sign) ``(n,)``.
    start : tuple of ndarray
        An admissible solved load of each point: the actual (relative) ratio ``(n,)``
        [-], the carrier-frame creeps ``(n, n_c)`` [-] and each creep's change from zero
        load ``(n, n_c)`` [-], whose sign is the one it grows in. The disc contact held
        first is the one whose creep reaches the limit at the lower load, extrapolated
        along that change (with its signs alone: the disc nearer its limit; that choice
        held the wrong disc first at some ratios of Table I's map with disc 2 driving and
        the carrier held, then a second search held the other: the map took 6 % longer).
    options : SolverOptions
        Solver options.
    """
    tau0, x0, change = (np.asarray(v, dtype=float) for v in start)
    n, nc = x0.shape
    pin = float(drive.design.creep_limit) * (1.0 - PIN_MARGIN)
    load = np.full(n, np.nan)
    growth = np.sign(change)
    with np.errstate(divide="ignore", invalid="ignore"):
        reach = (pin - np.abs(x0[:, [0, -1]])) / np.abs(change[:, [0, -1]])  # in loads
    first = np.where(~(reach[:, 1] < reach[:, 0]), 0, nc - 1)  # the disc at its limit first
    usable = np.all(np.isfinite(x0), axis=-1) & np.all(growth[:, [0, -1]] != 0, axis=-1)
    for attempt in range(2):  # the other disc where the first one's load is inadmissible
        idx = np.flatnonzero(usable & np.isnan(load))
        if idx.size == 0:
            break
        k = first[idx] if attempt == 0 else nc - 1 - first[idx]  # one batch, either disc
        x, tau = _held_start(point.ratio[idx], x0[idx], growth[idx], (k, pin))
        got = _held(drive, mode, _rows(point, idx), (tau, x), (k, pin), options)
        load[idx] = got
    return load


def _held_start(ideal, x0, growth, held):
    """The creeps ``(n, n_c)`` and actual ratios ``(n,)`` a held search starts from: the
    start's creeps scaled as creep ``k`` of ``held = (k, pin)`` (one per point) to its
    limit ``pin``, in the sign it grows in, each within the limit (from the start's load the
    creeps grow near in proportion: the first held solve took 13 iterations from the
    start's creeps with both discs' set to the limit, 10 so), and the ratio they give
    (`relative_ratio`)."""
    k, pin = held
    rows = np.arange(x0.shape[0])
    with np.errstate(divide="ignore", invalid="ignore"):
        x = np.clip(x0 * (pin / np.abs(x0[rows, k]))[:, None], -pin, pin)
    x[rows, k] = growth[rows, k] * pin
    return x, relative_ratio(ideal, x)


def _held(drive, mode, point, start, held, options, max_passes: int = 30) -> np.ndarray:
    """The fixed point on the actual ratio with creep ``k`` of ``held = (k, pin)`` (one
    contact, or one per point) held at its value in the start: the load magnitudes [N m]
    ``(n,)`` (NaN where a solve failed, the speeds left their range, a creep passed
    ``pin`` or the load does not brake)."""
    k, pin = held
    tau, x = (np.array(v, dtype=float) for v in start)
    n = tau.size
    ratio, direction, w = (np.broadcast_to(np.asarray(v, dtype=float), (n,))
                           for v in (point.ratio, point.load_torque, point.driver_speed))  # fmt: skip
    bound = carrier_speed_bound(drive, mode, point.clamp_force)
    per_load = mode.torque_condition(1.0)[2]  # the target per unit load: +1 or -1
    load, passes = np.full(n, np.nan), RatioPasses(n, options, drive.fluid)
    todo = np.arange(n)
    for _ in range(max_passes):
        sp, ok = member_speeds(mode, w[todo], tau[todo], bound)
        todo, sp = todo[ok], {m: v[ok] for m, v in sp.items()}
        if todo.size == 0:
            break
        sub = ModePoint(ratio[todo], 0.0, w[todo], point.clamp_force)
        pb, sign = carrier_frame_problem(drive, mode, sub, sp)
        t2, sol = solve_pinned(pb, np.broadcast_to(k, (n,))[todo], x[todo], options)
        st = sol.state
        a, b = pb.torque_weights
        here = direction[todo] * sign * (a * st.input_torque + b * t2) / per_load
        x[todo] = st.creep
        new = st.omega[:, -1] / st.omega[:, 0]
        settled = passes.settles(tau, new, todo)
        within = np.max(np.abs(st.creep), axis=-1) <= pin * (1.0 + 1e-9)
        good = sol.converged & settled & within & (here > 0.0)
        load[todo[good]] = here[good]
        tau[todo] = passes.step(tau, new, todo)
        todo = todo[sol.converged & ~settled & within]
        if todo.size == 0:
            break
    return load


def _rows(point: ModePoint, rows) -> ModePoint:
    """The points ``rows`` of a batch ``point`` (ratio, load and driver speed ``(n,)``)."""
    return replace(point, ratio=point.ratio[rows], load_torque=point.load_torque[rows],
                   driver_speed=point.driver_speed[rows])  # fmt: skip
