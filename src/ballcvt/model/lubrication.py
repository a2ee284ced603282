"""Lubrication models: how the load of a contact is shared by the film and the asperities.

A lubrication model is a `LubricationModel` entry of
`ballcvt.registry.LUBRICATION_MODELS` (docs/model.md §16). It wraps the fluid's traction
law (any law of `ballcvt.registry.TRACTION_LAWS`), so that the two choices are
independent:

``full-film``
    The paper's: the film carries the whole load; the traction law's coefficients as they
    are (the default, and the only model of the paper's drive).
``mixed``
    The asperities carry a fraction ``f_a`` of the load, found from the film parameter
    ``lambda = h / sigma`` by the load-sharing idea of Johnson, Greenwood and Poon, Wear 19
    (1972) 91-108, with the asperity pressure of Greenwood and Tripp, Proc. Instn Mech.
    Engrs 185 (1970-71) 625-633 (as in the mixed-lubrication model of Gelinck and
    Schipper, Tribol. Int. 33 (2000) 175-181). The film carries ``(1 - f_a)`` of the load
    and shears by the fluid's law; the asperities carry ``f_a`` with a boundary friction
    coefficient ``mu_b``, along the local sliding (so they add to the spin moment too):

        ``mu = (1 - f_a) mu_film + f_a mu_b M``, ``chi = (1 - f_a) chi_film + f_a mu_b N``,

    ``M``, ``N`` the traction and spin coefficients of a unit regularised Coulomb shear
    over the Hertz pressure (`boundary_coefficients`): Coulomb's ``mu_b p`` once the local
    slip exceeds the contact's tangential compliance (creep of order 1e-3), elastic below.

Load sharing (Johnson, Greenwood and Poon 1972): the film carries the pressure
``p / gamma_1`` and forms as a smooth EHL film of load ``F / gamma_1`` on a modulus
``E' / gamma_1``; the asperities carry ``p / gamma_2``, with ``1/gamma_1 + 1/gamma_2 = 1``,
so ``f_a = 1 / gamma_2``. With the Hamrock-Dowson film of Eq. 56 (``h ~ U^0.67 G^0.53
W^-0.067`` with ``U ~ 1/E'``, ``G ~ E'``, ``W ~ F/E'``) the film is
``h = h_s gamma_1^0.14 = h_s (1 - f_a)^-0.14`` (``h_s`` the smooth film of the whole load),
and Greenwood-Tripp's asperity pressure at the separation ``h`` over the Hertz area
``A = pi a_x a_y`` closes the balance

    ``f_a = K E' F_5/2(h / sigma) / p_mean``, ``p_mean = F_N / A``,
    ``K = (16 sqrt(2) / 15) pi (eta beta sigma)^2 sqrt(sigma / beta)``,

``F_n(t) = (2 pi)^-1/2 int_t^inf (s - t)^n exp(-s^2/2) ds`` (Gaussian summit heights),
solved for ``f_a`` per contact (`load_sharing`). ``F_5/2`` is truncated at
``lambda = LAMBDA_CUTOFF`` (a C1 join: the Gaussian tail above 4 sigma, 3e-5 of the
summits, dropped), so that above it ``f_a = 0`` and the result is exactly the full film's.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from ..params.models import Design, Fluid
from ..registry import LUBRICATION_MODELS, TRACTION_LAWS
from .greenwood_tripp import (
    FILM_SHARE_EXPONENT,
    LAMBDA_CUTOFF,
    asperity_integral,
    film_factor,
    solve_share,
)
from .traction.contact import ContactState, contact_coefficients
from .traction.isothermal import shear_coefficients
from .traction.quadrature import Quadrature

__all__ = [
    "Asperities",
    "LubricationModel",
    "LUBRICATION_MODELS",
    "LAMBDA_CUTOFF",
    "FILM_SHARE_EXPONENT",
    "asperities",
    "asperity_integral",
    "load_sharing",
    "boundary_coefficients",
    "boundary_rule",
    "BOUNDARY_ANGULAR",
    "creep_stiffness",
    "STEEL_CREEP_STIFFNESS",
    "lubricated_coefficients",
]

#: Relative step of the derivative with respect to the film thickness [-].
_STEP = 1e-6
#: Rule of that derivative (the film's share of the load by the film thickness, a
#: Jacobian column only: the converged equilibrium does not depend on it) where the
#: law's own rule has more nodes.
FILM_SHARE_RULE = Quadrature("centred", 12, 8, 8)
#: Angular nodes of the boundary shear's rule where the law's rule has twice as many or
#: more (`boundary_rule`) [-].
BOUNDARY_ANGULAR = 12
#: Kalker's longitudinal creep coefficient ``C_11`` of a circular contact at Poisson's
#: ratios 0, 0.25, 0.5 (Kalker 1967, as tabulated in Johnson, *Contact Mechanics* (1985)
#: §8.4: ``F_x = C_11 G a b xi`` for small creep ``xi``) [-].
_KALKER_POISSON, _KALKER_C11 = (0.0, 0.25, 0.5), (3.40, 4.12, 5.20)


def creep_stiffness(youngs_modulus: float, poisson_ratio: float) -> float:
    """Tangential stiffness per unit creep of an asperity contact: ``k = C_11 G / pi`` [Pa].

    The shear ``tau = k s`` of a local slip ``s`` (sliding over rolling speed) spread over
    the Hertz ellipse gives Kalker's linear creep force ``F_x = C_11 G a b xi`` of a rolling
    contact without slip (Johnson 1985 §8.4; ``G = E / (2 (1 + nu))``, ``C_11``
    interpolated in ``nu`` from Kalker's circle values). Steel (210 GPa, 0.3): 1.11e11 Pa,
    so that ``mu_b p_max / k`` is 7e-4 at 0.1 and 0.76 GPa, the order of the creep at which
    a Hertz contact slips throughout (Carter's ``mu a / R = 2 mu p_0 / E*``, Johnson 1985
    §8.2: 1.3e-3 there).

    Parameters
    ----------
    youngs_modulus : float
        ``E`` [Pa] of both bodies.
    poisson_ratio : float
        ``nu`` [-].

    Returns
    -------
    float
        ``k`` [Pa].
    """
    c11 = float(np.interp(poisson_ratio, _KALKER_POISSON, _KALKER_C11))
    return c11 * youngs_modulus / (2.0 * (1.0 + poisson_ratio)) / np.pi


#: `creep_stiffness` of bearing steel (E 210 GPa, nu 0.3) [Pa].
STEEL_CREEP_STIFFNESS = creep_stiffness(210.0e9, 0.3)


@dataclass(frozen=True)
class Asperities:
    """A drive's lubrication model and what it needs beyond the `ContactState`.

    Attributes
    ----------
    model : str
        Name in `LUBRICATION_MODELS`.
    roughness : float
        Composite RMS roughness ``sigma`` [m] (``Design.surface_roughness``).
    modulus : float
        ``E' = E / (1 - nu^2)`` [Pa].
    boundary_friction : float
        ``mu_b`` [-].
    density_product, slope : float
        ``eta beta sigma`` and ``sigma / beta`` [-].
    creep_stiffness : float
        ``k`` of the asperities' boundary shear [Pa] (`creep_stiffness`).
    """

    model: str
    roughness: float
    modulus: float
    boundary_friction: float = 0.0
    density_product: float = 0.0
    slope: float = 0.0
    creep_stiffness: float = STEEL_CREEP_STIFFNESS

    @property
    def pressure_scale(self) -> float:
        """``K E'`` of Greenwood and Tripp's asperity pressure ``K E' F_5/2`` [Pa]."""
        k = 16.0 * np.sqrt(2.0) / 15.0 * np.pi * self.density_product**2 * np.sqrt(self.slope)
        return float(k * self.modulus)


def asperities(design: Design) -> Asperities:
    """The lubrication of ``design`` (``full-film`` without ``[design.lubrication]``)."""
    lub, e = design.lubrication, design.material.reduced_modulus
    if lub is None:
        return Asperities("full-film", design.surface_roughness, e)
    return Asperities(
        lub.model,
        design.surface_roughness,
        e,
        lub.boundary_friction,
        lub.asperity_density_product,
        lub.asperity_slope,
        creep_stiffness(design.material.youngs_modulus, design.material.poisson_ratio),
    )


def load_sharing(film, load, ax, ay, asp: Asperities):
    """Asperity load fraction ``f_a`` and film parameter ``h / sigma`` of contacts.

    Solves ``f = g(lambda_s (1 - f)^-e)``, ``g = K E' F_5/2 / p_mean`` (module docstring;
    Johnson, Greenwood and Poon 1972) by safeguarded Newton in ``[0, 1)``: the left side
    rises and the right falls with ``f``, so the root is unique.

    Parameters
    ----------
    film : array_like
        Smooth central film thickness of the whole load ``h_s`` [m] (Eq. 56).
    load, ax, ay : array_like
        Normal load [N] and Hertz semi-axes [m].
    asp : Asperities
        The asperity parameters.

    Returns
    -------
    fraction : ndarray
        ``f_a`` [-], 0 where ``h_s / sigma >= LAMBDA_CUTOFF``.
    lam : ndarray
        ``h / sigma`` with ``h = h_s (1 - f_a)^-e`` the film at its share [-].
    """
    lam_s = np.asarray(film, dtype=float) / asp.roughness
    scale = np.broadcast_to(asp.pressure_scale * np.pi * ax * ay / load, lam_s.shape)
    frac = np.zeros(lam_s.shape)
    on = lam_s < LAMBDA_CUTOFF
    if np.any(on):
        frac[on] = solve_share(lam_s[on], scale[on])
    return frac, lam_s * film_factor(1.0 - frac)


@lru_cache(maxsize=16)
def _coulomb_fluid(fluid: Fluid, friction: float, stiffness: float) -> Fluid:
    """Eq. 53 made the regularised Coulomb law of `boundary_coefficients`: limiting shear
    stress ``1 Pa + friction x p`` (the zero intercept kept positive for the kernels'
    logarithms: 1 Pa against ``mu_b p`` of order 1e8 Pa) and a pressure-free viscosity
    ``stiffness`` [Pa s], so that over a film ``h = u_ref`` [m] the Newtonian stress
    ``eta |V| / h`` is ``k s``."""
    return fluid.model_copy(
        update={
            "traction_law": "isothermal",
            "viscosity": stiffness,
            "pole_viscosity": stiffness,  # log(eta_0 / eta_inf) = 0: no pressure growth
            "limiting_shear_stress": 1.0,
            "limiting_shear_slope": friction,
        }
    )


def boundary_coefficients(
    state: ContactState,
    fluid: Fluid,
    friction: float,
    quadrature: Quadrature,
    derivatives: bool,
    stiffness: float = STEEL_CREEP_STIFFNESS,
):
    """Traction and spin coefficients of the asperities' boundary shear, per unit load.

    The asperities shear in Coulomb friction ``mu_b p`` along the local sliding ``V``
    (Eq. 55) once their junctions slip, and elastically before: a junction under a
    boundary film slips when the local slip ``s = |V| / u_ref`` exceeds its tangential
    compliance, not when a viscous film's stress reaches ``mu_b p``. The local law is the
    regularised Coulomb law

        ``tau = mu_b p (1 - exp(-k s / (mu_b p))) V / |V|``,

    linear ``k s`` at small slip with the stiffness ``k = C_11 G / pi`` that gives a
    contact without slip Kalker's linear creep force (`creep_stiffness`; Johnson,
    *Contact Mechanics* (1985) §8.4), and Coulomb's ``mu_b p`` once ``s >> s_c = mu_b p /
    k`` (the local form of the full-slip creep of Carter's and Johnson's rolling contacts,
    Johnson 1985 §8.2-8.4: ``s_c`` 7e-4 at the peak pressure of a 0.76 GPa steel contact,
    ``mu_b`` 0.1; the same exponential saturation as Eq. 53, and the slip-dependent
    friction of a brush model). It does not depend on the film or the rolling speed. So
    ``|mu| -> mu_b`` in sliding (creep >> s_c), and in pure spin the moment tends to a dry
    contact's with the Hertz pressure (for a circle ``(3 pi / 16) mu_b F a``, Johnson 1985
    §8.4). Computed by the kernels of Eq. 53 (`_coulomb_fluid`, film ``h = u_ref``).

    Parameters
    ----------
    state : ContactState
        The contacts (their film is not used).
    fluid : Fluid
        The traction fluid (the kernels' fluid is built from it).
    friction : float
        ``mu_b`` [-].
    quadrature : Quadrature
        The traction law's quadrature.
    derivatives : bool
        Also the derivatives.
    stiffness : float
        ``k`` [Pa] (default: bearing steel's).

    Returns
    -------
    As `ballcvt.model.traction.isothermal.shear_coefficients` (``mu, chi`` and with
    ``derivatives`` their derivatives by ``creep_term``, ``spin``, ``log u_ref``; the last
    zero: the law depends on the slip alone).
    """
    speed = np.maximum(np.asarray(state.u_ref, dtype=float), 1e-30)  # V = 0 where u_ref = 0
    out = shear_coefficients(
        state.replace(film=speed),
        _coulomb_fluid(fluid, friction, stiffness),
        quadrature,
        derivatives,
    )
    if derivatives:
        for g in out[2:]:
            g[..., 2] = 0.0  # d/d log u at fixed u/h, minus the same by log h: 0
    return out


def _mixed_values(state: ContactState, fluid: Fluid, asp: Asperities, q: Quadrature, d: bool,
                  boundary=None):  # fmt: skip
    """``f_a`` and the film and boundary coefficients of the mixed model; ``boundary``: the
    boundary coefficients when known (they depend on the slip alone, not on the film)."""
    frac, _ = load_sharing(state.film, state.load, state.ax, state.ay, asp)
    keep = 1.0 - frac
    film_state = state.replace(
        load=state.load * keep,
        p_max=state.p_max * keep,
        film=state.film * film_factor(keep),
    )
    film = contact_coefficients(film_state, fluid, q, d)
    if boundary is None:
        boundary = boundary_coefficients(
            state, fluid, asp.boundary_friction, boundary_rule(q), d, asp.creep_stiffness
        )
    return frac, film, boundary


def _mixed(state: ContactState, fluid: Fluid, asp: Asperities, q: Quadrature, d: bool,
           boundary=None):  # fmt: skip
    """``mu, chi`` (and derivatives) of the mixed model, without the film-thickness column,
    ``f_a`` and the boundary coefficients (``boundary``: as in `_mixed_values`)."""
    frac, film, boundary = _mixed_values(state, fluid, asp, q, d, boundary)
    keep, wet = 1.0 - frac, frac > 0.0  # where no asperity touches: the film's, exactly
    out = [np.where(wet, keep * a + frac * b, a) for a, b in zip(film[:2], boundary[:2])]
    if d:
        wet_d, keep_d, frac_d = wet[..., None], keep[..., None], frac[..., None]
        out += [
            np.where(wet_d, keep_d * a + frac_d * b, a) for a, b in zip(film[2:], boundary[2:])
        ]
    return tuple(out), frac, boundary


def mixed_coefficients(
    state: ContactState, fluid: Fluid, asp: Asperities, quadrature: Quadrature, derivatives: bool
):
    """``mu, chi`` of the mixed model (module docstring; docs/model.md §16).

    With ``derivatives``, ``dmu``, ``dchi`` have four columns: the creep term, the spin,
    ``log u_ref`` at a fixed film (the law's, weighted by the shares: ``f_a`` depends on the
    film alone) and ``log h_s`` at a fixed ``u_ref / h_s`` (the load sharing's, by a
    difference of step `_STEP`; zero where no asperity touches).
    """
    (mu, chi, *rest), frac, boundary = _mixed(state, fluid, asp, quadrature, derivatives)
    if not derivatives:
        return mu, chi
    dmu, dchi = (np.concatenate([g, np.zeros(g.shape[:-1] + (1,))], axis=-1) for g in rest)
    wet = frac > 0.0
    if np.any(wet):
        rule, base = quadrature, (mu, chi, boundary)
        if _nodes(quadrature) > _nodes(FILM_SHARE_RULE):  # the difference on fewer nodes
            rule = replace(FILM_SHARE_RULE, engine=quadrature.engine)
            (mu_c, chi_c), _, boundary_c = _mixed(state, fluid, asp, rule, False)
            base = (mu_c, chi_c, boundary_c)
        up = state.replace(film=state.film * (1 + _STEP), u_ref=state.u_ref * (1 + _STEP))
        # the boundary law depends on the slip alone, the same at ``up`` (where ``u_ref``
        # moves with the film): only the film's share and coefficients are solved again
        (mu_up, chi_up), _, _ = _mixed(up, fluid, asp, rule, False, base[2][:2])
        dmu[..., 3] = np.where(wet, (mu_up - base[0]) / np.log1p(_STEP), 0.0)
        dchi[..., 3] = np.where(wet, (chi_up - base[1]) / np.log1p(_STEP), 0.0)
    return mu, chi, dmu, dchi


def boundary_rule(q: Quadrature) -> Quadrature:
    """The rule of the boundary shear under the law's rule ``q``: ``q`` with half its
    angular nodes, and no fewer than `BOUNDARY_ANGULAR` (pole-centred rules; ``q`` itself
    otherwise). The boundary integrand (no pressure-viscosity, no sharp viscous ring) has
    converged in angle there: against 64 x 48 x 64 nodes, its ``M`` on 32 x 12 x 32 and on
    the default 32 x 24 x 32 are off by the same 3.5e-6 (hub duty-cycle contacts) and 4e-5
    (the hub's map over ratios 0.5-2); the radial nodes set its error (1.1e-5 on 24
    radial), and 8 angular nodes are 10 times worse (`tests/test_boundary_rule.py`). Its
    error counts with the asperities' share of the load, 0.15 % (median) to 4.4 % on the
    hub. The boundary shear costs about half of a mixed contact's coefficients: halving
    its nodes made the hub's duty cycle some 20 % faster (session 36)."""
    if q.method != "pole" or q.n_angular <= BOUNDARY_ANGULAR:
        return q
    return replace(q, n_angular=max(BOUNDARY_ANGULAR, q.n_angular // 2))


def _nodes(q: Quadrature) -> int:
    """Nodes per contact of the rule ``q`` (of its first fan: pole-centred or centred)."""
    return q.n_radial * q.n_angular


def _full_film(state, fluid, asp, quadrature, derivatives):
    """The fluid's law as it is (the paper's model); with ``derivatives``, the fourth
    column of a law that has one (`TractionLaw.film_coefficients`)."""
    film = TRACTION_LAWS.get(fluid.traction_law).film_coefficients
    if derivatives and film is not None:
        return film(state, fluid, quadrature)
    return contact_coefficients(state, fluid, quadrature, derivatives)


def _no_asperities(film, load, ax, ay, asp):
    """``f_a = 0`` and ``h / sigma`` of the smooth film."""
    lam = np.asarray(film, dtype=float) / asp.roughness
    return np.zeros(lam.shape), lam


@dataclass(frozen=True)
class LubricationModel:
    """A lubrication model: what `LUBRICATION_MODELS` holds for it.

    Parameters
    ----------
    name : str
        The value of ``[design.lubrication] model``.
    coefficients : callable
        ``(state, fluid, asperities, quadrature, derivatives)`` -> ``mu, chi`` and with
        ``derivatives`` ``dmu, dchi`` of 3 columns (as a traction law's) or 4 (a fourth:
        by ``log h_s`` at a fixed ``u_ref / h_s``).
    sharing : callable
        ``(film, load, ax, ay, asperities)`` -> ``f_a, h / sigma`` (reported per contact).
    description : str
        One line, with the model's source.
    """

    name: str
    coefficients: Callable[..., tuple]
    sharing: Callable[..., tuple]
    description: str = ""


LUBRICATION_MODELS.register(
    LubricationModel(
        "full-film", _full_film, _no_asperities, "the paper's: the film carries the whole load"
    )
)
LUBRICATION_MODELS.register(
    LubricationModel(
        "mixed",
        mixed_coefficients,
        load_sharing,
        "film and asperities share the load (Johnson, Greenwood and Poon 1972; Greenwood "
        "and Tripp 1970), boundary friction on the asperities",
    )
)


def lubricated_coefficients(
    state: ContactState,
    fluid: Fluid,
    asp: Asperities,
    quadrature: Quadrature = Quadrature(),
    derivatives: bool = False,
):
    """``mu, chi`` (and derivatives) of contacts under ``asp.model`` and the fluid's law."""
    return LUBRICATION_MODELS.get(asp.model).coefficients(
        state, fluid, asp, quadrature, derivatives
    )
