"""Compiled (numba) film-temperature solve of the thermal law: the same steps as its NumPy
path (`ballcvt.model.traction.thermal`), one contact at a time.

The NumPy path iterates Newton on the rise ``dT = R q(dT)`` over whole arrays, calling the
traction kernel once per iteration on the contacts not yet converged (four to six times
per evaluation of the law), with the array bookkeeping of each call in Python. Here each
contact runs its own iterations inside one compiled call, on the traction sums of
`ballcvt.model.traction.kernels.contact_sums` at the film ``h exp((beta - beta_L) dT)``:
the same safeguarded Newton on the cheap rule, the same stopping test, then the same one
step on the requested rule. A contact's iterations never depended on the others', so the
results are those of the NumPy path to round-off (tests compare the two).

Each contact's row of ``out`` holds ``(dT, mu, chi, dmu/dc, dmu/dsigma, dmu/dlog u,
dmu/ddT, dchi/dc, dchi/dsigma, dchi/dlog u, dchi/ddT)`` (`thermal_kernel`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .kernels import _FAST, ALL, AVAILABLE, LOG_U, contact_sums

njit: Any
try:
    from numba import njit
except ImportError:  # pragma: no cover - numba is a declared dependency
    njit = None

__all__ = ["thermal_kernel", "N_THERMAL", "total_derivatives", "RISE_RTOL"]

#: Columns of the thermal kernel's output per contact.
N_THERMAL = 11
#: Relative step of the rise's Newton on the cheap rule at which it stops [-]. The step on
#: the requested rule that follows leaves an error quadratic in the distance from its
#: fixed point, so the stop barely shows: from 1e-6 (until session 35) to 1e-3 the
#: coefficients move by 2e-12 relative at most (680 contacts of Table I's thermal sweep;
#: 1.3e-10 at 1e-2), and Newton takes 2.6 evaluations on the cheap rule instead of 3.1.
RISE_RTOL = 1e-3

if AVAILABLE:

    @njit(cache=True, fastmath=_FAST, inline="always")
    def _at(par, i, dt, rule, table, heat, deriv):
        """``mu, chi``, their partials ``(c, sigma, log u)`` and ``d/ddT`` of contact ``i`` at
        the rise ``dt`` [K] (``_Contacts.at`` of the NumPy path); ``heat``: ``(beta_L,
        beta - beta_L)`` [1/K]; ``deriv``: `ALL`, or `LOG_U` (the partials by ``c`` and
        ``sigma`` then 0: ``d/ddT`` needs only the one by ``log u``)."""
        beta_l, b = heat
        f_t = math.exp(-beta_l * dt)
        s = contact_sums(par, i, par[8, i] * math.exp(b * dt), rule, table, deriv, False)
        mu, chi = f_t * s[0], f_t * s[1]
        m0, m1, m2 = f_t * s[2], f_t * s[3], f_t * s[4]
        c0, c1, c2 = f_t * s[5], f_t * s[6], f_t * s[7]
        return mu, chi, m0, m1, m2, -beta_l * mu - b * m2, c0, c1, c2, -beta_l * chi - b * c2

    @njit(cache=True, fastmath=_FAST, inline="always")
    def _rise(par, i, k, r, cheap, table, heat):
        """Safeguarded Newton on ``dT = r q(dT)`` on the rule ``cheap``, kept inside the
        bracket ``[0, r q(0)]`` (``_solve_rise``: tolerance `RISE_RTOL`, 60 iterations) [K]."""
        cr, sg = par[0, i], par[1, i]
        dt, lo, hi = 0.0, 0.0, math.inf
        for _ in range(60):
            v = _at(par, i, dt, cheap, table, heat, LOG_U)
            q = k * (cr * v[0] + sg * v[1])
            q_t = k * (cr * v[5] + sg * v[9])
            g = dt - r * q
            if g <= 0.0:
                lo = dt
            if g >= 0.0:
                hi = dt
            slope = 1.0 - r * q_t
            new = dt - g / (slope if slope > 0.0 else math.inf)
            if (new <= lo) or (new >= hi) or (slope <= 0.0):
                new = 0.5 * (lo + hi) if math.isfinite(hi) else r * q
            step = abs(new - dt)
            dt = new
            if not step > RISE_RTOL * (1.0 + abs(new)):
                break
        return dt

    @njit(cache=True, fastmath=_FAST, inline="always")
    def _thermal(par, contact, rules, table, heat, out, deriv):
        """Every contact's rise and coefficients (rows of ``out``, module docstring; the
        partials by ``c`` and ``sigma`` 0 unless ``deriv`` is `ALL`)."""
        cheap, rule = rules
        k_all, r_all = contact
        for i in range(par.shape[1]):
            cr, sg, k, r = par[0, i], par[1, i], k_all[i], r_all[i]
            dt = _rise(par, i, k, r, cheap, table, heat)
            v = _at(par, i, dt, rule, table, heat, deriv)
            q = k * (cr * v[0] + sg * v[1])
            q_t = k * (cr * v[5] + sg * v[9])
            step = -(dt - r * q) / (1.0 - r * q_t)
            if step < -dt:  # the rise stays >= 0 (NaN stays NaN)
                step = -dt
            out[i, 0] = dt + step
            out[i, 1] = v[0] + v[5] * step
            out[i, 2] = v[1] + v[9] * step
            f_t = math.exp(-heat[0] * step)  # the partials' tau_L factor at dT + step
            for j in range(4):
                out[i, 3 + j] = v[2 + j] * f_t
                out[i, 7 + j] = v[6 + j] * f_t

    # the two specialisations (the partials wanted or not): fixed at compile time
    @njit(cache=True, fastmath=_FAST)
    def _thermal_all(par, contact, cheap, rule, table, heat, out):
        _thermal(par, contact, (cheap, rule), table, heat, out, ALL)

    @njit(cache=True, fastmath=_FAST)
    def _thermal_values(par, contact, cheap, rule, table, heat, out):
        _thermal(par, contact, (cheap, rule), table, heat, out, LOG_U)

    def thermal_kernel(par, contact, rules, table, heat, out, partials=True):
        """The film temperature rise and the coefficients of every contact (rows of
        ``out``, ``(n, N_THERMAL)``, module docstring).

        ``par``: the contacts' ``(c, sigma, a_x, a_y, p_max, F_N, r_c, u, h)`` as rows
        ``(9, n)``; ``contact``: ``(F_N u / (pi a_x a_y) [W/m^2], R [K m^2/W])`` per
        contact, the flux per unit of ``c mu + sigma chi`` and the thermal resistance;
        ``rules``: the cheap rule the rise converges on and the requested one, each as
        `ballcvt.model.traction.kernels.traction_kernel` takes it; ``table``: ``(fl, tab)``
        of the rigid-plastic film (`viscosity_table`); ``heat``: ``(beta_L, beta -
        beta_L)`` [1/K]; ``partials``: also the partials by ``c`` and ``sigma`` (else 0:
        the coefficients alone cost 10-20 % less).
        """
        kernel = _thermal_all if partials else _thermal_values
        kernel(par, contact, rules[0], rules[1], table, heat, out)

    # no fast-math: the same operations in the same order as the NumPy path's, so the same
    # bits (a fold of the thermal law turns on the last bit, `ballcvt.solvers.secant`)
    @njit(cache=True)
    def _totals(values, contact, creeps, out):
        mu, chi, dmu, dchi = values
        k, r, r_flash = contact
        c, s = creeps
        out_mu, out_chi = out
        for i in range(mu.shape[0]):
            q = k[i] * (c[i] * mu[i] + s[i] * chi[i])
            dq = (
                k[i] * (c[i] * dmu[i, 0] + s[i] * dchi[i, 0]) + k[i] * mu[i],
                k[i] * (c[i] * dmu[i, 1] + s[i] * dchi[i, 1]) + k[i] * chi[i],
                k[i] * (c[i] * dmu[i, 2] + s[i] * dchi[i, 2]) + q,
                q,
            )
            dr = (0.0, 0.0, -0.5 * r_flash[i], r[i] - 1.5 * r_flash[i])
            slope = k[i] * (c[i] * dmu[i, 3] + s[i] * dchi[i, 3])
            den = 1.0 - r[i] * slope
            for j in range(out_mu.shape[1]):
                d_dt = (r[i] * dq[j] + q * dr[j]) / den
                out_mu[i, j] = dmu[i, 3] * d_dt
                out_chi[i, j] = dchi[i, 3] * d_dt
                if j < 3:  # Eq. 53 at a fixed rise: no d log h at fixed u / h
                    out_mu[i, j] += dmu[i, j]
                    out_chi[i, j] += dchi[i, j]

    def total_derivatives(values, contact, creeps, film):
        """The total derivatives of ``mu, chi`` (the rise's response included) by the
        creep term, the spin, ``log u`` at a fixed film and, with ``film``, ``log h`` at a
        fixed ``u / h``: ``(dmu, dchi)``, ``(n, 3)`` or ``(n, 4)`` (the NumPy path's
        `ballcvt.model.traction.thermal._with_derivatives`, the same bits).

        ``values``: ``mu, chi`` [-] ``(n,)`` and their partials ``(c, sigma, log u, dT)``
        at a fixed rise ``(n, 4)``; ``contact``: ``(F_N u / (pi a_x a_y) [W/m^2], R [K
        m^2/W], R_flash [K m^2/W])``; ``creeps``: the creep term and the spin [-].
        """
        mu, chi, dmu, dchi = values
        n = 4 if film else 3
        out_mu, out_chi = np.empty((mu.shape[0], n)), np.empty((mu.shape[0], n))
        k, r, r_flash = (np.ascontiguousarray(a, dtype=float) for a in contact)
        c, s = (np.ascontiguousarray(a, dtype=float) for a in creeps)
        dmu, dchi = np.ascontiguousarray(dmu), np.ascontiguousarray(dchi)
        _totals((mu, chi, dmu, dchi), (k, r, r_flash), (c, s), (out_mu, out_chi))
        return out_mu, out_chi

else:  # pragma: no cover
    thermal_kernel = total_derivatives = None  # type: ignore[assignment]
