"""A sweep's curves solved in chunks, written straight into the output arrays.

Memory stays bounded: each chunk of `CHUNK_POINTS` points (whole curves, contiguous) is
solved (`ballcvt.analysis.sweeps.curves.solve_curves`) and its results copied into arrays
allocated once for the whole grid, in the layout of the final `xarray.Dataset`; the chunk's
intermediates (Jacobians, quadrature states, per-contact scratch) are then dropped. The
peak is the output arrays (about 0.5 kB per point, docs/performance.md) plus one chunk's
work per process.

With ``workers > 1`` the chunks go to a pool of worker processes started once; each result
is written into the output arrays as it arrives and then dropped.
"""

from __future__ import annotations

from concurrent.futures import ProcessPoolExecutor, as_completed
from dataclasses import dataclass

import numpy as np

from ...model.architectures import CONTACT_NAMES
from ...solvers.limit import LimitSearch, bisection_steps
from .curves import OperatingRows, solve_curves
from .variables import (
    CONTACT_VARIABLES,
    LOSS_SUBTOTALS,
    POINT_VARIABLES,
    SWEEP_LOSSES,
    component_losses,
    contact_columns,
    subtotal_losses,
)

__all__ = ["CHUNK_POINTS", "SweepArrays", "solve_chunked", "curve_chunks"]

#: Points (curves x torques) solved together: bounds a sweep's working memory (about 5 kB
#: per point in flight) while keeping the batches long enough for the batched solver.
CHUNK_POINTS = 8192
#: The fewest points of a chunk made only to give a worker process some work.
SPLIT_POINTS = 1024

#: Per-curve outputs (no torque axis).
CURVE_VARIABLES = ("limit_torque", "eta_at_limit")
#: Per-point outputs with their dtype and fill value (NaN where not solved).
POINT_OUTPUTS = {
    "status": (np.int8, 0),
    "warnings": (np.int8, 0),
    "iterations": (np.int64, 0),
    "residual_norm": (float, np.nan),
    **{name: (float, np.nan) for name in POINT_VARIABLES},
}


@dataclass
class SweepArrays:
    """The output arrays of a sweep, ``(architecture, curve, output_torque[, ...])``.

    Attributes
    ----------
    data : dict of ndarray
        Variable name -> array; curves in C order of ``(clamp_force, input_speed, ratio)``.
    contacts : list of str
        The union contact axis of the architectures swept.
    """

    data: dict
    contacts: list

    @classmethod
    def allocate(cls, n_arch: int, n_curves: int, n_torque: int, contacts, law: bool):
        """Arrays for ``n_arch`` architectures x ``n_curves`` curves x ``n_torque``
        torques (``clamp_force`` per point when ``law``)."""
        lead = (n_arch, n_curves)
        data = {name: np.full(lead, np.nan) for name in CURVE_VARIABLES}
        for name, (dtype, fill) in POINT_OUTPUTS.items():
            data[name] = np.full(lead + (n_torque,), fill, dtype=dtype)
        data["loss_subtotals"] = np.full(lead + (n_torque, len(LOSS_SUBTOTALS)), np.nan)
        data["losses"] = np.full(lead + (n_torque, len(SWEEP_LOSSES)), np.nan)
        for name in CONTACT_VARIABLES:
            data[name] = np.full(lead + (n_torque, len(contacts)), np.nan)
        if law:
            data["clamp_force"] = np.full(lead + (n_torque,), np.nan)
        return cls(data, list(contacts))

    def write(self, arch_index: int, arch: str, rows: slice, result: dict) -> None:
        """Copy the `solve_curves` ``result`` of curves ``rows`` of architecture ``arch``."""
        d, at = self.data, (arch_index, rows)
        for name in (*CURVE_VARIABLES, *POINT_OUTPUTS):
            d[name][at] = result[name]
        cols = contact_columns(self.contacts, CONTACT_NAMES[arch])
        for name in CONTACT_VARIABLES:
            d[name][arch_index][rows, :, cols] = result[name]  # one advanced index
        kinds = result["losses"]
        d["loss_subtotals"][at] = subtotal_losses(kinds)
        d["losses"][at] = component_losses(kinds)
        if "clamp_force" in d:
            d["clamp_force"][at] = result["clamp_force"]


def curve_chunks(n_curves: int, n_torque: int, workers: int = 1) -> list[slice]:
    """Contiguous chunks of whole curves of at most `CHUNK_POINTS` points each (at least
    one curve), as even as can be.

    With ``workers`` > 1 a grid of fewer chunks than workers is split further, into
    chunks of no fewer than `SPLIT_POINTS` points (then the results can differ from one
    process's by round-off; a grid of `CHUNK_POINTS` points or more is split the same
    way whatever ``workers``, so gives the same bits).
    """
    nt = max(1, n_torque)
    count = -(-n_curves * nt // CHUNK_POINTS)
    if count < workers:
        count = max(count, min(workers, n_curves * nt // SPLIT_POINTS))
    size = max(1, min(CHUNK_POINTS // nt, -(-n_curves // max(1, count))))
    return [slice(a, min(a + size, n_curves)) for a in range(0, n_curves, size)]


def _limits_of(limits, rows: slice):
    """The given limits of curves ``rows`` (an array or a `LimitSearch`), or None."""
    if limits is None:
        return None
    if isinstance(limits, LimitSearch):
        return limits.take(np.arange(rows.start, rows.stop))
    return limits[rows]


@dataclass(frozen=True)
class ChunkRun:
    """How one architecture's curves are solved into `SweepArrays`.

    Attributes
    ----------
    curves : OperatingRows
        Every curve of the architecture (C order).
    torque : ndarray
        Output torques [N m], increasing.
    limits : ndarray, LimitSearch or None
        Limits handed over (flat), or None to search them.
    arch_index : int
        Index of the architecture in the output arrays.
    """

    curves: OperatingRows
    torque: np.ndarray
    limits: object
    arch_index: int

    def steps(self, chunks) -> int:
        """Progress-bar steps of a one-process run: the torques of each chunk, and the
        steps of the limit search (one search of every curve when there are chunks)."""
        return self.torque.size * len(chunks) + (bisection_steps() if self.limits is None else 0)

    def job(self, rows: slice):
        """The arguments of `solve_curves` for the curves ``rows``."""
        return (
            self.curves.take(np.arange(rows.start, rows.stop)),
            self.torque,
            _limits_of(self.limits, rows),
        )


def solve_chunked(run: ChunkRun, out: SweepArrays, chunks, pool=None, callback=None) -> None:
    """Solve the ``chunks`` (`curve_chunks`) of ``run`` into ``out``; ``pool``: a
    `ProcessPoolExecutor` to solve them in (``callback`` then gets one call per chunk,
    else one per step)."""
    arch = run.curves.drive.architecture
    if pool is None:
        for rows in chunks:
            curves, torque, limits = run.job(rows)
            out.write(run.arch_index, arch, rows, solve_curves(curves, torque, limits, callback))
        return
    futures = {pool.submit(solve_curves, *run.job(rows)): rows for rows in chunks}
    for f in as_completed(futures):
        out.write(run.arch_index, arch, futures.pop(f), f.result())
        if callback is not None:
            callback()


def worker_pool(workers: int):
    """A pool of ``workers`` processes (None for one: solved in this process)."""
    return ProcessPoolExecutor(max_workers=workers) if workers > 1 else None
