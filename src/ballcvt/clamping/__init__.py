"""Clamping laws: the source of the clamping force (docs/model.md §11)."""

from .laws import CLAMP_LAWS, CamClamp, ConstantClamp, OptimalClamp, axial_force, clamp_law

__all__ = ["CLAMP_LAWS", "CamClamp", "ConstantClamp", "OptimalClamp", "axial_force", "clamp_law"]
