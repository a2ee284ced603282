"""Compiled (numba) kernels of the traction integrals: the same sums as the NumPy path.

`ballcvt.contact.traction._integrate` writes the integrand of Eqs. 57-66 as whole-array
NumPy expressions; at tens of thousands of contacts times hundreds of nodes those
temporaries make it memory bound. These kernels loop over contacts and nodes and keep
everything in registers, generating the pole-centred nodes on the fly. They compute
exactly the same quantities (tests compare the two paths to round-off); the NumPy path
stays the reference and the fallback when numba is not installed.

The Roelands viscosity, whose power and exponential cost more than the rest of a node,
enters the shear law only as ``E = eta / tau_L`` (the ratio of viscosity to limiting shear
stress, with ``tau_L = tau_L0 + a p``); ``E`` is read from a cubic Hermite table over the
pressure (`viscosity_table`: exact values and derivatives at nodes spaced so that
``log E`` changes by at most 0.01 between them, a relative error below 1e-10), so a node
costs no exponential and no division for it. On the rays of the pole-centred rule the
sliding velocity is the ray's direction times the distance from the pole (the pole is
where it vanishes), so its magnitude is computed once per ray.

Each kernel writes, per contact, ``out[i] = (mu, chi, dmu/dc, dmu/dsigma, dmu/dlog u,
dchi/dc, dchi/dsigma, dchi/dlog u)`` (see `traction_coefficients`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

njit: Any
try:
    from numba import njit
except ImportError:  # pragma: no cover - numba is a declared dependency
    njit = None

__all__ = ["AVAILABLE", "pole_kernel", "centred_kernel", "N_OUT", "viscosity_table"]

AVAILABLE = njit is not None
#: Fast-math flags that keep IEEE NaN and infinity semantics (a NaN must propagate).
_FAST = {"nsz", "arcp", "contract", "afn", "reassoc"}
N_OUT = 8


def viscosity_table(fluid, p_max: float, intervals: int = 2048, log_step: float = 0.01):
    """Hermite table of ``E = eta / tau_L`` over the pressure on ``[0, p_max]``.

    ``eta`` is the Roelands viscosity (Eq. 51) and ``tau_L = tau_L0 + a p`` the limiting
    shear stress (Eq. 54); the shear law depends on the viscosity through their ratio only
    (module docstring).

    Parameters
    ----------
    fluid : Fluid
        Traction fluid (Roelands and limiting-shear parameters).
    p_max : float
        Largest pressure to cover [Pa].
    intervals : int
        Least number of equal pressure intervals; more are used where needed for
        ``log E`` to change by at most ``log_step`` over one interval.
    log_step : float
        Largest change of ``log E`` over one interval [-] (0.01: interpolation error
        ``(0.01)^4 / 384``, about 3e-11 relative).

    Returns
    -------
    fl : ndarray
        ``(tau_L0 [Pa], a [-], intervals / p_max [1/Pa], G [Pa])``: ``G`` is the film's
        shear modulus of the visco-elastic law, 0 for a rigid-plastic film.
    tab : ndarray
        ``(intervals + 1, 2)``: ``E`` [s] and its derivative times the interval [s].
    """
    top = max(float(p_max), 1.0) * (1.0 + 1e-12)
    log_ratio = np.log(fluid.viscosity / fluid.pole_viscosity)
    z, cp = fluid.roelands_index, fluid.pole_pressure
    tl0, slope_tl = fluid.limiting_shear_stress, fluid.limiting_shear_slope

    def log_slope(p):  # d log E / dp [1/Pa]
        return log_ratio * z * np.exp((z - 1.0) * np.log1p(p / cp)) / cp - slope_tl / (
            tl0 + slope_tl * p
        )

    probe = np.linspace(0.0, top, 4097)
    steep = float(np.max(np.abs(log_slope(probe)))) * top
    n = int(min(max(intervals, np.ceil(steep / log_step)), 2**20))
    p = np.linspace(0.0, top, n + 1)
    log_e = np.log(fluid.viscosity / (tl0 + slope_tl * p)) + log_ratio * np.expm1(
        z * np.log1p(p / cp)
    )
    e = np.exp(log_e)
    modulus = fluid.shear_modulus if fluid.traction_law == "viscoelastic" else 0.0
    fl = np.array([tl0, slope_tl, n / top, modulus])
    return fl, np.column_stack([e, e * log_slope(p) * (top / n)])


if AVAILABLE:

    @njit(cache=True, fastmath=_FAST, inline="always")
    def _node(x, y, vx, vy, speed, w, k, fl, tab, deriv, acc):
        """Add one node's contribution to ``acc`` (8 sums, see module docstring).

        ``(vx, vy)`` is the sliding velocity at the node and ``speed`` its magnitude;
        ``k`` holds the contact's constants: ``c u, u sigma a_y / r_c, u sigma a_x / r_c,
        u a_y / r_c, u a_x / r_c, u, 1 / h, p_max, a_x, a_y``.
        """
        q = 1.0 - x * x - y * y
        p = k[7] * math.sqrt(q) if q > 0.0 else 0.0
        # E = eta / tau_L from its cubic Hermite table (Roelands, Eq. 51; Eq. 54)
        v = p * fl[2]
        i = min(int(v), tab.shape[0] - 2)
        t = v - i
        r = 1.0 - t
        e = r * r * ((1.0 + 2.0 * t) * tab[i, 0] + t * tab[i, 1]) + t * t * (
            (3.0 - 2.0 * t) * tab[i + 1, 0] - r * tab[i + 1, 1]
        )
        ek = e * k[6]  # eta / (h tau_L)
        eh = ek * (fl[0] + fl[1] * p)  # eta / h
        a = ek * speed
        # saturation (1 - exp(-a)) / a: series below 1e-3 (error a^5 / 720), else exp
        # (cheaper than expm1; cancellation costs at most 1e-13 relative there)
        if a < 1e-3:
            sat = 1.0 - a * (0.5 - a * (1.0 / 6.0 - a * (1.0 / 24.0 - a * (1.0 / 120.0))))
            inv_a = 0.0
        else:
            inv_a = 1.0 / a
            sat = (1.0 - math.exp(-a)) * inv_a
        g = eh * sat
        corr = 1.0
        lin_extra = 0.0
        if fl[3] > 0.0:
            # Maxwell elasticity (docs/model.md §14): tau = tau_steady (1 - exp(-theta)),
            # theta = G t / (eta sat), t = a_x (X + sqrt(1 - Y^2)) / u since entry
            q_in = 1.0 - y * y
            t_in = k[8] * (x + (math.sqrt(q_in) if q_in > 0.0 else 0.0))
            theta = fl[3] * t_in * k[6] / (k[5] * g) if k[5] * g > 0.0 else 1e300
            em = math.exp(-theta)
            f = theta * (1.0 - 0.5 * theta) if theta < 1e-5 else 1.0 - em
            corr = f - theta * em
            lin_extra = -g * theta * em
            g = g * f
        wx = w * k[8] * x
        wy = w * k[9] * y
        tx = g * vx
        ty = g * vy
        acc[0] += w * tx
        acc[1] += wx * ty - wy * tx
        if deriv:
            if a < 1e-3:
                slope = -0.5 + a / 3.0 - a * a / 8.0
            else:
                slope = ((1.0 - sat) - a * sat) * inv_a
            kk = eh * ek * slope / speed if speed > 0.0 else 0.0
            if fl[3] > 0.0:
                kk *= corr
            # d/dc: dV = (u, 0)
            u = k[5]
            dtx = g * u + kk * vx * u * vx
            dty = kk * vx * u * vy
            acc[2] += w * dtx
            acc[5] += wx * dty - wy * dtx
            # d/dsigma: dV = (-u a_y y / r_c, u a_x x / r_c)
            dvx = -k[3] * y
            dvy = k[4] * x
            dot = vx * dvx + vy * dvy
            dtx = g * dvx + kk * dot * vx
            dty = g * dvy + kk * dot * vy
            acc[3] += w * dtx
            acc[6] += wx * dty - wy * dtx
            # d/dlog u: dV = V
            lin = g + kk * speed * speed
            if fl[3] > 0.0:
                lin += lin_extra
            acc[4] += w * lin * vx
            acc[7] += lin * (wx * vy - wy * vx)

    @njit(cache=True, fastmath=_FAST, inline="always")
    def _constants(par, i, k):
        c, sg, ax, ay, pm = par[0, i], par[1, i], par[2, i], par[3, i], par[4, i]
        rc, u, h = par[6, i], par[7, i], par[8, i]
        k[0] = c * u
        k[1] = u * sg * ay / rc
        k[2] = u * sg * ax / rc
        k[3] = u * ay / rc
        k[4] = u * ax / rc
        k[5] = u
        k[6] = 1.0 / h
        k[7] = pm
        k[8] = ax
        k[9] = ay

    @njit(cache=True, fastmath=_FAST, inline="always")
    def _finish(acc, par, i, out):
        ax, ay, fn, rc = par[2, i], par[3, i], par[5, i], par[6, i]
        area = ax * ay
        for j in range(N_OUT):
            out[j] = acc[j] * area / fn
        out[1] /= rc
        for j in range(5, N_OUT):
            out[j] /= rc

    @njit(cache=True, fastmath=_FAST)
    def pole_kernel(yp, par, r01, wr, sin_phi, cos_phi, dphi, fl, tab, deriv, out):
        """Pole-centred rule: rays from ``(0, yp[i])`` to the boundary (see quadrature).

        At ``(rho cos phi, yp + rho sin phi)`` the sliding velocity is
        ``rho (-k_1 sin phi, k_2 cos phi)``: it vanishes at the pole ``yp = k_0 / k_1``.
        """
        acc = np.empty(N_OUT)
        k = np.empty(10)
        for i in range(yp.shape[0]):
            _constants(par, i, k)
            acc[:] = 0.0
            y0 = yp[i]
            for m in range(sin_phi.shape[0]):
                b = y0 * sin_phi[m]
                reach = -b + math.sqrt(b * b + (1.0 - y0 * y0))
                dx = -k[1] * sin_phi[m]
                dy = k[2] * cos_phi[m]
                ray_speed = math.sqrt(dx * dx + dy * dy)
                for j in range(r01.shape[0]):
                    rho = reach * r01[j]
                    _node(
                        rho * cos_phi[m],
                        y0 + rho * sin_phi[m],
                        rho * dx,
                        rho * dy,
                        rho * ray_speed,
                        rho * reach * wr[j] * dphi,
                        k,
                        fl,
                        tab,
                        deriv,
                        acc,
                    )
            _finish(acc, par, i, out[i])

    @njit(cache=True, fastmath=_FAST)
    def centred_kernel(par, x, y, w, fl, tab, deriv, out):
        """Fixed nodes ``x, y, w`` (1-D) shared by every contact."""
        acc = np.empty(N_OUT)
        k = np.empty(10)
        for i in range(par.shape[1]):
            _constants(par, i, k)
            acc[:] = 0.0
            for j in range(x.shape[0]):
                vx = k[0] - k[1] * y[j]
                vy = k[2] * x[j]
                _node(
                    x[j], y[j], vx, vy, math.sqrt(vx * vx + vy * vy), w[j], k, fl, tab, deriv, acc
                )
            _finish(acc, par, i, out[i])
else:  # pragma: no cover
    pole_kernel = centred_kernel = None  # type: ignore[assignment]
