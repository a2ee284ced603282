"""Operating modes: which member of the planetary is held and which drives (docs/model.md §13)."""

from .members import MEMBERS, OperatingMode, member_torques, relative_ratio_coefficients

__all__ = ["MEMBERS", "OperatingMode", "member_torques", "relative_ratio_coefficients"]
