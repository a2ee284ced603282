"""Sweeps: the model over grids of operating conditions, as an `xarray.Dataset`.

`sweep` evaluates every combination of architecture, clamping force, input speed, ratio and
output torque. For each curve (all inputs but the torque fixed) it first finds the limiting
torque by batched bisection (`limit_torque_batch`), then walks up the torque grid with
continuation: each point starts from the solution at the torque below. Points above the
limit are not solved; they are NaN with ``status = 1``. Points that do not converge are NaN
with ``status = 2``. Nothing is dropped.
"""

from __future__ import annotations

import sys
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np
import xarray as xr

from .._version import __version__
from ..equilibrium.problem import build_problem
from ..equilibrium.residual import evaluate
from ..errors import InputError
from ..geometry.layout import CONTACT_NAMES
from ..params.models import ARCHITECTURES, Design, Fluid
from ..performance.efficiency import efficiency, power_losses
from ..performance.validity import validity
from ..solver.batch import solve_batch
from ..solver.limit import bisection_steps, limit_torque_batch
from ..solver.point import SolverOptions
from .variables import CONTACT_VARIABLES, LOSS_KINDS, POINT_VARIABLES, STATUS, attrs_for

__all__ = ["sweep", "STATUS"]


def sweep(design: Design, fluid: Fluid, *, ratio, output_torque, clamp_force,
          input_speed, architecture="double", options: SolverOptions = SolverOptions(),
          creep_limit: float | None = None, limit_torque=None, workers: int = 1,
          progress: bool | None = None, label: str | None = None) -> xr.Dataset:
    """Evaluate the model over a grid of operating conditions.

    Parameters
    ----------
    design, fluid : Design, Fluid
        Parameter sets.
    ratio : float or array_like
        Ideal speed ratios ``tau_ID`` [-].
    output_torque : float or array_like
        Output torques ``T_2`` >= 0 [N m], increasing (the continuation axis).
    clamp_force : float or array_like
        Clamping forces ``F_N0`` > 0 [N].
    input_speed : float or array_like
        Input speeds ``omega_0`` > 0 [rad/s].
    architecture : str or sequence of str
        ``"double"`` and/or ``"single"``.
    options : SolverOptions
        Solver options (the fast batched Newton method by default).
    creep_limit : float, optional
        ``C_lim`` of the limiting torque; ``design.creep_limit`` by default.
    limit_torque : array_like, optional
        Limiting torques already found at these conditions (`limit_torque_batch` with
        the same ``creep_limit``), broadcastable to ``(clamp_force, input_speed, ratio)``
        [N m]; one architecture only. By default they are computed.
    workers : int
        Processes to use (curves are split between them).
    progress : bool, optional
        Show a progress bar; by default only when stderr is a terminal.
    label : str, optional
        What the progress bar says it computes (default: ``"sweep, <arch> idler"``).

    Returns
    -------
    xarray.Dataset
        Dimensions ``architecture, clamp_force, input_speed, ratio, output_torque`` (and
        ``contact`` for per-contact variables, ``loss`` for ``losses``); every variable has
        ``units`` and ``long_name``. ``status`` flags each point (0 converged, 1 beyond the
        limiting torque, 2 not converged); flagged points are NaN. ``warnings`` holds the
        validity warnings of each converged point as bit flags (``flag_masks``,
        ``flag_meanings``; docs/model.md §10). The design, fluid and solver settings are
        attributes (``design_<key>``, ``fluid_<key>``).
    """
    start = time.perf_counter()
    archs = [architecture] if isinstance(architecture, str) else list(architecture)
    for a in archs:
        if a not in ARCHITECTURES:
            raise InputError("architecture", a, "one of: " + ", ".join(ARCHITECTURES))
    c_lim = design.creep_limit if creep_limit is None else float(creep_limit)
    if not 0.0 < c_lim < 1.0:
        raise InputError("creep_limit", c_lim, "0 < creep_limit < 1")
    axes = {name: _axis(name, value) for name, value in
            (("clamp_force", clamp_force), ("input_speed", input_speed), ("ratio", ratio),
             ("output_torque", output_torque))}
    torque = axes["output_torque"]
    if np.any(np.diff(torque) < 0):
        raise InputError("output_torque", float(torque[np.argmax(np.diff(torque) < 0) + 1]),
                         "an increasing sequence (torque is the continuation axis)")
    # validate every input once (raises InputError on the first bad value)
    build_problem(design, fluid, archs[0], axes["ratio"][:, None], torque,
                  axes["clamp_force"][:, None, None], axes["input_speed"][:, None, None, None])
    shape = tuple(len(axes[n]) for n in ("clamp_force", "input_speed", "ratio"))
    grid = np.meshgrid(axes["clamp_force"], axes["input_speed"], axes["ratio"], indexing="ij")
    flat = [g.ravel() for g in grid]
    if limit_torque is not None:
        if len(archs) != 1:
            raise InputError("architecture", ", ".join(archs),
                             "a single architecture when limit_torque is given")
        limits = np.broadcast_to(np.asarray(limit_torque, dtype=float), shape).ravel()
    contacts = _contact_axis(archs)
    show = sys.stderr.isatty() if progress is None else progress
    chunks = np.array_split(np.arange(flat[0].size), max(1, min(workers, flat[0].size)))
    blocks = {}
    for arch in archs:
        jobs = [(design, fluid, arch, flat[0][c], flat[1][c], flat[2][c], torque, options,
                 c_lim, None if limit_torque is None else limits[c]) for c in chunks]
        text = f"{label}, {arch} idler" if label and len(archs) > 1 else label
        blocks[arch] = _run(jobs, workers, show, text or f"sweep, {arch} idler")
    ds = _assemble(blocks, archs, axes, shape, contacts)
    ds.attrs.update(
        title="ballcvt sweep", Conventions="CF-1.10", institution="ballcvt",
        source=f"ballcvt {__version__}", ballcvt_version=__version__,
        references="Tomaselli, Bottiglione, Lino, Carbone, Mech. Mach. Theory 150 (2020) "
                   "103877, doi:10.1016/j.mechmachtheory.2020.103877",
        creep_limit=c_lim, quadrature=repr(options.quadrature), solver=options.method,
        tolerance=options.tol, run_time_s=time.perf_counter() - start)
    ds.attrs.update(flat_attrs("design", design.model_dump()))
    ds.attrs.update(flat_attrs("fluid", fluid.model_dump()))
    return ds


