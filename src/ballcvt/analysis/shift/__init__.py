"""The shift transient (docs/shifting.md): tilt, ratio, side slip, moments, torques and
losses over time, skew-steered or tilt-direct."""

from .result import SUMMARY_KEYS, ShiftResult
from .transient import (
    MECHANISMS,
    LinearViscousMoments,
    MomentModel,
    ShiftCommand,
    ShiftDrive,
    run_shift,
)

__all__ = [
    "MECHANISMS",
    "LinearViscousMoments",
    "MomentModel",
    "ShiftCommand",
    "ShiftDrive",
    "ShiftResult",
    "SUMMARY_KEYS",
    "run_shift",
]
