"""Traction and spin coefficients by quadrature over the contact ellipse (Eqs. 53-66).

With ``X = x / a_x``, ``Y = y / a_y`` on the unit disc, the local sliding speed of the body
over the ball (Eq. 55, docs/model.md §3) is

    ``V = u_ref (c - s_y Y, s_x X)``, ``s_x = sigma a_x / r_c``, ``s_y = sigma a_y / r_c``,

with ``u_ref = |Omega_c| r_c`` and ``c`` the creep term (`creep_term`). The shear stress is
``tau = tau_L (1 - exp(-eta |V| / (h tau_L))) V / |V|`` (Eq. 53), with the Hertz pressure
``p = p_max sqrt(1 - X^2 - Y^2)`` in the Roelands viscosity and the limiting shear stress.
Then (Eqs. 57-66, lever arms with their semi-axes, docs/model.md §3)

    ``mu = (a_x a_y / F_N) int tau_x dX dY``,
    ``chi = (a_x a_y / (F_N r_c)) int (a_x X tau_y - a_y Y tau_x) dX dY``.

``mu`` has the sign of the creep and ``chi`` the sign of the spin.
"""

from __future__ import annotations

import math
import threading
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from typing import NamedTuple

import numpy as np

from ...params.models import Fluid
from ..rheology import (
    limiting_shear_stress,
    roelands_viscosity,
    saturation_factor,
    saturation_slope,
)
from . import kernels
from .contact import ContactState, contact_coefficients, legacy_arguments
from .quadrature import Quadrature, centred_rule, inner_pole_rule, radial_rule

__all__ = [
    "ShearLaw",
    "pole_position",
    "shear_coefficients",
    "shear_law_coefficients",
    "traction_coefficients",
]


@dataclass(frozen=True)
class ShearLaw:
    """A node-local shear law ``tau = (eta / h) S(a) V`` with ``a = eta |V| / (h tau_L)``.

    Eq. 53 is ``S(a) = (1 - exp(-a)) / a`` (the default); any law whose stress is the
    limiting shear stress times a function of ``a`` is another ``S`` (``S(0) = 1``: the
    Newtonian limit). ``eta`` is the Roelands viscosity (Eq. 51), ``tau_L`` the limiting
    shear stress (Eq. 54), both at the node's Hertz pressure.

    Parameters
    ----------
    factor : callable
        ``S(a)`` of an array ``a >= 0`` [-].
    slope : callable
        ``dS/da`` of ``(a, S(a))`` [-] (for Newton's Jacobians).
    modulus : float
        Shear modulus ``G`` of a visco-elastic (Maxwell) film [Pa]; 0: none.
    """

    factor: Callable = saturation_factor
    slope: Callable = saturation_slope
    modulus: float = 0.0


def pole_position(creep_term, spin, ay, radius):
    """``Y`` of the no-sliding point ``(0, Y_p)``: ``Y_p = c r_c / (sigma a_y)`` [-].

    ``inf`` where the spin vanishes (the sliding field is then uniform).
    """
    c = np.asarray(creep_term, dtype=float)
    sy = np.asarray(spin, dtype=float) * np.asarray(ay) / np.asarray(radius)
    if c.shape != sy.shape:
        c, sy = np.broadcast_arrays(c, sy)
    return np.divide(c, sy, out=np.full(c.shape, np.inf), where=np.abs(sy) > 1e-300)


