"""Sweeps: the model over grids of operating conditions, as an `xarray.Dataset`.

`sweep` evaluates every combination of architecture, clamping force, input speed, ratio and
output torque. For each curve (all inputs but the torque fixed) it first finds the limiting
torque (`ballcvt.solvers.limit.limit_search`), then solves every point below it in one
batch, each started from the creeps interpolated in torque towards the curve's solution at
its limit (with the limits given instead, it walks up the torque grid, each point started
from the solution at the torque below). Points above the limit are not solved; they are NaN
with ``status = 1``. Points that do not converge are NaN with ``status = 2``. Nothing is
dropped.
"""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
import xarray as xr

from ..._version import __version__
from ...equilibrium.problem import build_problem
from ...errors import InputError
from ...model.architectures import CONTACT_NAMES
from ...model.clamping import clamp_law as clamp_law_of
from ...model.clamping.base import DEFAULT_LAW, names_fixed_force
from ...params.drive import Drive
from ...params.models import ARCHITECTURES, Design, Fluid
from ...solvers.limit import LimitSearch
from ...solvers.options import SolverOptions, at_residual_floor
from .chunks import (
    CURVE_VARIABLES,
    ChunkRun,
    SweepArrays,
    curve_chunks,
    solve_chunked,
    worker_pool,
)
from .curves import OperatingRows, limit_search_curves
from .variables import CONTACT_VARIABLES, LOSS_SUBTOTALS, SWEEP_LOSSES, attrs_for

__all__ = ["sweep", "SweepRequest"]


@dataclass(frozen=True)
class SweepRequest:
    """The grid a `sweep` evaluates and how.

    Attributes
    ----------
    ratio : float or array_like
        Ideal speed ratios ``tau_ID`` [-].
    output_torque : float or array_like
        Output torques ``T_2`` >= 0 [N m], increasing (the continuation axis).
    clamp_force : float or array_like, optional
        Clamping forces ``F_N0`` > 0 [N] of the constant law (a dimension of the result).
    input_speed : float or array_like
        Input speeds ``omega_0`` > 0 [rad/s].
    clamp_law : str or law object, optional
        ``"cam"``, ``"optimal"`` or a law of `ballcvt.model.clamping` (docs/model.md §11); then
        ``clamp_force`` is not given, the result has no ``clamp_force`` dimension, and
        ``clamp_force`` is a variable: the force the law sets at each point. The limiting
        torque is the law's (`limit_torque_batch`).
    architecture : str or sequence of str
        ``"double"`` and/or ``"single"``.
    options : SolverOptions
        Solver options (the fast batched Newton method by default).
    creep_limit : float, optional
        ``C_lim`` of the limiting torque; ``design.creep_limit`` by default.
    limit_torque : array_like or LimitSearch, optional
        Limiting torques already found at these conditions (`limit_torque_batch` with
        the same ``creep_limit``), broadcastable to ``(clamp_force, input_speed, ratio)``
        [N m]; one architecture only. By default they are computed. A
        `ballcvt.solvers.limit.LimitSearch` of these curves (C order) also hands over the
        creeps at the limits, from which every point is started in one batch; with bare
        torques the sweep walks up the torque grid instead.
    workers : int
        Processes to use: the chunks of curves (`ballcvt.analysis.sweeps.chunks`) are
        shared between them (a grid of one chunk is split in chunks of at least
        ``SPLIT_POINTS`` points to share it).
    progress : bool, optional
        Show a progress bar; by default only when stderr is a terminal.
    label : str, optional
        What the progress bar says it computes (default: ``"sweep, <arch> idler"``).
    input_speed_rpm : array_like, optional
        The same input speeds in rpm: the speed dimension is then ``input_speed_rpm``
        with these values, and ``input_speed`` [rad/s] a second coordinate on it.

    Notes
    -----
    The curves are solved in chunks of about ``CHUNK_POINTS`` points written into the output
    arrays as they finish, so a sweep's memory is its output (about 0.5 kB per point with
    the double idler: float64 throughout) plus one chunk's work per process.
    """

    ratio: Any = None
    output_torque: Any = None
    clamp_force: Any = None
    input_speed: Any = None
    clamp_law: Any = None
    architecture: Any = "double"
    options: SolverOptions = SolverOptions()
    creep_limit: float | None = None
    limit_torque: Any = None
    workers: int = 1
    progress: bool | None = None
    label: str | None = None
    input_speed_rpm: Any = None


