"""Compiled (numba) kernels of the traction integrals: the same sums as the NumPy path.

`ballcvt.contact.traction._integrate` writes the integrand of Eqs. 57-66 as whole-array
NumPy expressions; at tens of thousands of contacts times hundreds of nodes those
temporaries make it memory bound. These kernels loop over contacts and nodes and keep
everything in registers, generating the pole-centred nodes on the fly. They compute
exactly the same quantities (tests compare the two paths to round-off); the NumPy path
stays the reference and the fallback when numba is not installed.

The Roelands viscosity, whose power and exponential cost more than the rest of a node,
is read from a cubic Hermite table of ``log(eta / eta_0)`` over the pressure (`viscosity_table`,
values and exact derivatives at 2048 intervals: relative error below 1e-10).

Each kernel writes, per contact, ``out[i] = (mu, chi, dmu/dc, dmu/dsigma, dmu/dlog u,
dchi/dc, dchi/dsigma, dchi/dlog u)`` (see `traction_coefficients`).
"""

from __future__ import annotations

import math

import numpy as np

try:
    from numba import njit
except ImportError:  # pragma: no cover - numba is a declared dependency
    njit = None

__all__ = ["AVAILABLE", "pole_kernel", "centred_kernel", "N_OUT", "viscosity_table"]

AVAILABLE = njit is not None
#: Fast-math flags that keep IEEE NaN and infinity semantics (a NaN must propagate).
_FAST = {"nsz", "arcp", "contract", "afn", "reassoc"}
N_OUT = 8



def viscosity_table(fluid, p_max: float, intervals: int = 2048):
    """Hermite table of the Roelands exponent ``log(eta / eta_0)`` on ``[0, p_max]``.

    Parameters
    ----------
    fluid : Fluid
        Traction fluid (Roelands parameters).
    p_max : float
        Largest pressure to cover [Pa].
    intervals : int
        Number of equal pressure intervals.

    Returns
    -------
    fl : ndarray
        ``(eta_0 [Pa s], tau_L0 [Pa], slope [-], intervals / p_max [1/Pa])``.
    tab : ndarray
        ``(intervals + 1, 2)``: the exponent and its derivative times the interval [-].
    """
    top = max(float(p_max), 1.0) * (1.0 + 1e-12)
    p = np.linspace(0.0, top, intervals + 1)
    log_ratio = np.log(fluid.viscosity / fluid.pole_viscosity)
    z, cp = fluid.roelands_index, fluid.pole_pressure
    value = log_ratio * np.expm1(z * np.log1p(p / cp))
    slope = log_ratio * z * np.exp((z - 1.0) * np.log1p(p / cp)) / cp
    fl = np.array([fluid.viscosity, fluid.limiting_shear_stress, fluid.limiting_shear_slope,
                   intervals / top])
    return fl, np.column_stack([value, slope * (top / intervals)])


if AVAILABLE:
    @njit(cache=True, fastmath=_FAST, inline="always")
    def _node(x, y, w, k, fl, tab, deriv, acc):
        """Add one node's contribution to ``acc`` (8 sums, see module docstring).

        ``k`` holds the contact's constants: ``c u, u sigma a_y / r_c, u sigma a_x / r_c,
        u a_y / r_c, u a_x / r_c, u, 1 / h, p_max, a_x, a_y``.
        """
        q = 1.0 - x * x - y * y
        p = k[7] * math.sqrt(q) if q > 0.0 else 0.0
        # Roelands (Eq. 68) from its cubic Hermite table, limiting shear stress (Eq. 54)
        v = p * fl[3]
        i = min(int(v), tab.shape[0] - 2)
        t = v - i
        r = 1.0 - t
        log_eta = (r * r * ((1.0 + 2.0 * t) * tab[i, 0] + t * tab[i, 1])
                   + t * t * ((3.0 - 2.0 * t) * tab[i + 1, 0] - r * tab[i + 1, 1]))
        eh = fl[0] * math.exp(log_eta) * k[6]                 # eta / h
        inv_tl = 1.0 / (fl[1] + fl[2] * p)
        vx = k[0] - k[1] * y
        vy = k[2] * x
        speed = math.sqrt(vx * vx + vy * vy)
        a = eh * speed * inv_tl
        if a < 1e-8:
            sat = 1.0 - 0.5 * a
            inv_a = 0.0
        else:
            inv_a = 1.0 / a
            sat = -math.expm1(-a) * inv_a
        g = eh * sat
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
            kk = eh * eh * inv_tl * slope / speed if speed > 0.0 else 0.0
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
        """Pole-centred rule: rays from ``(0, yp[i])`` to the boundary (see quadrature)."""
        acc = np.empty(N_OUT)
        k = np.empty(10)
        for i in range(yp.shape[0]):
            _constants(par, i, k)
            acc[:] = 0.0
            y0 = yp[i]
            for m in range(sin_phi.shape[0]):
                b = y0 * sin_phi[m]
                reach = -b + math.sqrt(b * b + (1.0 - y0 * y0))
                for j in range(r01.shape[0]):
                    rho = reach * r01[j]
                    _node(rho * cos_phi[m], y0 + rho * sin_phi[m], rho * reach * wr[j] * dphi,
                          k, fl, tab, deriv, acc)
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
                _node(x[j], y[j], w[j], k, fl, tab, deriv, acc)
            _finish(acc, par, i, out[i])
else:  # pragma: no cover
    pole_kernel = centred_kernel = None
