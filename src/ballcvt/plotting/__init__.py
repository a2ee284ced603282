"""A leaf: figures (matplotlib). Never imported by the physics layers.

Importing this package does not change matplotlib's backend.
"""

from .capacity import capacity_figure
from .cycles import cycle_figure
from .figures import (
    LABELS,
    draw_efficiency_map,
    draw_life_contours,
    efficiency_map,
    line_panels,
    map_title,
    plot_curves,
    plot_efficiency_map,
    ratio_vs_tilt,
    save,
)
from .shift import shift_figure
from .shift_effort import shift_effort_map
from .studies import maps_figure, parameters_figure, pareto_figure
from .traction import fit_figure, plot_traction_curve, traction_curve_figure
from .uncertainty import uncertainty_figure

__all__ = [
    "capacity_figure",
    "cycle_figure",
    "shift_figure",
    "save",
    "line_panels",
    "map_title",
    "efficiency_map",
    "shift_effort_map",
    "draw_efficiency_map",
    "draw_life_contours",
    "plot_efficiency_map",
    "plot_curves",
    "ratio_vs_tilt",
    "LABELS",
    "fit_figure",
    "maps_figure",
    "parameters_figure",
    "pareto_figure",
    "plot_traction_curve",
    "traction_curve_figure",
    "uncertainty_figure",
]
