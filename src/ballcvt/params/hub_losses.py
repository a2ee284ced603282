"""The hub's own bearings: optional keys of ``[design.parasitic]`` (docs/model.md §12).

A bicycle hub carries the wheel's share of the rider's and bike's weight on the shell
bearings and the chain pull on the driver (sprocket) bearing. Their friction torques are
the built-in loss term ``hub_bearings`` (`ballcvt.model.losses.hub_bearings`), on only
when ``hub_bearing_diameter`` is given; a drive without these keys (the paper's) is as
before.
"""

from __future__ import annotations

from pydantic import model_validator

from ..errors import InputError
from .base import ParameterModel, _opt

__all__ = ["HubBearingParameters", "HUB_BEARING_KEYS"]

#: The keys of the hub's bearings, all given together or none.
HUB_BEARING_KEYS = (
    "hub_bearing_diameter",
    "driver_bearing_diameter",
    "wheel_load",
    "sprocket_radius",
    "hub_bearing_f0",
    "hub_bearing_f1",
    "hub_bearing_viscosity",
)


class HubBearingParameters(ParameterModel):
    """Shell and driver bearings of a hub (Palmgren's friction model; all keys or none)."""

    hub_bearing_diameter: float | None = _opt(
        "m",
        "pitch diameter d_m of each of the two shell bearings (hub shell on the axle)",
        gt=0,
        lt=1,
    )
    driver_bearing_diameter: float | None = _opt(
        "m",
        "pitch diameter d_m of the driver (sprocket) bearing, which carries the chain pull",
        gt=0,
        lt=1,
    )
    wheel_load: float | None = _opt(
        "N",
        "radial load of the wheel on the hub, shared by the two shell bearings",
        ge=0,
        lt=1e6,
    )
    sprocket_radius: float | None = _opt(
        "m", "pitch radius of the sprocket: chain pull = input torque / radius", gt=0, lt=1
    )
    hub_bearing_f0: float | None = _opt(
        "-", "Palmgren's load-independent coefficient f_0 of the hub bearings", ge=0, lt=100
    )
    hub_bearing_f1: float | None = _opt(
        "-", "Palmgren's load coefficient f_1 = z (P_0/C_0)^y of the hub bearings", ge=0, lt=1
    )
    hub_bearing_viscosity: float | None = _opt(
        "m^2/s",
        "kinematic viscosity of the hub bearings' lubricant (a grease's base oil)",
        gt=0,
        lt=1,
    )

    @model_validator(mode="after")
    def _all_or_none(self) -> HubBearingParameters:
        given = [k for k in HUB_BEARING_KEYS if getattr(self, k) is not None]
        if given and len(given) < len(HUB_BEARING_KEYS):
            missing = next(k for k in HUB_BEARING_KEYS if getattr(self, k) is None)
            raise InputError(
                f"parasitic.{missing}",
                None,
                "a value",
                message=f"[design.parasitic] gives {given[0]} but not {missing}: the hub's "
                f"bearings need all of {', '.join(HUB_BEARING_KEYS)} (docs/model.md §12)",
            )
        return self

    @property
    def has_hub_bearings(self) -> bool:
        """Whether the hub's bearings are given."""
        return self.hub_bearing_diameter is not None
