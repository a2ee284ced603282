"""Fitting model parameters to measurements: fluid traction parameters (docs/model.md §14)."""

from .fluid import (
    COLUMNS,
    DEFAULT_PARAMETERS,
    FITTABLE,
    Curves,
    FluidFit,
    fit_fluid,
    model_mu,
    read_curves,
)

__all__ = [
    "COLUMNS",
    "DEFAULT_PARAMETERS",
    "FITTABLE",
    "Curves",
    "FluidFit",
    "fit_fluid",
    "model_mu",
    "read_curves",
]