def sweep(
    design: Design, fluid: Fluid, settings: SweepRequest | None = None, **keywords
) -> xr.Dataset:
    """Evaluate the model over a grid of operating conditions.

    Parameters
    ----------
    design, fluid : Design, Fluid
        Parameter sets.
    settings : SweepRequest, optional
        The grid and how to evaluate it; or give its fields as keywords (``ratio=...,
        output_torque=..., clamp_force=..., input_speed=...``; ``ratio``,
        ``output_torque`` and ``input_speed`` are required).

    Returns
    -------
    xarray.Dataset
        Dimensions ``architecture, clamp_force, input_speed, ratio, output_torque`` (no
        ``clamp_force`` dimension under a clamping law other than ``constant``) (and
        ``contact`` for per-contact variables, ``loss`` for ``losses``); every variable has
        ``units`` and ``long_name``. ``status`` flags each point (0 converged, 1 beyond the
        limiting torque, 2 not converged); flagged points are NaN. ``warnings`` holds the
        validity warnings of each converged point as bit flags (``flag_masks``,
        ``flag_meanings``; docs/model.md §10). The design, fluid and solver settings are
        attributes (``design_<key>``, ``fluid_<key>``).
    """
    start = time.perf_counter()
    s = replace(settings or SweepRequest(), **keywords)
    for name in ("ratio", "output_torque", "input_speed"):
        if getattr(s, name) is None:
            raise InputError(name, None, "a number or a non-empty 1-D sequence")
    archs = [s.architecture] if isinstance(s.architecture, str) else list(s.architecture)
    for a in archs:
        if a not in ARCHITECTURES:
            raise InputError("architecture", a, "one of: " + ", ".join(ARCHITECTURES))
    c_lim = design.creep_limit if s.creep_limit is None else float(s.creep_limit)
    if not 0.0 < c_lim < 1.0:
        raise InputError("creep_limit", c_lim, "0 < creep_limit < 1")
    law, clamp_force = _law(design, s)
    axes = _axes(design, fluid, archs[0], s, law, clamp_force)
    torque = axes["output_torque"]
    shape = tuple(len(axes[n]) for n in ("clamp_force", "input_speed", "ratio"))
    grid = np.meshgrid(axes["clamp_force"], axes["input_speed"], axes["ratio"], indexing="ij")
    flat = [g.ravel() for g in grid]
    limits = _given_limits(s.limit_torque, archs, shape)
    show = sys.stderr.isatty() if s.progress is None else s.progress
    contacts = _contact_axis(archs)
    out = SweepArrays.allocate(len(archs), flat[0].size, torque.size, contacts, law is not None)
    chunks = curve_chunks(flat[0].size, torque.size, s.workers)
    pool = worker_pool(s.workers if len(chunks) > 1 else 1)
    try:
        for a, arch in enumerate(archs):
            rows = OperatingRows(
                Drive(design, fluid, arch), flat[2], flat[1], flat[0], law, s.options, c_lim
            )
            run = ChunkRun(rows, torque, limits, a)
            text = f"{s.label}, {arch} idler" if s.label and len(archs) > 1 else s.label
            _run(run, out, chunks, pool, (show, text or f"sweep, {arch} idler"))
    finally:
        if pool is not None:
            pool.shutdown()
    ds = _assemble(out, archs, axes, shape, s.input_speed_rpm)
    if law is not None:
        speed_dim = "input_speed" if s.input_speed_rpm is None else "input_speed_rpm"
        used = out.data["clamp_force"].reshape((len(archs),) + shape + (torque.size,))
        ds = ds.isel(clamp_force=0, drop=True)
        ds["clamp_force"] = xr.Variable(
            ("architecture", speed_dim, "ratio", "output_torque"),
            used[:, 0],
            attrs_for("clamp_force"),
        )
    ds.attrs.update(
        clamp_law=law.name if law else DEFAULT_LAW,
        traction_law=fluid.traction_law,
        title="ballcvt sweep",
        Conventions="CF-1.10",
        institution="ballcvt",
        source=f"ballcvt {__version__}",
        ballcvt_version=__version__,
        references="Tomaselli, Bottiglione, Lino, Carbone, Mech. Mach. Theory 150 (2020) "
        "103877, doi:10.1016/j.mechmachtheory.2020.103877",
        creep_limit=c_lim,
        quadrature=repr(s.options.quadrature),
        solver=s.options.method,
        tolerance=at_residual_floor(s.options, fluid).tol,
        run_time_s=time.perf_counter() - start,
    )
    ds.attrs.update(flat_attrs("design", design.model_dump()))
    ds.attrs.update(flat_attrs("fluid", fluid.model_dump()))
    return ds


def _law(design: Design, s: SweepRequest):
    """(clamping law other than constant or None, the constant law's forces)."""
    if names_fixed_force(s.clamp_law):  # the forces are a dimension
        if s.clamp_force is None:
            clamp_law_of(s.clamp_law, design, None)  # raises: says what is missing
        return None, s.clamp_force
    law = clamp_law_of(s.clamp_law, design, s.clamp_force)
    if law.fixed_force:
        return None, law.force
    return law, s.clamp_force


def _axes(design: Design, fluid: Fluid, arch: str, s: SweepRequest, law, clamp_force):
    """The grid's axes, each validated (one `InputError` on the first bad value)."""
    axes = {
        name: _axis(name, value)
        for name, value in (
            ("clamp_force", np.nan if law else clamp_force),
            ("input_speed", s.input_speed),
            ("ratio", s.ratio),
            ("output_torque", s.output_torque),
        )
    }
    torque = axes["output_torque"]
    if np.any(np.diff(torque) < 0):
        raise InputError(
            "output_torque",
            float(torque[np.argmax(np.diff(torque) < 0) + 1]),
            "an increasing sequence (torque is the continuation axis)",
        )
    build_problem(
        design,
        fluid,
        arch,
        axes["ratio"][:, None],
        torque,
        1.0 if law else axes["clamp_force"][:, None, None],
        axes["input_speed"][:, None, None, None],
    )
    return axes


