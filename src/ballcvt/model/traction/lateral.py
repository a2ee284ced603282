"""Traction with side slip: the longitudinal, lateral and spin coefficients (docs/model.md §17).

A lateral creep ``s_lat`` (the lateral sliding speed over ``u_ref``) adds a uniform term to
the transverse sliding of Eq. 55 (docs/model.md §3):

    ``V = u_ref (c - s_y Y, s_lat + s_x X)``, ``s_x = sigma a_x / r_c``, ``s_y = sigma a_y / r_c``,

in the contact frame of Eq. 55 (``x`` the rolling direction of the creep term, ``y`` the
transverse direction that with the spin term makes the frame right-handed). The shear law
is the fluid's, unchanged (Eq. 53; with Maxwell elasticity; or at the heated film
temperature of the thermal law): it is isotropic, the stress along the local sliding, so
a lateral creep is resisted exactly as a longitudinal one of the same size. Then, besides
``mu`` and ``chi`` (Eqs. 57-66), the lateral traction coefficient

    ``mu_y = (a_x a_y / F_N) int tau_y dX dY``   (``F_y = mu_y F_N`` along ``+y``).

The no-sliding point moves off the ``Y`` axis, to ``(X_p, Y_p) = (-s_lat / s_x, c / s_y)``;
the pole-centred rule of `ballcvt.model.traction.quadrature` becomes a fan of rays from
that point (the same rays and radial nodes; with ``s_lat = 0`` the same nodes), blended
with the centred rule as ``|(X_p, Y_p)|`` passes ``BLEND`` (as ``|Y_p|`` does without side
slip). This is the NumPy path only, used only where a lateral creep is asked for: the
solvers' traction (`shear_coefficients` and the compiled kernels) is untouched, so every
result without side slip is bit-for-bit what it was. Creep forces under combined
longitudinal, lateral and spin creep: Johnson (1985, Contact Mechanics, §8.4 and §9.4);
for traction fluids, the same rheology integrated over the Hertz ellipse (Johnson and
Tevaarwerk 1977; Tomaselli et al. 2020, Appendix A).
"""

from __future__ import annotations

import numpy as np

from ...params.models import Fluid
from .contact import ContactState
from .isothermal import ShearLaw, _pole_weight, node_rheology
from .quadrature import Quadrature, centred_rule, radial_rule
from .thermal import _Contacts

__all__ = [
    "lateral_shear_coefficients",
    "thermal_lateral_coefficients",
    "lateral_pole_rule",
    "limiting_traction",
]


def lateral_pole_rule(xp, yp, n_radial: int, n_angular: int):
    """Rays from inside poles ``(xp, yp)`` (1-D arrays, ``xp^2 + yp^2 < 1``) to the boundary.

    The ray in direction ``(cos phi, sin phi)`` reaches the unit circle at
    ``rho = -b + sqrt(b^2 + 1 - |p|^2)``, ``b = xp cos phi + yp sin phi``; nodes
    ``p + rho r_j (cos phi, sin phi)``, weights ``rho^2 r_j w_j dphi`` (polar about ``p``).
    With ``xp = 0`` these are the nodes of
    `ballcvt.model.traction.quadrature.inner_pole_rule`.

    Returns
    -------
    X, Y, W : ndarray
        Shape ``(xp.size, n_radial * n_angular)`` [-].
    """
    r01, wr = radial_rule(n_radial)
    phi = 2.0 * np.pi * np.arange(n_angular) / n_angular
    sp, cp = np.sin(phi), np.cos(phi)
    xp, yp = xp[:, None], yp[:, None]
    b = xp * cp + yp * sp
    reach = -b + np.sqrt(np.maximum(b * b + (1.0 - xp * xp - yp * yp), 0.0))
    rho = reach[:, None, :] * r01[None, :, None]  # (m, n_r, n_a)
    x = xp[:, None] + rho * cp
    y = yp[:, None] + rho * sp
    w = rho * reach[:, None, :] * wr[None, :, None] * (2.0 * np.pi / n_angular)
    m = xp.shape[0]
    return x.reshape(m, -1), y.reshape(m, -1), w.reshape(m, -1)


