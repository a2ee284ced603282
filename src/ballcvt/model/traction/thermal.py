"""Thermal traction law: shear heating raises the film temperature (docs/model.md §14).

The paper's law (Eq. 53) is isothermal. Here each contact's film runs at one temperature
``T_in + dT`` above the inlet, with the viscosity and the limiting shear stress
thinned by it:

    ``eta = eta_R(p) exp(-beta dT)``, ``tau_L = (tau_L0 + a p) exp(-beta_L dT)``.

The rise ``dT`` is the mean heat flux of the contact, ``q = Q / (pi a_x a_y)``, times two
thermal resistances in series, after Olver and Spikes (1998, Proc. IMechE J 212, 321):

* the flash temperature of the surfaces, each taking half the heat through a moving
  semi-infinite solid at high Peclet number (Jaeger 1942; Carslaw and Jaeger 1959 §2.9):
  the mean over the contact of ``2 (q/2) sqrt(kappa t / pi) / K`` with ``t = (x + a_x)/u``,
  ``R_flash = 1.064 sqrt(kappa a_x / u) / (2 K)``;
* the temperature rise of the mid-film over the surfaces with the heat generated
  uniformly across a Couette film, ``R_film = h / (8 k)``.

The shear heat of a contact is its sliding power, ``Q = u F_N (c mu + sigma chi)``: the
integral of ``tau . V`` over the ellipse written with the definitions of ``mu`` and
``chi`` (Eqs. 57-66). With one temperature per contact, the shear law becomes the
isothermal one with ``h`` scaled and ``tau`` scaled:

    ``tau(dT) = exp(-beta_L dT) tau_iso(h exp((beta - beta_L) dT))``

(Eq. 53 depends on ``eta / h`` and ``eta / tau_L`` only), so the isothermal quadrature
serves unchanged. ``dT`` solves ``dT = (R_flash + R_film) q(dT)`` by safeguarded Newton
on the cheap `TEMPERATURE_RULE`, then one Newton step on the requested rule.

The traction at fixed speed peaks at a creep of a few per cent and then falls (the heat
grows with the sliding), so the drive can have two equilibria at one operating point: one
on the branch that starts at zero torque, one past its fold (on Table I's drive at 2 kN,
1000 rpm, ratio 0.718 and 130 N m: efficiency 0.9247 and 0.8935). The drive reaches the
first; the law is registered with ``multiple_equilibria=True``, so every solver follows each
point from zero torque (`ballcvt.solvers.continuation`, docs/model.md §14).
"""

from __future__ import annotations

import numpy as np

from ...params.models import Fluid
from . import kernels, thermal_kernels
from .contact import ContactState, legacy_arguments
from .isothermal import kernel_rule, kernel_table, shear_coefficients
from .quadrature import Quadrature

__all__ = [
    "thermal_law_coefficients",
    "thermal_law_film_coefficients",
    "thermal_law_rise",
    "temperature_rise",
    "thermal_coefficients",
    "thermal_coefficients_and_rise",
    "film_temperature_rise",
    "TEMPERATURE_RULE",
    "FLASH_FACTOR",
]

#: Cheap rule on which Newton finds the film temperature before one step on the
#: requested rule (`_rise_and_coefficients`).
TEMPERATURE_RULE = Quadrature("pole", 8, 8, 8)
#: Mean flash temperature of a uniform moving source at high Peclet number,
#: ``(4/3) sqrt(2/pi)`` (Jaeger 1942).
FLASH_FACTOR = 4.0 / 3.0 * np.sqrt(2.0 / np.pi)


