"""Clamping laws: where the input-contact normal load ``F_N0`` comes from (docs/model.md §11).

A clamping law is a named, pluggable piece: a `ClampLaw` subclass registered in
`ballcvt.registry.CLAMP_LAWS` (`base` says what a law answers). The built-in laws are
``constant`` (`ConstantClamp`), ``cam`` (`CamClamp`) and ``optimal`` (`OptimalClamp`);
a law defined in user code is registered the same way
(examples/extending/clamp_law.py).
"""

from ...registry import CLAMP_LAWS
from .base import ClampLaw, axial_force, clamp_law
from .cam import CamClamp
from .constant import ConstantClamp
from .optimal import OptimalClamp

# registered here, in this order (the order of the choices in messages and the CLI)
for _law in (ConstantClamp, CamClamp, OptimalClamp):
    CLAMP_LAWS.register(_law, name=_law.name)

__all__ = [
    "ClampLaw",
    "ConstantClamp",
    "CamClamp",
    "OptimalClamp",
    "CLAMP_LAWS",
    "axial_force",
    "clamp_law",
]
