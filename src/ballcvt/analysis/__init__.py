"""Workflows on top of the solvers: sweeps and maps, tables, duty cycles, design studies,
fluid fitting and the reproduction of the paper. They take a drive and solver options,
never the public API object."""

from .._lazy import lazy_exports

#: Public name -> the submodule that defines it (loaded on first use: `ballcvt._lazy`).
_EXPORTS = {
    "traction_ceiling": ".capacity",
    "torque_capacity": ".capacity",
    "Capacity": ".capacity",
    "kinematic_spin": ".kinematics",
    "ratio_tilt_curve": ".kinematics",
    "OperatingMode": ".planetary",
    "mode_capacity": ".planetary",
    "mode_curves": ".planetary",
    "mode_kinematics": ".planetary",
    "write_table": ".sweeps.export",
}
__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)

__all__ = [
    "traction_ceiling",
    "torque_capacity",
    "Capacity",
    "ratio_tilt_curve",
    "kinematic_spin",
    "OperatingMode",
    "mode_kinematics",
    "mode_curves",
    "mode_capacity",
    "write_table",
]