def _pole(params, lateral):
    """``(X_p, Y_p)`` of the no-sliding point; ``inf`` where the spin vanishes [-]."""
    c, sg, ax, ay, rc = params[0], params[1], params[2], params[3], params[6]
    sx, sy = sg * ax / rc, sg * ay / rc
    spin = np.abs(sy) > 1e-300
    xp = np.divide(-lateral, sx, out=np.full(c.shape, np.inf), where=spin)
    yp = np.divide(c, sy, out=np.full(c.shape, np.inf), where=spin)
    return xp, yp


def lateral_shear_coefficients(
    state: ContactState,
    fluid: Fluid,
    lateral,
    quadrature: Quadrature = Quadrature(),
    law: ShearLaw = ShearLaw(),
    entry=1.0,
):
    """``mu``, ``mu_y`` and ``chi`` of contacts with a lateral creep (module docstring).

    Parameters
    ----------
    state : ContactState
        The contacts (``creep_term`` [-], ``spin`` [-], ``ax, ay`` [m], ``p_max`` [Pa],
        ``load`` [N], ``radius`` [m], ``u_ref`` [m/s], ``film`` [m]).
    fluid : Fluid
        Traction fluid (Roelands and limiting-shear parameters, Eqs. 51, 54).
    lateral : array_like
        Lateral creep ``s_lat``: lateral sliding speed over ``u_ref`` [-], broadcast with
        the state's arrays.
    quadrature : Quadrature
        Rule and node counts (the pole-centred rule's rays start at the moved pole).
    law : ShearLaw
        The node-local shear law: Eq. 53 by default; ``ShearLaw(modulus=G)`` for the
        visco-elastic law (docs/model.md §14).
    entry : array_like
        Direction of the rolling along ``x`` [-]: +1, the surfaces move along ``+x`` and
        enter at ``X = -1`` (the solvers' Maxwell law assumes it at every contact, where
        ``mu`` and ``chi`` do not depend on it); -1, they enter at ``X = +1``. Only the
        Maxwell film's ``mu_y`` depends on it.

    Returns
    -------
    mu, mu_y, chi : ndarray
        Longitudinal (Eq. 30) and lateral traction coefficients and the spin-moment
        coefficient (Eq. 31) [-], of the broadcast shape. ``mu_y`` is odd in ``s_lat``
        under the rigid-plastic laws (and zero at ``s_lat = 0``); the Maxwell film's
        entry memory breaks the ``X -> -X`` symmetry, so a spinning visco-elastic contact
        has a small ``mu_y`` at zero side slip.
    """
    shape = np.broadcast_shapes(state.shape, np.shape(lateral))
    params = np.empty((9,) + shape)
    for i, value in enumerate(state):
        params[i, ...] = value
    params = params.reshape(9, -1)
    lat = np.broadcast_to(np.asarray(lateral, dtype=float), shape).ravel()
    side = np.broadcast_to(np.asarray(entry, dtype=float), shape).ravel()
    out = np.zeros((3, lat.size))
    xp, yp = _pole(params, lat)
    q = quadrature
    weight = np.zeros(lat.size) if q.method == "centred" else _pole_weight(np.hypot(xp, yp))
    n_centred = q.n_angular if q.method == "centred" else q.n_centred
    parts = [(weight > 0.0, weight, "pole"), (~(weight >= 1.0), 1.0 - weight, "centred")]
    for part, rule_weight, kind in parts:
        if part.any():
            nodes = (
                lateral_pole_rule(xp[part], yp[part], q.n_radial, q.n_angular)
                if kind == "pole"
                else centred_rule(q.n_radial, n_centred, (int(part.sum()),))
            )
            values = _integrate(nodes, params[:, part], (lat[part], side[part]), fluid, law)
            out[:, part] += rule_weight[part] * np.stack(values)
    return tuple(v.reshape(shape) for v in out)


