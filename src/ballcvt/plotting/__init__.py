"""Layer 10: figures (matplotlib). Never imported by the physics layers."""

from .figures import efficiency_map, line_panels, ratio_vs_tilt, save

__all__ = ["save", "line_panels", "efficiency_map", "ratio_vs_tilt"]
