"""Parameter sets: drive design, material, bearings, fluid and operating point.

All models are frozen pydantic models, validated on construction. No field the paper's
model uses has a default (the few that do are named constants of an opt-in model, or
optional fields an opt-in law checks for): the numbers live in named parameter files
(``ballcvt/params/data``), so a
design file that omits a key is an error, never a silent fallback. Every field's
unit is in its ``unit`` metadata and in its description. Angles are stored in degrees
(the name says ``_deg``); everything else is SI.
"""

from __future__ import annotations

import math
from typing import Any, Literal

from pydantic import (
    Field,
    model_serializer,
    model_validator,
)

from ..errors import InputError
from ..registry import ARCHITECTURES as _ARCHITECTURES
from ..registry import TRACTION_LAWS
from ..units import rad_s_to_rpm
from .base import ParameterModel, _f, _opt
from .drive_models import DriveModels, reconcile_models
from .feasibility import check_design
from .hints import check_unit_mistakes
from .hub_losses import HubBearingParameters
from .laws import LAW_FIELDS, check_law
from .lubrication import Lubrication
from .operating import OperatingContext
from .ratings import BearingRatings
from .thermal import FluidTemperatureFields, ThermalModel

__all__ = [
    "ParameterModel",
    "Material",
    "BearingModel",
    "BearingRatings",
    "CamModel",
    "ParasiticModel",
    "ThermalModel",
    "Lubrication",
    "Design",
    "Fluid",
    "OperatingPoint",
    "OperatingContext",
    "DriveModels",
    "Architecture",
    "ARCHITECTURES",
    "TRACTION_LAWS",
    "LAW_FIELDS",
]

#: An architecture's name: one of `ARCHITECTURES`.
Architecture = str
#: The idler architectures: the live registry of names (`ballcvt.registry.ARCHITECTURES`;
#: the built-in ``double`` and ``single`` and any registered from a user's code).
ARCHITECTURES = _ARCHITECTURES


class Material(ParameterModel):
    """Elastic properties of rollers, discs and idlers (all of one material)."""

    youngs_modulus: float = _f("Pa", "Young's modulus E", gt=0, lt=math.inf)
    poisson_ratio: float = _f("-", "Poisson ratio nu", ge=0, lt=0.5)
    density: float = Field(
        7810.0,
        description="density, for the balls' centrifugal force "
        "and gyroscopic moment with the carrier turning (docs/model.md "
        "§13); 7810 kg/m^3 is AISI 52100 bearing steel [kg/m^3]",
        json_schema_extra={"unit": "kg/m^3"},
        gt=0,
        lt=math.inf,
    )

    @property
    def reduced_modulus(self) -> float:
        """Plane-strain modulus ``E' = E / (1 - nu^2)`` (docs/model.md §3) [Pa]."""
        return self.youngs_modulus / (1.0 - self.poisson_ratio**2)


class BearingModel(BearingRatings):
    """Rolling-bearing friction torque coefficients of Eqs. 15-16 (Harris / SKF form), and
    the optional catalogue ratings of the fatigue life (`BearingRatings`)."""

    f0: float = _f("-", "load-independent coefficient f0 of Eq. 15", ge=0, lt=math.inf)
    f1: float = _f("-", "load-dependent coefficient f1 of Eq. 16", ge=0, lt=math.inf)
    speed_exponent: float = _f(
        "-",
        "exponent of (eta_c N) in Eq. 15 (printed 0.69; Palmgren's classical value is 2/3)",
        gt=0,
        lt=2,
    )
    low_speed_factor: float = _f(
        "-",
        "floor of (eta_c N)^e in Eq. 15 (160 as printed; the "
        "floor makes Eq. 15 continuous, docs/model.md)",
        ge=0,
        lt=math.inf,
    )
    load_exponent: float = _f("-", "exponent a of the bearing load P in Eq. 16", gt=0, lt=3)
    diameter_exponent: float = _f("-", "exponent b of the mean diameter in Eq. 16", gt=0, lt=3)


