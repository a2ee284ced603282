"""A sweep under the oil's heat balance: each point, and each curve's limiting torque, at
its own oil temperature (docs/model.md §15; the method: `ballcvt.analysis.oil_paths`).

The sweep is run at each rung of the ladder of oil temperatures; each point's quantities
are interpolated to its balance temperature, and each curve's ``limit_torque`` and
``eta_at_limit`` to the temperature its limit point produces (the limit point solved at
each rung; the rungs climb on for the limits as far as they need). The dataset gains
``oil_temperature`` [K] at every point and ``oil_temperature_at_limit`` [K] per curve.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import xarray as xr

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
from .sweeps.grid import SweepRequest, sweep
from .sweeps.points import evaluate_points

__all__ = [
    "balanced_sweep",
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
#: Variables taken at the nearest rung rather than interpolated (counts and codes).
CODES = ("status", "warnings", "iterations")
#: Relative resolution [-] of the search for where a balanced point flips between carried
#: and refused, from the ends found at the fixed point's temperature (`balanced_tops`,
#: `ballcvt.api.oil`'s `_balanced_ends`), and its reach above the largest end [-] (an end
#: between two intervals may move as far as its neighbour).
STRETCH_RTOL, STRETCH_MAX = 5e-4, 0.2


def balanced_sweep(design: Design, fluid: Fluid, thermal, request: SweepRequest) -> xr.Dataset:
    """`ballcvt.analysis.sweeps.grid.sweep` with every point at its oil balance.

    Parameters
    ----------
    design, fluid : Design, Fluid
        The drive (the fluid with its viscosity-temperature data).
    thermal : ThermalModel
        The housing, ``[design.thermal]``.
    request : SweepRequest
        The grid, without ``limit_torque`` (each temperature searches its own).

    Returns
    -------
    xarray.Dataset
        As `sweep`, with ``oil_temperature`` [K] at each point and
        ``oil_temperature_at_limit`` [K] per curve, and the attribute ``oil_model``
        ``"balance"``.
    """
    if request.limit_torque is not None:
        raise InputError(
            "limit_torque",
            "given",
            "None under the oil's heat balance (each temperature searches its own limits)",
        )

    def at(f: Fluid):
        ds = sweep(design, f, request)
        return ds, _points(ds, ds["losses"].sel(loss="total")).ravel()

    ladder = climb(fluid, thermal, at)
    first = ladder.results[0]
    out = _interpolated(ladder, list(first["status"].dims))
    _limits_into(out, design, fluid, thermal, (request, ladder))
    out.attrs.update(first.attrs, oil_model="balance", oil_rungs=len(ladder.temperatures))
    return out


def _limits_into(out: xr.Dataset, design, fluid, thermal, run) -> None:
    """``out`` gains the curves' balanced ``limit_torque``, ``eta_at_limit`` and
    ``oil_temperature_at_limit``; ``run`` is the request and the points' ladder."""
    request, points = run
    first = points.results[0]
    dims = first["limit_torque"].dims
    flat = {
        float(t): tuple(
            r[v].transpose(*dims).values.ravel() for v in ("limit_torque", "eta_at_limit")
        )
        for t, r in zip(points.temperatures, points.results, strict=True)
    }
    ladder = limit_ladder(_curve_rows(design, fluid, first, request), thermal, flat)
    temp, weights, outcome = balance_weights(ladder)
    runaways_at_top(ladder, temp, weights, outcome)
    shape = first["limit_torque"].shape
    rows = _curve_rows(design, fluid, first, request)
    top = interpolate(np.stack([r[0] for r in ladder.results]), weights)
    eta = interpolate(np.stack([r[1] for r in ladder.results]), weights)
    top, eta, temp = _moved(rows, thermal, top, (eta, temp))
    for name, values in (("limit_torque", top), ("eta_at_limit", eta)):
        out[name] = xr.Variable(dims, values.reshape(shape), first[name].attrs)
    temp = np.where(np.isfinite(top), temp, np.nan)
    out["oil_temperature_at_limit"] = xr.Variable(
        dims,
        temp.reshape(shape),
        {"long_name": "oil temperature the limit point produces", "units": "K"},
    )


def _points(ds: xr.Dataset, var: xr.DataArray) -> np.ndarray:
    """``var`` with the point dimensions of ``ds`` (its ``status``'s) first, in order."""
    dims = list(ds["status"].dims)
    return var.transpose(*dims, ...).values


