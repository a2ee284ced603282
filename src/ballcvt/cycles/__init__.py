"""Duty cycles: a drive over a time series (docs/cycles.md).

`run_cycle` and `CycleResult` load the sweep machinery (xarray, pandas) only when used,
so that the command line starts fast.
"""

from .io import KINDS, STRATEGIES, UNITS, Cycle, cycle_from_arrays, read_cycle

__all__ = [
    "Cycle",
    "CycleResult",
    "FLAGS",
    "KINDS",
    "STRATEGIES",
    "UNITS",
    "cycle_from_arrays",
    "read_cycle",
    "run_cycle",
]


def __getattr__(name):
    if name in ("run_cycle", "CycleResult", "FLAGS"):
        from . import run

        return getattr(run, name)
    raise AttributeError(f"module 'ballcvt.cycles' has no attribute {name!r}")
