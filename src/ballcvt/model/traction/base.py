"""Traction laws: one registry, one dispatcher (docs/model.md §14).

A traction law maps a contact's creep, spin, geometry, load, speed and film to its
traction and spin-moment coefficients ``mu`` and ``chi`` (and their derivatives), with
the signature of `ballcvt.model.traction.isothermal.traction_coefficients`. The fluid names its
law (``Fluid.traction_law``) and carries the law's parameters, so every solver, sweep and
command uses it without knowing which it is. Adding a law is a function here, its fluid
fields in `ballcvt.params.models.LAW_FIELDS`, and its tests.

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

from collections.abc import Callable
from dataclasses import dataclass

from ...params.models import TRACTION_LAWS, Fluid
from ...registry import TRACTION_LAWS as REGISTRY
from .isothermal import traction_coefficients
from .quadrature import Quadrature
from .thermal import thermal_coefficients

__all__ = ["LAWS", "MONOTONE", "law_coefficients", "traction_rises_with_creep"]

#: Law name -> coefficient function (signature of `traction_coefficients`).
LAWS: dict[str, Callable] = {
    "isothermal": traction_coefficients,
    "viscoelastic": traction_coefficients,  # the elastic factor is node-local
    "thermal": thermal_coefficients,
}
#: Whether a law's traction coefficient rises monotonically with the creep. Where it can
#: fall (the thermal law past its peak), the limiting torque is the peak of the traction
#: curve when that comes before the creep limit (`ballcvt.solvers.limit`).
MONOTONE: dict[str, bool] = {"isothermal": True, "viscoelastic": True, "thermal": False}
assert set(LAWS) == set(TRACTION_LAWS) == set(MONOTONE)


@dataclass(frozen=True)
class TractionLaw:
    """A registered traction law: its name, coefficient function and monotonicity."""

    name: str
    coefficients: Callable
    monotone: bool = True


for _name in LAWS:
    REGISTRY.register(TractionLaw(_name, LAWS[_name], MONOTONE[_name]))


def traction_rises_with_creep(fluid: Fluid) -> bool:
    """Whether ``fluid``'s traction law gives a traction that never falls with the creep."""
    return MONOTONE[fluid.traction_law]


def law_coefficients(
    creep_term,
    spin,
    ax,
    ay,
    p_max,
    load,
    radius,
    u_ref,
    film,
    fluid: Fluid,
    quadrature: Quadrature = Quadrature(),
    derivatives: bool = False,
):
    """``mu, chi`` (and with ``derivatives`` their derivatives) under ``fluid``'s law.

    Parameters, units and returns as in
    `ballcvt.model.traction.isothermal.traction_coefficients`.
    """
    return LAWS[fluid.traction_law](
        creep_term,
        spin,
        ax,
        ay,
        p_max,
        load,
        radius,
        u_ref,
        film,
        fluid,
        quadrature,
        derivatives=derivatives,
    )
