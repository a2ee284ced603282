"""Layer 2: contact mechanics (Hertz, rheology, film, traction integrals; Eqs. 41-66)."""

from ..film import central_film_thickness
from ..hertz import hertz_contact, rolling_curvature_ratio, transverse_curvature_ratio
from ..rheology import limiting_shear_stress, roelands_viscosity, saturation_factor
from .base import LAWS, law_coefficients
from .isothermal import pole_position, traction_coefficients
from .quadrature import METHODS, REFERENCE, Quadrature, centred_rule, inner_pole_rule
from .thermal import film_temperature_rise, thermal_coefficients

__all__ = [
    "central_film_thickness",
    "hertz_contact",
    "rolling_curvature_ratio",
    "transverse_curvature_ratio",
    "METHODS",
    "REFERENCE",
    "Quadrature",
    "centred_rule",
    "inner_pole_rule",
    "limiting_shear_stress",
    "roelands_viscosity",
    "saturation_factor",
    "pole_position",
    "traction_coefficients",
    "LAWS",
    "law_coefficients",
    "film_temperature_rise",
    "thermal_coefficients",
]
