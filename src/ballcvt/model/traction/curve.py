"""Traction curve of one elliptical contact, as on a twin-disc or ball-on-disc machine.

Given the equivalent radii, the load (or the peak pressure), the rolling (entrainment)
speed ``U``, the spin and a range of slide-to-roll ratios, the contact is the one of a
drive (Hertz, Eqs. 45-50; film, Eq. 56) with ``u_ref = U``: the sliding speed is
``Delta U = s U`` and the spin adds ``omega_spin (-y, x)`` with
``omega_spin = sigma U / R_x``. The coefficients follow from the fluid's traction law
(`ballcvt.model.traction.base`, `ballcvt.registry.TRACTION_LAWS`): ``mu`` is the
traction coefficient, ``chi`` the spin moment over ``F_N R_x`` (Eq. 31 with ``r_c = R_x``). docs/model.md §14.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..._compat import warn_renamed
from ...errors import InputError
from ...params.models import Fluid
from ...registry import TRACTION_LAWS
from ..film import central_film_thickness
from ..hertz import hertz_contact
from .contact import ContactState
from .quadrature import Quadrature

__all__ = [
    "MachineContact",
    "TractionCurve",
    "traction_curve",
    "load_for_pressure",
    "machine_state",
    "contact_arguments",
]


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


#: ``E' = E / (1 - nu^2)`` of the steel of Table I [Pa], the default of a test pair.
STEEL_MODULUS = 210e9 / (1.0 - 0.3**2)


@dataclass(frozen=True)
class MachineContact:
    """A contact as on a traction machine (twin-disc or ball-on-disc).

    Parameters
    ----------
    rx, ry : float or array_like
        Equivalent radii of curvature along and across the rolling direction [m].
    speed : float or array_like
        Rolling (entrainment) speed ``U`` [m/s], > 0.
    load, p_max : float, optional
        Normal load [N] or Hertz peak pressure [Pa] (Eq. 50): exactly one.
    spin : float or array_like
        Spin-to-roll ratio ``sigma = omega_spin R_x / U`` [-].
    reduced_modulus : float
        ``E' = E / (1 - nu^2)`` of the pair [Pa] (default: the steel of Table I).
    """

    rx: Any
    ry: Any
    speed: Any
    load: Any = None
    p_max: Any = None
    spin: Any = 0.0
    reduced_modulus: float = STEEL_MODULUS

    def checked(self) -> MachineContact:
        """This contact of one condition, checked, with its load (`InputError` if not)."""
        for name, value in (("rx", self.rx), ("ry", self.ry), ("speed", self.speed)):
            if not np.isfinite(value) or value <= 0.0:
                raise InputError(name, value, "> 0 and finite")
        if (self.load is None) == (self.p_max is None):
            raise InputError("load", self.load, "exactly one of load and p_max")
        load = self.load
        if load is None:
            if not np.isfinite(self.p_max) or self.p_max <= 0:
                raise InputError("p_max", self.p_max, "> 0 Pa and finite")
            load = float(load_for_pressure(self.p_max, self.rx, self.ry, self.reduced_modulus))
        if not np.isfinite(load) or load <= 0:
            raise InputError("load", load, "> 0 N and finite")
        if not np.isfinite(self.spin) or abs(self.spin) > 10:
            raise InputError("spin", self.spin, "|spin| <= 10")
        return replace(self, load=load, p_max=None)


def machine_state(fluid: Fluid, machine: MachineContact, creep) -> ContactState:
    """The `ContactState` of contacts given as on a traction machine (``machine``, its
    ``load`` given) at the slide-to-roll ratios ``creep`` [-] (arrays broadcast): Hertz
    semi-axes and pressure (Eqs. 45-50), the film at the rolling speed (Eq. 56), ``u_ref``
    the rolling speed and ``r_c = R_x``."""
    m = machine
    ax, ay, p_max, _ = hertz_contact(m.load, m.rx, m.ry, m.reduced_modulus)
    film = central_film_thickness(
        fluid.viscosity,
        fluid.pressure_viscosity_coefficient,
        m.reduced_modulus,
        m.rx,
        m.speed,
        m.load,
        ay / ax,
    )
    return ContactState(creep, m.spin, ax, ay, p_max, m.load, m.rx, m.speed, film)


def contact_arguments(fluid: Fluid, *args, **kwargs) -> tuple:
    """Deprecated: ``contact_arguments(fluid, rx, ry, load, speed, spin, creep,
    reduced_modulus)``, the nine arrays of `machine_state`."""
    warn_renamed(
        "contact_arguments(fluid, rx, ...)", "machine_state(fluid, MachineContact(rx, ...), creep)"
    )
    names = ("rx", "ry", "load", "speed", "spin", "creep", "reduced_modulus")
    kw = {**dict(zip(names, args)), **kwargs}
    creep = kw.pop("creep")
    return machine_state(fluid, MachineContact(**kw), creep).values()


def traction_curve(
    fluid: Fluid,
    machine: MachineContact | None = None,
    *,
    creep,
    quadrature: Quadrature = Quadrature(),
    **conditions: Any,
) -> TractionCurve:
    """Traction curve of one elliptical contact under ``fluid``'s traction law.

    Parameters
    ----------
    fluid : Fluid
        Fluid, with its ``traction_law`` and that law's parameters.
    machine : MachineContact, optional
        The contact (radii [m], speed [m/s], load [N] or peak pressure [Pa], spin [-],
        ``E'`` [Pa]); else given by ``conditions``, its attributes as keywords
        (``rx=..., ry=..., speed=..., load=...``).
    creep : array_like
        Slide-to-roll ratios ``s`` [-], ``|s| < 2``.
    quadrature : Quadrature
        Rule for the traction integrals.

    Returns
    -------
    TractionCurve
    """
    m = (machine if machine is not None else MachineContact(**conditions)).checked()
    s = np.asarray(creep, dtype=float)
    if s.size == 0 or not np.all(np.isfinite(s)) or np.any(np.abs(s) >= 2.0):
        raise InputError("creep", s.tolist() if s.size < 5 else "...", "|creep| < 2")
    state = machine_state(fluid, m, s)
    law = TRACTION_LAWS.get(fluid.traction_law)
    if law.with_rise is not None:  # one solve of the film temperature for both
        mu, chi, rise = law.with_rise(state, fluid, quadrature)
    else:
        (mu, chi), rise = law.coefficients(state, fluid, quadrature, False), np.zeros_like(s)
    conditions = {
        "fluid": fluid.name,
        "rx": m.rx,
        "ry": m.ry,
        "load": m.load,
        "speed": m.speed,
        "spin": m.spin,
        "p_max": float(state.p_max),
        "ax": float(state.ax),
        "ay": float(state.ay),
        "film": float(state.film),
        "reduced_modulus": m.reduced_modulus,
    }
    return TractionCurve(
        s, np.asarray(mu), np.asarray(chi), np.asarray(rise), fluid.traction_law, conditions
    )
