"""`BearingRatings`: the catalogue figures of the support bearings, for the fatigue life.

All optional (``[design.bearings]`` of a drive file): a bearing without its dynamic rating
``C`` is left out of the life (docs/life.md), and the life modification factor ``a_ISO``
(ISO 281:2007 §9.3) applies to a bearing only when the contamination factor ``e_C`` and
that bearing's fatigue load limit ``C_u`` are both given.
"""

from __future__ import annotations

import math
from typing import Any

from pydantic import model_serializer

from .base import ParameterModel, _opt

__all__ = ["BearingRatings", "RATING_FIELDS"]

_C = "basic dynamic load rating C (catalogue) of "
_CU = "fatigue load limit C_u (catalogue) of "


class BearingRatings(ParameterModel):
    """Optional catalogue figures of the ball-axle, idler and disc bearings."""

    roller_bearing_rating: float | None = _opt(
        "N", _C + "one ball-axle bearing (two per ball)", gt=0, lt=math.inf
    )
    idler_bearing_rating: float | None = _opt("N", _C + "one idler bearing", gt=0, lt=math.inf)
    disc_bearing_rating: float | None = _opt(
        "N", _C + "the thrust bearing between the discs", gt=0, lt=math.inf
    )
    roller_bearing_fatigue_limit: float | None = _opt(
        "N", _CU + "one ball-axle bearing, for a_ISO", gt=0, lt=math.inf
    )
    idler_bearing_fatigue_limit: float | None = _opt(
        "N", _CU + "one idler bearing, for a_ISO", gt=0, lt=math.inf
    )
    disc_bearing_fatigue_limit: float | None = _opt(
        "N", _CU + "the disc thrust bearing, for a_ISO", gt=0, lt=math.inf
    )
    contamination_factor: float | None = _opt(
        "-",
        "ISO 281 contamination factor e_C of the bearings' lubricant (1: very clean); "
        "given, the bearings with a C_u carry a_ISO",
        gt=0,
        le=1,
    )
    viscosity_ratio: float | None = _opt(
        "-",
        "ISO 281 viscosity ratio kappa = nu / nu_1 of a_ISO; by default from the fluid's "
        "kinematic viscosity and each bearing's speed and diameter",
        gt=0,
        lt=math.inf,
    )

    @model_serializer(mode="wrap")
    def _dump(self, handler) -> dict[str, Any]:
        """The fields, without the ratings not given (so that files and results of drives
        without them are as they were)."""
        data = handler(self)
        if isinstance(data, dict):
            data = {k: v for k, v in data.items() if v is not None or k not in RATING_FIELDS}
        return data


#: The fields of `BearingRatings`.
RATING_FIELDS = tuple(BearingRatings.model_fields)