class CamModel(ParameterModel):
    """Torque-sensing loading cam: a ball ramp plus a preload spring (docs/model.md §11).

    The cam turns the torque of the disc it sits on into axial thrust,
    ``F_ax = F_pre + |T| / (r_m tan(phi + atan(mu_r)))`` (the power-screw relation,
    Budynas and Nisbett, Shigley's Mechanical Engineering Design, 10th ed., Eq. 8-1;
    loading cams of traction drives: Loewenthal and Zaretsky, NASA RP-1154, 1985).
    """

    disc: Literal["input", "output"] = Field(
        ..., description="disc whose torque the cam senses ('input' or 'output')"
    )
    preload: float = _f(
        "N",
        "axial preload of the spring F_pre (> 0: without it the cam never grips)",
        gt=0,
        lt=math.inf,
    )
    ramp_angle_deg: float = _f("deg", "ramp angle phi at the mean radius", gt=0, lt=60)
    mean_radius: float = _f("m", "mean radius r_m of the ramp balls", gt=0, lt=10)
    friction: float = _f("-", "ramp friction coefficient mu_r (rolling balls: ~0.005)", ge=0, lt=1)
    branch: Literal["loading", "unloading"] = Field(
        "loading",
        description="which side of the ramp friction's hysteresis the cam is on: 'loading' "
        "(torque rising, friction resists the ramp's climb: tan(phi + atan mu_r), the "
        "default) or 'unloading' (torque falling: tan(phi - atan mu_r), a larger thrust) [-]",
        json_schema_extra={"unit": "-"},
    )

    @model_serializer(mode="wrap")
    def _dump(self, handler) -> dict[str, Any]:
        """The fields, without ``branch`` on its default (files and results of cams
        written before it are as they were)."""
        data = handler(self)
        if isinstance(data, dict) and data.get("branch") == "loading":
            data.pop("branch")
        return data

    @model_validator(mode="after")
    def _unloads(self) -> CamModel:
        if self.branch == "unloading" and math.radians(self.ramp_angle_deg) <= math.atan(
            self.friction
        ):
            raise InputError(
                "cam.branch",
                self.branch,
                "'loading' (the ramp self-locks: ramp_angle_deg <= atan(friction), it never "
                "unloads)",
            )
        return self

    @property
    def ramp_angle(self) -> float:
        """Ramp angle [rad]."""
        return math.radians(self.ramp_angle_deg)


class ParasiticModel(HubBearingParameters):
    """Losses beyond the paper's contacts and bearings (docs/model.md §12); optional.

    The hub's own bearings (`HubBearingParameters`) are optional keys of the table."""

    oil_fraction: float = _f(
        "-",
        "volume fraction of oil in the oil-air mixture around the "
        "balls and discs (effective density = fraction x density)",
        ge=0,
        le=1,
    )
    churning_factor: float = _f(
        "-",
        "multiplier on the moment coefficient of the churning model (1 = as published)",
        ge=0,
        lt=math.inf,
    )
    disc_radius: float = _f("m", "outer radius of the discs (churning)", gt=0, lt=10)
    seal_diameter: float = _f(
        "m", "counterface diameter of the shaft seals (one on each shaft)", ge=0, lt=10
    )
    seal_k1: float = _f(
        "N mm", "K_S1 of the seal torque K_S1 d_s^beta + K_S2 (d_s in mm)", ge=0, lt=math.inf
    )
    seal_beta: float = _f("-", "beta of the seal torque", ge=0, lt=5)
    seal_k2: float = _f("N mm", "K_S2 of the seal torque", ge=0, lt=math.inf)
    disc_bearing_diameter: float = _f(
        "m",
        "bore diameter of the thrust bearing that "
        "closes the clamping loop between the discs; 0 for "
        "none",
        ge=0,
        lt=10,
    )
    disc_bearing_friction: float = _f(
        "-", "its constant friction coefficient (SKF: 0.0013 for thrust ball bearings)", ge=0, lt=1
    )


