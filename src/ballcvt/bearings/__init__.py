"""Layer 3: rolling-bearing friction torques (Eqs. 15-16, docs/model.md §4)."""

from .friction import load_dependent_torque, speed_dependent_torque

__all__ = ["load_dependent_torque", "speed_dependent_torque"]
