"""Idler architectures (Sec. II.A, Eqs. 1-2, 29; docs/model.md §1): one module each.

Each module defines an `Architecture` subclass and registers an instance in
`ballcvt.registry.ARCHITECTURES`; `contact_layout` builds the `ContactLayout` of a design
for a registered name.
"""

from __future__ import annotations

from .base import (
    CONTACT_NAMES,
    Architecture,
    ContactGeometry,
    ContactLayout,
    check_architecture,
    contact_layout,
)
from .double import DOUBLE, DoubleIdler
from .single import SINGLE, SingleIdler

__all__ = [
    "Architecture",
    "ContactGeometry",
    "ContactLayout",
    "contact_layout",
    "check_architecture",
    "CONTACT_NAMES",
    "DoubleIdler",
    "SingleIdler",
    "DOUBLE",
    "SINGLE",
]
