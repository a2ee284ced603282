"""Layer 1: geometry and kinematics (Eqs. 1-14, 29)."""

from .kinematics import (
    body_speeds,
    check_ratio,
    creep_term,
    entrainment_factor,
    ideal_ratio,
    ratio_range,
    rolling_radius,
    spin,
    spin_axis_projection,
    tilt_from_ratio,
    tilt_limits,
)
from .layout import CONTACT_NAMES, ContactLayout, contact_layout

__all__ = [
    "CONTACT_NAMES",
    "ContactLayout",
    "contact_layout",
    "body_speeds",
    "check_ratio",
    "creep_term",
    "entrainment_factor",
    "ideal_ratio",
    "ratio_range",
    "rolling_radius",
    "spin",
    "spin_axis_projection",
    "tilt_from_ratio",
    "tilt_limits",
]
