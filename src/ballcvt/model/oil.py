"""The fluid at another bulk temperature, and the housing's heat balance (docs/model.md §15).

* Viscosity: Walther's law as standardised in ASTM D341 (Walther 1931; ASTM D341-20,
  "Standard Practice for Viscosity-Temperature Equations and Charts for Liquid Petroleum or
  Hydrocarbon Products"), ``log10 log10(nu + 0.7) = A - B log10 T`` with ``nu`` in mm^2/s
  and ``T`` in K, through two data points (least squares in those coordinates through more);
  or Vogel's law ``eta = a exp(b / (T - c))`` (Vogel 1921) through exactly three.
* Density: ``rho = rho_ref exp(-beta_v (T - T_ref))`` (constant volumetric expansion).
* Pressure-viscosity coefficient: ``alpha ~ nu^t``, the form of the correlation of Gold,
  Schmidt, Dicke, Loos and Assmann (J. Synthetic Lubrication 18 (2001) 51-79),
  ``alpha = s nu^t``, with ``s`` fixed by the fluid's own ``alpha`` at its reference
  temperature; Roelands' index ``Z_1`` follows so that ``Z_1 ln(eta_0/eta_inf) / c_p``
  (Roelands' low-pressure slope) stays equal to ``alpha``.
* Limiting shear stress: ``tau_L0 ~ exp(-beta_L dT)`` (the thermal law's coefficient).

`fluid_at` anchors every property on the fluid's own value at its reference temperature
(``inlet_temperature``): the data give the change with temperature, the fluid's numbers
stay its own (Table I's viscosity is not the data's at 40 C: docs/model.md §15).
"""

from __future__ import annotations

import math

from ..errors import InputError
from ..params.models import Fluid
from ..units import ZERO_CELSIUS

__all__ = [
    "walther_constants",
    "kinematic_viscosity",
    "viscosity_slope",
    "fluid_at",
    "steady_temperature",
    "transient_step",
    "housing_coefficient",
    "C_TO_K",
    "MAX_OIL_TEMPERATURE",
]

#: 0 C in kelvin.
C_TO_K = ZERO_CELSIUS
#: Highest bulk oil temperature the balance and the transient go to [K] (150 C: beyond the
#: fluids' data and the service temperature of lip seals and traction fluids).
MAX_OIL_TEMPERATURE = 150.0 + ZERO_CELSIUS
#: The constant of Walther's law (ASTM D341) [mm^2/s].
WALTHER_SHIFT = 0.7
#: Air near 300 K (Incropera and DeWitt, Fundamentals of Heat and Mass Transfer, Table
#: A.4): conductivity [W/(m K)], kinematic viscosity [m^2/s], Prandtl number [-].
AIR = (0.0263, 1.589e-5, 0.707)
#: Stefan-Boltzmann constant [W/(m^2 K^4)].
STEFAN_BOLTZMANN = 5.670e-8
#: Smallest ratio eta_0 / eta_inf at which Roelands' law is evaluated [-].
MIN_POLE_RATIO = 1.5


def _walther_y(nu: float) -> float:
    return math.log10(math.log10(nu + WALTHER_SHIFT))


def walther_constants(points) -> tuple[float, float]:
    """``(A, B)`` of ``log10 log10(nu + 0.7) = A - B log10 T`` (ASTM D341).

    Parameters
    ----------
    points : sequence of (float, float)
        ``(temperature [C], kinematic viscosity [mm^2/s])``; through two points exactly,
        least squares in ``(log10 T, log10 log10(nu + 0.7))`` through more.
    """
    x = [math.log10(t + C_TO_K) for t, _ in points]
    y = [_walther_y(v) for _, v in points]
    n = len(x)
    mx, my = sum(x) / n, sum(y) / n
    slope = sum((a - mx) * (b - my) for a, b in zip(x, y, strict=True)) / sum(
        (a - mx) ** 2 for a in x
    )
    return my - slope * mx, -slope


