"""A sweep, map or table under the oil's heat balance: each point, and each curve's
limiting torque, at its own oil temperature (docs/model.md §15; the method:
`ballcvt.analysis.oil_paths`).

The sweep is run at each rung of the ladder of oil temperatures; each point's quantities
are interpolated to its balance temperature, and each curve's ``limit_torque`` and
``eta_at_limit`` to the temperature its limit point produces (`ballcvt.analysis.oil_sweep`).
A point whose interpolation is in doubt (`in_doubt`) is then solved once more at its own
temperature (`ballcvt.analysis.oil_sweep.settle`). The dataset gains ``oil_temperature``
[K] at every point and ``oil_temperature_at_limit`` [K] per curve.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from ..errors import InputError
from ..model.architectures import CONTACT_NAMES
from ..params.models import Design, Fluid
from .oil_paths import (
    Ladder,
    balance_weights,
    climb,
    interpolate,
    lagrange,
    nearest,
    runaway_status,
    runaways_at_top,
)
from .oil_sweep import curve_rows, limit_ladder, moved_tops, settle
from .sweeps.grid import SweepRequest, sweep
from .sweeps.points import evaluate_points
from .sweeps.variables import (
    CONTACT_VARIABLES,
    component_losses,
    contact_columns,
    subtotal_losses,
)

__all__ = ["balanced_sweep", "in_doubt", "SETTLE_TOL"]

#: Variables taken at the nearest rung rather than interpolated (counts and codes).
CODES = ("status", "warnings", "iterations")
#: A point is solved again at its own temperature where its efficiency [-] interpolated
#: through its stencil of rungs and through the stencil less its farthest rung differ by
#: more than this, or its total loss by more than `SETTLE_TOL` times 10 of itself: the
#: stencil then spans a kink of the point's efficiency in the temperature (the
#: mixed-lubrication tables are once differentiable in lambda), which no polynomial
#: through the rungs follows (harden task 4242:863: 9e-6 in eta off `Variator.solve`).
#: On a 3 x 3 hub sweep at 114 rpm (docs/model.md §15) 3 of 9 points were re-solved; all
#: 9 then agreed with `solve` within 2.2e-8.
SETTLE_TOL = 1e-9


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
    balance = balance_weights(ladder)
    out = _interpolated(ladder, list(first["status"].dims), balance)
    rows = curve_rows(design, fluid, first, request)
    _settled(out, (ladder, balance), rows, thermal)
    _limits_into(out, rows, thermal, ladder)
    out.attrs.update(first.attrs, oil_model="balance", oil_rungs=len(ladder.temperatures))
    return out


def _limits_into(out: xr.Dataset, rows, thermal, points: Ladder) -> None:
    """``out`` gains the curves' balanced ``limit_torque``, ``eta_at_limit`` and
    ``oil_temperature_at_limit``; ``rows`` are the curves (`curve_rows`), ``points`` the
    points' ladder."""
    first = points.results[0]
    dims = first["limit_torque"].dims
    flat = {
        float(t): tuple(
            r[v].transpose(*dims).values.ravel() for v in ("limit_torque", "eta_at_limit")
        )
        for t, r in zip(points.temperatures, points.results, strict=True)
    }
    ladder = limit_ladder(rows, thermal, flat)
    temp, weights, outcome = balance_weights(ladder)
    runaways_at_top(ladder, temp, weights, outcome)
    shape = first["limit_torque"].shape
    top = interpolate(np.stack([r[0] for r in ladder.results]), weights)
    eta = interpolate(np.stack([r[1] for r in ladder.results]), weights)
    top, eta, temp = moved_tops(rows, thermal, top, (eta, temp))
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


def _interpolated(ladder: Ladder, dims: list[str], balance: tuple) -> xr.Dataset:
    """The variables of the rungs' datasets over ``dims`` at each point's balance
    (``balance``: `balance_weights`')."""
    temp, weights, outcome = balance
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