class _Contacts:
    """Flat contact arrays and the temperature-independent parts of the heat balance."""

    def __init__(self, args, fluid: Fluid):
        (self.c, self.s, self.ax, self.ay, self.pm, self.fn, self.rc, self.u, self.h) = args
        self.fluid = fluid
        #: The contacts as the compiled kernel's rows ``(9, n)`` where stacked already.
        self.par: np.ndarray | None = None
        values = (
            fluid.temperature_viscosity_coefficient,
            fluid.limiting_shear_temperature_coefficient,
            fluid.thermal_conductivity,
            fluid.surface_conductivity,
            fluid.surface_diffusivity,
        )
        if any(v is None for v in values):
            raise ValueError(f"fluid '{fluid.name}' lacks the thermal law's parameters")
        beta, beta_l, k_f, k_s, kappa = (float(v) for v in values if v is not None)
        self.beta_l = beta_l
        self.b = beta - beta_l
        self.load_flux = self.fn / (np.pi * self.ax * self.ay)  # F_N / contact area
        self.r_flash = FLASH_FACTOR * np.sqrt(kappa * self.ax / self.u) / (2.0 * k_s)
        # thermal resistance of the contact, flash and film in series [K m^2/W]
        self.resistance = self.r_flash + self.h / (8.0 * k_f)

    @classmethod
    def from_state(cls, state: ContactState, fluid: Fluid) -> tuple[_Contacts, tuple[int, ...]]:
        """Contacts of ``state`` as flat arrays, and their shape."""
        params, shape = state.stacked()
        con = cls(list(params), fluid)
        con.par = params  # the compiled kernel's input as it is (`_compiled`)
        return con, shape

    def take(self, i) -> _Contacts:
        out = object.__new__(_Contacts)
        out.__dict__.update(
            {
                k: (v[i] if isinstance(v, np.ndarray) else v)
                for k, v in self.__dict__.items()
                if k != "par"
            }
        )
        out.par = None
        return out

    def at(self, dt, quadrature: Quadrature):
        """``mu, chi`` and their partials ``(c, sigma, log u, dT)`` at the rises ``dt``."""
        f_t = np.exp(-self.beta_l * dt)
        state = ContactState(
            self.c, self.s, self.ax, self.ay, self.pm, self.fn, self.rc, self.u, self.h
        )
        mu, chi, dmu, dchi = shear_coefficients(
            state.replace(film=self.h * np.exp(self.b * dt)), self.fluid, quadrature, True
        )
        mu, chi, dmu, dchi = f_t * mu, f_t * chi, f_t[:, None] * dmu, f_t[:, None] * dchi
        d_t = lambda v, dv: -self.beta_l * v - self.b * dv[:, 2]  # noqa: E731
        return (
            mu,
            chi,
            np.column_stack([dmu, d_t(mu, dmu)]),
            np.column_stack([dchi, d_t(chi, dchi)]),
        )

    def flux(self, mu, chi):
        """Mean shear-heat flux ``Q / (pi a_x a_y)`` [W/m^2]; linear in ``mu, chi``, so of
        their derivatives it gives the flux's (columns of ``(n, k)`` arrays: one each)."""
        k, c, s = self.load_flux * self.u, self.c, self.s
        if np.ndim(mu) == 2:
            k, c, s = k[:, None], c[:, None], s[:, None]
        return k * (c * mu + s * chi)


def _solve_rise(con: _Contacts, quadrature: Quadrature, tol=thermal_kernels.RISE_RTOL,
                max_iter=60):  # fmt: skip
    """``dT = R q(dT)`` per contact: Newton, kept inside the bracket ``[0, R q(0)]``."""
    r = con.resistance
    dt = np.zeros(con.c.shape)
    lo, hi = np.zeros_like(dt), np.full_like(dt, np.inf)
    todo = np.arange(dt.size)
    for _ in range(max_iter):
        sub = con.take(todo)
        mu, chi, dmu, dchi = sub.at(dt[todo], quadrature)
        q = sub.flux(mu, chi)
        q_t = sub.flux(dmu[:, 3], dchi[:, 3])
        g = dt[todo] - r[todo] * q
        lo[todo] = np.where(g <= 0.0, dt[todo], lo[todo])
        hi[todo] = np.where(g >= 0.0, dt[todo], hi[todo])
        slope = 1.0 - r[todo] * q_t
        new = dt[todo] - g / np.where(slope > 0.0, slope, np.inf)
        hi_t, lo_t = hi[todo], lo[todo]
        outside = (new <= lo_t) | (new >= hi_t) | (slope <= 0.0)
        new = np.where(outside, np.where(np.isfinite(hi_t), 0.5 * (lo_t + hi_t), r[todo] * q), new)
        step = np.abs(new - dt[todo])
        dt[todo] = new
        todo = todo[step > tol * (1.0 + np.abs(new))]
        if todo.size == 0:
            break
    return dt


def _rise_and_coefficients(con: _Contacts, quadrature: Quadrature, partials: bool = True):
    """The rise on the requested rule and the coefficients there (4-column partials).

    Newton converges on `TEMPERATURE_RULE`; one Newton step on ``quadrature`` then moves
    the rise to that rule's fixed point, and the coefficients with it (to first order:
    the remaining error is the square of a step of a fraction of a kelvin). The partials
    at a fixed rise are taken to the stepped rise by their limiting-shear factor
    ``exp(-beta_L step)`` (since session 36; they were the unstepped rise's, and Newton's
    Jacobian off by some 3e-3: `tests/test_thermal_partials.py`); their dependence on the
    rise through the film, ``h exp((beta - beta_L) dT)``, stays the unstepped rise's. In one
    compiled call (`ballcvt.model.traction.thermal_kernels`) when both rules use the
    compiled engine (without ``partials`` there, those by ``c`` and ``sigma`` are 0); the
    NumPy path (`_solve_rise`) otherwise.
    """
    compiled = quadrature.engine == TEMPERATURE_RULE.engine == "auto"
    if compiled and kernels.AVAILABLE and con.c.size:
        return _compiled(con, quadrature, partials)
    dt = _solve_rise(con, TEMPERATURE_RULE)
    mu, chi, dmu, dchi = con.at(dt, quadrature)
    r = con.resistance
    step = -(dt - r * con.flux(mu, chi)) / (1.0 - r * con.flux(dmu[:, 3], dchi[:, 3]))
    step = np.maximum(step, -dt)  # the rise stays >= 0
    f_t = np.exp(-con.beta_l * step)[:, None]  # the partials' tau_L factor at dT + step
    return dt + step, mu + dmu[:, 3] * step, chi + dchi[:, 3] * step, dmu * f_t, dchi * f_t


