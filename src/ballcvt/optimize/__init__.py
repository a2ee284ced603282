"""Layer 8: design and operating choices (optimal clamping force)."""

from .clamp import ClampOptimum, optimal_clamp_force

__all__ = ["ClampOptimum", "optimal_clamp_force"]
