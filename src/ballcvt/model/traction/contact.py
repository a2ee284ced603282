"""The per-contact state a traction law reads, and the dispatcher to the fluid's law.

Every traction law maps the same nine per-contact quantities (`ContactState`) and a fluid
to the traction and spin-moment coefficients ``mu`` and ``chi`` (Eqs. 30, 31, 57-66). The
law is the fluid's (``Fluid.traction_law``), looked up in
`ballcvt.registry.TRACTION_LAWS`, so that `contact_coefficients` serves the built-in laws
and any law registered from user code alike (docs/model.md §14).
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from ..._compat import warn_renamed
from ...params.models import Fluid
from ...registry import TRACTION_LAWS
from .quadrature import Quadrature

__all__ = ["ContactState", "contact_coefficients", "legacy_arguments"]


class ContactState(NamedTuple):
    """The nine per-contact quantities of a traction law (arrays broadcast together).

    An immutable named tuple (cheap to build: the solvers make one per evaluation).

    Attributes
    ----------
    creep_term : array_like
        Gross sliding over ``u_ref``: ``C_0`` at the input, ``C/(1-C)`` elsewhere [-].
    spin : array_like
        Spin coefficient ``sigma`` (Eqs. 11-14) [-].
    ax, ay : array_like
        Hertz semi-axes along rolling and transverse directions [m] (Eqs. 45-49).
    p_max : array_like
        Hertz peak pressure [Pa] (Eq. 50).
    load : array_like
        Normal load ``F_N`` [N].
    radius : array_like
        Radial position of the contact ``r_c`` [m].
    u_ref : array_like
        Body surface speed ``|Omega_c| r_c`` [m/s].
    film : array_like
        Central film thickness ``h`` [m] (Eq. 56).
    """

    creep_term: Any
    spin: Any
    ax: Any
    ay: Any
    p_max: Any
    load: Any
    radius: Any
    u_ref: Any
    film: Any

    def values(self) -> tuple:
        """The nine quantities in the order of the attributes."""
        return tuple(self)

    @property
    def shape(self) -> tuple[int, ...]:
        """The broadcast shape of the quantities (that of the coefficients)."""
        return np.broadcast(*self).shape  # (C: a few microseconds less than broadcast_shapes)

    def stacked(self) -> tuple[np.ndarray, tuple[int, ...]]:
        """The quantities as rows of a ``(9, n)`` float array (broadcast, flattened), and
        their broadcast shape."""
        shape = np.broadcast(*self).shape
        out = np.empty((9,) + shape)
        for i, value in enumerate(self):
            out[i, ...] = value
        return out.reshape(9, -1), shape

    def flat(self) -> ContactState:
        """The same contacts as flat float arrays of one length."""
        return ContactState(*self.stacked()[0])

    def replace(self, **changes: Any) -> ContactState:
        """A copy with some quantities changed (e.g. ``film=...``)."""
        return self._replace(**changes)


def contact_coefficients(
    state: ContactState,
    fluid: Fluid,
    quadrature: Quadrature = Quadrature(),
    derivatives: bool = False,
):
    """``mu, chi`` (and with ``derivatives`` their derivatives) under ``fluid``'s law.

    Parameters
    ----------
    state : ContactState
        The contacts (arrays broadcast to the shape ``(...)`` of the result).
    fluid : Fluid
        Traction fluid; ``fluid.traction_law`` names the law (`ballcvt.registry`).
    quadrature : Quadrature
        Rule and node counts (see `ballcvt.model.traction.quadrature`).
    derivatives : bool
        Also return the derivatives of ``mu`` and ``chi``.

    Returns
    -------
    mu, chi : ndarray
        Traction coefficient (Eq. 30) and spin-moment coefficient (Eq. 31) [-].
    dmu, dchi : ndarray
        Only with ``derivatives``: shape ``(..., 3)``, the derivatives with respect to
        ``creep_term`` [-], ``spin`` [-] and ``log(u_ref)`` [-] (Newton's Jacobians).
    """
    law = TRACTION_LAWS.get(fluid.traction_law)
    return law.coefficients(state, fluid, quadrature, derivatives)


_NAMES = ContactState._fields


def legacy_arguments(old: str, new: str, args: tuple, kwargs: dict):
    """An old-style call (the nine quantities first, then the rest) as ``(state, args,
    kwargs)`` of the new call, with one deprecation warning naming ``new``."""
    warn_renamed(old, new, stacklevel=4)
    kwargs = dict(kwargs)
    values = list(args[:9]) + [kwargs.pop(n) for n in _NAMES[len(args[:9]) :]]
    return ContactState(*values), args[9:], kwargs