def shear_coefficients(
    state: ContactState,
    fluid: Fluid,
    quadrature: Quadrature = Quadrature(),
    derivatives: bool = False,
    modulus: float = 0.0,
):
    """Traction coefficient ``mu`` and spin-moment coefficient ``chi`` of contacts.

    The shear law is node-local: the isothermal law of Eq. 53 or, with a film shear
    ``modulus`` > 0, that law with Maxwell elasticity (docs/model.md §14). The thermal law
    wraps this function (`ballcvt.model.traction.thermal`);
    `ballcvt.model.traction.contact.contact_coefficients` dispatches to the fluid's law.

    Parameters
    ----------
    state : ContactState
        The contacts; their arrays broadcast together to the shape ``(...)`` of the result.
    fluid : Fluid
        Traction fluid (Roelands and limiting-shear parameters, Eqs. 51, 54).
    quadrature : Quadrature
        Rule and node counts (see `ballcvt.model.traction.quadrature`).
    derivatives : bool
        Also return the derivatives of ``mu`` and ``chi``, computed in the same pass.
    modulus : float
        Shear modulus ``G`` of a visco-elastic film [Pa]; 0: rigid-plastic (Eq. 53).

    Returns
    -------
    mu, chi : ndarray
        Traction coefficient (Eq. 30) and spin-moment coefficient (Eq. 31) [-].
    dmu, dchi : ndarray
        Only with ``derivatives``: shape ``(..., 3)``, the derivatives with respect to
        ``creep_term`` [-], ``spin`` [-] and ``log(u_ref)`` [-]. The shear law depends on
        the sliding speed over the film thickness only, so the derivative with respect to
        ``log(film)`` is minus the last one. The motion of the nodes with the pole is not
        differentiated (it changes the result only by the discretisation error), nor is the
        blend weight: these are Jacobians for Newton's method, not exact gradients.
    """
    params, shape = state.stacked()
    n_out = 8 if derivatives else 2
    if params.shape[1] == 0:
        out = np.zeros((n_out, 0))
    elif quadrature.engine == "auto" and kernels.AVAILABLE:
        out = _compiled(params, fluid, quadrature, derivatives, modulus)[:n_out]
    else:
        out = _numpy_rules(params, fluid, quadrature, derivatives, ShearLaw(modulus=modulus))
    return _shaped(out[:n_out], shape, derivatives)


def shear_law_coefficients(
    state: ContactState,
    fluid: Fluid,
    law: ShearLaw,
    quadrature: Quadrature = Quadrature(),
    derivatives: bool = False,
):
    """``mu, chi`` (and their derivatives) of contacts under the shear law ``law``.

    The same quadrature as `shear_coefficients` (the NumPy path, any `ShearLaw`); for a
    traction law defined outside the package (examples/extending/traction_law.py).
    Parameters and returns as in `shear_coefficients`.
    """
    params, shape = state.stacked()
    n_out = 8 if derivatives else 2
    out = np.zeros((n_out, 0))
    if params.shape[1]:
        out = _numpy_rules(params, fluid, quadrature, derivatives, law)[:n_out]
    return _shaped(out, shape, derivatives)


def _shaped(out, shape, derivatives: bool):
    """The sums ``(2 or 8, n)`` as ``mu, chi`` (and ``dmu, dchi``) of shape ``shape``."""
    if not derivatives:
        return out[0].reshape(shape), out[1].reshape(shape)
    out = out.reshape((out.shape[0],) + shape)
    last = tuple(range(1, len(shape) + 1)) + (0,)  # the derivatives' axis last
    return out[0], out[1], out[2:5].transpose(last), out[5:8].transpose(last)


def traction_coefficients(*args, **kwargs):
    """Deprecated: ``traction_coefficients(creep_term, spin, ax, ay, p_max, load, radius,
    u_ref, film, fluid, quadrature, derivatives)`` is
    `ballcvt.model.traction.contact.contact_coefficients` of a `ContactState` (the fluid's
    law, as before for the isothermal and visco-elastic laws)."""
    state, rest, kw = legacy_arguments(
        "traction_coefficients(creep_term, ..., film, fluid)",
        "contact_coefficients(ContactState(creep_term, ..., film), fluid)",
        args,
        kwargs,
    )
    return contact_coefficients(state, *rest, **kw)


def _compiled(params, fluid: Fluid, q: Quadrature, derivatives: bool, modulus: float):
    """The compiled kernels' sums ``(8, n)``: both rules and their blend in one call."""
    out = np.empty((params.shape[1], kernels.N_OUT))
    par = np.ascontiguousarray(params)
    table = kernel_table(fluid, float(par[4].max()), modulus)
    kernels.traction_kernel(par, kernel_rule(q), table, derivatives, out)
    return out.T