def _integrate(nodes, params, slip, fluid: Fluid, law: ShearLaw):
    """``mu, mu_y, chi`` of flat contacts on the given nodes (Eqs. 53, 57-66 with the
    lateral creep), the integrand of `ballcvt.model.traction.isothermal._integrate`;
    ``slip``: the lateral creeps and the rolling directions (``entry``)."""
    x, y, w = nodes
    lateral, entry = slip
    c, sg, ax, ay, pm, fn, rc, u, h = params
    ex = lambda v: v[..., None]  # noqa: E731  (broadcast over the nodes)
    eta, tau_l = node_rheology(pm, x, y, fluid)
    vx = ex(u) * (ex(c) - ex(sg * ay / rc) * y)
    vy = ex(u) * (ex(lateral) + ex(sg * ax / rc) * x)
    arg = eta * np.hypot(vx, vy) / (ex(h) * tau_l)
    g = eta / ex(h) * law.factor(arg)  # tau = g V
    if law.modulus > 0.0:  # Maxwell elasticity (docs/model.md §14)
        t_in = ex(ax) * (ex(entry) * x + np.sqrt(np.maximum(1.0 - y * y, 0.0))) / ex(u)
        g = g * -np.expm1(-law.modulus * t_in / (ex(h) * g))
    area = ax * ay
    tx, ty = g * vx, g * vy
    return (
        area / fn * np.sum(w * tx, axis=-1),
        area / fn * np.sum(w * ty, axis=-1),
        area / (fn * rc) * np.sum(w * (ex(ax) * x * ty - ex(ay) * y * tx), axis=-1),
    )


def limiting_traction(state: ContactState, fluid: Fluid):
    """The largest resultant traction coefficient the film can carry [-].

    ``|(mu, mu_y)| <= (1/F_N) int tau_L dA = pi a_x a_y (tau_L0 + (2/3) a p_max) / F_N``
    (Eq. 54 over the Hertz pressure of Eq. 50, whose mean is ``(2/3) p_max``): every node
    at its limiting shear stress, all in one direction (Eq. 53 never exceeds ``tau_L``).
    The thermal law's warmer film carries less (``exp(-beta_L dT)``).
    """
    ax, ay = np.asarray(state.ax), np.asarray(state.ay)
    tau_mean = fluid.limiting_shear_stress + 2.0 / 3.0 * fluid.limiting_shear_slope * np.asarray(
        state.p_max
    )
    return np.pi * ax * ay * tau_mean / np.asarray(state.load)


def thermal_lateral_coefficients(
    state: ContactState, fluid: Fluid, lateral, quadrature: Quadrature = Quadrature(), entry=1.0
):
    """``mu``, ``mu_y``, ``chi`` [-] under the thermal law with a lateral creep.

    The film runs at ``T_in + dT`` (`ballcvt.model.traction.thermal`): the isothermal
    coefficients at the film ``h exp((beta - beta_L) dT)`` times ``exp(-beta_L dT)``, with
    ``dT = (R_flash + R_film) q`` and the shear heat now including the lateral sliding,
    ``q = F_N u (c mu + s_lat mu_y + sigma chi) / (pi a_x a_y)`` (the integral of
    ``tau . V``). ``dT`` is found by the Illinois false-position method in the bracket
    ``[0, R q(0)]`` (the heat falls as the film warms). Parameters as in
    `lateral_shear_coefficients`.
    """
    values = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (*state, lateral, entry)))
    shape = values[0].shape
    flat = [v.ravel() for v in values]
    con = _Contacts(flat[:9], fluid)
    lat, side = flat[9], flat[10]
    fl_state = ContactState(*flat[:9])

    def at(dt):
        f_t = np.exp(-con.beta_l * dt)
        got = lateral_shear_coefficients(
            fl_state.replace(film=con.h * np.exp(con.b * dt)),
            fluid,
            lat,
            quadrature,
            entry=side,
        )
        return tuple(f_t * v for v in got)

    def excess(dt):  # dT - R q(dT), and the coefficients there
        mu, mu_y, chi = at(dt)
        q = con.load_flux * con.u * (con.c * mu + lat * mu_y + con.s * chi)
        return dt - con.resistance * q, (mu, mu_y, chi)

    g_lo, got = excess(np.zeros(lat.size))
    lo, hi = np.zeros(lat.size), -g_lo
    g_hi, _ = excess(hi)
    for _ in range(60):
        span = g_hi - g_lo
        dt = np.where(span > 0.0, lo - g_lo * (hi - lo) / np.where(span > 0.0, span, 1.0), lo)
        g, got = excess(dt)
        left = g < 0.0
        lo, g_lo, g_hi = (
            np.where(left, dt, lo),
            np.where(left, g, g_lo),
            np.where(left, 0.5 * g_hi, g),
        )
        hi = np.where(left, hi, dt)
        g_lo = np.where(left, g_lo, 0.5 * g_lo)
        if np.all(np.abs(g) <= 1e-6 * (1.0 + dt)):
            break
    return tuple(v.reshape(shape) for v in got)
