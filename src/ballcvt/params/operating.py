"""`OperatingContext`: where a drive runs, the optional ``[operating]`` table of a drive file.

A drive file may say at which input speed, over which ratios and speeds and under which
clamping law the drive is used (an e-bike hub turns at pedalling speed, not at the
paper's 2000 rpm). The command line and the explorer start there when ``--design`` names
such a drive and the flag is not typed (typed flags always win); a drive without the
table (the paper's Table I drive) keeps the paper's defaults (`ballcvt.params.PAPER_POINT`).
The ratio range is checked against the drive's usable range when a variator is built
(`ballcvt.api.check_operating`): the tilt limits live in the model layer.
"""

from __future__ import annotations

import math
from typing import Annotated

from pydantic import Field, model_validator

from ..errors import InputError
from .base import ParameterModel, _opt

__all__ = ["OperatingContext"]

#: A positive finite number (an end of a range).
_Positive = Annotated[float, Field(gt=0, lt=math.inf)]


class OperatingContext(ParameterModel):
    """The operating context of a drive (every key optional; docs/drive-files.md).

    Speeds are in rpm, as the command line takes them.
    """

    input_speed_rpm: float | None = _opt(
        "rpm", "default input speed of every command", gt=0, le=1e5
    )
    ratio_range: tuple[_Positive, _Positive] | None = _opt(
        "-", "usable ideal-ratio range (min, max) the drive is run over"
    )
    speed_range_rpm: tuple[_Positive, _Positive] | None = _opt(
        "rpm", "input speeds (min, max) of lookup tables"
    )
    clamp_law: str | None = _opt(
        "-", "default clamping law (a name in ballcvt.registry.CLAMP_LAWS)"
    )
    clamp_force: float | None = _opt(
        "N", "default force F_N0 of the constant clamping law", gt=0, le=1e6
    )
    rated_torque: float | None = _opt(
        "N m", "rated output torque (what `design size-cam` sizes the cam for)", gt=0, le=1e6
    )

    @model_validator(mode="after")
    def _ordered(self) -> OperatingContext:
        for name in ("ratio_range", "speed_range_rpm"):
            pair = getattr(self, name)
            if pair is not None and not pair[0] < pair[1]:
                raise InputError(name, list(pair), "[min, max] with 0 < min < max")
        lo_hi, speed = self.speed_range_rpm, self.input_speed_rpm
        if lo_hi is not None and speed is not None and not lo_hi[0] <= speed <= lo_hi[1]:
            raise InputError(
                "input_speed_rpm",
                speed,
                f"{lo_hi[0]:g} to {lo_hi[1]:g} rpm (within speed_range_rpm)",
            )
        return self
