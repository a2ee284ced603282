"""The thrust bearing that closes the clamping loop between the discs (docs/model.md §12).

It turns at the discs' relative speed: it brakes the faster disc and drives the slower
one. Its torque's direction follows the discs' solved relative speed, creep included, as
regularised Coulomb friction (`ballcvt.model.losses.base.coulomb_direction`): just above
``tau_ID = 1`` the creep can make the output the slower disc (issue 23). The built-in loss
term ``disc_bearing`` (kind ``disc_bearings``), read from
``design.parasitic``.
"""

from __future__ import annotations

import numpy as np

from ...registry import LOSS_TERMS
from .base import DragInputs, LossTerm, has_parasitic

__all__ = ["thrust_bearing_torque", "DISC_BEARING"]


def thrust_bearing_torque(thrust, diameter, friction):
    """Friction torque of a thrust ball bearing ``M = mu F_ax d / 2`` [N m].

    The constant-coefficient estimate of SKF (Rolling bearings, catalogue 17000 EN, 2018,
    "Estimating the frictional moment", ``mu = 0.0013`` for thrust ball bearings).

    Parameters
    ----------
    thrust : array_like
        Axial load ``F_ax`` [N].
    diameter : float
        Bearing bore diameter ``d`` [m].
    friction : float
        Constant friction coefficient ``mu`` [-].

    Returns
    -------
    ndarray
        Torque magnitude [N m].
    """
    return friction * np.abs(np.asarray(thrust, dtype=float)) * diameter / 2.0


def _disc_bearing(at: DragInputs):
    """Torque of the disc thrust bearing at the discs' thrust (`thrust_bearing_torque`)."""
    par = at.design.parasitic
    assert par is not None
    return thrust_bearing_torque(at.thrust, par.disc_bearing_diameter, par.disc_bearing_friction)


DISC_BEARING = LOSS_TERMS.register(
    LossTerm(
        "disc_bearing",
        "between_discs",
        _disc_bearing,
        "disc_bearings",
        "design.parasitic: disc_bearing_diameter, disc_bearing_friction",
        has_parasitic,
    )
)