class Design(ParameterModel):
    """Geometry of a planetary ball variator (Sec. II.A, Table I, docs/model.md §1).

    Lengths in metres, angles in degrees (names ending in ``_deg``).
    """

    name: str = Field(..., description="label of the design")
    aspect_ratio: float = _f("-", "k = r_1 / r_S (Eq. 2)", gt=0, lt=100)
    roller_radius: float = _f("m", "ball radius r_S", gt=0, lt=10)
    theta0_deg: float = _f("deg", "input disc contact angle theta_0", gt=0, lt=90)
    theta2_deg: float = _f("deg", "output disc contact angle theta_2", gt=0, lt=90)
    alpha_deg: float = _f("deg", "double-idler contact angle alpha", ge=0, lt=90)
    n_rollers: int = _f("-", "number of balls n", ge=1, le=64)
    roller_bearing_diameter: float = _f("m", "ball axle bearing mean diameter d_S", gt=0, lt=10)
    idler_bearing_diameter: float = _f("m", "idler bearing mean diameter d_I", gt=0, lt=10)
    disc_groove_ratio: float = _f(
        "-",
        "r_02/r_S = r_22/r_S: transverse (meridian) radius "
        "of the concave disc tracks over r_S, > 1; inf for straight",
        gt=1,
    )
    idler_groove_ratio: float = _f(
        "-", "r_a2/r_S = r_b2/r_S of the double-idler tracks, > 1; inf for straight", gt=1
    )
    single_idler_groove_ratio: float = _f(
        "-",
        "transverse track radius of the single idler "
        "over r_S; inf = straight cylinder "
        "(docs/model.md §1)",
        gt=1,
    )
    tilt_safety_factor: float = _f(
        "-", "fraction of the Eq. 6 tilt limits that is usable (Fig. 3 uses 0.8)", gt=0, le=1
    )
    creep_limit: float = _f(
        "-", "largest |creep| counted as traction (docs/model.md §8)", gt=0, lt=1
    )
    max_pressure: float = _f(
        "Pa",
        "largest admissible Hertz peak pressure (clamping-force optimisation, validity warning)",
        gt=0,
    )
    min_roller_gap: float = _f(
        "m",
        "smallest clearance between neighbouring balls, idler "
        "contacts and disc contacts (feasibility, docs/model.md §10)",
        ge=0,
        lt=10,
    )
    surface_roughness: float = _f(
        "m",
        "composite RMS roughness sqrt(Rq1^2 + Rq2^2) of the "
        "contacting surfaces (film thickness ratio, validity "
        "warning)",
        gt=0,
        lt=1e-3,
    )
    material: Material
    bearings: BearingModel
    cam: CamModel | None = Field(
        None,
        description="loading cam of the 'cam' clamping law (optional: only that law needs it)",
    )
    parasitic: ParasiticModel | None = Field(
        None, description="churning, seal and disc bearing losses (optional: none without it)"
    )
    thermal: ThermalModel | None = Field(
        None, description="the housing that rejects the losses (optional: the oil's temperature)"
    )
    operating: OperatingContext | None = Field(
        None,
        description="where the drive runs: the drive file's [operating] table (optional: "
        "the paper's operating point without it)",
    )
    lubrication: Lubrication | None = Field(
        None,
        description="lubrication model and asperity parameters (optional: the paper's "
        "full film without it, docs/model.md §15)",
    )

    models: DriveModels | None = Field(
        None,
        description="the models the drive is computed with: the drive file's [models] "
        "table (optional: the package's defaults without it)",
    )

    @model_serializer(mode="wrap")
    def _dump(self, handler) -> dict[str, Any]:
        """The fields, without ``operating``, ``thermal``, ``models`` and ``lubrication``
        when they are not given (so that files and results of drives without them are as
        they were)."""
        data = handler(self)
        for key in ("operating", "thermal", "models", "lubrication"):
            if isinstance(data, dict) and data.get(key) is None:
                data.pop(key, None)
        return data

    def with_lubrication(self, model: str | None) -> Design:
        """This design under the lubrication model ``model`` (itself when ``model`` is None
        or its own): the table's asperity parameters are kept, or the typical ones
        (`ballcvt.params.lubrication`) given. The name is unchanged: the model is a choice
        of physics, not of the design's data."""
        own = self.lubrication.model if self.lubrication is not None else "full-film"
        if model is None or model == own:
            return self
        table = self.lubrication.model_dump() if self.lubrication is not None else {}
        update: dict[str, Any] = {"lubrication": Lubrication(**{**table, "model": model})}
        if self.models is not None and self.models.lubrication is not None:  # [models] too
            update["models"] = self.models.model_copy(update={"lubrication": model})
        return self.model_copy(update=update)

    @model_validator(mode="before")
    @classmethod
    def _renamed_keys(cls, data: Any) -> Any:
        """``min_ball_gap`` (before one name per body) reads as ``min_roller_gap``."""
        if isinstance(data, dict) and "min_ball_gap" in data:
            from .._compat import warn_renamed

            warn_renamed("[design] min_ball_gap", "min_roller_gap", stacklevel=4)
            data = dict(data)
            data.setdefault("min_roller_gap", data.pop("min_ball_gap"))
        return data

    @model_validator(mode="after")
    def _buildable(self) -> Design:
        check_unit_mistakes(self)
        check_design(self)
        reconcile_models(self)
        return self

    @property
    def min_ball_gap(self) -> float:
        """Renamed `min_roller_gap` [m] (warns)."""
        from .._compat import warn_renamed

        warn_renamed("Design.min_ball_gap", "Design.min_roller_gap")
        return self.min_roller_gap

    @property
    def theta0(self) -> float:
        """Input contact angle [rad]."""
        return math.radians(self.theta0_deg)

    @property
    def theta2(self) -> float:
        """Output contact angle [rad]."""
        return math.radians(self.theta2_deg)

    @property
    def alpha(self) -> float:
        """Double-idler contact angle [rad]."""
        return math.radians(self.alpha_deg)