def _vogel_constants(points) -> tuple[float, float, float]:
    """``(ln a, b, c)`` of ``nu = a exp(b / (T - c))`` through three points (T in K)."""
    (t1, v1), (t2, v2), (t3, v3) = ((t + C_TO_K, math.log(v)) for t, v in points)
    # (v1 - v2)/(v2 - v3) = (1/(t1-c) - 1/(t2-c)) / (1/(t2-c) - 1/(t3-c)); solved for c
    r = (v1 - v2) / (v2 - v3)
    c = (r * t1 * (t2 - t3) - t3 * (t1 - t2)) / (r * (t2 - t3) - (t1 - t2))
    if not c < t1:
        raise InputError("viscosity_data", None, "three points a Vogel law fits (T > c)")
    b = (v1 - v2) / (1 / (t1 - c) - 1 / (t2 - c))
    return v1 - b / (t1 - c), b, c


def kinematic_viscosity(fluid: Fluid, temperature: float) -> float:
    """The data's kinematic viscosity at ``temperature`` [K] (the fluid's law) [m^2/s]."""
    data = _data(fluid)
    if fluid.viscosity_law == "vogel":
        ln_a, b, c = _vogel_constants(data)
        if not temperature > c + 1.0:
            raise InputError("temperature", temperature, f"> {c + 1.0:.1f} K (Vogel's pole)")
        return math.exp(ln_a + b / (temperature - c)) * 1e-6
    a, b = walther_constants(data)
    return (10 ** (10 ** (a - b * math.log10(temperature))) - WALTHER_SHIFT) * 1e-6


def viscosity_slope(fluid: Fluid, temperature: float) -> float:
    """``-d ln(nu) / dT`` of the data's law at ``temperature`` [1/K] (central difference)."""
    step = 0.01
    hi = kinematic_viscosity(fluid, temperature + step)
    lo = kinematic_viscosity(fluid, temperature - step)
    return -math.log(hi / lo) / (2 * step)


def _data(fluid: Fluid):
    if fluid.viscosity_data is None:
        raise InputError(
            "viscosity_data",
            None,
            "[[temperature C, viscosity mm^2/s], ...] in the fluid file (a fluid at "
            "another temperature needs its viscosity-temperature data)",
        )
    return fluid.viscosity_data


def fluid_at(fluid: Fluid, temperature: float) -> Fluid:
    """The fluid at the bulk temperature ``temperature`` [K] (docs/model.md §15).

    Every property is the fluid's own at its reference temperature ``T_ref =
    fluid.inlet_temperature`` times the change the data give from ``T_ref`` to ``T``:

    * ``rho = rho_ref exp(-beta_v dT)``;
    * ``eta_0 = eta_ref (nu(T) / nu(T_ref)) (rho / rho_ref)`` (``nu`` from the law);
    * ``alpha = alpha_ref (nu(T) / nu(T_ref))^t`` (Gold et al. 2001) and ``Z_1`` so that
      Roelands' low-pressure slope ``Z_1 ln(eta_0/eta_inf)/c_p`` scales as ``alpha``;
    * ``tau_L0 = tau_L0,ref exp(-beta_L dT)``;
    * the thermal law's ``beta`` scaled as the law's local slope ``-d ln nu/dT``;
    * ``inlet_temperature = T``.

    At ``T_ref`` the fluid itself is returned (the same object). Thermal conductivity,
    shear modulus, Roelands' pole values and the limiting-shear slope are kept.

    Raises
    ------
    InputError
        A fluid without ``viscosity_data``, ``inlet_temperature``,
        ``density_temperature_coefficient``, ``pressure_viscosity_exponent`` or
        ``limiting_shear_temperature_coefficient``; or a temperature where the viscosity
        falls to Roelands' pole viscosity.
    """
    ref = _required(fluid, "inlet_temperature", "the temperature of the fluid's values [K]")
    if temperature == ref:
        return fluid
    if not 150.0 < temperature < 700.0:
        raise InputError("oil temperature", temperature, "150 to 700 K")
    d_t = temperature - ref
    ratio = kinematic_viscosity(fluid, temperature) / kinematic_viscosity(fluid, ref)
    beta_v = _required(fluid, "density_temperature_coefficient", "its thermal expansion [1/K]")
    t_exp = _required(fluid, "pressure_viscosity_exponent", "t of alpha ~ nu^t [-]")
    beta_l = _required(fluid, "limiting_shear_temperature_coefficient", "beta_L [1/K]")
    density = fluid.density * math.exp(-beta_v * d_t)
    eta = fluid.viscosity * ratio * density / fluid.density
    if not eta > MIN_POLE_RATIO * fluid.pole_viscosity:
        raise InputError(
            "oil temperature",
            temperature,
            f"a temperature where eta_0 ({eta:.3g} Pa s) stays above Roelands' pole "
            f"viscosity {fluid.pole_viscosity:.3g} Pa s",
        )
    alpha = fluid.pressure_viscosity_coefficient * ratio**t_exp
    logs = math.log(fluid.viscosity / fluid.pole_viscosity) / math.log(eta / fluid.pole_viscosity)
    changes = {
        "viscosity": eta,
        "density": density,
        "pressure_viscosity_coefficient": alpha,
        "roelands_index": fluid.roelands_index * ratio**t_exp * logs,
        "limiting_shear_stress": fluid.limiting_shear_stress * math.exp(-beta_l * d_t),
        "inlet_temperature": temperature,
    }
    if fluid.temperature_viscosity_coefficient is not None:
        scale = viscosity_slope(fluid, temperature) / viscosity_slope(fluid, ref)
        changes["temperature_viscosity_coefficient"] = min(
            fluid.temperature_viscosity_coefficient * scale, 0.999
        )
    return Fluid(**{**fluid.model_dump(), **changes})


