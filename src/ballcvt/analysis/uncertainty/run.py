"""Propagate a drive file's uncertain parameters to its efficiency and capacity.

The samples are drawn once (`sampling.draw`, seeded), evaluated in chunks of
`UncertaintyRequest.chunk` drives, in this process or on Dask (a local cluster of
``workers`` processes, a scheduler's address or a client: `ballcvt.analysis.studies.Compute`,
as a design study runs), and gathered in sample order: the same seed gives the same
numbers, in process or on any cluster.
"""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass

import numpy as np

from ..._version import __version__
from ...errors import InputError
from ...params.drive import Drive
from ...params.uncertainty import UncertaintyTable
from ...solvers import SolverOptions
from ...units import rad_s_to_rpm, rpm_to_rad_s
from ..studies.run import Compute, local_client
from .evaluate import Context, Duty, evaluate_chunk
from .result import UncertaintyResult
from .sampling import METHODS, draw

__all__ = ["UncertaintyRequest", "UncertainDrive", "run_uncertainty", "duty_of"]


@dataclass(frozen=True)
class UncertaintyRequest:
    """What to propagate and where.

    Attributes
    ----------
    samples : int
        Drives drawn (1 to 100000).
    seed : int
        Seed of the sampling design.
    method : str
        ``sobol``, ``lhs`` or ``random`` (`ballcvt.analysis.uncertainty.sampling.METHODS`).
    ratio : tuple of float
        Ideal ratios [-] of the operating points (and of the capacity rows).
    output_torque : tuple of float, optional
        Output torques [N m]; or
    input_power : tuple of float, optional
        input powers [W] (one of the two).
    input_speed_rpm : tuple of float
        Input speeds [rpm]. The points are the grid ratio x load x speed. (The API,
        `ballcvt.api.uncertainty`, fills in the drive's ``[operating]`` speed.)
    chunk : int
        Drives per task.
    """

    samples: int = 256
    seed: int = 0
    method: str = "sobol"
    ratio: tuple[float, ...] = (1.0,)
    output_torque: tuple[float, ...] | None = None
    input_power: tuple[float, ...] | None = None
    input_speed_rpm: tuple[float, ...] | None = (2000.0,)
    chunk: int = 16

    def __post_init__(self) -> None:
        if not 1 <= int(self.samples) <= 100_000:
            raise InputError("samples", self.samples, "1 to 100000")
        if self.method not in METHODS:
            raise InputError("method", self.method, "one of " + ", ".join(METHODS))
        if self.output_torque is not None and self.input_power is not None:
            raise InputError("input_power", self.input_power, "not with output_torque")
        checks = [
            ("ratio", self.ratio, "finite numbers > 0"),
            ("input_speed_rpm", self.input_speed_rpm, "finite numbers > 0"),
            ("output_torque", self.output_torque, "finite numbers >= 0"),
            ("input_power", self.input_power, "finite numbers > 0"),
        ]
        for name, values, allowed in checks:
            low = 0.0 if ">=" in allowed else np.nextafter(0.0, 1.0)
            if values is not None and not (
                len(values) and all(np.isfinite(v) and v >= low for v in values)
            ):
                raise InputError(name, values, "one or more " + allowed)
        if not 1 <= self.chunk <= 10_000:
            raise InputError("chunk", self.chunk, "1 to 10000")


@dataclass(frozen=True)
class UncertainDrive:
    """A drive with its uncertain parameters and the clamping it runs with.

    Attributes
    ----------
    drive : Drive
        The nominal drive (design, fluid, architecture).
    table : UncertaintyTable
        Its uncertain values (the ``[uncertainty]`` table of its file).
    clamp_law : str
        Clamping law (`ballcvt.registry.CLAMP_LAWS`).
    clamp_force : float or None
        ``F_N0`` [N] of a fixed-force law.
    options : SolverOptions
        Solver options.
    name : str
        The drive's name or file, as reported.
    """

    drive: Drive
    table: UncertaintyTable
    clamp_law: str = "constant"
    clamp_force: float | None = None
    options: SolverOptions = SolverOptions()
    name: str = ""


def duty_of(request: UncertaintyRequest) -> Duty:
    """The operating points (grid ratio x load x speed) and capacity rows (ratio x speed)."""
    power = request.input_power is not None
    load = request.input_power if power else request.output_torque
    if load is None or request.input_speed_rpm is None:
        raise InputError("output_torque", load, "a torque or a power, and a speed")
    r, t, w = (
        a.ravel()
        for a in np.meshgrid(
            np.asarray(request.ratio, float),
            np.asarray(load, float),
            rpm_to_rad_s(np.asarray(request.input_speed_rpm, float)),
            indexing="ij",
        )
    )
    cr, cw = (
        a.ravel()
        for a in np.meshgrid(
            np.asarray(sorted(set(request.ratio)), float),
            rpm_to_rad_s(np.asarray(sorted(set(request.input_speed_rpm)), float)),
            indexing="ij",
        )
    )
    return Duty(r, w, t, power, cr, cw)