def _given_limits(limit_torque, archs, shape):
    """The limits handed over (flat, C order), or None to search them."""
    if isinstance(limit_torque, (bool, np.bool_)):
        raise InputError(
            "limit_torque",
            limit_torque,
            "torques [N m] or a LimitSearch (None: computed)",
        )
    if limit_torque is None:
        return None
    if len(archs) != 1:
        raise InputError(
            "architecture",
            ", ".join(archs),
            "a single architecture when limit_torque is given",
        )
    if isinstance(limit_torque, LimitSearch):
        limits = limit_torque.flat()
        if limits.torque.size != int(np.prod(shape)):
            raise InputError(
                "limit_torque",
                f"a search of {limits.torque.size} curves",
                f"one per (clamp_force, input_speed, ratio): {int(np.prod(shape))}",
            )
        return limits
    return np.broadcast_to(np.asarray(limit_torque, dtype=float), shape).ravel()


def flat_attrs(prefix: str, data: dict) -> dict:
    """Nested parameters as flat NetCDF attributes ``<prefix>_<key>[_<subkey>]`` (a table
    of rows, the fluid's ``viscosity_data``, row after row: NetCDF attributes are 1-D)."""
    out = {}
    for key, value in data.items():
        if value is None:  # an optional table the design lacks
            continue
        if isinstance(value, dict):
            out.update(flat_attrs(f"{prefix}_{key}", value))
        elif isinstance(value, list | tuple) and value and isinstance(value[0], list | tuple):
            out[f"{prefix}_{key}"] = [x for row in value for x in row]
        else:
            out[f"{prefix}_{key}"] = value
    return out


def _axis(name, value):
    arr = np.atleast_1d(np.asarray(value, dtype=float))
    if arr.ndim != 1 or arr.size == 0:
        raise InputError(name, value, "a number or a non-empty 1-D sequence")
    return arr


def _contact_axis(archs):
    names = []
    for a in ("input", "idler", "idler_a", "idler_b", "output"):
        if any(a in CONTACT_NAMES[arch] for arch in archs):
            names.append(a)
    return names


def _run(run: ChunkRun, out: SweepArrays, chunks, pool, bar) -> None:
    """Solve ``run``'s ``chunks`` into ``out`` behind a progress bar (``bar``: whether to
    show it, its label): steps in one process, chunks on a pool.

    With more than one chunk, the limits not given are searched first, for every curve
    in one batch (memory per curve, not per point), so that each curve's limit is the
    same whatever the chunks."""
    from tqdm.auto import tqdm  # only the orchestration needs a progress bar

    show, label = bar
    search = run.limits is None and len(chunks) > 1
    total = run.steps(chunks) if pool is None else len(chunks) + (run.steps([]) if search else 0)
    with tqdm(total=total, desc=label, disable=not show, unit="step") as progress:
        if search:
            run = replace(run, limits=limit_search_curves(run.curves, progress.update)[1])
        solve_chunked(run, out, chunks, pool, progress.update)


def _assemble(out: SweepArrays, archs, axes, shape, rpm=None):
    """The Dataset of the output arrays (views of them: nothing is copied)."""
    speed_dim = "input_speed" if rpm is None else "input_speed_rpm"
    lead = ("architecture", "clamp_force", speed_dim, "ratio")
    trail = {"loss_subtotals": ("subtotal",), "losses": ("loss",)}
    trail.update({name: ("contact",) for name in CONTACT_VARIABLES})
    data = {}
    for name, arr in out.data.items():
        if name == "clamp_force":  # a law's forces: set apart by `sweep`
            continue
        d: tuple[str, ...] = lead if name in CURVE_VARIABLES else lead + ("output_torque",)
        d += trail.get(name, ())
        data[name] = xr.Variable(
            d, arr.reshape((len(archs),) + shape + arr.shape[2:]), attrs_for(name)
        )
    contacts = out.contacts
    coords = {
        "architecture": ("architecture", np.array(archs), {"long_name": "idler architecture"}),
        "contact": ("contact", np.array(contacts), {"long_name": "contact"}),
        "loss": ("loss", np.array(SWEEP_LOSSES), {"long_name": "kind of power loss"}),
        "subtotal": ("subtotal", np.array(LOSS_SUBTOTALS), {"long_name": "loss subtotal"}),
    }
    for n, v in axes.items():
        coords[n] = (n, v, attrs_for(n))
    if rpm is not None:
        coords["input_speed"] = (speed_dim, axes["input_speed"], attrs_for("input_speed"))
        coords[speed_dim] = (
            speed_dim,
            np.atleast_1d(np.asarray(rpm, dtype=float)),
            attrs_for(speed_dim),
        )
    return xr.Dataset(data, coords=coords)
