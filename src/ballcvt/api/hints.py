"""Hints at likely unit mistakes in the arguments of the Python API."""

from __future__ import annotations

import warnings

from ..errors import InputError, UnitHintWarning
from ..units import rad_s_to_rpm, rpm_to_rad_s

__all__ = ["check_speed_unit", "one_speed", "RPM_LIKE_SPEED"]

#: An ``input_speed`` above this [rad/s] (9549 rpm) is hinted to be meant in rpm: ball
#: CVTs run from a bicycle's cadence (~10 rad/s) to an engine's speed (6000 rpm, 628
#: rad/s), while the usual rpm figures (1000 to 6000) read as rad/s all lie above it.
RPM_LIKE_SPEED = 1000.0


def check_speed_unit(input_speed) -> None:
    """Warn (`UnitHintWarning`) when ``input_speed`` [rad/s] looks like rpm.

    Parameters
    ----------
    input_speed : float or None
        ``omega_0`` as the user gave it in rad/s (None: given in rpm, not checked).
    """
    if input_speed is not None and float(input_speed) > RPM_LIKE_SPEED:
        w = float(input_speed)
        warnings.warn(
            f"input_speed = {w:g} rad/s ({rad_s_to_rpm(w):.0f} rpm) looks like rpm: did "
            f"you mean input_speed_rpm={w:g}? (used as {w:g} rad/s)",
            UnitHintWarning,
            stacklevel=5,  # the user's call of Variator.solve
        )


def one_speed(input_speed, input_speed_rpm) -> float:
    """The input speed [rad/s] from exactly one of ``input_speed`` [rad/s] or
    ``input_speed_rpm`` [rpm]; a rad/s figure that looks like rpm is hinted at."""
    if (input_speed is None) == (input_speed_rpm is None):
        raise InputError(
            "input_speed",
            input_speed,
            "exactly one of input_speed [rad/s] or input_speed_rpm [rpm]",
        )
    check_speed_unit(input_speed)
    return float(input_speed) if input_speed is not None else rpm_to_rad_s(float(input_speed_rpm))
