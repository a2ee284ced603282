"""The analysis layer: sweeps over operating conditions as `xarray.Dataset` objects, and their export."""

from ..._lazy import lazy_exports

#: Public name -> the submodule that defines it (loaded on first use: `ballcvt._lazy`).
_EXPORTS = {
    "OperatingRows": ".curves",
    "limit_search_curves": ".curves",
    "solve_curves": ".curves",
    "load_dataset": ".export",
    "parameters": ".export",
    "to_csv": ".export",
    "to_frame": ".export",
    "to_netcdf": ".export",
    "sweep": ".grid",
    "LOSS_KINDS": ".variables",
    "VARIABLES": ".variables",
}

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


def _renamed(name):
    if name == "STATUS":  # the old name -> code table of a sweep's status
        from ..._compat import warn_renamed
        from .variables import SWEEP_CODES

        warn_renamed("ballcvt.analysis.sweeps.STATUS", "ballcvt.status.Status")
        return {s.label: int(s) for s in SWEEP_CODES}
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, _renamed)
