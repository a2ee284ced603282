"""Parasitic losses beyond the paper: churning, seals, disc thrust bearings and a hub's own
bearings (docs/model.md §12).

Each loss is a `LossTerm` registered in `ballcvt.registry.LOSS_TERMS` (one module per
built-in term); `parasitic_drags` sums the registered terms. The built-in terms read
``[design.parasitic]`` and are off without it, so every figure of the paper is unchanged.
All torque functions are pure, SI in and out, and broadcast.
"""

from __future__ import annotations

from .base import (
    ACTS_ON,
    STICK_SPEED,
    DragInputs,
    DragMagnitudes,
    LossTerm,
    ParasiticDrags,
    active_terms,
    coulomb_direction,
    drag_kinds,
    drag_magnitudes,
    drag_power,
    has_parasitic,
    parasitic_drags,
    parasitic_torques,
    shaft_drags,
)
from .churning import BALL_CHURNING, DISC_CHURNING, moment_coefficient, windage_torque
from .seals import SEALS, seal_torque
from .thrust_bearing import DISC_BEARING, thrust_bearing_torque

# isort: split
# registered after the paper-era terms: the kinds keep their order (churning, seals,
# disc_bearings), the hub's bearings come after them
from .hub_bearings import DRIVER_BEARING, SHELL_BEARINGS, palmgren_torque

__all__ = [
    "ACTS_ON",
    "STICK_SPEED",
    "DragInputs",
    "DragMagnitudes",
    "LossTerm",
    "ParasiticDrags",
    "active_terms",
    "coulomb_direction",
    "drag_kinds",
    "drag_magnitudes",
    "drag_power",
    "has_parasitic",
    "parasitic_drags",
    "parasitic_torques",
    "shaft_drags",
    "moment_coefficient",
    "windage_torque",
    "seal_torque",
    "thrust_bearing_torque",
    "palmgren_torque",
    "BALL_CHURNING",
    "DISC_CHURNING",
    "SEALS",
    "DISC_BEARING",
    "SHELL_BEARINGS",
    "DRIVER_BEARING",
    "PARASITIC_KINDS",
]

#: The built-in kinds of parasitic loss: the first columns of the shaft drag torques.
PARASITIC_KINDS = ("churning", "seals", "disc_bearings", "hub_bearings")
