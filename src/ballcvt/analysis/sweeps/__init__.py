"""Layer 7: sweeps over operating conditions as `xarray.Dataset` objects, and their export."""

from .curves import limit_torques, solve_curves
from .export import load_dataset, parameters, to_csv, to_frame, to_netcdf
from .grid import STATUS, sweep
from .variables import LOSS_KINDS, VARIABLES

__all__ = [
    "sweep",
    "solve_curves",
    "limit_torques",
    "STATUS",
    "VARIABLES",
    "LOSS_KINDS",
    "to_netcdf",
    "to_csv",
    "to_frame",
    "load_dataset",
    "parameters",
]
