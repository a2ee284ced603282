"""The oil's temperature: a fluid's viscosity-temperature data and a drive's housing.

`FluidTemperatureFields` holds the optional fields of a `ballcvt.params.models.Fluid`
from which `ballcvt.model.oil.fluid_at` evaluates the fluid at another bulk temperature
(Walther / ASTM D341 or Vogel viscosity law, thermal expansion, pressure-viscosity
exponent); `ThermalModel` is the optional ``[design.thermal]`` table of a drive file: the
housing that rejects the losses to the air (docs/model.md §15).
"""

from __future__ import annotations

import math
from typing import Literal

from pydantic import Field, model_validator

from ..errors import InputError
from .base import ParameterModel, _f, _opt

__all__ = ["FluidTemperatureFields", "ThermalModel", "VISCOSITY_LAWS"]

#: The viscosity-temperature laws of `FluidTemperatureFields.viscosity_law`.
VISCOSITY_LAWS = ("walther", "vogel")


class FluidTemperatureFields(ParameterModel):
    """How a fluid's properties change with its bulk temperature (all optional; the fluid
    is used as given, at its ``inlet_temperature``, until a temperature is asked for)."""

    viscosity_data: tuple[tuple[float, float], ...] | None = Field(
        None,
        description="kinematic viscosities at atmospheric pressure, [[temperature, "
        "viscosity], ...] in C and mm^2/s as data sheets give them: two or more points "
        "for the Walther law, three for Vogel's [C, mm^2/s]",
        json_schema_extra={"unit": "C, mm^2/s"},
    )
    viscosity_law: Literal["walther", "vogel"] = Field(
        "walther",
        description="viscosity-temperature law through viscosity_data: 'walther' (ASTM "
        "D341, log log (nu + 0.7) = A - B log T) or 'vogel' (eta = a exp(b / (T - c))) [-]",
        json_schema_extra={"unit": "-"},
    )
    density_temperature_coefficient: float | None = _opt(
        "1/K",
        "volumetric thermal expansion beta_v of the fluid, rho = rho_ref exp(-beta_v dT) "
        "(mineral oils: about 6.4e-4)",
        ge=0,
        lt=0.01,
    )
    pressure_viscosity_exponent: float | None = _opt(
        "-",
        "t in alpha ~ nu^t (the form of Gold et al. 2001): the pressure-viscosity "
        "coefficient at another temperature",
        ge=0,
        lt=1,
    )

    @model_validator(mode="after")
    def _data_usable(self):
        data = self.viscosity_data
        if data is None:
            return self
        need = 3 if self.viscosity_law == "vogel" else 2
        if len(data) < need or (self.viscosity_law == "vogel" and len(data) != 3):
            raise InputError(
                "viscosity_data",
                [list(p) for p in data],
                f"{'exactly 3' if need == 3 else 'at least 2'} [temperature C, viscosity "
                f"mm^2/s] points for the {self.viscosity_law} law",
            )
        temps = [t for t, _ in data]
        nus = [v for _, v in data]
        ok = all(-100.0 < t < 400.0 for t in temps) and all(0.0 < v < 1e7 for v in nus)
        rising = all(a < b for a, b in zip(temps, temps[1:], strict=False))
        thinning = all(a > b for a, b in zip(nus, nus[1:], strict=False))
        if not (ok and rising and thinning):
            raise InputError(
                "viscosity_data",
                [list(p) for p in data],
                "points of rising temperature (-100 to 400 C) and falling viscosity (> 0 mm^2/s)",
            )
        return self


class ThermalModel(ParameterModel):
    """The housing that rejects a drive's losses (``[design.thermal]``, docs/model.md §15).

    Steady: ``P_loss(T) = h A (T - T_amb)``; transient (duty cycles):
    ``C dT/dt = P_loss - h A (T - T_amb)`` with ``C`` the thermal mass of oil and housing.
    """

    housing_area: float = _f("m^2", "outer surface A of the housing", gt=0, lt=100)
    heat_transfer_coefficient: float = _f(
        "W/(m^2 K)",
        "h from the housing to the air, convection and radiation together",
        gt=0,
        lt=1e4,
    )
    ambient_temperature: float = _f("K", "of the air T_amb", gt=150, lt=400)
    thermal_mass: float | None = _opt(
        "J/K", "C = sum m c of the oil and the parts at its temperature (duty cycles)", gt=0
    )

    @property
    def conductance(self) -> float:
        """``h A`` [W/K]."""
        return self.heat_transfer_coefficient * self.housing_area

    @property
    def time_constant(self) -> float:
        """``C / (h A)`` [s] (inf without a thermal mass)."""
        return math.inf if self.thermal_mass is None else self.thermal_mass / self.conductance
