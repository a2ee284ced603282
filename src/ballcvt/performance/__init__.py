"""The performance layer: power losses and efficiency (Eqs. 9, 36-40, docs/model.md §7)."""

from .efficiency import Efficiency, PowerLosses, efficiency, power_losses

__all__ = ["Efficiency", "PowerLosses", "efficiency", "power_losses"]
