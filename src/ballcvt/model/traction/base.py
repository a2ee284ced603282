"""Traction laws: one registry entry each, one dispatcher (docs/model.md §14).

A traction law maps a contact's creep, spin, geometry, load, speed and film (a
`ballcvt.model.traction.contact.ContactState`) to its traction and spin-moment
coefficients ``mu`` and ``chi`` (and their derivatives). The fluid names its law
(``Fluid.traction_law``) and carries the law's parameters (its own fields, or
``Fluid.law_parameters`` for a law defined outside the package), so every solver, sweep
and command uses it without knowing which it is. A law is a `TractionLaw` entry in
`ballcvt.registry.TRACTION_LAWS`: everything law-specific (the fields it needs, whether
its traction is monotone in the creep, the parameters a fit adjusts by default, its film
temperature) is an attribute of the entry, so no code outside this module tests a law's
name. Adding a law is one ``TRACTION_LAWS.register(TractionLaw(...))`` call (here for a
built-in law, from user code for another: examples/extending/traction_law.py).

``isothermal``
    The paper's law (Eq. 53), rigid-plastic, one temperature (the default).
``viscoelastic``
    Eq. 53 with Maxwell elasticity (Johnson and Tevaarwerk 1977): the initial slope of the
    traction curve follows from the film's shear modulus.
``thermal``
    Eq. 53 at a film temperature raised by the contact's shear heat (flash temperature
    after Jaeger 1942 and conduction across the film, after Olver and Spikes 1998).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..._compat import warn_renamed
from ...errors import InputError
from ...params.models import Fluid
from ...registry import TRACTION_LAWS
from .contact import ContactState, contact_coefficients, legacy_arguments
from .isothermal import ShearLaw, shear_coefficients
from .lateral import lateral_shear_coefficients, thermal_lateral_coefficients
from .quadrature import Quadrature
from .thermal import thermal_law_coefficients, thermal_law_film_coefficients, thermal_law_rise

__all__ = [
    "TractionLaw",
    "TRACTION_LAWS",
    "LAWS",
    "MONOTONE",
    "contact_coefficients",
    "lateral_coefficients",
    "law_coefficients",
    "traction_law",
    "traction_rises_with_creep",
    "has_multiple_equilibria",
    "residual_floor",
    "THERMAL_RESIDUAL_FLOOR",
]

#: ``(state, fluid, quadrature, derivatives) -> (mu, chi)`` or, with ``derivatives``,
#: ``(mu, chi, dmu, dchi)`` (`ballcvt.model.traction.contact.contact_coefficients`).
Coefficients = Callable[[ContactState, Fluid, Quadrature, bool], tuple]


@dataclass(frozen=True)
class TractionLaw:
    """A traction law: what the registry holds for it (docs/model.md §14).

    Parameters
    ----------
    name : str
        The law's name, the value of ``Fluid.traction_law``.
    coefficients : callable
        ``(state, fluid, quadrature, derivatives)`` -> ``mu, chi`` [-] and, with
        ``derivatives``, ``dmu, dchi`` of shape ``(..., 3)`` (with respect to the creep
        term, the spin and ``log u_ref``; Newton's Jacobians), as
        `ballcvt.model.traction.isothermal.shear_coefficients`.
    description : str
        One line, with the law's source (shown in the documentation and the CLI).
    fields : tuple of str
        `Fluid` fields the law needs (optional fields that must then be given).
    parameters : tuple of str
        Keys of ``Fluid.law_parameters`` the law needs (a law defined outside the package
        keeps its own parameters there).
    monotone : bool
        Whether ``mu`` never falls as the creep grows. Where it can fall (the thermal law
        past its peak), the limiting torque is the peak of the traction curve when that
        comes before the creep limit (`ballcvt.solvers.limit`).
    fit_parameters : tuple of str
        `Fluid` fields `ballcvt.analysis.fitting.fit_fluid` adjusts by default.
    with_rise : callable, optional
        ``(state, fluid, quadrature)`` -> ``mu, chi, dT``: the coefficients and the film
        temperature rise [K] in one solve, for a law that heats the film (traction
        curves report the rise; zero for a law without it).
    multiple_equilibria : bool
        Whether the drive can have more than one equilibrium at an operating point (the
        thermal law: a second one past the peak of a traction curve). The solvers then
        return the one the drive reaches, followed continuously in torque from zero torque
        at the point's speed (`ballcvt.solvers.continuation`, docs/model.md §14); a law
        opts in by this attribute alone. False (the paper's law): Newton from any start.
    odd_lateral : bool
        Whether ``mu_y`` is odd in the lateral creep, so that it vanishes without side
        slip (a rigid-plastic law: the stress follows the local sliding, with no memory of
        the film's entry edge; docs/model.md §17). A steady point's holding moment is then
        zero, and `ballcvt.results.moments.steady_moments` does not integrate it. False:
        integrated (a Maxwell film's ``mu_y`` at zero side slip is small, not zero).
    film_coefficients : callable, optional
        ``(state, fluid, quadrature)`` -> ``mu, chi, dmu, dchi`` with a fourth derivative
        column, by ``log h`` at a fixed ``u_ref / h`` (as a lubrication model's,
        `ballcvt.model.lubrication`): for a law whose coefficients depend on the film
        otherwise than through ``u_ref / h`` (the thermal law's film temperature), so that
        Newton's Jacobians include it. None: through ``u_ref / h`` only (Eq. 53).
    residual_floor : float
        The least residual norm [-] the solvers ask of an equilibrium under the law
        (`ballcvt.solvers.options.at_residual_floor`: the tolerance is raised to it): the
        rounding noise of its coefficients, below which Newton cannot go. 0: none (the
        paper's law, whose residual is smooth to ~1e-15).
    """

    name: str
    coefficients: Coefficients
    description: str = ""
    fields: tuple[str, ...] = ()
    parameters: tuple[str, ...] = ()
    monotone: bool = True
    fit_parameters: tuple[str, ...] = ("limiting_shear_stress", "limiting_shear_slope")
    with_rise: Callable[[ContactState, Fluid, Quadrature], tuple] | None = None
    multiple_equilibria: bool = False
    lateral: Callable[[ContactState, Fluid, Any, Quadrature, Any], tuple] | None = None
    odd_lateral: bool = False
    film_coefficients: Callable[[ContactState, Fluid, Quadrature], tuple] | None = None
    residual_floor: float = 0.0


def _viscoelastic(state: ContactState, fluid: Fluid, quadrature: Quadrature, derivatives: bool):
    """Eq. 53 with Maxwell elasticity of modulus ``fluid.shear_modulus`` (§14)."""
    modulus = fluid.shear_modulus
    assert modulus is not None  # a required field of the law (`Fluid` validation)
    return shear_coefficients(state, fluid, quadrature, derivatives, modulus)


def _isothermal_lateral(state: ContactState, fluid: Fluid, lateral, quadrature: Quadrature, entry):
    """Eq. 53 with side slip (docs/model.md §17)."""
    return lateral_shear_coefficients(state, fluid, lateral, quadrature, entry=entry)


def _viscoelastic_lateral(
    state: ContactState, fluid: Fluid, lateral, quadrature: Quadrature, entry
):
    """Eq. 53 with Maxwell elasticity and side slip (docs/model.md §14, §17)."""
    modulus = fluid.shear_modulus
    assert modulus is not None  # a required field of the law (`Fluid` validation)
    law = ShearLaw(modulus=modulus)
    return lateral_shear_coefficients(state, fluid, lateral, quadrature, law, entry)


#: The thermal law's `TractionLaw.residual_floor` [-]. Its coefficients carry rounding
#: noise that the paper's law does not (measured along a disc creep in steps of 2.5e-10 on
#: harden task 2028:592, 3 GPa, 2,923 rpm: second differences of ``mu`` ~3e-13 relative at
#: the discs' contacts against 1e-15 under the paper's law, and ~4e-11 absolute at the
#: idler's, whose ``mu`` is ~7e-9), so the idler's balance is noisy to ~2e-10; at the
#: solvers' 1e-11 Newton stalled there, and the limiting torque at one force ranged from
#: 55 % to 99.98 % of the fold with the batch it was solved in. At 1e-9 (five times the
#: noise) it is the fold to 1e-8 whatever the batch. The noise came from the saturation's
#: slope (`ballcvt.model.rheology.saturation_slope`, fixed in session 35: the residual is
#: now smooth to 2e-16 up to 3.5 GPa); the floor stays as the margin the fold searches were
#: validated with (docs/model.md §14).
THERMAL_RESIDUAL_FLOOR = 1e-9

_THERMAL_FIELDS = (
    "temperature_viscosity_coefficient",
    "limiting_shear_temperature_coefficient",
    "thermal_conductivity",
    "inlet_temperature",
    "surface_conductivity",
    "surface_diffusivity",
)
for _law in (
    TractionLaw(
        "isothermal",
        shear_coefficients,
        "the paper's rigid-plastic law, Eq. 53 (Tomaselli et al. 2020)",
        lateral=_isothermal_lateral,
        odd_lateral=True,
    ),
    TractionLaw(
        "thermal",
        thermal_law_coefficients,
        "Eq. 53 at a film temperature raised by shear heat (Jaeger 1942; Olver and Spikes 1998)",
        fields=_THERMAL_FIELDS,
        monotone=False,
        fit_parameters=(
            "limiting_shear_stress",
            "limiting_shear_slope",
            "temperature_viscosity_coefficient",
        ),
        with_rise=thermal_law_rise,
        multiple_equilibria=True,
        lateral=thermal_lateral_coefficients,
        odd_lateral=True,
        film_coefficients=thermal_law_film_coefficients,
        residual_floor=THERMAL_RESIDUAL_FLOOR,
    ),
    TractionLaw(
        "viscoelastic",
        _viscoelastic,
        "Eq. 53 with Maxwell elasticity (Johnson and Tevaarwerk 1977)",
        fields=("shear_modulus",),
        fit_parameters=("limiting_shear_stress", "limiting_shear_slope", "shear_modulus"),
        lateral=_viscoelastic_lateral,
    ),
):
    TRACTION_LAWS.register(_law)


def traction_law(fluid: Fluid) -> TractionLaw:
    """The registered law ``fluid`` names (`InputError` listing the laws if none)."""
    return TRACTION_LAWS.get(fluid.traction_law)


def lateral_coefficients(
    state: ContactState,
    fluid: Fluid,
    lateral,
    quadrature: Quadrature = Quadrature(),
    entry=1.0,
):
    """``mu``, ``mu_y`` and ``chi`` [-] of contacts with a lateral creep, under ``fluid``'s
    law (docs/model.md §17).

    Parameters
    ----------
    state : ContactState
        The contacts, as for `contact_coefficients`.
    fluid : Fluid
        Traction fluid; its law must have a side-slip form (`TractionLaw.lateral`: the
        built-in laws have).
    lateral : array_like
        Lateral creep ``s_lat`` (lateral sliding speed over ``u_ref``) [-].
    quadrature : Quadrature
        Rule and node counts.
    entry : array_like
        Rolling direction along Eq. 55's ``x`` (+1: the surfaces enter at ``X = -1``, the
        solvers' assumption; -1: at ``X = +1``) [-]; only a Maxwell film's ``mu_y``
        depends on it (`lateral_shear_coefficients`).

    Returns
    -------
    mu, mu_y, chi : ndarray
        Longitudinal and lateral traction coefficients, spin-moment coefficient [-].
        Without side slip use `contact_coefficients` (the solvers' path, unchanged);
        ``mu_y`` is then exactly zero under a law with ``odd_lateral``.
    """
    law = traction_law(fluid)
    if law.lateral is None:
        with_lateral = [n for n in TRACTION_LAWS if TRACTION_LAWS.get(n).lateral is not None]
        raise InputError(
            "traction_law", law.name, "a law with side slip: " + ", ".join(with_lateral)
        )
    mu, mu_y, chi = law.lateral(state, fluid, lateral, quadrature, entry)
    if law.odd_lateral:  # zero without side slip, not the quadrature's round-off
        mu_y = np.where(np.asarray(lateral) == 0.0, 0.0, mu_y)
    return mu, mu_y, chi


def traction_rises_with_creep(fluid: Fluid) -> bool:
    """Whether ``fluid``'s traction law gives a traction that never falls with the creep."""
    return traction_law(fluid).monotone


def residual_floor(fluid: Fluid) -> float:
    """The least residual norm [-] the solvers ask under ``fluid``'s traction law
    (`TractionLaw.residual_floor`)."""
    return traction_law(fluid).residual_floor


def has_multiple_equilibria(fluid: Fluid) -> bool:
    """Whether ``fluid``'s traction law can give the drive more than one equilibrium at a
    point (`TractionLaw.multiple_equilibria`)."""
    return traction_law(fluid).multiple_equilibria


class _View(Mapping):
    """Law name -> one attribute of its entry, read from the registry when asked (so that
    a law registered later is in it)."""

    def __init__(self, attribute: str, old: str) -> None:
        self._attribute, self._old = attribute, old

    def __getitem__(self, name: str) -> Any:
        warn_renamed(self._old, f"TRACTION_LAWS.get(name).{self._attribute}")
        return getattr(TRACTION_LAWS.get(name), self._attribute)

    def __iter__(self):
        return iter(TRACTION_LAWS)

    def __len__(self) -> int:
        return len(TRACTION_LAWS)


#: Deprecated: law name -> coefficient function (now ``TRACTION_LAWS.get(name).coefficients``).
LAWS: Mapping[str, Coefficients] = _View("coefficients", "ballcvt.model.traction.base.LAWS")
#: Deprecated: law name -> monotone (now ``TRACTION_LAWS.get(name).monotone``).
MONOTONE: Mapping[str, bool] = _View("monotone", "ballcvt.model.traction.base.MONOTONE")


def law_coefficients(*args, **kwargs):
    """Deprecated: the nine contact arrays, then ``fluid, quadrature, derivatives``; use
    `contact_coefficients` of a `ContactState`."""
    state, rest, kw = legacy_arguments(
        "law_coefficients(creep_term, ..., film, fluid)",
        "contact_coefficients(ContactState(creep_term, ..., film), fluid)",
        args,
        kwargs,
    )
    return contact_coefficients(state, *rest, **kw)
