"""The model layer's traction laws: quadrature, kernels, the isothermal, thermal and viscoelastic laws (Eqs. 53-66).

A traction law is a `TractionLaw` in `ballcvt.registry.TRACTION_LAWS` (see
`ballcvt.model.traction.base`); `contact_coefficients` evaluates the fluid's law at a
`ContactState`.
"""

from ...registry import TRACTION_LAWS
from ..film import central_film_thickness
from ..hertz import hertz_contact, rolling_curvature_ratio, transverse_curvature_ratio
from ..rheology import limiting_shear_stress, roelands_viscosity, saturation_factor
from .base import LAWS, TractionLaw, lateral_coefficients, law_coefficients, traction_law
from .contact import ContactState, contact_coefficients
from .isothermal import (
    ShearLaw,
    pole_position,
    shear_coefficients,
    shear_law_coefficients,
    traction_coefficients,
)
from .lateral import lateral_shear_coefficients, limiting_traction
from .quadrature import METHODS, REFERENCE, Quadrature, centred_rule, inner_pole_rule
from .thermal import (
    film_temperature_rise,
    temperature_rise,
    thermal_coefficients,
    thermal_law_coefficients,
)

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
    "ContactState",
    "TractionLaw",
    "TRACTION_LAWS",
    "contact_coefficients",
    "lateral_coefficients",
    "lateral_shear_coefficients",
    "limiting_traction",
    "shear_coefficients",
    "ShearLaw",
    "shear_law_coefficients",
    "thermal_law_coefficients",
    "temperature_rise",
    "traction_law",
    "traction_coefficients",
    "LAWS",
    "law_coefficients",
    "film_temperature_rise",
    "thermal_coefficients",
]
