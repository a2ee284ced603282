"""`Drive`: the parameter sets that travel together (design, fluid, idler architecture)."""

from __future__ import annotations

from dataclasses import dataclass

from ..units import rpm_to_rad_s
from .models import Design, Fluid, OperatingPoint

__all__ = ["Drive", "PAPER_POINT"]

#: The paper's operating point of Figs. 7 and 9-13 (Sec. 4): tau_ID = 1, T_2 = 40 N m,
#: F_N0 = 2000 N, 2000 rpm input. The command line's, the explorer's and the
#: reproduction's starting point.
PAPER_POINT = OperatingPoint(
    ratio=1.0, output_torque=40.0, clamp_force=2000.0, input_speed=rpm_to_rad_s(2000.0)
)


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
