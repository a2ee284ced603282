"""Layer 7: result objects (and, later, sweeps)."""

from .point import ContactResult, OperatingResult, make_result

__all__ = ["ContactResult", "OperatingResult", "make_result"]
