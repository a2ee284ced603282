"""Contact layout of the two architectures (Sec. II.A, Eqs. 1-2, 29; docs/model.md §1).

Frame: ``j`` main axis, ``k`` radial through the ball centre, ``i = j x k`` the rolling
direction. Every per-contact quantity is an array over the contacts, in the order of
`ContactLayout.names`.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..errors import InputError
from ..params.feasibility import check_architecture
from ..params.models import ARCHITECTURES, Design
from ..registry import ARCHITECTURES as REGISTRY

__all__ = ["ContactLayout", "contact_layout", "CONTACT_NAMES"]

#: Contact names per architecture (also the JSON keys of the command-line interface).
CONTACT_NAMES = {
    "double": ("input", "idler_a", "idler_b", "output"),
    "single": ("input", "idler", "output"),
}
for _name, _contacts in CONTACT_NAMES.items():
    REGISTRY.register(_contacts, name=_name)


@dataclass(frozen=True)
class ContactLayout:
    """Tilt-independent geometry of the contacts of one ball.

    Attributes
    ----------
    architecture : str
        ``"double"`` or ``"single"`` idler.
    names : tuple of str
        Contact names; index 0 is the input disc, the last is the output disc.
    z_j, z_k : ndarray
        Components of the outward ball normal ``z_c`` on ``j`` and ``k`` [-].
    radius : ndarray
        Radial distance of the contact point from the main axis over ``r_S``,
        ``r~_c`` (Eq. 2) [-].
    kappa : ndarray
        Sign of the tangential force on the ball along ``+i`` for positive traction
        coefficient: +1 input and idlers, -1 output (docs/model.md §5) [-].
    load_factor : ndarray
        Normal load over ``F_N0`` (Eq. 29; single idler: radial balance) [-].
    groove_ratio : ndarray
        Transverse track radius over ``r_S`` (``inf`` for a straight generatrix) [-].
    is_idler : ndarray of bool
        True for the idler contacts.
    """

    architecture: str
    names: tuple[str, ...]
    z_j: np.ndarray
    z_k: np.ndarray
    radius: np.ndarray
    kappa: np.ndarray
    load_factor: np.ndarray
    groove_ratio: np.ndarray
    is_idler: np.ndarray

    @property
    def n_contacts(self) -> int:
        """Number of contacts per ball."""
        return len(self.names)

    @property
    def idler_index(self) -> np.ndarray:
        """Indices of the idler contacts."""
        return np.flatnonzero(self.is_idler)


def contact_layout(design: Design, architecture: str) -> ContactLayout:
    """Build the `ContactLayout` of ``design`` for ``architecture``.

    Parameters
    ----------
    design : Design
        Drive geometry.
    architecture : {"double", "single"}
        Double idler (the disassembled 2017 drive) or single cylindrical idler
        (the original patent, docs/model.md §1).

    Returns
    -------
    ContactLayout

    Raises
    ------
    InputError
        If the design cannot be built with this architecture (docs/model.md §10).
    """
    if architecture not in ARCHITECTURES:
        raise InputError("architecture", architecture, "one of: " + ", ".join(ARCHITECTURES))
    return _layout(design, architecture)


@lru_cache(maxsize=64)
def _layout(design: Design, architecture: str) -> ContactLayout:
    """`contact_layout` for a valid architecture, kept per (design, architecture): every
    operating point asks for it, and its arrays are read-only."""
    check_architecture(design, architecture)
    k = design.aspect_ratio
    t0, t2, al = design.theta0, design.theta2, design.alpha
    f2 = np.sin(t0) / np.sin(t2)  # Eq. 29
    if architecture == "double":
        fa = np.sin(t0 + t2) / (2.0 * np.cos(al) * np.sin(t2))  # Eq. 29
        z_j = [-np.sin(t0), -np.sin(al), np.sin(al), np.sin(t2)]
        z_k = [np.cos(t0), -np.cos(al), -np.cos(al), np.cos(t2)]
        radius = [1 + k + np.cos(t0), 1 + k - np.cos(al), 1 + k - np.cos(al), 1 + k + np.cos(t2)]
        kappa = [1.0, 1.0, 1.0, -1.0]
        load = [1.0, fa, fa, f2]
        groove = [
            design.disc_groove_ratio,
            design.idler_groove_ratio,
            design.idler_groove_ratio,
            design.disc_groove_ratio,
        ]
    else:
        f1 = np.cos(t0) + f2 * np.cos(t2)  # radial balance
        z_j = [-np.sin(t0), 0.0, np.sin(t2)]
        z_k = [np.cos(t0), -1.0, np.cos(t2)]
        radius = [1 + k + np.cos(t0), k, 1 + k + np.cos(t2)]
        kappa = [1.0, 1.0, -1.0]
        load = [1.0, f1, f2]
        groove = [
            design.disc_groove_ratio,
            design.single_idler_groove_ratio,
            design.disc_groove_ratio,
        ]
    names = CONTACT_NAMES[architecture]
    is_idler = np.array([n.startswith("idler") for n in names])
    is_idler.flags.writeable = False

    def arr(v):
        a = np.asarray(v, dtype=float)
        a.flags.writeable = False
        return a

    return ContactLayout(
        architecture,
        names,
        arr(z_j),
        arr(z_k),
        arr(radius),
        arr(kappa),
        arr(load),
        arr(groove),
        is_idler,
    )