def _compiled(con: _Contacts, quadrature: Quadrature, partials: bool):
    """`_rise_and_coefficients` by the compiled kernel (the same steps, per contact;
    without ``partials`` those by ``c`` and ``sigma`` are 0)."""
    par = con.par
    if par is None:
        par = np.stack(np.broadcast_arrays(con.c, con.s, con.ax, con.ay, con.pm, con.fn,
                                           con.rc, con.u, con.h))  # fmt: skip
    par = np.ascontiguousarray(par, dtype=float)
    out = np.empty((par.shape[1], thermal_kernels.N_THERMAL))
    contact = (
        np.ascontiguousarray(con.load_flux * con.u, dtype=float),
        np.ascontiguousarray(con.resistance, dtype=float),
    )
    rules = (kernel_rule(TEMPERATURE_RULE), kernel_rule(quadrature))
    table = kernel_table(con.fluid, float(par[4].max()))
    heat = (con.beta_l, con.b)
    thermal_kernels.thermal_kernel(par, contact, rules, table, heat, out, partials)
    return out[:, 0], out[:, 1], out[:, 2], out[:, 3:7], out[:, 7:11]


def temperature_rise(
    state: ContactState, fluid: Fluid, quadrature: Quadrature = Quadrature()
) -> np.ndarray:
    """Film temperature rise ``dT`` above the inlet of contacts under the thermal law [K].

    Parameters are those of `thermal_law_coefficients` (same units).
    """
    return thermal_law_rise(state, fluid, quadrature)[2]


def thermal_law_rise(state: ContactState, fluid: Fluid, quadrature: Quadrature = Quadrature()):
    """``mu``, ``chi`` [-] and the film temperature rise ``dT`` [K] from one solve of the
    film temperature (parameters as in `thermal_law_coefficients`)."""
    con, shape = _Contacts.from_state(state, fluid)
    dt, mu, chi, _, _ = _rise_and_coefficients(con, quadrature, partials=False)
    return mu.reshape(shape), chi.reshape(shape), dt.reshape(shape)


def thermal_law_coefficients(
    state: ContactState,
    fluid: Fluid,
    quadrature: Quadrature = Quadrature(),
    derivatives: bool = False,
):
    """``mu`` and ``chi`` of contacts under the thermal law (module docstring).

    Parameters and returns are those of
    `ballcvt.model.traction.isothermal.shear_coefficients`: the contacts' ``state``
    (`ContactState`: ``creep_term`` [-], ``spin`` [-], ``ax, ay`` [m], ``p_max`` [Pa],
    ``load`` [N], ``radius`` [m], ``u_ref`` [m/s], ``film`` [m]). The fluid needs the
    thermal fields (`ballcvt.params.Fluid`). The derivatives include the film
    temperature's response (implicit function theorem); the one with respect to ``log u``
    is at fixed ``film`` (the identity with ``-d/dlog h`` of the isothermal law does not
    hold with heating; Newton's Jacobians only use it).
    """
    con, shape = _Contacts.from_state(state, fluid)
    _, mu, chi, dmu, dchi = _rise_and_coefficients(con, quadrature, derivatives)
    if not derivatives:
        return mu.reshape(shape), chi.reshape(shape)
    return _with_derivatives(con, (mu, chi, dmu, dchi), shape, film=False)


