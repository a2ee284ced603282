"""Traction curve of one elliptical contact, as on a twin-disc or ball-on-disc machine.

Given the equivalent radii, the load (or the peak pressure), the rolling (entrainment)
speed ``U``, the spin and a range of slide-to-roll ratios, the contact is the one of a
drive (Hertz, Eqs. 45-50; film, Eq. 56) with ``u_ref = U``: the sliding speed is
``Delta U = s U`` and the spin adds ``omega_spin (-y, x)`` with
``omega_spin = sigma U / R_x``. The coefficients follow from the fluid's traction law
(`ballcvt.model.traction.base`): ``mu`` is the traction coefficient, ``chi`` the spin moment over
``F_N R_x`` (Eq. 31 with ``r_c = R_x``). docs/model.md §14.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...errors import InputError
from ...params.models import Fluid
from ..film import central_film_thickness
from ..hertz import hertz_contact
from .base import law_coefficients
from .quadrature import Quadrature
from .thermal import thermal_coefficients_and_rise

__all__ = ["TractionCurve", "traction_curve", "load_for_pressure", "contact_arguments"]


@dataclass(frozen=True)
class TractionCurve:
    """Traction coefficient against slide-to-roll ratio at one contact condition.

    Attributes
    ----------
    creep : ndarray
        Slide-to-roll ratio ``s = Delta U / U`` [-].
    mu : ndarray
        Traction coefficient ``F_T / F_N`` [-].
    chi : ndarray
        Spin-moment coefficient ``M / (F_N R_x)`` [-].
    temperature_rise : ndarray
        Film temperature rise above the inlet (thermal law; zeros otherwise) [K].
    law : str
        Traction law.
    conditions : dict
        ``rx, ry`` [m], ``load`` [N], ``speed`` [m/s], ``spin`` [-], ``p_max`` [Pa],
        ``ax, ay`` [m], ``film`` [m], ``reduced_modulus`` [Pa], ``fluid`` (name).
    """

    creep: np.ndarray
    mu: np.ndarray
    chi: np.ndarray
    temperature_rise: np.ndarray
    law: str
    conditions: dict = field(default_factory=dict)

    def as_dict(self) -> dict:
        """JSON-ready: ``creep``, ``mu``, ``chi``, ``temperature_rise``, ``law``, conditions."""
        return {
            "law": self.law,
            **self.conditions,
            **{k: getattr(self, k).tolist() for k in ("creep", "mu", "chi", "temperature_rise")},
        }


def load_for_pressure(p_max, rx, ry, reduced_modulus):
    """Normal load [N] that gives the Hertz peak pressure ``p_max`` [Pa] (Eq. 50).

    ``p_max`` grows as ``F_N^(1/3)`` at fixed radii [m] and modulus [Pa].
    """
    _, _, p_unit, _ = hertz_contact(1.0, rx, ry, reduced_modulus)
    return (np.asarray(p_max, dtype=float) / p_unit) ** 3


#: ``(creep_term, spin, ax, ay, p_max, load, radius, u_ref, film)`` of a traction law.
ContactArguments = tuple[Any, Any, Any, Any, Any, Any, Any, Any, Any]


def contact_arguments(
    fluid: Fluid, rx, ry, load, speed, spin, creep, reduced_modulus
) -> ContactArguments:
    """The arguments of a traction law (`ballcvt.model.traction.base.law_coefficients`, up to the
    fluid) for contacts given as on a traction machine: radii ``rx, ry`` [m], ``load``
    [N], rolling speed [m/s], spin-to-roll ratio [-], slide-to-roll ratio [-] and ``E'``
    [Pa] (arrays broadcast). Hertz semi-axes and pressure (Eqs. 45-50), the film at the
    rolling speed (Eq. 56), ``u_ref`` the rolling speed and ``r_c = R_x``."""
    ax, ay, p_max, _ = hertz_contact(load, rx, ry, reduced_modulus)
    film = central_film_thickness(
        fluid.viscosity,
        fluid.pressure_viscosity_coefficient,
        reduced_modulus,
        rx,
        speed,
        load,
        ay / ax,
    )
    return (creep, spin, ax, ay, p_max, load, rx, speed, film)


def traction_curve(
    fluid: Fluid,
    *,
    rx: float,
    ry: float,
    speed: float,
    creep,
    load: float | None = None,
    p_max: float | None = None,
    spin: float = 0.0,
    reduced_modulus: float = 210e9 / (1.0 - 0.3**2),
    quadrature: Quadrature = Quadrature(),
) -> TractionCurve:
    """Traction curve of one elliptical contact under ``fluid``'s traction law.

    Parameters
    ----------
    fluid : Fluid
        Fluid, with its ``traction_law`` and that law's parameters.
    rx, ry : float
        Equivalent radii of curvature along and across the rolling direction [m].
    speed : float
        Rolling (entrainment) speed ``U`` [m/s], > 0.
    creep : array_like
        Slide-to-roll ratios ``s`` [-], ``|s| < 2``.
    load, p_max : float
        Normal load [N] or Hertz peak pressure [Pa]: exactly one.
    spin : float
        Spin-to-roll ratio ``sigma = omega_spin R_x / U`` [-].
    reduced_modulus : float
        ``E' = E / (1 - nu^2)`` of the pair [Pa] (default: the steel of Table I).
    quadrature : Quadrature
        Rule for the traction integrals.

    Returns
    -------
    TractionCurve
    """
    for name, value, low in (("rx", rx, 0.0), ("ry", ry, 0.0), ("speed", speed, 0.0)):
        if not np.isfinite(value) or value <= low:
            raise InputError(name, value, f"> {low:g} and finite")
    if (load is None) == (p_max is None):
        raise InputError("load", load, "exactly one of load and p_max")
    if load is None:
        assert p_max is not None
        if not np.isfinite(p_max) or p_max <= 0:
            raise InputError("p_max", p_max, "> 0 Pa and finite")
        load = float(load_for_pressure(p_max, rx, ry, reduced_modulus))
    if not np.isfinite(load) or load <= 0:
        raise InputError("load", load, "> 0 N and finite")
    if not np.isfinite(spin) or abs(spin) > 10:
        raise InputError("spin", spin, "|spin| <= 10")
    s = np.asarray(creep, dtype=float)
    if s.size == 0 or not np.all(np.isfinite(s)) or np.any(np.abs(s) >= 2.0):
        raise InputError("creep", s.tolist() if s.size < 5 else "...", "|creep| < 2")
    args = contact_arguments(fluid, rx, ry, load, speed, spin, s, reduced_modulus)
    ax, ay, pm, film = (float(v) for v in (args[2], args[3], args[4], args[8]))
    if fluid.traction_law == "thermal":  # one solve of the film temperature for both
        mu, chi, rise = thermal_coefficients_and_rise(*args, fluid, quadrature)
    else:
        (mu, chi), rise = law_coefficients(*args, fluid, quadrature), np.zeros_like(s)
    conditions = {
        "fluid": fluid.name,
        "rx": rx,
        "ry": ry,
        "load": load,
        "speed": speed,
        "spin": spin,
        "p_max": pm,
        "ax": ax,
        "ay": ay,
        "film": film,
        "reduced_modulus": reduced_modulus,
    }
    return TractionCurve(
        s, np.asarray(mu), np.asarray(chi), np.asarray(rise), fluid.traction_law, conditions
    )
