"""The results layer: immutable result objects, saved and loaded."""

from .point import ContactResult, OperatingResult, make_result

__all__ = ["ContactResult", "OperatingResult", "make_result"]
