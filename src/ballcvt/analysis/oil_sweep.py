"""Scattered points and limit curves under the oil's heat balance, each at its own oil
temperature (docs/model.md §15; the method: `ballcvt.analysis.oil_paths`; a sweep's grid:
`ballcvt.analysis.oil_grid`).

Points (`balanced_rows`: studies, uncertainty) are solved at each rung of the
ladder of oil temperatures, interpolated to their balance temperature and then solved
once more at it (`settle`); each curve's limiting torque (`balanced_limits`) is found at
the temperature its limit point produces (the limit point solved at each rung; the rungs
climb on for the limits as far as they need), then moved to where the balanced point flips
between carried and refused (`balanced_tops`).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import xarray as xr
from scipy.optimize import brentq

from ..errors import InputError
from ..model.clamping import clamp_law as clamp_law_of
from ..model.oil import fluid_at
from ..params.drive import Drive
from ..params.models import Design, Fluid
from ..performance.efficiency import LOSS_KINDS
from ..solvers.limit import LimitSearch
from ..status import Status
from .oil_paths import (
    BALANCED,
    LIMIT_STEP,
    Ladder,
    balance_weights,
    bracketing,
    climb,
    interpolate,
    nearest,
    runaway_status,
    runaways_at_top,
)
from .sweeps.curves import OperatingRows, limit_search_curves
from .sweeps.points import evaluate_points

__all__ = [
    "settle",
    "curve_rows",
    "moved_tops",
    "balanced_limits",
    "balanced_rows",
    "at_own_oil",
    "limits_at_own_oil",
    "balanced_tops",
    "inward_trial",
    "outward_trial",
    "limit_ladder",
    "oil_balance_of",
    "LIMIT_SHY",
]

#: The limit point is solved this fraction below the limiting torque (at the limit itself
#: the admissibility test may fall either way by round-off) [-].
LIMIT_SHY = 1e-6
#: Relative resolution [-] of the search for where a balanced point flips between carried
#: and refused, from the ends found at the fixed point's temperature (`balanced_tops`,
#: `ballcvt.api.oil`'s `_balanced_ends`), and its reach above the largest end [-] (an end
#: between two intervals may move as far as its neighbour).
STRETCH_RTOL, STRETCH_MAX = 5e-4, 0.2
#: Tolerance of a row's balance found alone (`_balanced_alone`) [K].
ROOT_TOL = 1e-4


def limit_ladder(rows: OperatingRows, thermal, cached: dict | None = None) -> Ladder:
    """The rows' limits on the ladder of oil temperatures.

    Parameters
    ----------
    rows : OperatingRows
        The curves (ratio, speed, force or law), with the fluid as given.
    thermal : ThermalModel
        The housing.
    cached : dict, optional
        ``{T [K]: (limit torques, efficiencies at them)}`` already found (a sweep's).

    Returns
    -------
    Ladder
        Its results: ``(limit torque [N m], efficiency at the limit [-], LimitSearch or
        None)`` of each row at each rung; its excess, the limit point's (solved
        `LIMIT_SHY` below the limit), climbing while a limit point needs it.
    """
    known = cached or {}

    def at(f: Fluid):
        got = known.get(f.inlet_temperature)  # (fluid_at sets it)
        limit, eta, search, loss = _limit_points(
            _with_fluid(rows, f), None if got is None else got[0]
        )
        return (limit, eta if got is None else got[1], search), loss

    return climb(rows.drive.fluid, thermal, at, LIMIT_STEP)


def _limit_points(rows: OperatingRows, limit=None) -> tuple:
    """``(limit [N m], eta [-], LimitSearch or None, total loss [W])`` of the rows at their
    fluid: their limits (searched unless ``limit`` is given) and their limit points solved
    `LIMIT_SHY` below them (NaN where a row has no limit)."""
    search = None
    if limit is None:
        search = limit_search_curves(rows)[1]
        limit = search.torque.ravel() if search is not None else np.full(rows.size, np.nan)
    point = evaluate_points(rows, np.nan_to_num(limit * (1.0 - LIMIT_SHY), nan=0.0))
    finite = np.isfinite(limit)
    loss = np.where(finite, point["losses"][:, LOSS_KINDS.index("total")], np.nan)
    return limit, np.where(finite, point["eta"], np.nan), search, loss


def balanced_limits(rows: OperatingRows, thermal) -> tuple[np.ndarray, np.ndarray, LimitSearch]:
    """Each row's limiting torque at the oil temperature its limit point produces.

    Returns
    -------
    torque : ndarray
        ``(m,)`` [N m], NaN where none (or where its limit point has no balance).
    temperature : ndarray
        The limit point's oil temperature ``(m,)`` [K].
    search : LimitSearch
        The search at the rung nearest each row's temperature, with ``torque`` the
        balanced limit (its creeps a start for the points near it).
    """
    ladder = limit_ladder(rows, thermal)
    temp, weights, outcome = balance_weights(ladder)
    runaways_at_top(ladder, temp, weights, outcome)
    torque = interpolate(np.stack([r[0] for r in ladder.results]), weights)
    alone = _balanced_alone(rows, thermal, ladder, outcome)
    for i, (t, found) in alone.items():
        torque[i], temp[i] = found.torque.ravel()[0], t
    torque, _, temp = moved_tops(rows, thermal, torque, (torque, temp))
    k = np.abs(ladder.temperatures[:, None] - temp[None, :]).argmin(axis=0)
    searches = [r[2] for r in ladder.results]
    base = searches[0].flat()
    pick = [
        alone[i][1].flat() if i in alone else searches[j].flat().take(np.array([i]))
        for i, j in enumerate(k)
    ]
    search = LimitSearch(
        torque,
        np.concatenate([p.creep for p in pick]) if pick else base.creep,
        np.concatenate([p.creep_zero for p in pick]) if pick else base.creep_zero,
    )
    return torque, np.where(np.isfinite(torque), temp, np.nan), search


def _balanced_alone(rows: OperatingRows, thermal, ladder: Ladder, outcome) -> dict:
    """The rows whose limit point has a balance to seek at one rung and no admissible
    torque at the next (the capacity vanishes between them: harden task 2719:153, a
    capacity of 0.08 N m at 20 C, none at 30 C), each balanced alone between the two: the
    limit at a trial temperature, and its limit point's loss (none where no torque is
    admissible, as `Variator.limit_torque`'s balance takes it), to the temperature where
    it meets the heat the housing rejects (Brent's method, `ROOT_TOL`). ``{row: (T [K],
    LimitSearch of the row there)}``; a row whose balance is not bracketed so is left
    out."""
    out = {}
    temps = ladder.temperatures
    for i in np.flatnonzero(outcome >= 1):
        j = int(outcome[i])
        if not ladder.excess[j - 1, i] > 0.0:
            continue
        one = rows.take(np.array([i]))
        found: dict = {}

        def excess(t: float, one=one, found=found) -> float:
            limit, _, search, loss = _limit_points(_with_fluid(one, fluid_at(rows.drive.fluid, t)))
            if np.isfinite(limit[0]):
                found[t] = search
            heat = float(loss[0]) if np.isfinite(limit[0]) else 0.0
            return heat - thermal.conductance * (t - thermal.ambient_temperature)

        try:
            root = brentq(excess, temps[j - 1], temps[j], xtol=ROOT_TOL)
        except ValueError:  # (a NaN loss, or no change of sign: left as it was)
            continue
        below = [t for t in found if t <= root]
        if below:  # the warmest trial at or below the root with an admissible torque
            t = max(below)
            out[int(i)] = (t, found[t])
    return out


def curve_rows(design: Design, fluid: Fluid, ds: xr.Dataset, request) -> OperatingRows:
    """The curves of a sweep dataset as rows (in the C order of its ``limit_torque``)."""
    if ds.sizes["architecture"] != 1:
        raise InputError(
            "architecture",
            ", ".join(ds["architecture"].values),
            "one architecture under the oil's heat balance",
        )
    law = None
    if "clamp_force" not in ds["limit_torque"].dims:  # a law sets the force
        law = clamp_law_of(request.clamp_law, design, request.clamp_force)
    axes = [ds["input_speed"].values, ds["ratio"].values]
    axes = ([ds["clamp_force"].values] if law is None else []) + axes
    grid = [g.ravel() for g in np.meshgrid(*axes, indexing="ij")]
    drive = Drive(design, fluid, str(ds["architecture"].values[0]))
    force = grid[0] if law is None else None
    c_lim = float(ds.attrs["creep_limit"])
    return OperatingRows(drive, grid[-1], grid[-2], force, law, request.options, c_lim)


def oil_balance_of(design: Design):
    """The housing ``[design.thermal]`` when the drive's ``[models]`` name the oil's
    balance, else None (the fluid as given)."""
    models = design.models
    named = getattr(models, "oil_temperature", None) if models is not None else None
    return design.thermal if named == "balance" and design.thermal is not None else None


def at_own_oil(rows: OperatingRows, evaluate) -> tuple[np.ndarray, dict]:
    """``evaluate`` (as `balanced_rows` takes it) of the rows under the oil model their
    drive file names: each point at its own oil balance where it names the balance
    (`balanced_rows`), else with the fluid as given."""
    thermal = oil_balance_of(rows.drive.design)
    if thermal is None:
        return evaluate(rows, slice(None))
    return balanced_rows(rows, thermal, evaluate)


def limits_at_own_oil(rows: OperatingRows) -> np.ndarray:
    """The rows' limiting torques [N m] under the oil model their drive file names: at the
    oil temperature each limit point produces where it names the balance
    (`balanced_limits`), else with the fluid as given."""
    thermal = oil_balance_of(rows.drive.design)
    if thermal is None:
        return limit_search_curves(rows)[1].torque
    return balanced_limits(rows, thermal)[0]


def balanced_rows(rows: OperatingRows, thermal, evaluate) -> tuple[np.ndarray, dict]:
    """Scattered points (`evaluate_points`' rows) each at its oil balance.

    ``evaluate(rows, idx) -> (output torque [N m] (m,), evaluate_points' dict)`` solves
    the rows ``rows`` (the points ``idx`` of ``rows``, an index or a slice) at their fluid
    (e.g. at a given input power); returned interpolated to each point's balance, with
    ``oil_temperature`` [K] (NaN where not solved) and the status of the rung nearest (a
    runaway's 2), then each balanced point solved at its own temperature (`settle`).
    """

    def at(f: Fluid):
        t2, res = evaluate(_with_fluid(rows, f), slice(None))
        ok = res["status"] == 0
        return (t2, res), np.where(ok, res["losses"][:, LOSS_KINDS.index("total")], np.nan)

    ladder = climb(rows.drive.fluid, thermal, at)
    temp, weights, outcome = balance_weights(ladder)
    res = {}
    for key in ladder.results[0][1]:
        stack = np.stack([r[1][key] for r in ladder.results])
        if key == "status":
            res[key] = runaway_status(nearest(stack, ladder, temp, outcome), outcome)
        elif np.issubdtype(stack.dtype, np.floating):
            res[key] = interpolate(stack, weights)
    t2 = interpolate(
        np.stack([np.broadcast_to(r[0], temp.shape) for r in ladder.results]), weights
    )
    res["oil_temperature"] = np.where(res["status"] == 0, temp, np.nan)
    settle(rows, (thermal, evaluate), (ladder, temp, outcome), (t2, res))
    return t2, res


def settle(rows: OperatingRows, how, balance, out, only=None) -> None:
    """Each point balanced between two rungs solved once more at its own temperature,
    in place in ``out`` = ``(t2, res)`` of `balanced_rows` (``how`` = ``(thermal,
    evaluate)``, ``balance`` = ``(ladder, temperature, outcome)``; ``only``: a mask of
    the points to settle, all when None; ``evaluate``'s ``losses`` have the total last, as
    `LOSS_KINDS` and a sweep's `SWEEP_LOSSES`): one Newton step on its
    balance from the interpolated temperature (the excess solved there, the slope the
    secant of the rungs either side), then the point solved at that temperature. The
    polynomial through the rungs cannot follow a kink of a point's efficiency in the
    temperature: 1.7e-4 off `Variator.solve`'s on a 48 rpm cam drive (harden task
    4242:31, docs/model.md §15); solved at its own temperature, to the balance's own
    tolerance."""
    thermal, evaluate = how
    ladder, temp, outcome = balance
    t2, res = out
    below, above = bracketing(ladder, temp)
    n = np.arange(temp.size)
    e, t = ladder.excess, ladder.temperatures
    slope = (e[above, n] - e[below, n]) / np.where(above > below, t[above] - t[below], np.nan)
    todo = (outcome == BALANCED) & (res["status"] == 0) & (above > below)
    todo &= np.isfinite(slope) & (slope < 0.0) & (True if only is None else only)
    for i in np.flatnonzero(todo):
        one = rows.take(np.array([i]))
        got = evaluate(_with_fluid(one, fluid_at(rows.drive.fluid, temp[i])), [i])
        loss = got[1]["losses"][0, -1]  # the total
        excess = loss - thermal.conductance * (temp[i] - thermal.ambient_temperature)
        if not np.isfinite(excess):
            continue
        t_oil = float(np.clip(temp[i] - excess / slope[i], t[below[i]], t[above[i]]))
        t_i, got = evaluate(_with_fluid(one, fluid_at(rows.drive.fluid, t_oil)), [i])
        for key in res:
            if key in got:
                res[key][i] = got[key][0]
        t2[i] = np.broadcast_to(t_i, (1,))[0]
        res["oil_temperature"][i] = t_oil if got["status"][0] == 0 else np.nan


def balanced_tops(rows: OperatingRows, thermal, top) -> np.ndarray:
    """Each row's largest torque [N m] moved from ``top`` to where the row, solved at its
    own oil balance (`balanced_rows`), flips between carried (`Status.CONVERGED`: within
    the creep limit and, under a torque-following law, ``max_pressure``) and refused (a
    runaway of the oil included), to `STRETCH_RTOL`.

    ``top`` is the limit of the fluid at the temperature its limit point produces (the
    ladder's fixed point ``t = L(T(t))``); every other torque runs at its own balance, so
    the flip lies elsewhere where the losses change with the temperature, or where the
    limit point's oil runs away (docs/model.md §15). As `ballcvt.api.oil` moves
    `Variator.limit_torque`, batched: from ``top`` in steps growing fourfold from
    `STRETCH_RTOL` (outwards as far as `STRETCH_MAX` above it where it is carried, else
    inwards towards zero), then bisection; every step one balanced solve of the rows still
    searching. A row carried nowhere below ``top`` has the limit 0 if it carries zero
    torque, else none (NaN): its oil runs away at every torque, say (harden task 2720:23,
    where the 150 C oil's limit was kept, refused by `Variator.solve`; the scalar path
    then raises why).
    """
    out = np.array(top, dtype=float)
    idx = np.flatnonzero(np.isfinite(out) & (out > 0.0))
    if idx.size == 0:
        return out
    rows, end = rows.take(idx), out[idx]
    ok = _carries(rows, thermal, end)
    inside, outside = np.where(ok, end, np.nan), np.where(ok, np.nan, end)
    reach, k = end * (1.0 + STRETCH_MAX), 0
    while True:  # bracket: outwards where carried, inwards (towards zero) where refused
        inward = inward_trial(end, 0.0, k)
        up, down = np.isnan(outside), np.isnan(inside) & np.isfinite(inward)
        live = up | down
        if not live.any():
            break
        trial = np.where(up, outward_trial(end, reach, k), inward)[live]
        ok = _carries(rows.take(np.flatnonzero(live)), thermal, trial)
        at_reach = up[live] & (trial == reach[live])
        inside[live] = np.where(ok, trial, inside[live])
        outside[live] = np.where(ok & ~at_reach, outside[live], trial)
        k += 1
    while True:  # bisect the brackets
        live = np.isfinite(inside) & (np.abs(outside - inside) > STRETCH_RTOL * inside)
        if not live.any():
            break
        mid = 0.5 * (inside + outside)[live]
        ok = _carries(rows.take(np.flatnonzero(live)), thermal, mid)
        inside[live] = np.where(ok, mid, inside[live])
        outside[live] = np.where(ok, outside[live], mid)
    nowhere = np.flatnonzero(np.isnan(inside))
    if nowhere.size:  # refused down to the smallest torque tried: zero torque decides
        zero = _carries(rows.take(nowhere), thermal, np.zeros(nowhere.size))
        inside[nowhere] = np.where(zero, 0.0, np.nan)
    out[idx] = inside
    return out


def outward_trial(end, reach, k) -> np.ndarray:
    """The ``k``-th torque [N m] tried from a carried ``end`` towards ``reach`` for where a
    balanced point stops being carried: steps growing fourfold from `STRETCH_RTOL` of
    ``end``, ``reach`` itself once a step would pass it."""
    end, reach = np.asarray(end, dtype=float), np.asarray(reach, dtype=float)
    side = np.sign(reach - end)
    trial = end + side * STRETCH_RTOL * 4.0**k * np.abs(end)
    return np.where(side * (trial - reach) >= 0.0, reach, trial)


def inward_trial(end, stop, k) -> np.ndarray:
    """The ``k``-th torque [N m] tried from a refused ``end`` towards ``stop`` (the
    interval's other end) for where a balanced point starts to be carried: steps growing
    fourfold from `STRETCH_RTOL` of ``end`` while under half the span, then the distance
    left to ``stop`` halved, down to `STRETCH_RTOL` of the span; NaN past the last.
    (Fourfold steps alone stopped at half the span: a flip further in, e.g. an oil
    runaway at 45 % of the 150 C oil's limit, left the limit where solve refuses.)"""
    end, stop, k = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (end, stop, k)))
    span, side = np.abs(end - stop), np.sign(end - stop)
    first = STRETCH_RTOL * np.abs(end)
    with np.errstate(divide="ignore", invalid="ignore"):
        n_near = np.maximum(np.ceil(np.log(0.5 * span / first) / np.log(4.0)), 0.0)
    left = 0.5 ** (k - n_near + 1.0)  # share of the span left to ``stop`` (far steps)
    trial = np.where(k < n_near, end - side * first * 4.0**k, stop + side * span * left)
    return np.where((k < n_near) | (left >= STRETCH_RTOL), trial, np.nan)


def _carries(rows: OperatingRows, thermal, torque: np.ndarray) -> np.ndarray:
    """Whether each row carries its ``torque`` [N m] at its own oil balance, judged as
    `ballcvt.api.oil`'s scalar path judges it: the balance from the losses of every
    converged point, within the capacity or beyond it (as `Variator.solve` with
    ``check_capacity=False`` gives them), and the verdict at that temperature: the rungs'
    either side where they agree, else the row solved at its own temperature (a rung up
    to 0.5 K away decided it before: the limit 0.17 % off, docs/model.md §15). A row not
    converged at a rung below its balance, or running away, is refused."""
    total = LOSS_KINDS.index("total")

    def at(f: Fluid):
        res = evaluate_points(_with_fluid(rows, f), torque, beyond=True)
        return res["status"] == Status.CONVERGED, res["losses"][:, total]

    ladder = climb(rows.drive.fluid, thermal, at)
    temp, _, outcome = balance_weights(ladder)
    below, above = bracketing(ladder, temp)
    ok = np.stack(ladder.results)
    n = np.arange(temp.size)
    carried = ok[below, n] & ok[above, n] & (outcome == BALANCED)
    for i in np.flatnonzero((outcome == BALANCED) & (ok[below, n] != ok[above, n])):
        one = _with_fluid(rows.take(np.array([i])), fluid_at(rows.drive.fluid, temp[i]))
        carried[i] = evaluate_points(one, torque[i : i + 1])["status"][0] == Status.CONVERGED
    return carried


def _with_fluid(rows: OperatingRows, fluid: Fluid) -> OperatingRows:
    """``rows`` with the drive's fluid ``fluid``."""
    return replace(rows, drive=replace(rows.drive, fluid=fluid))


def moved_tops(rows: OperatingRows, thermal, top: np.ndarray, at_top: tuple) -> tuple:
    """``(top, eta, oil temperature)`` with the tops moved (`balanced_tops`); a moved
    row's efficiency and oil temperature those of its new limit point (`LIMIT_SHY` below
    it), the others' ``at_top`` as given."""
    eta, temp = (np.array(a, dtype=float) for a in at_top)
    new = balanced_tops(rows, thermal, top)
    moved = np.flatnonzero(np.isfinite(new) & (new != top))
    if moved.size:
        shy = new[moved] * (1.0 - LIMIT_SHY)
        _, res = balanced_rows(
            rows.take(moved), thermal, lambda r, i: (shy[i], evaluate_points(r, shy[i]))
        )
        eta[moved], temp[moved] = res["eta"], res["oil_temperature"]
    return new, eta, temp
