"""Workflows on top of the solvers: sweeps and maps, tables, duty cycles, design studies,
fluid fitting and the reproduction of the paper. They take a drive and solver options,
never the public API object."""

from .capacity import limit_curves, traction_ceiling
from .kinematics import kinematic_spin, ratio_tilt_curve
from .planetary import OperatingMode, mode_capacity, mode_curves, mode_kinematics
from .sweeps.export import write_table

__all__ = [
    "traction_ceiling",
    "limit_curves",
    "ratio_tilt_curve",
    "kinematic_spin",
    "OperatingMode",
    "mode_kinematics",
    "mode_curves",
    "mode_capacity",
    "write_table",
]