def _required(fluid: Fluid, name: str, what: str) -> float:
    value = getattr(fluid, name)
    if value is None:
        raise InputError(
            name, None, f"{what} in the fluid file (the fluid at another temperature)"
        )
    return float(value)


def steady_temperature(loss: float, conductance: float, ambient: float) -> float:
    """``T_amb + P / (h A)``: the housing's balance for a loss ``P`` [W] held constant
    (``conductance = h A`` [W/K], ``ambient`` [K]) [K]."""
    return ambient + loss / conductance


def transient_step(temperature: float, loss: float, dt: float, thermal) -> float:
    """The oil temperature after ``dt`` [s] of a loss ``loss`` [W] held over the step,
    from ``temperature`` [K]: the exact solution of ``C dT/dt = P - h A (T - T_amb)`` with
    ``P`` constant, ``T_inf + (T - T_inf) exp(-dt / tau)``, ``tau = C / (h A)``,
    ``T_inf = T_amb + P / (h A)`` (exponential integrator: stable at any step) [K].

    ``thermal`` is the drive's `ballcvt.params.thermal.ThermalModel` (with a thermal mass).
    """
    target = steady_temperature(loss, thermal.conductance, thermal.ambient_temperature)
    return target + (temperature - target) * math.exp(-dt / thermal.time_constant)


def housing_coefficient(
    diameter: float, rise: float, ambient: float, air_speed: float = 0.0, emissivity: float = 0.8
) -> float:
    """Heat-transfer coefficient of a horizontal cylindrical housing to the air [W/(m^2 K)].

    Convection, natural (Churchill and Chu 1975, Int. J. Heat Mass Transfer 18, 1049: a
    horizontal cylinder) and forced (Churchill and Bernstein 1977, J. Heat Transfer 99,
    300: a cylinder in cross flow) combined as ``Nu^3 = Nu_N^3 + Nu_F^3`` (Incropera and
    DeWitt, §9.9), plus radiation to surroundings at the ambient, ``eps sigma (T_s + T_a)
    (T_s^2 + T_a^2)`` (ibid., Eq. 1.9); air properties `AIR`.

    Parameters
    ----------
    diameter : float
        Of the housing [m].
    rise : float
        Surface temperature over the ambient, > 0 [K].
    ambient : float
        Air temperature [K].
    air_speed : float
        Speed of the air across the housing (a bicycle's riding speed) [m/s].
    emissivity : float
        Of the surface (painted or anodised metal: about 0.8-0.9) [-].
    """
    k, nu, pr = AIR
    film = ambient + 0.5 * rise
    rayleigh = 9.81 * rise / film * diameter**3 * pr / nu**2
    natural = (
        0.60 + 0.387 * rayleigh ** (1 / 6) / (1 + (0.559 / pr) ** (9 / 16)) ** (8 / 27)
    ) ** 2
    re = air_speed * diameter / nu
    forced = 0.3 + 0.62 * re**0.5 * pr ** (1 / 3) / (1 + (0.4 / pr) ** (2 / 3)) ** 0.25 * (
        1 + (re / 282000.0) ** (5 / 8)
    ) ** (4 / 5)
    nusselt = (natural**3 + forced**3) ** (1 / 3)
    surface = ambient + rise
    radiation = emissivity * STEFAN_BOLTZMANN * (surface + ambient) * (surface**2 + ambient**2)
    return nusselt * k / diameter + radiation