@lru_cache(maxsize=16)
def kernel_rule(q: Quadrature) -> tuple:
    """The rule ``q`` as the compiled kernels take it: ``(r01, wr, pole_rays,
    centred_rays, blend)`` (`ballcvt.model.traction.kernels.traction_kernel`; cached: the
    rules are frozen, their arrays read-only)."""
    r01, wr, sin_phi, cos_phi = _ray_nodes(q.n_radial, q.n_angular)
    rays = (sin_phi, cos_phi, 2.0 * np.pi / q.n_angular)
    if q.method == "centred":
        centred, blend = rays, (0.0, 0.0)
    else:
        _, _, sin_c, cos_c = _ray_nodes(q.n_radial, q.n_centred)
        centred, blend = (sin_c, cos_c, 2.0 * np.pi / q.n_centred), BLEND
    return r01, wr, rays, centred, blend


def kernel_table(fluid: Fluid, p_max: float, modulus: float = 0.0) -> tuple:
    """The viscosity table ``(fl, tab)`` the compiled kernels use for contacts up to
    ``p_max`` [Pa] (`table_pressure`; cached)."""
    return _viscosity_table(fluid, table_pressure(p_max), modulus)


def node_rheology(p_max, x, y, fluid: Fluid):
    """Roelands viscosity [Pa s] and limiting shear stress [Pa] at quadrature nodes.

    Parameters
    ----------
    p_max : ndarray
        Hertz peak pressure of each contact ``(m,)`` [Pa].
    x, y : ndarray
        Node coordinates on the unit disc ``X = x / a_x``, ``Y = y / a_y`` [-].
    fluid : Fluid
        Traction fluid.

    Returns
    -------
    eta, tau_l : ndarray
        At the node's Hertz pressure ``p_max sqrt(1 - X^2 - Y^2)`` (Eq. 50): Eq. 51 and
        Eq. 54, shape ``(m, nodes)``.
    """
    p = p_max[..., None] * np.sqrt(np.maximum(1.0 - x * x - y * y, 0.0))
    eta = roelands_viscosity(
        p, fluid.viscosity, fluid.pole_viscosity, fluid.pole_pressure, fluid.roelands_index
    )
    return eta, limiting_shear_stress(p, fluid.limiting_shear_stress, fluid.limiting_shear_slope)


def _numpy_rules(params, fluid: Fluid, q: Quadrature, derivatives: bool, law: ShearLaw):
    """The NumPy reference path's sums ``(8 or 2, n)``: each rule on its contacts, blended
    (the same sums as `_compiled`)."""
    yp = pole_position(params[0], params[1], params[3], params[6])
    if q.method == "centred":
        parts = [(np.ones(yp.shape, bool), np.ones(yp.shape), "centred", q.n_angular)]
    else:
        # Pole-centred rule while the pole is well inside, centred rule once it is
        # outside, blended in between so that mu and chi stay continuous (C1) in the creep.
        weight = _pole_weight(np.abs(yp))
        parts = [
            (weight > 0.0, weight, "pole", q.n_angular),
            (~(weight >= 1.0), 1.0 - weight, "centred", q.n_centred),  # NaN: NaN out
        ]
    out = np.zeros((8 if derivatives else 2, yp.size))
    for part, rule_weight, kind, n_angular in parts:
        if part.any():
            y, p = yp[part], params[:, part]
            nodes = (
                inner_pole_rule(y, q.n_radial, n_angular)
                if kind == "pole"
                else centred_rule(q.n_radial, n_angular, y.shape)
            )
            values = _integrate(nodes, list(p), fluid, derivatives, law)
            if derivatives:
                values = np.concatenate([np.stack(values[:2]), values[2].T, values[3].T])
            out[:, part] += rule_weight[part] * np.stack(values)
    return out


#: Pressure up to which every viscosity table reaches [Pa]: above any rolling contact's
#: (bearing steels fail near 4-5 GPa), so that the table, and with it every interpolated
#: viscosity, does not depend on which other contacts share a batch.
TABLE_PRESSURE = 2.0e10


