"""An idler architecture: its contacts, layout and feasibility (Sec. II.A; docs/model.md §1).

An `Architecture` is an entry of `ballcvt.registry.ARCHITECTURES`: it names the contacts of
one ball, builds their geometry for a design (`ContactGeometry`) and refuses designs it
cannot be built with. `contact_layout` turns it into the read-only `ContactLayout` every
operating point uses. Adding an architecture is one module with a subclass and one
``ARCHITECTURES.register(...)`` call (docs/architecture.md).
"""

from __future__ import annotations

import abc
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ...errors import InputError
from ...params.models import Design
from ...registry import ARCHITECTURES
from ..layout import ContactLayout

__all__ = [
    "Architecture",
    "ContactGeometry",
    "ContactLayout",
    "contact_layout",
    "check_architecture",
    "CONTACT_NAMES",
]


@dataclass(frozen=True)
class ContactGeometry:
    """Per-contact numbers of a design in one architecture (the fields of `ContactLayout`
    with the same names, as sequences in the order of `Architecture.contacts`) [-]."""

    z_j: Sequence[float]
    z_k: Sequence[float]
    radius: Sequence[float]
    kappa: Sequence[float]
    load_factor: Sequence[float]
    groove_ratio: Sequence[float]
    radial_share: Sequence[float]


class Architecture(abc.ABC):
    """An idler layout: subclass, set `name` and `contacts`, implement the three methods.

    Attributes
    ----------
    name : str
        Registry name (also the ``architecture`` option of the API and the CLI).
    contacts : tuple of str
        Contact names: the input disc first, the output disc last; the idler contacts'
        names start with ``idler`` (the JSON keys of the command-line interface).
    """

    name: str = ""
    contacts: tuple[str, ...] = ()

    @abc.abstractmethod
    def geometry(self, design: Design) -> ContactGeometry:
        """Normals, radii, load factors and groove ratios of the contacts of ``design``."""

    @abc.abstractmethod
    def idler_radius(self, design: Design) -> float:
        """Radius of the idler at its contacts [m] (bounds its bearing, Eq. F6)."""

    def check_layout(self, design: Design) -> None:
        """Refuse a design this layout cannot be built with (beyond Eq. F6); none by default.

        Raises
        ------
        InputError
            On the first violated bound.
        """
        return None

    def check(self, design: Design) -> None:
        """`check_layout`, then the idler bearing inside the idler (Eq. F6).

        Raises
        ------
        InputError
            On the first violated bound (docs/model.md §10).
        """
        self.check_layout(design)
        idler_radius = self.idler_radius(design)
        if design.idler_bearing_diameter >= 2.0 * idler_radius:  # Eq. F6
            raise InputError(
                "idler_bearing_diameter",
                design.idler_bearing_diameter,
                f"< {2 * idler_radius:.4g} m, the {self.name} idler's diameter at its contacts",
            )

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self.name!r}: {', '.join(self.contacts)})"


class _ContactNames(Mapping):
    """Architecture name -> contact names, read from the registry (a live view)."""

    def __getitem__(self, name: str) -> tuple[str, ...]:
        return ARCHITECTURES.get(name).contacts

    def __iter__(self) -> Iterator[str]:
        return iter(ARCHITECTURES)

    def __len__(self) -> int:
        return len(ARCHITECTURES)


#: Contact names per architecture (also the JSON keys of the command-line interface).
CONTACT_NAMES: Mapping[str, tuple[str, ...]] = _ContactNames()


def check_architecture(design: Design, architecture: str) -> None:
    """Refuse a design that cannot be built with ``architecture`` (Eqs. F4-F6).

    Raises
    ------
    InputError
        For an unknown architecture, or on the first violated bound.
    """
    ARCHITECTURES.get(architecture).check(design)


def contact_layout(design: Design, architecture: str) -> ContactLayout:
    """Build the `ContactLayout` of ``design`` for ``architecture``.

    Parameters
    ----------
    design : Design
        Drive geometry.
    architecture : str
        A name of `ballcvt.registry.ARCHITECTURES`: ``"double"`` idler (the disassembled
        2017 drive) or ``"single"`` cylindrical idler (the original patent,
        docs/model.md §1).

    Returns
    -------
    ContactLayout

    Raises
    ------
    InputError
        If the architecture is unknown or the design cannot be built with it
        (docs/model.md §10).
    """
    return _layout(design, ARCHITECTURES.get(architecture))


@lru_cache(maxsize=64)
def _layout(design: Design, arch: Architecture) -> ContactLayout:
    """`contact_layout` for a registered architecture, kept per (design, architecture):
    every operating point asks for it, and its arrays are read-only."""
    arch.check(design)
    g = arch.geometry(design)
    is_idler = np.array([n.startswith("idler") for n in arch.contacts])
    is_idler.flags.writeable = False

    def arr(v):
        a = np.asarray(v, dtype=float)
        a.flags.writeable = False
        return a

    return ContactLayout(
        arch.name,
        arch.contacts,
        arr(g.z_j),
        arr(g.z_k),
        arr(g.radius),
        arr(g.kappa),
        arr(g.load_factor),
        arr(g.groove_ratio),
        is_idler,
        arr(g.radial_share),
    )
