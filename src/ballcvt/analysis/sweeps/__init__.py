"""The analysis layer: sweeps over operating conditions as `xarray.Dataset` objects, and their export."""

from .curves import OperatingRows, limit_search_curves, solve_curves
from .export import load_dataset, parameters, to_csv, to_frame, to_netcdf
from .grid import sweep
from .variables import LOSS_KINDS, VARIABLES

__all__ = [
    "sweep",
    "solve_curves",
    "limit_search_curves",
    "OperatingRows",
    "VARIABLES",
    "LOSS_KINDS",
    "to_netcdf",
    "to_csv",
    "to_frame",
    "load_dataset",
    "parameters",
]


def __getattr__(name):
    if name == "STATUS":  # the old name -> code table of a sweep's status
        from ..._compat import warn_renamed
        from .variables import SWEEP_CODES

        warn_renamed("ballcvt.analysis.sweeps.STATUS", "ballcvt.status.Status")
        return {s.label: int(s) for s in SWEEP_CODES}
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