class Fluid(FluidTemperatureFields):
    """Traction fluid (Table I, Appendix A, docs/model.md §3, §4)."""

    name: str = Field(..., description="label of the fluid")
    viscosity: float = _f(
        "Pa s", "absolute viscosity eta_0 at atmospheric pressure", gt=0, lt=math.inf
    )
    roelands_index: float = _f("-", "Roelands viscosity-pressure index Z_1 (Eq. 51)", gt=0, lt=5)
    pressure_viscosity_coefficient: float = _f(
        "1/Pa",
        "zeta, for the film thickness (Eq. 56; > 0: no film forms without it)",
        gt=0,
        lt=1e-6,
    )
    limiting_shear_stress: float = _f(
        "Pa", "tau_L0 at atmospheric pressure (Eq. 54)", gt=0, lt=math.inf
    )
    limiting_shear_slope: float = _f("-", "a in tau_L = tau_L0 + a p (Eq. 54)", ge=0, lt=1)
    pole_pressure: float = _f("Pa", "Roelands pole pressure c_p (Eq. 51)", gt=0, lt=math.inf)
    pole_viscosity: float = _f(
        "Pa s", "Roelands pole viscosity eta_inf (Eq. 51)", gt=0, lt=math.inf
    )
    density: float = _f(
        "kg/m^3",
        "density, for the kinematic viscosity of Eq. 15 (an assumption, docs/model.md §4)",
        gt=0,
        lt=math.inf,
    )
    max_rolling_speed: float = _f(
        "m/s",
        "largest rolling (entrainment) speed covered by the "
        "fluid's traction data (validity warning)",
        gt=0,
        lt=math.inf,
    )
    traction_law: str = Field(
        "isothermal",
        description="shear law of the film (docs/model.md §14), a name in "
        "ballcvt.registry.TRACTION_LAWS: 'isothermal' (the paper's Eq. 53), 'thermal' "
        "(shear heating thins the film), 'viscoelastic' (Maxwell elasticity gives the "
        "initial slope) or a law registered from user code [-]",
        json_schema_extra={"unit": "-"},
    )
    law_parameters: dict[str, float] | None = Field(
        None,
        description="parameters of a traction law defined outside the package, by name "
        "(the law's TractionLaw.parameters; units as the law documents) [-]",
        json_schema_extra={"unit": "-"},
    )
    temperature_viscosity_coefficient: float | None = _opt(
        "1/K", "beta in eta ~ exp(-beta dT), thermal law", ge=0, lt=1
    )
    limiting_shear_temperature_coefficient: float | None = _opt(
        "1/K", "beta_L in tau_L ~ exp(-beta_L dT), thermal law", ge=0, lt=1
    )
    thermal_conductivity: float | None = _opt(
        "W/(m K)", "of the fluid, thermal law", gt=0, lt=math.inf
    )
    inlet_temperature: float | None = _opt(
        "K",
        "of the fluid entering the contacts, at which eta_0 and tau_L0 apply, thermal law",
        gt=0,
        lt=math.inf,
    )
    surface_conductivity: float | None = _opt(
        "W/(m K)",
        "of the solids bounding the film (steel: about 46), thermal law",
        gt=0,
        lt=math.inf,
    )
    surface_diffusivity: float | None = _opt(
        "m^2/s",
        "of the solids bounding the film (steel: about 1.3e-5), thermal law",
        gt=0,
        lt=math.inf,
    )
    shear_modulus: float | None = _opt(
        "Pa", "elastic shear modulus G of the film, viscoelastic law", gt=0, lt=math.inf
    )

    @model_serializer(mode="wrap")
    def _dump(self, handler) -> dict[str, Any]:
        """The fields, without ``law_parameters`` and the temperature fields when not given
        (nor the default viscosity law), so that files and results of fluids without them
        are as they were."""
        data = handler(self)
        if not isinstance(data, dict):
            return data
        for key in ("law_parameters", *FluidTemperatureFields.model_fields):
            if data.get(key) is None or (key == "viscosity_law" and data[key] == "walther"):
                data.pop(key, None)
        if data.get("viscosity_data") is not None:
            data["viscosity_data"] = [list(p) for p in data["viscosity_data"]]
        return data

    def __hash__(self) -> int:  # law_parameters is a dict (the solvers cache per fluid)
        given = self.law_parameters
        if given is None:
            return hash((type(self), tuple(self.__dict__.values())))
        rest = tuple(v for k, v in self.__dict__.items() if k != "law_parameters")
        return hash((type(self), rest, tuple(sorted(given.items()))))

    @model_validator(mode="after")
    def _law_complete(self) -> Fluid:
        check_law(self)
        return self

    def with_traction_law(self, law: str | None) -> Fluid:
        """This fluid under the traction law ``law`` (itself when ``law`` is None or its own),
        validated (the law's parameters must be there) and with its name unchanged: the law
        is a choice of model, not a change of the fluid's data."""
        if law is None or law == self.traction_law:
            return self
        return Fluid(**{**self.model_dump(), "traction_law": law})

    @property
    def kinematic_viscosity(self) -> float:
        """``eta_0 / rho`` [m^2/s]."""
        return self.viscosity / self.density


class OperatingPoint(ParameterModel):
    """A steady operating point: speed-ratio set-point, load torque, clamping, speed."""

    ratio: float = _f(
        "-", "ideal speed ratio tau_ID = omega_2 / omega_0 (Eq. 4)", gt=0, lt=math.inf
    )
    output_torque: float = _f("N m", "output (load) torque T_2", ge=0, lt=math.inf)
    clamp_force: float = _f("N", "normal load F_N0 at each input disc contact", gt=0, lt=math.inf)
    input_speed: float = _f("rad/s", "input disc speed omega_0", gt=0, lt=math.inf)

    @property
    def input_speed_rpm(self) -> float:
        """Input speed [rpm], to 12 significant digits (2000 rpm reads back as 2000)."""
        return float(f"{rad_s_to_rpm(self.input_speed):.12g}")
