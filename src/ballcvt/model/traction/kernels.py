"""Compiled (numba) kernels of the traction integrals: the same sums as the NumPy path.

`ballcvt.model.traction.isothermal._integrate` writes the integrand of Eqs. 57-66 as whole-array
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
costs no exponential and no division for it.

Both rules are fans of rays: the pole-centred rule from the pole ``(0, Y_p)`` to the
boundary, the centred rule from the centre with unit reach. One ray loop (`_ray`) serves
both; its nodes' sums are kept in scalar registers, so that LLVM vectorises the loop over a
ray's nodes (8 nodes per instruction with AVX-512). On the pole's rays the sliding velocity
is the ray's direction times the distance from the pole (the pole is where it vanishes), so
its magnitude needs no square root per node; the shear law's slope uses ``1/a`` (one
division per node). The exponential of the saturation is `_exp_neg`, a range-reduced
polynomial that vectorises (a call to ``exp`` would not: numba has no vector math library),
its power of two built from the exponent bits (session 31: a table's gather cost 12 % of a
node without derivatives, 17 % of a visco-elastic node with them); its relative error is
below ``4e-16 + 4e-17 a``. Whether the derivatives and the
visco-elastic factor are computed is fixed at compile time: four specialised kernels,
chosen by `traction_kernel`. The pole position and the blend of the two rules are computed
per contact in the same compiled call. Measured on the 30 x 30 benchmark map (double idler,
32 x 24 nodes, with derivatives): 26 -> 5.6 ns per node.

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

__all__ = ["AVAILABLE", "traction_kernel", "N_OUT", "viscosity_table", "exp_neg", "contact_sums"]
__all__ += ["scalar_powers"]

AVAILABLE = njit is not None
#: Fast-math flags that keep IEEE NaN and infinity semantics (a NaN must propagate).
_FAST = {"nsz", "arcp", "contract", "afn", "reassoc"}
N_OUT = 8
#: The kernels' ``deriv`` levels: the derivatives by ``log u`` alone (the thermal law's
#: film temperature needs no others), or by the creep term, the spin and ``log u``.
LOG_U, ALL = 1, 2
#: Largest ``log E`` a viscosity table holds [-]: ``E = e^300`` s (~2e130) saturates the
#: film at its limiting shear at any slip (``E`` multiplies the shear rate), so the table
#: keeps it there (flat) where ``E`` (or ``E^2`` in the Jacobian) would overflow to inf and
#: the coefficients to NaN. Reached past ~40 GPa with the paper's fluid (``log E`` = 254 at
#: 30 GPa), i.e. only by a Newton trial step (the hub under its oil balance took one).
LOG_E_MAX = 300.0


def viscosity_table(
    fluid, p_max: float, intervals: int = 2048, log_step: float = 0.01, modulus: float = 0.0
):
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
    modulus : float
        Shear modulus ``G`` of a visco-elastic film [Pa] (the law's, e.g.
        ``fluid.shear_modulus`` under the visco-elastic law); 0: rigid-plastic.

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
    capped = log_e > LOG_E_MAX
    e = np.exp(np.minimum(log_e, LOG_E_MAX))
    de = np.where(capped, 0.0, e * log_slope(p) * (top / n))
    # |E' h| <= 3 E at every node keeps every interval's cubic positive (it is then at
    # least (1 - t)^3 E_k + t^3 E_k+1). Never active where log E changes by at most
    # `log_step` per interval (|E' h| <= 0.01 E); active only where the interval cap leaves
    # the table coarser than that: the boundary film's law (`ballcvt.model.lubrication`,
    # limiting shear 1 Pa + mu_b p) falls by a factor ~80 over its first interval, and the
    # unbounded cubic went negative there, the kernel's saturation with it (|mu| ~ 1e6).
    de = np.clip(de, -3.0 * e, 3.0 * e)
    fl = np.array([tl0, slope_tl, n / top, float(modulus)])
    return fl, np.column_stack([e, de])


def _powers_python(base, exponent, out):
    """``out[i] = base[i] ** exponent`` [-] where ``base[i] < 1`` (1-D arrays), one scalar
    C-library ``pow`` per element (as `math.pow`): no vector maths (numba has none
    without SVML), so every element's bits are independent of its position in the batch.
    """
    for i in range(base.shape[0]):
        if base[i] < 1.0:
            out[i] = math.pow(base[i], exponent)


#: `_powers_python`, compiled where numba is installed.
scalar_powers = njit(cache=True)(_powers_python) if AVAILABLE else _powers_python


def _kernel_flags(deriv, fl):
    """(derivatives, visco-elastic) of the specialised kernel to call."""
    return bool(deriv), bool(fl[3] > 0.0)


if AVAILABLE:
    from llvmlite import ir
    from numba.core import types
    from numba.extending import intrinsic

    @intrinsic
    def _as_double(_typingctx, _bits):
        """The float64 whose bits are the int64 ``bits`` (an LLVM bit cast, which
        vectorises)."""

        def codegen(_context, builder, _signature, args):
            return builder.bitcast(args[0], ir.DoubleType())

        return types.float64(types.int64), codegen

    @njit(cache=True, fastmath=_FAST, inline="always")
    def _exp_neg(a):
        """``exp(-a)`` for ``0 <= a <= 708`` (clamped outside, NaN to 708).

        ``a = k ln 2 + r`` with ``|r| <= ln 2 / 2`` (Cody and Waite's two-part ``ln 2``, exact
        products ``k ln2_hi``); then ``2^-k``, built from its exponent bits, times the
        degree-12 Taylor polynomial of ``exp(-r)`` (coefficients ``(-1)^n / n!``,
        truncation below 2e-16 relative). Measured relative error below
        ``4e-16 + 4e-17 a`` (the fast-math reassociation costs the second term; it is
        immaterial in ``1 - exp(-a)``). Branch-free, so that it vectorises.
        """
        # past 708 clamped: exp(-708) ~ 3e-308 is the smallest normal power reached
        # (k <= 1021), and where the kernels use it (1 - e^-a, a e^-a) it is 0 to round-off
        a = a if a < 708.0 else 708.0  # NaN too: a safe exponent (callers keep the NaN)
        a = a if a > 0.0 else 0.0
        k = int(a * 1.4426950408889634 + 0.5)
        r = (a - k * 0.693145751953125) - k * 1.4286068203094173e-06  # ln 2, two parts
        e = 2.08767569878681e-09
        e = e * r - 2.505210838544172e-08
        e = e * r + 2.755731922398589e-07
        e = e * r - 2.7557319223985893e-06
        e = e * r + 2.48015873015873e-05
        e = e * r - 0.0001984126984126984
        e = e * r + 0.001388888888888889
        e = e * r - 0.008333333333333333
        e = e * r + 0.041666666666666664
        e = e * r - 0.16666666666666666
        e = e * r + 0.5
        e = e * r - 1.0
        e = e * r + 1.0
        return e * _as_double((1023 - k) << 52)  # 2^-k: biased exponent 1023 - k

    @njit(cache=True, fastmath=_FAST)
    def exp_neg(a):
        """``exp(-a)`` as the kernels compute it (`_exp_neg`), for the tests [-]."""
        out = np.empty_like(a)
        for i in range(a.shape[0]):
            out[i] = _exp_neg(a[i])
        return out

    # many parameters: _ray and _contact keep scalar arguments (14 and 13): they are
    # inlined into the contact loop, where numba keeps scalars in registers; a tuple of
    # them would be rebuilt per ray, and the node loop must see plain scalars to vectorise.
    @njit(cache=True, fastmath=_FAST, inline="always")
    def _ray(pole, y0, v0, reach, sm, cm, r01, wr, dphi, c, fl, tab, deriv, ve):
        """Sums of the nodes on one ray from ``(0, y0)`` in the direction ``(cm, sm)``.

        The nodes are ``(rho cm, y0 + rho sm)``, ``rho = reach r01[j]``, with weights
        ``rho reach wr[j] dphi``; the sliding velocity there is ``(v0 + rho d_x, rho d_y)``,
        ``d = (-c_1 sm, c_2 cm)`` (``v0 = 0`` on the rays from the pole). ``c`` holds the
        contact's ``(c_1, c_2, c_3, c_4, u, 1/h, p_max, a_x, a_y)``: ``c_1 = u sigma a_y /
        r_c``, ``c_2 = u sigma a_x / r_c``, ``c_3 = u a_y / r_c``, ``c_4 = u a_x / r_c``.
        Returns the 8 sums of the module docstring, before scaling.
        """
        c3, c4, u, ih, pm, ax, ay = c[2], c[3], c[4], c[5], c[6], c[7], c[8]
        tl0, tl1, scale, modulus = fl[0], fl[1], fl[2], fl[3]
        last = tab.shape[0] - 2
        dx, dy = -c[0] * sm, c[1] * cm
        ray_speed = math.sqrt(dx * dx + dy * dy)  # |V| / rho on a ray from the pole
        s0 = s1 = s2 = s3 = s4 = s5 = s6 = s7 = 0.0
        for j in range(r01.shape[0]):
            rho = reach * r01[j]
            x = rho * cm
            y = y0 + rho * sm
            vx = v0 + rho * dx
            vy = rho * dy
            speed = rho * ray_speed if pole else math.sqrt(vx * vx + vy * vy)
            w = rho * reach * wr[j] * dphi
            p = pm * math.sqrt(max(1.0 - x * x - y * y, 0.0))
            # E = eta / tau_L from its cubic Hermite table (Roelands, Eq. 51; Eq. 54)
            v = p * scale
            i = min(int(v), last)
            t = v - i
            r = 1.0 - t
            e = r * r * ((1.0 + 2.0 * t) * tab[i, 0] + t * tab[i, 1]) + t * t * (
                (3.0 - 2.0 * t) * tab[i + 1, 0] - r * tab[i + 1, 1]
            )
            ek = e * ih  # eta / (h tau_L)
            eh = ek * (tl0 + tl1 * p)  # eta / h
            a = ek * speed
            # saturation (1 - exp(-a)) / a (Eq. 53): series below 1e-3 (error a^5 / 720)
            small = a < 1e-3
            inv_a = 1.0 / a if a > 0.0 else 0.0
            em = _exp_neg(a)
            if small:
                sat = 1.0 - a * (0.5 - a * (1.0 / 6.0 - a * (1.0 / 24.0 - a * (1.0 / 120.0))))
            else:
                sat = (1.0 - em) * inv_a
            g = eh * sat
            corr = 1.0
            lin_extra = 0.0
            if ve:
                # Maxwell elasticity (docs/model.md §14): tau = tau_steady (1 - exp(-theta)),
                # theta = G t / (eta sat), t = a_x (X + sqrt(1 - Y^2)) / u since entry
                t_in = ax * (x + math.sqrt(max(1.0 - y * y, 0.0)))
                theta = modulus * t_in * ih / (u * g) if u * g > 0.0 else 1e300
                e_theta = _exp_neg(theta)
                f = theta * (1.0 - 0.5 * theta) if theta < 1e-5 else 1.0 - e_theta
                corr = f - theta * e_theta
                lin_extra = -g * theta * e_theta
                g = g * f
            wx, wy = w * ax * x, w * ay * y
            tx, ty = g * vx, g * vy
            s0 += w * tx
            s1 += wx * ty - wy * tx
            if deriv:  # ALL, or LOG_U: d/dlog u alone (the others stay 0)
                if small:
                    slope = -0.5 + a / 3.0 - a * a / 8.0
                else:  # (e^-a - S) / a: no cancellation at large a (`saturation_slope`)
                    slope = (em - sat) * inv_a
                kk = eh * ek * ek * slope * inv_a  # (g'/|V|) / |V|: eh ek slope / |V|
                if ve:
                    kk *= corr
                if deriv == ALL:  # d/dc: dV = (u, 0)
                    dtx = g * u + kk * vx * u * vx
                    dty = kk * vx * u * vy
                    s2 += w * dtx
                    s5 += wx * dty - wy * dtx
                    # d/dsigma: dV = (-u a_y y / r_c, u a_x x / r_c)
                    dvx = -c3 * y
                    dvy = c4 * x
                    dot = vx * dvx + vy * dvy
                    dtx = g * dvx + kk * dot * vx
                    dty = g * dvy + kk * dot * vy
                    s3 += w * dtx
                    s6 += wx * dty - wy * dtx
                # d/dlog u: dV = V
                lin = g + kk * speed * speed
                if ve:
                    lin += lin_extra
                s4 += w * lin * vx
                s7 += lin * (wx * vy - wy * vx)
        return s0, s1, s2, s3, s4, s5, s6, s7

    # many parameters: see _ray (inlined, scalars kept in registers).
    @njit(cache=True, fastmath=_FAST, inline="always")
    def _contact(pole, y0, v0, c, r01, wr, sin_phi, cos_phi, dphi, fl, tab, deriv, ve):
        """One contact's 8 sums on the rays from its pole (``pole``) or from the centre."""
        a0 = a1 = a2 = a3 = a4 = a5 = a6 = a7 = 0.0
        for m in range(sin_phi.shape[0]):
            sm, cm = sin_phi[m], cos_phi[m]
            if pole:
                b = y0 * sm
                reach = -b + math.sqrt(b * b + (1.0 - y0 * y0))
            else:
                reach = 1.0
            s = _ray(pole, y0, v0, reach, sm, cm, r01, wr, dphi, c, fl, tab, deriv, ve)
            a0 += s[0]
            a1 += s[1]
            a2 += s[2]
            a3 += s[3]
            a4 += s[4]
            a5 += s[5]
            a6 += s[6]
            a7 += s[7]
        return a0, a1, a2, a3, a4, a5, a6, a7

    @njit(cache=True, fastmath=_FAST, inline="always")
    def contact_sums(par, i, h, rule, table, deriv, ve):
        """The scaled sums of contact ``i`` (a column of ``par``) at the film ``h`` [m]: the
        pole-centred rule while the pole is well inside, the centred rule once it is
        outside, blended in between with the weight ``w = t^2 (3 - 2 t)``, ``t = (blend[1] -
        |Y_p|) / (blend[1] - blend[0])`` clipped to [0, 1]
        (`ballcvt.model.traction.isothermal`); ``blend[1] <= blend[0]``: the centred rule
        alone. A NaN pole gives NaN sums. ``rule``: ``(r01, wr, pole_rays, centred_rays,
        blend)``, ``table``: ``(fl, tab)`` (`traction_kernel`); ``deriv``: False, `LOG_U`
        (the derivatives by ``log u`` alone, the others 0) or `ALL`. The thermal law's
        kernel calls it at its own films (`ballcvt.model.traction.thermal_kernels`)."""
        fl, tab = table
        r01, wr, pole_rays, centred_rays, blend = rule
        sp, cp, dp = pole_rays
        sc, cc, dc = centred_rays
        lo, hi = blend
        cr, sg, ax, ay, pm = par[0, i], par[1, i], par[2, i], par[3, i], par[4, i]
        fn, rc, u = par[5, i], par[6, i], par[7, i]
        c = (u * sg * ay / rc, u * sg * ax / rc, u * ay / rc, u * ax / rc, u, 1.0 / h, pm, ax, ay)
        sy = sg * ay / rc
        yp = cr / sy if abs(sy) > 1e-300 else math.inf  # Y_p (`pole_position`)
        w = 0.0
        if hi > lo:
            t = (hi - abs(yp)) / (hi - lo)
            if t > 1.0:
                t = 1.0
            elif t < 0.0:
                t = 0.0
            w = t * t * (3.0 - 2.0 * t)  # NaN stays NaN
        b0 = b1 = b2 = b3 = b4 = b5 = b6 = b7 = 0.0
        if w > 0.0:
            s = _contact(True, yp, 0.0, c, r01, wr, sp, cp, dp, fl, tab, deriv, ve)
            b0, b1, b2, b3 = w * s[0], w * s[1], w * s[2], w * s[3]
            b4, b5, b6, b7 = w * s[4], w * s[5], w * s[6], w * s[7]
        if not w >= 1.0:
            k = 1.0 - w
            s = _contact(False, 0.0, cr * u, c, r01, wr, sc, cc, dc, fl, tab, deriv, ve)
            b0, b1, b2, b3 = b0 + k * s[0], b1 + k * s[1], b2 + k * s[2], b3 + k * s[3]
            b4, b5, b6, b7 = b4 + k * s[4], b5 + k * s[5], b6 + k * s[6], b7 + k * s[7]
        f = ax * ay / fn
        fc = f / rc
        return b0 * f, b1 * fc, b2 * f, b3 * f, b4 * f, b5 * fc, b6 * fc, b7 * fc

    @njit(cache=True, fastmath=_FAST, inline="always")
    def _blended(par, rule, fl, tab, deriv, ve, out):
        """Every contact's scaled sums (rows of ``out``, `contact_sums`)."""
        for i in range(par.shape[1]):
            s = contact_sums(par, i, par[8, i], rule, (fl, tab), deriv, ve)
            for j in range(N_OUT):
                out[i, j] = s[j]

    # the four specialisations (derivatives, visco-elastic): flags fixed at compile time
    @njit(cache=True, fastmath=_FAST)
    def _blended_plain(par, rule, fl, tab, out):
        _blended(par, rule, fl, tab, False, False, out)

    @njit(cache=True, fastmath=_FAST)
    def _blended_deriv(par, rule, fl, tab, out):
        _blended(par, rule, fl, tab, ALL, False, out)

    @njit(cache=True, fastmath=_FAST)
    def _blended_ve(par, rule, fl, tab, out):
        _blended(par, rule, fl, tab, False, True, out)

    @njit(cache=True, fastmath=_FAST)
    def _blended_ve_deriv(par, rule, fl, tab, out):
        _blended(par, rule, fl, tab, ALL, True, out)

    _SPECIALISED = {
        (False, False): _blended_plain,
        (True, False): _blended_deriv,
        (False, True): _blended_ve,
        (True, True): _blended_ve_deriv,
    }

    def traction_kernel(par, rule, table, deriv, out):
        """The traction sums of every contact (rows of ``out``, ``(n, 8)``).

        ``par``: the contacts' ``(c, sigma, a_x, a_y, p_max, F_N, r_c, u, h)`` as rows
        ``(9, n)`` (`ContactState.stacked`); ``rule``: ``(r01, wr, pole_rays,
        centred_rays, blend)``, the radial nodes on [0, 1] and weights (`radial_rule`),
        each rule's rays ``(sin phi, cos phi, dphi)`` and the ``|Y_p|`` range over which the
        pole-centred rule hands over to the centred one (``(0, 0)``: the centred rule
        alone); ``table``: ``(fl, tab)`` from `viscosity_table`; ``deriv``: also the
        derivatives.
        """
        fl, tab = table
        kernel = _SPECIALISED[_kernel_flags(deriv, fl)]
        kernel(par, rule, fl, tab, out)


else:  # pragma: no cover
    traction_kernel = exp_neg = contact_sums = None  # type: ignore[assignment]