def table_pressure(p_max: float) -> float:
    """The top of the viscosity table for contacts up to ``p_max`` [Pa]: `TABLE_PRESSURE`,
    or that doubled as often as needed to cover ``p_max``.

    A table over the batch's own largest pressure would interpolate each contact's
    viscosity slightly differently (about 1e-11 relative) in different batches; a
    Newton tolerance of 1e-11 then converges a point near the fold of a branch (the
    thermal law) in one batch and not in another, and a limit search gave answers a few
    per cent apart for the same point. With a fixed table a point's answer is the same
    in every batch.
    """
    if not p_max > TABLE_PRESSURE:  # NaN too: the kernels return NaN for it anyway
        return TABLE_PRESSURE
    return TABLE_PRESSURE * 2.0 ** math.ceil(math.log2(p_max / TABLE_PRESSURE))


class TableFluid(NamedTuple):
    """The values of a fluid its viscosity table depends on (Eqs. 51, 54): the table
    cache's key, and the fluid `kernels.viscosity_table` reads."""

    viscosity: float
    pole_viscosity: float
    roelands_index: float
    pole_pressure: float
    limiting_shear_stress: float
    limiting_shear_slope: float

    @classmethod
    def of(cls, fluid: Fluid) -> TableFluid:
        """The fluid's values; where its viscosity does not grow with the pressure
        (``eta_0 = eta_inf``: the asperities' boundary law, `ballcvt.model.lubrication`)
        the Roelands index and pole pressure multiply a zero in the table and are keyed
        as 1, so that fluids differing only there (the same oil at two temperatures)
        share one table, the same to the bit."""
        z, cp = float(fluid.roelands_index), float(fluid.pole_pressure)
        if fluid.viscosity == fluid.pole_viscosity:
            z, cp = 1.0, 1.0
        return cls(
            float(fluid.viscosity), float(fluid.pole_viscosity), z, cp,
            float(fluid.limiting_shear_stress), float(fluid.limiting_shear_slope),
        )  # fmt: skip


#: Bytes the cached viscosity tables may hold together (`_viscosity_table`): a table is
#: 0.4 MB for a traction fluid, up to 16 MB for the boundary law's; an oil balance or an
#: uncertainty run meets hundreds of oil temperatures, each a fluid.
TABLE_CACHE_BYTES = 256 * 2**20
_tables: OrderedDict = OrderedDict()
_tables_lock = threading.Lock()


def _viscosity_table(fluid: Fluid, p_max: float, modulus: float):
    """`kernels.viscosity_table`, kept for the iterations of a solve and for the other
    solves at the same fluid values and pressure range (the same table, so caching
    changes no result); the least recently used dropped beyond `TABLE_CACHE_BYTES`."""
    key = (TableFluid.of(fluid), p_max, modulus)
    with _tables_lock:
        got = _tables.get(key)
        if got is not None:
            _tables.move_to_end(key)
            return got
    got = kernels.viscosity_table(key[0], p_max, modulus=modulus)
    with _tables_lock:
        _tables[key] = got
        size = sum(t[1].nbytes for t in _tables.values())
        while size > TABLE_CACHE_BYTES and len(_tables) > 1:
            size -= _tables.popitem(last=False)[1][1].nbytes
    return got


#: Width [nodes] of the compiled kernels' vector loop over a ray (8 doubles: one AVX-512
#: register, two AVX2 ones); `_ray_nodes` pads a ray's nodes to a multiple of it.
VECTOR_NODES = 8


@lru_cache(maxsize=16)
def _ray_nodes(n_radial, n_angular):
    """Radial nodes and weights, sines and cosines of the ray angles (read-only): the
    rays of both rules (`ballcvt.model.traction.quadrature`).

    The radial nodes are padded with copies of the last node at zero weight up to a
    multiple of `VECTOR_NODES` when that adds at least 3 (the kernels' ray loop runs
    ``VECTOR_NODES`` nodes per vector instruction and the rest one by one, each costing
    about half a whole vector: the predictor's 12 radial nodes, 8 + 4, took 3.1 ms on
    1,960 contacts where 16 took 2.4, session 23). A padded node adds exactly zero to
    every sum (its weight is zero and its values are those of a real node, finite where
    that node's are), so the sums change only by the order of the additions (round-off).
    """
    r01, wr = radial_rule(n_radial)
    pad = -n_radial % VECTOR_NODES
    if pad >= 3:
        r01 = np.concatenate([r01, np.full(pad, r01[-1])])
        wr = np.concatenate([wr, np.zeros(pad)])
    phi = 2.0 * np.pi * np.arange(n_angular) / n_angular
    return r01, wr, np.sin(phi), np.cos(phi)


