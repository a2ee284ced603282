"""Compiled (numba) twin of the residual's arithmetic around the traction law (session 25).

`ballcvt.equilibrium.residual.evaluate_with_jacobian` perturbs every creep at once along an
extra batch axis and evaluates the cheap rest of the residual (speeds, spins, films, the
balances and bearings) on those ``1 + n_c`` rows with NumPy: some eighty array operations
of about a microsecond each, three quarters of an evaluation of one point and a tenth of
one of three hundred (the traction kernels do the rest). These two kernels do the same
arithmetic in loops, in the same order, so that they give the NumPy path's numbers to
the last bit or nearly (tests compare them); the NumPy path stays the reference, and the
one for the problems these kernels do not cover (`covers`): a batch of other than one
dimension. Since session 38 they also take the planetary modes' problems (docs/model.md
§13): a torque condition ``a T_0 + b T_2`` other than the output torque's, and the balls'
gyroscopic moment on the axle bearings (a mode's evaluation with the Jacobian: 154 -> 61
us for one point, 429 -> 316 us for ten).

`contact_rows` gives the contact inputs of every row (Eqs. 7-14, 55, 56); the traction
law is then evaluated at row 0 by the caller, in Python (any registered law); `balance_rows`
linearises it over the rows and closes the balances (Eqs. 15-27 and the corrected
Eq. 18/33, `ballcvt.equilibrium.residual`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from ..model.bearings import load_torque_constants, speed_torque_constants
from ..model.film import SPEED_EXPONENT
from ..model.losses import STICK_SPEED
from ..model.lubrication import lubricated_coefficients
from ..model.traction.contact import ContactState

njit: Any
try:
    from numba import njit
except ImportError:  # pragma: no cover - numba is a declared dependency
    njit = None

__all__ = ["AVAILABLE", "covers", "evaluate_rows", "contact_rows", "balance_rows", "jacobian_rows"]

AVAILABLE = njit is not None


def covers(problem, constants: dict) -> bool:
    """Whether the kernels compute ``problem``'s residual (module docstring): a 1-D batch
    (``constants``, its `_balance_constants`, are not needed since session 38, when the
    kernels took the planetary modes' torque condition and gyroscopic moment)."""
    del constants
    return AVAILABLE and problem.tilt.ndim == 1


def evaluate_rows(problem, creep, h, quadrature, memos) -> tuple[dict, np.ndarray]:
    """The fields of the `ballcvt.equilibrium.residual.EquilibriumState` at ``creep`` and
    the residuals of every row ``(n, rows, n_c)`` (``h``: the creeps' steps, or None for
    the creeps alone); ``memos``: the problem's film at unit speed, its balance constants
    and its asperities. The traction law is evaluated at the creeps in Python, between
    the two kernels."""
    film_unit, k, asp = memos
    geometry, speed, unit, constants, bearings = problem.memo(
        "compiled", lambda: _inputs(problem, film_unit, k)
    )
    n_rows = 1 if h is None else 1 + creep.shape[-1]
    own = np.ascontiguousarray
    steps = own(np.zeros(creep.shape) if h is None else h)
    rows = contact_rows(own(creep), steps, speed, geometry, unit, SPEED_EXPONENT, n_rows)
    c, sg, u, hf, om, ws = rows
    at = ContactState(c[:, 0], sg[:, 0], problem.ax, problem.ay, problem.p_max, problem.load,
                      problem.radius, u[:, 0], hf[:, 0])  # fmt: skip
    law = lubricated_coefficients(at, problem.fluid, asp, quadrature, derivatives=h is not None)
    if h is None:  # row 0 alone takes the law's values as they are
        law = law + (np.zeros(c.shape[:1] + c.shape[2:] + (3,)),) * 2
    res, row0, axle, t_bls, drags = balance_rows(law, (c, sg, u, hf), (om, ws), constants,
                                                 bearings)  # fmt: skip
    force, moment, body, t_bl, mu, chi = row0
    fields = {"creep": creep + 0.0, "omega_s": ws[:, 0], "omega": om[:, 0], "spin": sg[:, 0],
              "u_ref": u[:, 0], "film": hf[:, 0], "mu": mu, "chi": chi, "force": force,
              "moment": moment, "body_torque": body, "axle_reactions": axle,
              "roller_bearing_torque": t_bls, "idler_bearing_torque": t_bl,
              "residual": res[:, 0], "input_drag": drags[:, 0], "output_drag": drags[:, 1]}  # fmt: skip
    return fields, res


def _inputs(problem, unit, k) -> tuple:
    """The kernels' creep-independent inputs of ``problem`` (contiguous arrays, kept on
    the problem): ``geometry``, ``omega_0``, the film at unit speed, the balances'
    constants and the bearings' (`contact_rows`, `balance_rows`)."""
    lay, des, nu = problem.layout, problem.design, problem.fluid.kinematic_viscosity
    bearings = (
        speed_torque_constants(des.roller_bearing_diameter, nu, des.bearings),
        speed_torque_constants(des.idler_bearing_diameter, nu, des.bearings),
        load_torque_constants(des.roller_bearing_diameter, des.bearings),
    )
    own = lambda a: np.array(a, dtype=float)  # noqa: E731 (a writeable copy: once a problem)
    geometry = (own(problem.rho), own(problem.sz), lay.radius, lay.z_j, problem.radius)
    per_contact = [own(k[name]) for name in ("kappa_load", "load_radius", "rs_rho", "rs_sz")]
    per_point = ("roller_drag", "roller_scale")
    a, b = (float(w) for w in problem.torque_weights)
    constants = (
        tuple(per_contact) + geometry[1::-1] + (own(k["idler_load_torque"]),),
        tuple(own(k[name]) for name in per_point)
        + (own(problem.torque_scale), own(problem.output_torque)),
        (problem.radius, lay.z_j, lay.is_idler),
        (float(des.roller_radius), int(des.n_rollers)),
        _drags(k["shaft_drags"], problem.shape[0]),
        (a, b, (a, b) == (0.0, 1.0), own(np.broadcast_to(problem.gyro_factor, problem.shape))),
    )
    return geometry, own(problem.input_speed), own(unit), constants, bearings


def _drags(drags, n: int) -> tuple:
    """The shaft and between-disc drag magnitudes by kind ``(n, n_kinds)`` (none: no
    kinds) and the stick speed of their direction (`shaft_drags`)."""
    if drags is None:
        none = np.zeros((n, 0))
        return none, none, none, STICK_SPEED
    return (np.array(drags.input, dtype=float), np.array(drags.output, dtype=float),
            np.array(drags.between, dtype=float), STICK_SPEED)  # fmt: skip


if AVAILABLE:

    @njit(cache=True)
    def _sign(x):
        """``np.sign`` of a float (NaN stays NaN)."""
        if x > 0.0:
            return 1.0
        if x < 0.0:
            return -1.0
        return x if x != x else 0.0

    @njit(cache=True)
    def contact_rows(creep, h, w0, geometry, unit, exponent, rows):
        """Creep terms, spins, surface speeds, films and body speeds of every row.

        ``creep``, ``h`` ``(n, n_c)``: the creeps and their steps; row 0 the creeps, row
        ``r`` creep ``r - 1`` moved by its step. ``w0`` ``(n,)`` [rad/s]; ``geometry``:
        ``(rho, sz)`` ``(n, n_c)`` and the layout's ``(radius over r_S, z_j, r_c [m])``
        ``(n_c,)``; ``unit`` ``(n, n_c)``: Eq. 56 at 1 m/s [m]; ``exponent``: its speed
        exponent; ``rows``: ``1 + n_c``, or 1 for the creeps alone. Returns ``c, sigma,
        u_ref, film, omega`` ``(n, rows, n_c)`` and ``omega_s`` ``(n, rows)``.
        """
        rho, sz, r_lay, z_j, radius = geometry
        n, nc = creep.shape
        c = np.empty((n, rows, nc))
        sg, u, hf, om = np.empty_like(c), np.empty_like(c), np.empty_like(c), np.empty_like(c)
        ws = np.empty((n, rows))
        x = np.empty(nc)
        for i in range(n):
            for r in range(rows):
                for m in range(nc):
                    x[m] = creep[i, m] + h[i, m] if r == m + 1 else creep[i, m] + 0.0
                w_s = w0[i] * r_lay[0] * (1.0 - x[0]) / rho[i, 0]
                ws[i, r] = w_s
                for m in range(nc):
                    w = w0[i] if m == 0 else w_s * rho[i, m] * (1.0 - x[m]) / r_lay[m]
                    om[i, r, m] = w
                    sg[i, r, m] = (w_s * sz[i, m] - w * z_j[m]) / abs(w)
                    speed = abs(w) * radius[m]
                    u[i, r, m] = speed
                    if m == 0:
                        c[i, r, m] = x[m]
                        entrain = 1.0 - 0.5 * x[m]
                    else:
                        c[i, r, m] = x[m] / (1.0 - x[m])
                        entrain = (1.0 - 0.5 * x[m]) / (1.0 - x[m])
                    hf[i, r, m] = unit[i, m] * abs(speed * entrain) ** exponent
        return c, sg, u, hf, om, ws

    @njit(cache=True)
    def _linearised(law, rows, i, r, m):
        """The law's ``mu`` and ``chi`` at row ``r`` of contact ``m``, linearised from row 0
        (``law``: ``(mu, chi, dmu, dchi)`` at row 0; ``rows``: `contact_rows`' first four)."""
        mu0, chi0, dmu, dchi = law
        c, sg, u, hf = rows
        if r == 0:
            return mu0[i, m], chi0[i, m]
        d0 = c[i, r, m] - c[i, 0, m]
        d1 = sg[i, r, m] - sg[i, 0, m]
        d2 = math.log((u[i, r, m] * hf[i, 0, m]) / (u[i, 0, m] * hf[i, r, m]))
        a = dmu[i, m, 0] * d0 + dmu[i, m, 1] * d1 + dmu[i, m, 2] * d2
        b = dchi[i, m, 0] * d0 + dchi[i, m, 1] * d1 + dchi[i, m, 2] * d2
        if dmu.shape[2] == 4:  # a lubrication model's film column
            d3 = math.log(hf[i, r, m] / hf[i, 0, m])
            a += dmu[i, m, 3] * d3
            b += dchi[i, m, 3] * d3
        return mu0[i, m] + a, chi0[i, m] + b

    @njit(cache=True)
    def balance_rows(law, rows, speeds, k, bearings):
        """Residuals of every row and the state of row 0 (`_balances`).

        ``law``, ``rows``: as `_linearised`; ``speeds``: ``(omega, omega_s)`` of
        `contact_rows`; ``k``: ``(kappa F_N, F_N r_c, r_S rho, r_S sz, sz, rho,
        idler load torque)`` ``(n, n_c)``, ``(roller drag, F_N0 r_S, n F_N0 r_S, T_2)``
        ``(n,)``, ``(r_c, z_j, is_idler)`` ``(n_c,)``, ``(r_S, n)``, the shaft and
        between-disc drags (`_drags`), and the frame's ``(a, b, standard, gyro_factor
        (n,))``: the torque condition ``a T_0 + b T_2 = T`` of a planetary mode (the last
        balance; ``standard``: ``(0, 1)``, the output's, in the paper's form) and the
        factor of the balls' gyroscopic moment, which loads the axle bearings with the
        reactions (§13); ``bearings``: the roller's and the idler's
        `speed_torque_constants` and the roller's `load_torque_constants`. Returns ``res``
        ``(n, rows, n_c)``, and of row 0 ``(force, moment, body, t_bl, mu, chi)`` ``(n,
        n_c)``, the axle reactions ``(n, 2)``, ``t_bls`` ``(n,)`` and the input and output
        shafts' drags ``(n, 2)``.
        """
        om, ws = speeds
        contact, point, layout, ball, drags, frame = k
        w_a, w_b, standard, gyro = frame
        kappa_load, load_radius, rs_rho, rs_sz, sz, rho, idler_load = contact
        roller_drag, roller_scale, scale, t2 = point
        radius, z_j, is_idler = layout
        rs, n_balls = ball
        roller, idler, load = bearings
        n, n_rows, nc = om.shape
        res = np.empty((n, n_rows, nc))
        row0 = np.empty((6, n, nc))  # force, moment, body, t_bl, mu, chi
        axle0, t_bls0, drag0 = np.empty((n, 2)), np.empty(n), np.empty((n, 2))
        force, moment, t_bl = np.empty(nc), np.empty(nc), np.empty(nc)
        for i in range(n):
            for r in range(n_rows):
                m_s = m_u = f_sum = 0.0
                for m in range(nc):
                    mu, chi = _linearised(law, rows, i, r, m)
                    force[m] = kappa_load[i, m] * mu
                    moment[m] = -chi * load_radius[i, m]
                    m_s += rs_rho[i, m] * force[m] + sz[i, m] * moment[m]
                    m_u += rho[i, m] * moment[m] - rs_sz[i, m] * force[m]
                    f_sum += force[m]
                    if r == 0:
                        row0[4, i, m], row0[5, i, m] = mu, chi
                f_sum = -f_sum
                a0 = 0.5 * (f_sum + 2.0 * m_u / rs)
                a1 = 0.5 * (f_sum - 2.0 * m_u / rs)
                w_s = ws[i, r]
                g = gyro[i] * w_s  # the gyroscopic load of each axle end (none: as they are)
                l0, l1 = (math.hypot(a0, g), math.hypot(a1, g)) if g != 0.0 else (a0, a1)
                t_bls = 2.0 * _speed_torque(w_s, roller) + (
                    load[0] * abs(l0) ** load[1] + load[0] * abs(l1) ** load[1]
                )
                res[i, r, 0] = (m_s - _sign(w_s) * (t_bls + roller_drag[i])) / roller_scale[i]
                t_in, t_out = _shaft_drags(drags, i, om[i, r, 0], om[i, r, nc - 1])
                body0 = 0.0
                for m in range(nc):
                    w = om[i, r, m]
                    t_bl[m] = _speed_torque(w, idler) + idler_load[i, m] if is_idler[m] else 0.0
                    body = n_balls * (-force[m] * radius[m] - moment[m] * z_j[m])
                    if m == 0:
                        body0 = body
                    if 0 < m < nc - 1:
                        res[i, r, m] = (body - _sign(w) * t_bl[m]) / scale[i]
                    elif m == nc - 1 and standard:
                        res[i, r, m] = (body - (t2[i] + t_out)) / scale[i]
                    elif m == nc - 1:
                        torque = w_a * (-body0 + t_in) + w_b * (body - t_out)
                        res[i, r, m] = (torque - t2[i]) / scale[i]
                    if r == 0:
                        row0[2, i, m] = body
                if r == 0:
                    row0[0, i], row0[1, i], row0[3, i] = force, moment, t_bl
                    axle0[i, 0], axle0[i, 1], t_bls0[i] = a0, a1, t_bls
                    drag0[i, 0], drag0[i, 1] = t_in, t_out
        return res, row0, axle0, t_bls0, drag0

    @njit(cache=True)
    def jacobian_rows(res, h):
        """``d res_m / d creep_j`` ``(n, n_c, n_c)`` by forward differences of the rows
        ``res`` ``(n, 1 + n_c, n_c)`` of `balance_rows`, ``h`` ``(n, n_c)`` the steps."""
        n, rows, nc = res.shape
        jac = np.empty((n, nc, nc))
        for i in range(n):
            for m in range(nc):
                for j in range(nc):
                    jac[i, m, j] = (res[i, j + 1, m] - res[i, 0, m]) / h[i, j]
        return jac

    @njit(cache=True)
    def _shaft_drags(drags, i, w0, w2):
        """The input and output shafts' drags of point ``i`` at the disc speeds ``w0, w2``
        [rad/s], summed over the kinds (`ballcvt.model.losses.shaft_drags`)."""
        d_in, d_out, d_between, stick = drags
        t_in = t_out = 0.0
        for q in range(d_in.shape[1]):
            between = d_between[i, q] * math.tanh((w0 - w2) / stick)
            t_in += d_in[i, q] * math.tanh(w0 / stick) + between
            t_out += d_out[i, q] * math.tanh(w2 / stick) - between
        return t_in, t_out

    @njit(cache=True)
    def _speed_torque(speed, constants):
        """`speed_dependent_torque` of one speed [N m] from its constants."""
        scale, nu_rpm, low, exponent = constants
        v = (nu_rpm * abs(speed)) ** exponent
        return scale * (v if not low > v else low)

else:  # pragma: no cover
    contact_rows = balance_rows = jacobian_rows = None  # type: ignore[assignment]
