"""The api layer, the public API: `Variator` and every function the front ends use.

Everything the command line does is reachable from here (and from ``ballcvt``'s top-level
names): points, limits and limit curves, optimal clamping, sweeps, efficiency maps and
lookup tables, duty cycles, planetary modes, traction curves, fluid fitting, design
studies and drive files. The front ends (`ballcvt.interfaces`) import only this package,
the leaves and the reports (tests/test_public_api.py).
"""

from .._lazy import lazy_exports
from ..analysis.cycle_files import STRATEGIES, Cycle, cycle_from_arrays, read_cycle
from ..model.life import LIFE_MODELS
from ..model.modes import MEMBERS, OperatingMode
from ..model.traction.curve import TractionCurve, traction_curve
from ..params import PAPER_POINT, Design, Drive, Fluid, drive_to_toml, load_builtin, load_drive
from ..params.drive_models import DriveModels, drive_clamp, effective_models
from ..params.io import BUILTIN_DRIVES, BUILTIN_FLUIDS, builtin_text, resolve_drive, resolve_fluid
from ..results.planetary import PlanetaryResult
from ..results.point import ContactResult, OperatingResult
from ..solvers.limit import LimitSearch
from ..solvers.planetary_batch import ModeBatch
from .batched import CAM_KEYS
from .cam_sizing import (
    CamSizing,
    check_operating,
    drive_warnings,
    operating_ratio_range,
    operating_speed_rpm,
    rated_torque,
    size_cam,
)
from .capacity import CapacityCurve, capacity_curve
from .grids import LimitCurve
from .life import life_settings
from .oil import with_oil_temperature
from .settings import CycleSettings, MapGrid, SolveSettings, SweepSettings, TableGrid
from .shift_moments import ShiftMoments
from .tools import contact_fluid, drive_text, open_drive, read_study
from .variator import Variator

#: Names whose modules load xarray, pandas or Dask: imported on first use (`ballcvt._lazy`).
_LAZY = {
    "CycleResult": "..analysis.cycles",
    "ShiftResult": "..analysis.shift",
    "LifeResult": "..analysis.life.result",
    "ElementLife": "..analysis.life.result",
    "LifeSettings": "..analysis.life.core",
    "cycle_life": "..analysis.life.cycle",
    "sweep_life": "..analysis.life.maps",
    "Curves": "..analysis.fitting",
    "FluidFit": "..analysis.fitting",
    "fit_fluid": "..analysis.fitting",
    "read_curves": "..analysis.fitting",
    "StudyResult": "..analysis.studies",
    "StudySpec": "..analysis.studies",
    "run_study": "..analysis.studies",
    "folder_lock": "..analysis.studies",
    "load_dataset": "..analysis.sweeps.export",
    "to_csv": "..analysis.sweeps.export",
    "to_frame": "..analysis.sweeps.export",
    "to_netcdf": "..analysis.sweeps.export",
    "read_modelica_tables": "..analysis.tables",
    "table_arrays": "..analysis.tables",
    "write_tables": "..analysis.tables",
    "UncertaintyResult": "..analysis.uncertainty",
    "UncertaintyRequest": "..analysis.uncertainty",
    "uncertainty": ".propagate",
}
__getattr__, __dir__ = lazy_exports(__name__, _LAZY)

__all__ = [
    "folder_lock",
    "with_oil_temperature",
    "PAPER_POINT",
    "Drive",
    "Variator",
    "SolveSettings",
    "SweepSettings",
    "CycleSettings",
    "MapGrid",
    "TableGrid",
    "LimitCurve",
    "LimitSearch",
    "CapacityCurve",
    "capacity_curve",
    "CAM_KEYS",
    "DriveModels",
    "drive_clamp",
    "effective_models",
    "OperatingResult",
    "ContactResult",
    "PlanetaryResult",
    "OperatingMode",
    "MEMBERS",
    "ModeBatch",
    "Cycle",
    "CycleResult",
    "ShiftResult",
    "LifeResult",
    "ElementLife",
    "LifeSettings",
    "LIFE_MODELS",
    "ShiftMoments",
    "life_settings",
    "cycle_life",
    "sweep_life",
    "STRATEGIES",
    "read_cycle",
    "cycle_from_arrays",
    "to_netcdf",
    "to_csv",
    "to_frame",
    "load_dataset",
    "write_tables",
    "read_modelica_tables",
    "table_arrays",
    "traction_curve",
    "TractionCurve",
    "Curves",
    "FluidFit",
    "fit_fluid",
    "read_curves",
    "StudySpec",
    "StudyResult",
    "read_study",
    "run_study",
    "open_drive",
    "contact_fluid",
    "drive_text",
    "Design",
    "Fluid",
    "load_builtin",
    "load_drive",
    "drive_to_toml",
    "resolve_drive",
    "resolve_fluid",
    "builtin_text",
    "BUILTIN_DRIVES",
    "BUILTIN_FLUIDS",
    "CamSizing",
    "size_cam",
    "rated_torque",
    "drive_warnings",
    "check_operating",
    "operating_ratio_range",
    "operating_speed_rpm",
    "uncertainty",
    "UncertaintyResult",
    "UncertaintyRequest",
]