#: Range of |Y_p| over which the pole-centred rule hands over to the centred rule.
BLEND = (0.8, 1.0)


def _pole_weight(abs_yp):
    """Weight of the pole-centred rule: 1 below ``BLEND[0]``, 0 from ``BLEND[1]`` (C1)."""
    t = (BLEND[1] - abs_yp) / (BLEND[1] - BLEND[0])
    np.maximum(t, 0.0, out=t)  # (np.clip's wrapper costs more than the two ufuncs)
    np.minimum(t, 1.0, out=t)
    return t * t * (3.0 - 2.0 * t)


def _integrate(nodes, params, fluid: Fluid, derivatives: bool, law: ShearLaw):
    """Quadrature of Eqs. 57-66 for flat parameter arrays on the given nodes.

    Returns ``mu, chi`` and, with ``derivatives``, ``dmu, dchi`` of shape ``(m, 3)``
    (see `shear_coefficients`) under the node-local shear law ``law``.
    """
    x, y, w = nodes
    c, sg, ax, ay, pm, fn, rc, u, h = params
    ex = lambda v: v[..., None]  # noqa: E731  (broadcast over the nodes)
    eta, tau_l = node_rheology(pm, x, y, fluid)
    vx = ex(u) * (ex(c) - ex(sg * ay / rc) * y)
    vy = ex(u * sg * ax / rc) * x
    speed = np.hypot(vx, vy)
    arg = eta * speed / (ex(h) * tau_l)
    sat = law.factor(arg)
    g = eta / ex(h) * sat  # tau = g V
    corr, lin_extra = 1.0, 0.0
    if law.modulus > 0.0:  # Maxwell elasticity (§14)
        t_in = ex(ax) * (x + np.sqrt(np.maximum(1.0 - y * y, 0.0))) / ex(u)
        theta = law.modulus * t_in / (ex(h) * g)
        em = np.exp(-theta)
        f = -np.expm1(-theta)
        corr, lin_extra = f - theta * em, -g * theta * em
        g = g * f
    area = ax * ay
    wx, wy = w * ex(ax) * x, w * ex(ay) * y  # lever-arm weights of chi

    def moments(tx, ty):
        return (
            area / fn * np.sum(w * tx, axis=-1),
            area / (fn * rc) * np.sum(wx * ty - wy * tx, axis=-1),
        )

    mu, chi = moments(g * vx, g * vy)
    if not derivatives:
        return mu, chi
    # d tau = g dV + (dg/d|V|) (V.dV / |V|) V; k = (dg/d|V|) / |V| stays finite times V.V
    k = (eta / ex(h)) ** 2 / tau_l * law.slope(arg, sat)
    k = np.divide(k, speed, out=np.zeros_like(k), where=speed > 0.0) * corr
    dvx_s, dvy_s = -ex(u * ay / rc) * y, ex(u * ax / rc) * x  # dV / d sigma
    d_c = moments(g * ex(u) + k * vx * ex(u) * vx, k * vx * ex(u) * vy)
    dot_s = vx * dvx_s + vy * dvy_s
    d_s = moments(g * dvx_s + k * dot_s * vx, g * dvy_s + k * dot_s * vy)
    lin = g + k * speed * speed + lin_extra  # dV / d log u = V
    d_u = moments(lin * vx, lin * vy)
    return (
        mu,
        chi,
        np.stack([d_c[0], d_s[0], d_u[0]], axis=-1),
        np.stack([d_c[1], d_s[1], d_u[1]], axis=-1),
    )
