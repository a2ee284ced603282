"""The params layer: parameter sets (design, material, bearings, fluid, drive, operating point)."""

from .drive import PAPER_POINT, Drive
from .io import BUILTIN_DRIVES, builtin_text, drive_to_toml, load_builtin, load_drive, parse_drive
from .material import FatigueMaterial, load_material
from .models import (
    ARCHITECTURES,
    Architecture,
    BearingModel,
    CamModel,
    Design,
    Fluid,
    Lubrication,
    Material,
    OperatingContext,
    OperatingPoint,
    ParameterModel,
    ParasiticModel,
)

__all__ = [
    "Drive",
    "PAPER_POINT",
    "ARCHITECTURES",
    "Architecture",
    "BearingModel",
    "CamModel",
    "Design",
    "Fluid",
    "FatigueMaterial",
    "Lubrication",
    "Material",
    "OperatingPoint",
    "OperatingContext",
    "ParameterModel",
    "ParasiticModel",
    "BUILTIN_DRIVES",
    "builtin_text",
    "drive_to_toml",
    "load_builtin",
    "load_drive",
    "parse_drive",
    "load_material",
]
