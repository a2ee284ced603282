"""Parasitic losses beyond the paper: churning, seals, disc thrust bearings (docs/model.md §12).

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
    "BALL_CHURNING",
    "DISC_CHURNING",
    "SEALS",
    "DISC_BEARING",
    "PARASITIC_KINDS",
]

#: The built-in kinds of parasitic loss: the first columns of the shaft drag torques.
PARASITIC_KINDS = ("churning", "seals", "disc_bearings")
