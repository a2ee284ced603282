"""The reports layer: the reproduction of the paper (figures, claims, report)."""

from .reproduce import GRIDS, Reproduction, reproduce

__all__ = ["reproduce", "Reproduction", "GRIDS"]
