"""Adaptive-quadrature reference of the traction integrals (for validation only).

Nested `scipy.integrate.quad` over the normalised ellipse, with the pole passed as a
break point of the inner integral. Accurate but slow (seconds per contact; docs/model.md §3):
use it in tests and benchmarks, never in production.
"""

from __future__ import annotations

import math

from scipy.integrate import quad

from ...params.models import Fluid
from ..rheology import limiting_shear_stress, roelands_viscosity, saturation_factor
from .contact import ContactState, legacy_arguments
from .isothermal import pole_position

__all__ = ["adaptive_coefficients", "traction_coefficients_adaptive"]


def adaptive_coefficients(state: ContactState, fluid: Fluid, epsrel: float = 1e-9):
    """``mu`` and ``chi`` of one contact by nested adaptive quadrature (Eqs. 53, 57-66).

    Parameters
    ----------
    state : ContactState
        One contact (scalars, units of `ContactState`).
    fluid : Fluid
        Traction fluid (the isothermal law of Eq. 53).
    epsrel : float
        Relative tolerance of each `quad` call [-].

    Returns
    -------
    mu, chi : float
    """
    creep_term, spin, ax, ay, p_max, load, radius, u_ref, film = state.values()
    yp = float(pole_position(creep_term, spin, ay, radius))

    def stress(x, y):
        p = p_max * math.sqrt(max(1.0 - x * x - y * y, 0.0))
        eta = float(
            roelands_viscosity(
                p, fluid.viscosity, fluid.pole_viscosity, fluid.pole_pressure, fluid.roelands_index
            )
        )
        tau_l = float(
            limiting_shear_stress(p, fluid.limiting_shear_stress, fluid.limiting_shear_slope)
        )
        vx = u_ref * (creep_term - spin * ay / radius * y)
        vy = u_ref * spin * ax / radius * x
        g = eta / film * float(saturation_factor(eta * math.hypot(vx, vy) / (film * tau_l)))
        return g * vx, g * vy

    def integral(kernel):
        def inner(x):
            half = math.sqrt(max(1.0 - x * x, 0.0))
            pts = [yp] if -half < yp < half else None
            return quad(
                lambda y: kernel(x, y),
                -half,
                half,
                points=pts,
                epsrel=epsrel,
                epsabs=0.0,
                limit=200,
            )[0]

        return quad(inner, -1.0, 1.0, points=[0.0], epsrel=epsrel, epsabs=0.0, limit=200)[0]

    tx = integral(lambda x, y: stress(x, y)[0])
    moment = integral(lambda x, y: ax * x * stress(x, y)[1] - ay * y * stress(x, y)[0])
    area = ax * ay
    return area / load * tx, area / (load * radius) * moment


def traction_coefficients_adaptive(*args, **kwargs):
    """Deprecated: the nine contact scalars, then ``fluid, epsrel``; use
    `adaptive_coefficients` of a `ContactState`."""
    state, rest, kw = legacy_arguments(
        "traction_coefficients_adaptive(creep_term, ..., film, fluid)",
        "adaptive_coefficients(ContactState(creep_term, ..., film), fluid)",
        args,
        kwargs,
    )
    return adaptive_coefficients(state, *rest, **kw)
