"""`Drive`: the parameter sets that travel together (design, fluid, idler architecture)."""

from __future__ import annotations

from dataclasses import dataclass

from .models import Design, Fluid

__all__ = ["Drive"]


@dataclass(frozen=True)
class Drive:
    """A drive to analyse: its design, its fluid and its idler architecture.

    The analysis layer (cycles, studies) takes a `Drive` (or any object with these three
    attributes and, optionally, solver ``options``, such as `ballcvt.Variator`), never the
    public API object itself.

    Parameters
    ----------
    design : Design
        Geometry, materials, bearings, cam and parasitic-loss parameters.
    fluid : Fluid
        Traction fluid and its traction law.
    architecture : str
        ``"double"`` or ``"single"`` idler (``ballcvt.registry.ARCHITECTURES``).
    """

    design: Design
    fluid: Fluid
    architecture: str = "double"