def _interpolated(ladder: Ladder, dims: list[str]) -> xr.Dataset:
    """The variables of the rungs' datasets over ``dims`` at each point's balance."""
    temp, weights, outcome = balance_weights(ladder)
    first = ladder.results[0]
    shape = tuple(first.sizes[d] for d in dims)
    data = {}
    for name, var in first.data_vars.items():
        if tuple(var.dims[: len(dims)]) != tuple(dims):
            continue
        stack = np.stack([r[name].values for r in ladder.results])
        stack = stack.reshape((stack.shape[0], -1) + stack.shape[1 + len(dims) :])
        if name in CODES:
            values = nearest(stack, ladder, temp, outcome)
            values = runaway_status(values, outcome) if name == "status" else values
        else:
            values = interpolate(stack.astype(float), weights)
        data[name] = xr.Variable(var.dims, values.reshape(var.shape).astype(var.dtype), var.attrs)
    status = data.get("status")
    bad = outcome != -1
    temperature = np.where(bad, np.nan, temp).reshape(shape)
    if status is not None:  # a failed point's values are NaN (its rung's status says why)
        temperature = np.where(np.asarray(status.values) == 0, temperature, np.nan)
    data["oil_temperature"] = xr.Variable(
        dims, temperature, {"long_name": "bulk oil temperature (heat balance)", "units": "K"}
    )
    return xr.Dataset(data, coords=first.coords)


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
        r = replace(rows, drive=replace(rows.drive, fluid=f))
        got = known.get(f.inlet_temperature)  # (fluid_at sets it)
        search = None
        if got is None:
            search = limit_search_curves(r)[1]
            limit = search.torque.ravel() if search is not None else np.full(r.size, np.nan)
        else:
            limit = got[0]
        point = evaluate_points(r, np.nan_to_num(limit * (1.0 - LIMIT_SHY), nan=0.0))
        finite = np.isfinite(limit)
        loss = np.where(finite, point["losses"][:, LOSS_KINDS.index("total")], np.nan)
        eta = got[1] if got is not None else np.where(finite, point["eta"], np.nan)
        return (limit, eta, search), loss

    return climb(rows.drive.fluid, thermal, at, LIMIT_STEP)


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
    torque, _, temp = _moved(rows, thermal, torque, (torque, temp))
    k = np.abs(ladder.temperatures[:, None] - temp[None, :]).argmin(axis=0)
    searches = [r[2] for r in ladder.results]
    base = searches[0].flat()
    pick = [searches[j].flat().take(np.array([i])) for i, j in enumerate(k)]
    search = LimitSearch(
        torque,
        np.concatenate([p.creep for p in pick]) if pick else base.creep,
        np.concatenate([p.creep_zero for p in pick]) if pick else base.creep_zero,
    )
    return torque, np.where(np.isfinite(torque), temp, np.nan), search


def _curve_rows(design: Design, fluid: Fluid, ds: xr.Dataset, request) -> OperatingRows:
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
    runaway's 2), then each balanced point solved at its own temperature (`_settle`).
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
    _settle(rows, (thermal, evaluate), (ladder, temp, outcome), (t2, res))
    return t2, res


def _settle(rows: OperatingRows, how, balance, out) -> None:
    """Each point balanced between two rungs solved once more at its own temperature,
    in place in ``out`` = ``(t2, res)`` of `balanced_rows` (``how`` = ``(thermal,
    evaluate)``, ``balance`` = ``(ladder, temperature, outcome)``): one Newton step on its
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
    total = LOSS_KINDS.index("total")
    todo = (outcome == BALANCED) & (res["status"] == 0) & (above > below)
    for i in np.flatnonzero(todo & np.isfinite(slope) & (slope < 0.0)):
        one = rows.take(np.array([i]))
        got = evaluate(_with_fluid(one, fluid_at(rows.drive.fluid, temp[i])), [i])
        loss = got[1]["losses"][0, total]
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
    searching. A row carried nowhere below ``top`` keeps it (as the scalar path does).
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
    out[idx] = np.where(np.isnan(inside), end, inside)
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


def _moved(rows: OperatingRows, thermal, top: np.ndarray, at_top: tuple) -> tuple:
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
