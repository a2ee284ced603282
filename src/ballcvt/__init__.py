"""ballcvt: steady-state performance model of ball-type traction CVTs.

Implements Tomaselli, Bottiglione, Lino, Carbone, "NuVinci drive: modeling and performance
analysis", Mech. Mach. Theory 150 (2020) 103877, with the resolutions of its ambiguities
documented in ``docs/model.md``.

Quick start::

    from ballcvt import Variator
    r = Variator().solve(ratio=1.0, output_torque=40.0, clamp_force=2000.0,
                         input_speed_rpm=2000)
    print(r.eta, r.contacts["output"].creep)

Everything the command line does is a public name here (docs/api.md).
"""

from typing import TYPE_CHECKING, Any

from . import _compat, api
from ._version import __version__
from .api import (
    BUILTIN_DRIVES,
    BUILTIN_FLUIDS,
    MEMBERS,
    STRATEGIES,
    Cycle,
    CycleSettings,
    LimitCurve,
    MapGrid,
    ModeBatch,
    OperatingMode,
    PlanetaryResult,
    ShiftMoments,
    SolveSettings,
    SweepSettings,
    TableGrid,
    TractionCurve,
    Variator,
    contact_fluid,
    cycle_from_arrays,
    drive_text,
    open_drive,
    read_cycle,
    read_study,
    traction_curve,
)
from .errors import BallCVTError, ConvergenceError, InputError, TractionLimitError
from .model.traction.quadrature import REFERENCE, Quadrature
from .params import Design, Fluid, OperatingPoint, drive_to_toml, load_builtin, load_drive
from .results.point import ContactResult, OperatingResult
from .solvers.options import SolverOptions

if TYPE_CHECKING:
    from .reports.reproduce import reproduce as reproduce
    from .reports.study import study_report

_compat.install()

#: Names of the reports layer (above the API), imported on first use: they load matplotlib.
_REPORTS = {"reproduce": "ballcvt.reports", "study_report": "ballcvt.reports.study"}


def __getattr__(name: str) -> Any:
    import importlib

    if name in _REPORTS:
        return getattr(importlib.import_module(_REPORTS[name]), name)
    if name in api._LAZY:  # sweeps' files, tables, cycles' results, fitting, studies
        return getattr(api, name)
    raise AttributeError(f"module 'ballcvt' has no attribute {name!r}")


__all__ = [
    "__version__",
    "Variator",
    "Design",
    "Fluid",
    "OperatingPoint",
    "load_builtin",
    "load_drive",
    "drive_to_toml",
    "OperatingResult",
    "ContactResult",
    "SolverOptions",
    "Quadrature",
    "REFERENCE",
    "BallCVTError",
    "InputError",
    "TractionLimitError",
    "ConvergenceError",
    # settings and grids of the Variator methods
    "SolveSettings",
    "SweepSettings",
    "CycleSettings",
    "MapGrid",
    "TableGrid",
    "LimitCurve",
    # planetary modes
    "OperatingMode",
    "MEMBERS",
    "PlanetaryResult",
    "ModeBatch",
    # shifting (docs/model.md §15)
    "ShiftMoments",
    # duty cycles, tables and data files
    "Cycle",
    "CycleResult",
    "STRATEGIES",
    "read_cycle",
    "cycle_from_arrays",
    "to_netcdf",
    "to_csv",
    "load_dataset",
    "write_tables",
    "read_modelica_tables",
    # single contacts and fluid fitting
    "traction_curve",
    "TractionCurve",
    "Curves",
    "FluidFit",
    "fit_fluid",
    "read_curves",
    # drives by name or file
    "open_drive",
    "contact_fluid",
    "drive_text",
    "BUILTIN_DRIVES",
    "BUILTIN_FLUIDS",
    # design studies and the reproduction of the paper
    "StudySpec",
    "StudyResult",
    "read_study",
    "run_study",
    "study_report",
    "reproduce",
]