def flat_attrs(prefix: str, data: dict) -> dict:
    """Nested parameters as flat NetCDF attributes ``<prefix>_<key>[_<subkey>]``."""
    out = {}
    for key, value in data.items():
        if isinstance(value, dict):
            out.update(flat_attrs(f"{prefix}_{key}", value))
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


def _run(jobs, workers, show, label):
    from tqdm.auto import tqdm  # only the orchestration needs a progress bar
    if workers > 1 and len(jobs) > 1:
        with ProcessPoolExecutor(max_workers=workers) as pool:
            futures = [pool.submit(solve_curves, *job) for job in jobs]
            with tqdm(total=len(jobs), desc=label, disable=not show, unit="block") as bar:
                out = []
                for f in futures:
                    out.append(f.result())
                    bar.update()
        return _concat(out)
    steps = sum(len(job[6]) + (bisection_steps() if job[9] is None else 0) for job in jobs)
    with tqdm(total=steps, desc=label, disable=not show, unit="step") as bar:
        return _concat([solve_curves(*job, callback=bar.update) for job in jobs])


def _concat(parts):
    return {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}


def solve_curves(design, fluid, architecture, clamp_force, input_speed, ratio, torque,
                 options, creep_limit, limit=None, callback=None):
    """Solve the curves ``(clamp_force[i], input_speed[i], ratio[i])`` over ``torque``.

    ``limit``: the curves' limiting torques if already known (else computed here).

    Returns a dict of arrays ``(m, n_T)`` or ``(m, n_T, n_c)`` (and ``limit_torque``,
    ``(m,)``) with the variables of `ballcvt.sweeps.variables`; run in worker processes.
    """
    m, nt = ratio.size, torque.size
    base = build_problem(design, fluid, architecture, ratio, 0.0, clamp_force, input_speed)
    if limit is None:
        limit = limit_torque_batch(base, creep_limit, options, callback=callback)
    nc = base.layout.n_contacts
    creep = np.full((m, nt, nc), np.nan)
    # points within the limit start as "not converged" (2) until solved
    status = np.where(torque[None, :] <= np.nan_to_num(limit, nan=-1.0)[:, None], 2, 1)
    iterations = np.zeros((m, nt), dtype=int)
    residual = np.full((m, nt), np.nan)
    x = None
    for k in range(nt):
        todo = np.flatnonzero(status[:, k] == 2)
        if todo.size:
            pb = build_problem(design, fluid, architecture, ratio[todo], torque[k],
                               clamp_force[todo], input_speed[todo])
            sol = solve_batch(pb, options, None if x is None else x[todo])
            good = sol.converged
            creep[todo[good], k] = sol.state.creep[good]
            status[todo[good], k] = 0
            iterations[todo, k] = sol.iterations
            residual[todo, k] = sol.residual_norm
            if x is None:
                x = np.broadcast_to(sol.state.creep[:1], (m, nc)).copy()
            x[todo[good]] = sol.state.creep[good]
        if callback is not None:
            callback()
    out = {"limit_torque": limit, "eta_at_limit": _eta_at(design, fluid, architecture,
                                                          clamp_force, input_speed, ratio,
                                                          limit, options),
           "status": status.astype(np.int8), "iterations": iterations,
           "residual_norm": residual}
    out.update(_derived(design, fluid, architecture, clamp_force, input_speed, ratio, torque,
                        creep, status, options))
    return out