def in_doubt(ladder: Ladder, temperature, weights, stacks) -> np.ndarray:
    """Whether each point's interpolation is in doubt (`SETTLE_TOL`).

    Parameters
    ----------
    ladder : Ladder
        The rungs.
    temperature, weights : ndarray
        Each point's balance temperature ``(n,)`` [K] and Lagrange weights ``(k, n)``
        (`balance_weights`).
    stacks : tuple of ndarray
        The efficiency [-] and total loss [W] of each point at each rung, ``(k, n)``.

    Returns
    -------
    ndarray of bool
        ``(n,)``: interpolated between two rungs only (no estimate), or the stencil and
        the stencil less its farthest rung differ beyond `SETTLE_TOL`.
    """
    temps = ladder.temperatures
    fewer = np.zeros_like(weights)
    doubt = np.zeros(weights.shape[1], dtype=bool)
    for i in range(weights.shape[1]):
        nodes = np.flatnonzero(weights[:, i])
        if nodes.size < 3:  # at a rung (exact), not balanced, or a chord
            doubt[i] = nodes.size == 2
            continue
        keep = np.delete(nodes, np.argmax(np.abs(temps[nodes] - temperature[i])))
        fewer[keep, i] = lagrange(temps[keep], temperature[i])
    eta, loss = stacks
    d_eta = np.abs(interpolate(eta, weights) - interpolate(eta, fewer))
    full = interpolate(loss, weights)
    d_loss = np.abs(full - interpolate(loss, fewer))
    with np.errstate(invalid="ignore"):
        return doubt | (d_eta > SETTLE_TOL) | (d_loss > 10.0 * SETTLE_TOL * np.abs(full))


def _settled(out: xr.Dataset, run: tuple, rows, thermal) -> None:
    """The points of ``out`` in doubt (`in_doubt`) solved again at their own oil
    temperature (`settle`), in place; ``run`` is the ladder and its `balance_weights`,
    ``rows`` the curves (`curve_rows`). A re-solved point's ``iterations`` and
    ``residual_norm`` stay those of the rungs (`evaluate_points` reports neither)."""
    ladder, (temp, weights, outcome) = run
    first = ladder.results[0]
    dims = list(first["status"].dims)
    torque = np.asarray(first["output_torque"].values, dtype=float)
    n = temp.size
    stacks = tuple(
        np.stack([_points(r, get(r)).reshape(n) for r in ladder.results])
        for get in (lambda r: r["eta"], lambda r: r["losses"].sel(loss="total"))
    )
    doubt = in_doubt(ladder, temp, weights, stacks)
    if not np.any(doubt):
        return
    t2 = np.tile(torque, rows.size)  # the points in C order: each curve's torques
    points = rows.take(np.repeat(np.arange(rows.size), torque.size))
    arch = str(first["architecture"].values[0])
    contacts = [str(c) for c in first["contact"].values]
    res = {
        name: np.array(var.values).reshape((n,) + var.shape[len(dims) :])
        for name, var in out.data_vars.items()
        if tuple(var.dims[: len(dims)]) == tuple(dims)
    }

    def evaluate(r, i):
        return t2[i], _as_grid(evaluate_points(r, t2[i]), arch, contacts)

    settle(points, (thermal, evaluate), (ladder, temp, outcome), (t2.copy(), res), doubt)
    for name, values in res.items():
        var = out[name]
        out[name] = xr.Variable(var.dims, values.reshape(var.shape), var.attrs)


def _as_grid(got: dict, arch: str, contacts: list) -> dict:
    """`evaluate_points`' ``got`` laid out as a sweep's variables: its losses by kind as
    the sweep's components and subtotals, its contact variables on the sweep's contact
    axis ``contacts`` (as `ballcvt.analysis.sweeps.chunks.SweepArrays.write`)."""
    out = dict(got)
    out["losses"] = component_losses(got["losses"])
    out["loss_subtotals"] = subtotal_losses(got["losses"])
    cols = contact_columns(contacts, CONTACT_NAMES[arch])
    for name in CONTACT_VARIABLES:
        wide = np.full(got[name].shape[:1] + (len(contacts),), np.nan)
        wide[:, cols] = got[name]
        out[name] = wide
    return out