def run_uncertainty(
    target: UncertainDrive, request: UncertaintyRequest, compute: Compute | None = None
) -> UncertaintyResult:
    """Draw ``request.samples`` drives from ``target``'s uncertain parameters and evaluate
    each at the request's operating points and capacity rows.

    Parameters
    ----------
    target : UncertainDrive
        The drive and its uncertain parameters (at least one).
    request : UncertaintyRequest
        Samples, seed, method and operating points.
    compute : Compute, optional
        Where the samples are evaluated (default: in this process).

    Returns
    -------
    UncertaintyResult
    """
    if not len(target.table):
        raise InputError("uncertainty", target.name, "a drive with an [uncertainty] table")
    compute = compute or Compute(in_process=True)
    start = time.perf_counter()
    d = target.drive
    ctx = Context(
        d.design,
        d.fluid,
        d.architecture,
        target.table.paths,
        duty_of(request),
        target.clamp_law,
        target.clamp_force,
        target.options,
    )
    x = draw(target.table, int(request.samples), request.method, int(request.seed))
    nominal = evaluate_chunk(
        ctx, np.array([-1]), np.array([[v.nominal for v in target.table.values]])
    )
    parts, execution = _evaluate(ctx, x, request.chunk, compute)
    got = {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}
    return UncertaintyResult(
        inputs=_inputs(target, request, ctx.duty),
        values=x,
        built=got["built"],
        reason=got["reason"],
        eta=got["eta"],
        status=got["status"],
        output_torque=got["output_torque"],
        capacity=got["capacity"],
        nominal={"eta": nominal["eta"][0], "capacity": nominal["capacity"][0]},
        version=__version__,
        run_time=time.perf_counter() - start,
        execution=execution,
    )


def _evaluate(ctx: Context, x: np.ndarray, chunk: int, compute: Compute):
    """The chunks' results in sample order, and where they ran."""
    from tqdm.auto import tqdm

    n = len(x)
    parts = [np.arange(i, min(i + chunk, n)) for i in range(0, n, chunk)]
    show = sys.stderr.isatty() if compute.progress is None else compute.progress
    bar = tqdm(total=n, desc="uncertainty", unit="drive", disable=not show)
    if compute.in_process and compute.client is None:
        done = []
        for p in parts:
            done.append(evaluate_chunk(ctx, p, x[p]))
            bar.update(p.size)
        bar.close()
        return done, "in process (no Dask)"
    client, own, execution = _connect(compute)
    try:
        remote = client.scatter(ctx, broadcast=True)
        futures = [client.submit(evaluate_chunk, remote, p, x[p], pure=False) for p in parts]
        done = []
        for p, fut in zip(parts, futures):  # gathered in order: results in sample order
            done.append(fut.result())
            bar.update(p.size)
    finally:
        bar.close()
        if own is not None:
            cluster = getattr(own, "cluster", None)
            own.close()
            if cluster is not None:
                cluster.close()
    return done, execution


def _connect(compute: Compute):
    """(client, the client this run owns or None, how the samples are evaluated)."""
    if compute.client is not None:
        return compute.client, None, f"Dask client {compute.client.scheduler.address}"
    if compute.scheduler is not None:
        from distributed import Client

        client = Client(compute.scheduler)
        return client, client, f"Dask scheduler {compute.scheduler}"
    client = local_client(compute.workers)
    return client, client, f"local Dask cluster, {compute.workers} worker processes"


def _inputs(target: UncertainDrive, request: UncertaintyRequest, duty: Duty) -> dict:
    """The inputs of a result, as plain data."""
    key = "input_power" if duty.power else "output_torque"
    return {
        "drive": target.name,
        "architecture": target.drive.architecture,
        "clamp_law": target.clamp_law,
        "clamp_force": target.clamp_force,
        "parameters": [
            {
                "path": v.path,
                "nominal": v.nominal,
                "distribution": v.distribution,
                "description": v.describe(),
                "lo": v.lo,
                "hi": v.hi,
                "source": v.source,
            }
            for v in target.table.values
        ],
        "method": request.method,
        "samples": int(request.samples),
        "seed": int(request.seed),
        "points": [
            {"ratio": float(r), "input_speed_rpm": float(rad_s_to_rpm(w)), key: float(t)}
            for r, w, t in zip(duty.ratio, duty.input_speed, duty.load)
        ],
        "capacity_points": [
            {"ratio": float(r), "input_speed_rpm": float(rad_s_to_rpm(w))}
            for r, w in zip(duty.capacity_ratio, duty.capacity_speed)
        ],
    }