def _eta_at(design, fluid, arch, clamp_force, input_speed, ratio, torque, options):
    """Overall efficiency (Eq. 38) at one torque per curve (NaN where there is none)."""
    eta = np.full(ratio.size, np.nan)
    ok = np.flatnonzero(np.isfinite(torque))
    if ok.size:
        pb = build_problem(design, fluid, arch, ratio[ok], torque[ok], clamp_force[ok],
                           input_speed[ok])
        sol = solve_batch(pb, options)
        eta[ok] = np.where(sol.converged, efficiency(pb, sol.state).overall, np.nan)
    return eta


def _derived(design, fluid, arch, clamp_force, input_speed, ratio, torque, creep, status,
             options):
    """Every reported quantity at the converged points (NaN elsewhere)."""
    m, nt, nc = creep.shape
    ok = status == 0
    i, k = np.nonzero(ok)
    values = {name: np.full((m, nt), np.nan) for name in POINT_VARIABLES}
    values.update({name: np.full((m, nt, nc), np.nan) for name in CONTACT_VARIABLES})
    values["losses"] = np.full((m, nt, len(LOSS_KINDS)), np.nan)
    values["warnings"] = np.zeros((m, nt), dtype=np.int8)
    if i.size == 0:
        return values
    pb = build_problem(design, fluid, arch, ratio[i], torque[k], clamp_force[i], input_speed[i])
    st = evaluate(pb, creep[i, k], options.quadrature)
    loss = power_losses(pb, st)
    eff = efficiency(pb, st, loss)
    valid = validity(pb, st)
    point = {"eta": eff.overall, "eta_loss": eff.from_losses, "eta_speed": eff.speed,
             "eta_torque": eff.torque, "input_torque": st.input_torque,
             "actual_ratio": st.omega[:, -1] / st.omega[:, 0], "tilt_deg": np.degrees(pb.tilt)}
    contact = {"creep": st.creep, "spin": st.spin, "mu": st.mu, "chi": st.chi,
               "p_max": pb.p_max, "film_thickness": st.film, "normal_load": pb.load,
               "creep_loss": loss.creep, "spin_loss": loss.spin,
               "lambda_ratio": valid.lambda_ratio}
    for name, v in point.items():
        values[name][i, k] = v
    for name, v in contact.items():
        values[name][i, k] = v
    values["losses"][i, k] = np.stack(
        [loss.creep.sum(-1), loss.spin.sum(-1), loss.roller_bearings,
         loss.idler_bearings.sum(-1), loss.bearing, loss.total], axis=-1)
    values["warnings"][i, k] = valid.flags
    return values


def _assemble(blocks, archs, axes, shape, contacts):
    dims = ("clamp_force", "input_speed", "ratio")
    data = {}
    for name in ("limit_torque", "eta_at_limit", "status", "warnings", "iterations",
                 "residual_norm",
                 *POINT_VARIABLES, "losses", *CONTACT_VARIABLES):
        per_arch = []
        for arch in archs:
            v = blocks[arch][name]
            v = v.reshape(shape + v.shape[1:])
            if name in CONTACT_VARIABLES:
                full = np.full(v.shape[:-1] + (len(contacts),), np.nan)
                for j, c in enumerate(CONTACT_NAMES[arch]):
                    full[..., contacts.index(c)] = v[..., j]
                v = full
            per_arch.append(v)
        arr = np.stack(per_arch)
        d = ("architecture",) + dims
        if name not in ("limit_torque", "eta_at_limit"):
            d += ("output_torque",)
        if name in CONTACT_VARIABLES:
            d += ("contact",)
        elif name == "losses":
            d += ("loss",)
        data[name] = xr.Variable(d, arr, attrs_for(name))
    coords = {"architecture": ("architecture", np.array(archs),
                               {"long_name": "idler architecture"}),
              "contact": ("contact", np.array(contacts), {"long_name": "contact"}),
              "loss": ("loss", np.array(LOSS_KINDS), {"long_name": "kind of power loss"})}
    for n, v in axes.items():
        coords[n] = (n, v, attrs_for(n))
    return xr.Dataset(data, coords=coords)
