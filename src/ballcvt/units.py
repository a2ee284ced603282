"""Unit conversions: the one place that knows what an rpm or a degree is.

Every conversion is written the way the package always computed it (``rpm * pi / 30``,
in that order), so that the results are the same to the last bit wherever it is used.
A leaf: imports no physics.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["rpm_to_rad_s", "rad_s_to_rpm", "deg_to_rad", "rad_to_deg", "RAD_S_PER_RPM"]

#: One revolution per minute in rad/s.
RAD_S_PER_RPM = math.pi / 30.0


def rpm_to_rad_s(speed_rpm):
    """Angular speed [rpm] -> [rad/s] (``rpm * pi / 30``); scalars stay scalars."""
    if isinstance(speed_rpm, (int, float)):
        return float(speed_rpm) * math.pi / 30.0
    return np.asarray(speed_rpm, dtype=float) * math.pi / 30.0


def rad_s_to_rpm(speed):
    """Angular speed [rad/s] -> [rpm] (``rad/s * 30 / pi``); scalars stay scalars."""
    if isinstance(speed, (int, float)):
        return float(speed) * 30.0 / math.pi
    return np.asarray(speed, dtype=float) * 30.0 / math.pi


def deg_to_rad(angle_deg):
    """Angle [deg] -> [rad]."""
    if isinstance(angle_deg, (int, float)):
        return math.radians(angle_deg)
    return np.radians(np.asarray(angle_deg, dtype=float))


def rad_to_deg(angle):
    """Angle [rad] -> [deg]."""
    if isinstance(angle, (int, float)):
        return math.degrees(angle)
    return np.degrees(np.asarray(angle, dtype=float))