def thermal_law_film_coefficients(
    state: ContactState, fluid: Fluid, quadrature: Quadrature = Quadrature()
):
    """`thermal_law_coefficients` with its derivatives, and a fourth column: by ``log h``
    at a fixed ``u_ref / h`` (the lubrication models' fourth column,
    `ballcvt.model.lubrication`).

    Eq. 53 depends on the speed and the film through ``u_ref / h`` only, the film
    temperature does not: the thermal resistance grows with ``h`` (the film's, ``h / 8
    k``) and falls as ``u^(-1/2)`` (the flash's), and the heat grows with ``u``. Moving
    ``log u`` and ``log h`` together (``d log h`` at fixed ``u / h``) leaves Eq. 53 at a
    fixed rise and moves the rise by ``d dT = q (2 R - 3 R_flash / 2) / (1 - R dq/ddT)``
    (implicit function theorem). With it Newton's Jacobian has the film thickness's
    dependence on the creeps too, and converges quadratically.

    Parameters as in `thermal_law_coefficients`; returns ``mu, chi`` [-] and ``dmu,
    dchi`` of shape ``(..., 4)``.
    """
    con, shape = _Contacts.from_state(state, fluid)
    _, mu, chi, dmu, dchi = _rise_and_coefficients(con, quadrature)
    return _with_derivatives(con, (mu, chi, dmu, dchi), shape, film=True)


def _with_derivatives(con: _Contacts, values, shape, film: bool):
    """``mu, chi`` and their total derivatives (the rise's response included) by the creep
    term, the spin, ``log u`` at a fixed film and, with ``film``, ``log h`` at a fixed
    ``u / h``; ``values``: ``mu, chi`` and their 4-column partials at a fixed rise. In one
    compiled loop where numba is installed (`thermal_kernels.total_derivatives`, the same
    bits), else by `_totals`."""
    mu, chi = values[:2]
    if thermal_kernels.total_derivatives is not None:
        dmu_total, dchi_total = thermal_kernels.total_derivatives(
            values, (con.load_flux * con.u, con.resistance, con.r_flash), (con.c, con.s), film
        )
    else:
        dmu_total, dchi_total = _totals(con, values, film)
    n = dmu_total.shape[1]
    return (
        mu.reshape(shape),
        chi.reshape(shape),
        dmu_total.reshape(shape + (n,)),
        dchi_total.reshape(shape + (n,)),
    )


def _totals(con: _Contacts, values, film: bool):
    """The total derivatives ``(dmu, dchi)`` of `_with_derivatives`, by NumPy (the
    reference of the compiled loop)."""
    mu, chi, dmu, dchi = values
    q = con.flux(mu, chi)
    k = con.load_flux * con.u
    r = con.resistance
    slopes = con.flux(dmu, dchi)  # the flux's partials (c, sigma, log u, dT) at fixed c, sigma
    # d q / d(c, sigma, log u): q is also linear in c, sigma and proportional to u
    dq = slopes[:, :3] + np.column_stack([k * mu, k * chi, q])
    dr = np.column_stack([np.zeros_like(q), np.zeros_like(q), -0.5 * con.r_flash])
    if film:  # d log h at fixed u / h: dq = q, dR = R - 3 R_flash / 2 (the docstring)
        dq = np.column_stack([dq, q])
        dr = np.column_stack([dr, r - 1.5 * con.r_flash])
    d_dt = (r[:, None] * dq + q[:, None] * dr) / (1.0 - r * slopes[:, 3])[:, None]
    dmu_total = dmu[:, 3:] * d_dt
    dchi_total = dchi[:, 3:] * d_dt
    dmu_total[:, :3] += dmu[:, :3]  # Eq. 53 at a fixed rise: no d log h at fixed u / h
    dchi_total[:, :3] += dchi[:, :3]
    return dmu_total, dchi_total


def film_temperature_rise(*args, **kwargs):
    """Deprecated: the nine contact arrays, then ``fluid, quadrature``; use
    `temperature_rise` of a `ContactState`."""
    state, rest, kw = legacy_arguments(
        "film_temperature_rise(creep_term, ..., film, fluid)",
        "temperature_rise(ContactState(creep_term, ..., film), fluid)",
        args,
        kwargs,
    )
    return temperature_rise(state, *rest, **kw)


def thermal_coefficients_and_rise(*args, **kwargs):
    """Deprecated: the nine contact arrays, then ``fluid, quadrature``; use
    `thermal_law_rise` of a `ContactState`."""
    state, rest, kw = legacy_arguments(
        "thermal_coefficients_and_rise(creep_term, ..., film, fluid)",
        "thermal_law_rise(ContactState(creep_term, ..., film), fluid)",
        args,
        kwargs,
    )
    return thermal_law_rise(state, *rest, **kw)


def thermal_coefficients(*args, **kwargs):
    """Deprecated: the nine contact arrays, then ``fluid, quadrature, derivatives``; use
    `thermal_law_coefficients` of a `ContactState`."""
    state, rest, kw = legacy_arguments(
        "thermal_coefficients(creep_term, ..., film, fluid)",
        "thermal_law_coefficients(ContactState(creep_term, ..., film), fluid)",
        args,
        kwargs,
    )
    return thermal_law_coefficients(state, *rest, **kw)
