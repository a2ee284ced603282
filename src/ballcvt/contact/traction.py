"""Traction and spin coefficients by quadrature over the contact ellipse (Eqs. 53-66).

With ``X = x / a_x``, ``Y = y / a_y`` on the unit disc, the local sliding speed of the body
over the ball (Eq. 55, MODEL.md section 3) is

    ``V = u_ref (c - s_y Y, s_x X)``, ``s_x = sigma a_x / r_c``, ``s_y = sigma a_y / r_c``,

with ``u_ref = |Omega_c| r_c`` and ``c`` the creep term (`creep_term`). The shear stress is
``tau = tau_L (1 - exp(-eta |V| / (h tau_L))) V / |V|`` (Eq. 53), with the Hertz pressure
``p = p_max sqrt(1 - X^2 - Y^2)`` in the Roelands viscosity and the limiting shear stress.
Then (Eqs. 57-66, lever arms with their semi-axes, MODEL.md section 3)

    ``mu = (a_x a_y / F_N) int tau_x dX dY``,
    ``chi = (a_x a_y / (F_N r_c)) int (a_x X tau_y - a_y Y tau_x) dX dY``.

``mu`` has the sign of the creep and ``chi`` the sign of the spin.
"""

from __future__ import annotations

import numpy as np

from ..params.models import Fluid
from .quadrature import Quadrature, centred_rule, inner_pole_rule
from .rheology import limiting_shear_stress, roelands_viscosity, saturation_factor

__all__ = ["pole_position", "traction_coefficients"]


def pole_position(creep_term, spin, ay, radius):
    """``Y`` of the no-sliding point ``(0, Y_p)``: ``Y_p = c r_c / (sigma a_y)`` [-].

    ``inf`` where the spin vanishes (the sliding field is then uniform).
    """
    c = np.asarray(creep_term, dtype=float)
    sy = np.asarray(spin, dtype=float) * np.asarray(ay) / np.asarray(radius)
    with np.errstate(divide="ignore", invalid="ignore"):
        yp = c / sy
    return np.where(np.abs(sy) > 1e-300, yp, np.inf)


def traction_coefficients(creep_term, spin, ax, ay, p_max, load, radius, u_ref, film,
                          fluid: Fluid, quadrature: Quadrature = Quadrature()):
    """Traction coefficient ``mu`` and spin-moment coefficient ``chi`` of contacts.

    All array arguments broadcast together to the shape ``(...)`` of the result.

    Parameters
    ----------
    creep_term : array_like
        Gross sliding over ``u_ref``: ``C_0`` at the input, ``C/(1-C)`` elsewhere [-].
    spin : array_like
        Spin coefficient ``sigma`` (Eqs. 11-14) [-].
    ax, ay : array_like
        Hertz semi-axes along rolling and transverse directions [m].
    p_max : array_like
        Hertz peak pressure [Pa].
    load : array_like
        Normal load ``F_N`` [N].
    radius : array_like
        Radial position of the contact ``r_c`` [m].
    u_ref : array_like
        Body surface speed ``|Omega_c| r_c`` [m/s].
    film : array_like
        Central film thickness ``h`` [m].
    fluid : Fluid
        Traction fluid.
    quadrature : Quadrature
        Rule and node counts (see `ballcvt.contact.quadrature`).

    Returns
    -------
    mu, chi : ndarray
        Traction coefficient (Eq. 30) and spin-moment coefficient (Eq. 31) [-].
    """
    args = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in
                                 (creep_term, spin, ax, ay, p_max, load, radius, u_ref, film)))
    shape = args[0].shape
    flat = [a.ravel() for a in args]
    yp = pole_position(flat[0], flat[1], flat[3], flat[6])
    q = quadrature
    if q.method == "centred":
        mu, chi = _integrate(centred_rule(q.n_radial, q.n_angular, yp.shape), flat, fluid)
        return mu.reshape(shape), chi.reshape(shape)
    # Pole-centred rule while the pole is well inside, centred rule once it is outside,
    # blended in between so that mu and chi stay continuous (C1) in the creep.
    weight = _pole_weight(np.abs(yp))
    mu = np.zeros(yp.shape)
    chi = np.zeros(yp.shape)
    for part, rule_weight, rule in (
            (weight > 0.0, weight, lambda y: inner_pole_rule(y, q.n_radial, q.n_angular)),
            (weight < 1.0, 1.0 - weight,
             lambda y: centred_rule(q.n_radial, q.n_centred, y.shape))):
        if part.any():
            m, c = _integrate(rule(yp[part]), [a[part] for a in flat], fluid)
            mu[part] += rule_weight[part] * m
            chi[part] += rule_weight[part] * c
    return mu.reshape(shape), chi.reshape(shape)


#: Range of |Y_p| over which the pole-centred rule hands over to the centred rule.
BLEND = (0.8, 1.0)


def _pole_weight(abs_yp):
    """Weight of the pole-centred rule: 1 below ``BLEND[0]``, 0 from ``BLEND[1]`` (C1)."""
    t = np.clip((BLEND[1] - abs_yp) / (BLEND[1] - BLEND[0]), 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


def _integrate(nodes, params, fluid: Fluid):
    """Quadrature of Eqs. 57-66 for flat parameter arrays on the given nodes."""
    x, y, w = nodes
    c, sg, ax, ay, pm, fn, rc, u, h = params
    ex = lambda v: v[..., None]  # noqa: E731  (broadcast over the nodes)
    p = ex(pm) * np.sqrt(np.maximum(1.0 - x * x - y * y, 0.0))
    eta = roelands_viscosity(p, fluid.viscosity, fluid.pole_viscosity, fluid.pole_pressure,
                             fluid.roelands_index)
    tau_l = limiting_shear_stress(p, fluid.limiting_shear_stress, fluid.limiting_shear_slope)
    vx = ex(u) * (ex(c) - ex(sg * ay / rc) * y)
    vy = ex(u * sg * ax / rc) * x
    g = eta / ex(h) * saturation_factor(eta * np.hypot(vx, vy) / (ex(h) * tau_l))
    tx = g * vx
    ty = g * vy
    area = ax * ay
    mu = area / fn * np.sum(w * tx, axis=-1)
    chi = area / (fn * rc) * np.sum(w * (ex(ax) * x * ty - ex(ay) * y * tx), axis=-1)
    return mu, chi
