"""`ContactLayout`: the tilt-independent contact geometry of one ball (docs/model.md §1).

Built by an architecture (`ballcvt.model.architectures`); read by the kinematics, the
Hertz contacts and the balances. Frame: ``j`` main axis, ``k`` radial through the ball
centre, ``i = j x k`` the rolling direction. Every per-contact quantity is an array over
the contacts, in the order of `ContactLayout.names`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["ContactLayout"]


@dataclass(frozen=True)
class ContactLayout:
    """Tilt-independent geometry of the contacts of one ball.

    Attributes
    ----------
    architecture : str
        Name of the architecture (``"double"`` or ``"single"`` idler, or a registered one).
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
    radial_share : ndarray
        Normal load each contact loses per newton of outward radial force on the ball
        (the centrifugal force, docs/model.md §13) [-].
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
    radial_share: np.ndarray

    @property
    def n_contacts(self) -> int:
        """Number of contacts per ball."""
        return len(self.names)

    @property
    def idler_index(self) -> np.ndarray:
        """Indices of the idler contacts."""
        return np.flatnonzero(self.is_idler)
