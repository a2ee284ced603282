"""The equilibrium residual (docs/model.md §5), separate from any solver.

Unknowns: the creep coefficients of all contacts. Given them, `evaluate` computes the
speeds, spins, film thicknesses, traction and spin coefficients, contact forces and
moments, axle reactions, bearing torques and the residuals of

* the ball's moment balance about its spin axis ``s``;
* each idler's torque balance about ``j``;
* the output disc's torque balance (the rollers' torque on it equals ``T_2``).

Balances in vector form (docs/model.md §5), per ball, with ``F_c = kappa_c mu_c F_Nc`` along
``+i`` and the spin moment ``T_c = -chi_c F_Nc r_c`` about ``z_c``:

* ``M.s = sum_c (r_S rho_c F_c + (s.z_c) T_c)``, residual ``(M.s - T_BLS) / (F_N0 r_S)``
  (the corrected Eq. 18/33);
* ``M.u = sum_c (-r_S (s.z_c) F_c + rho_c T_c)`` gives ``F_Ra - F_Rb = 2 M.u / r_S``
  (Eq. 19/34) and ``F_Ra + F_Rb = -sum_c F_c`` (Eq. 17/35);
* body torque ``T_body,c = n (-F_c r_c - T_c z_c.j)``; idler residual
  ``(T_body - sign(Omega) T_BL) / (n F_N0 r_S)``; output ``(T_body,2 - T_2) / (n F_N0 r_S)``;
  input torque ``T_0 = -T_body,0`` (Eqs. 21-27, 32).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..model.bearings import load_dependent_torque, speed_dependent_torque
from ..model.film import SPEED_EXPONENT, central_film_thickness
from ..model.kinematics import body_speeds, creep_term, entrainment_factor, spin
from ..model.losses import DragMagnitudes, shaft_drags
from ..model.lubrication import asperities, lubricated_coefficients
from ..model.traction.contact import ContactState
from ..model.traction.quadrature import Quadrature
from . import compiled
from .problem import EquilibriumProblem

__all__ = [
    "EquilibriumState",
    "evaluate",
    "evaluate_with_jacobian",
    "balancing_output_torque",
    "carrier_reaction_torque",
]


@dataclass(frozen=True)
class EquilibriumState:
    """Every quantity that follows from a creep vector (arrays ``(...)`` or ``(..., n_c)``).

    Attributes
    ----------
    creep : ndarray
        Creep coefficients (Eq. 7) [-].
    omega_s : ndarray
        Ball speed about its axis [rad/s].
    omega : ndarray
        Signed body speeds about ``j`` [rad/s].
    spin : ndarray
        Spin coefficients (Eqs. 11-14) [-].
    u_ref : ndarray
        Body surface speed ``|Omega_c| r_c`` [m/s].
    film : ndarray
        Central film thickness [m].
    mu, chi : ndarray
        Traction and spin-moment coefficients (Eqs. 30-31) [-].
    force : ndarray
        Tangential force on the ball along ``+i``, ``F_c`` [N].
    moment : ndarray
        Spin moment on the ball about ``z_c``, ``T_c`` [N m].
    body_torque : ndarray
        Torque of the ``n`` balls on each body about ``j`` [N m].
    axle_reactions : ndarray
        ``(F_Ra, F_Rb)`` along ``i`` [N], shape ``(..., 2)``.
    roller_bearing_torque : ndarray
        ``T_BLS`` [N m].
    idler_bearing_torque : ndarray
        ``T_BL,c`` of each contact's body (0 where not an idler) [N m].
    residual : ndarray
        Dimensionless residuals, shape ``(..., n_c)``: ball moment, idlers, output.
    input_drag, output_drag : ndarray
        Parasitic drags on the input and output shafts at the solved speeds, opposing
        each shaft's rotation and, for the disc thrust bearing, the discs' relative speed
        [N m] (docs/model.md §12; zero by default).
    """

    creep: np.ndarray
    omega_s: np.ndarray
    omega: np.ndarray
    spin: np.ndarray
    u_ref: np.ndarray
    film: np.ndarray
    mu: np.ndarray
    chi: np.ndarray
    force: np.ndarray
    moment: np.ndarray
    body_torque: np.ndarray
    axle_reactions: np.ndarray
    roller_bearing_torque: np.ndarray
    idler_bearing_torque: np.ndarray
    residual: np.ndarray
    input_drag: np.ndarray
    output_drag: np.ndarray

    def take(self, index) -> EquilibriumState:
        """The points ``index`` (integer or boolean array) of a 1-D batch."""
        return EquilibriumState(**{name: np.asarray(v)[index] for name, v in vars(self).items()})

    def put(self, index, other: EquilibriumState) -> EquilibriumState:
        """A copy with the points ``index`` of a 1-D batch replaced by ``other``'s."""
        fields = {}
        for name, value in vars(self).items():
            value = np.array(value, copy=True)
            value[index] = getattr(other, name)
            fields[name] = value
        return EquilibriumState(**fields)

    @classmethod
    def joined(cls, size: int, parts) -> EquilibriumState:
        """A 1-D batch of ``size`` points from ``parts``, pairs ``(index, state)`` that
        cover every point once."""
        first = parts[0][1]
        fields = {}
        for name, value in vars(first).items():
            out = np.empty((size,) + np.shape(value)[1:], dtype=np.asarray(value).dtype)
            for index, part in parts:
                out[index] = getattr(part, name)
            fields[name] = out
        return cls(**fields)

    @property
    def input_torque(self) -> np.ndarray:
        """Input shaft torque ``T_0 = -T_body,0`` plus the input shaft's parasitic drag
        (zero without ``design.parasitic``) [N m]."""
        return -self.body_torque[..., 0] + self.input_drag


def evaluate(
    problem: EquilibriumProblem, creep, quadrature: Quadrature = Quadrature()
) -> EquilibriumState:
    """Evaluate every balance of ``problem`` at the creep vector ``creep``.

    Parameters
    ----------
    problem : EquilibriumProblem
        Operating point(s).
    creep : array_like
        Creep coefficients, shape ``problem.shape + (n_c,)``, each < 1 [-].
    quadrature : Quadrature
        Rule for the traction integrals.

    Returns
    -------
    EquilibriumState
    """
    creep = np.asarray(creep, dtype=float)
    unit, k = _film_unit(problem), _constants(problem)
    if compiled.covers(problem, k):
        return _compiled_rows(problem, creep, None, quadrature, (unit, k))[0]
    at = _contact_inputs(problem, creep)
    mu, chi = lubricated_coefficients(
        ContactState(
            creep_term(creep),
            at.spin,
            problem.ax,
            problem.ay,
            problem.p_max,
            problem.load,
            problem.radius,
            at.u_ref,
            at.film,
        ),
        problem.fluid,
        _asperities(problem),
        quadrature,
    )
    return _balances(problem, creep, at, mu, chi)


def _asperities(problem: EquilibriumProblem):
    """The problem's lubrication model and asperity parameters (`ballcvt.model.lubrication`)."""
    return problem.memo("asperities", lambda: asperities(problem.design))


def evaluate_with_jacobian(
    problem: EquilibriumProblem, creep, quadrature: Quadrature = Quadrature(), step: float = 1e-7
):
    """`evaluate` and the Jacobian of its residual with respect to the creeps.

    The traction integrals, the costly part, are evaluated once with their analytic
    derivatives (`contact_coefficients` with ``derivatives=True``). The Jacobian then
    follows by forward differences of the cheap rest (kinematics, film thickness,
    balances, bearings) with the traction coefficients linearised, all creeps perturbed
    at once along an extra batch axis.

    Parameters
    ----------
    problem : EquilibriumProblem
        Operating point(s), batch shape ``(...)``.
    creep : array_like
        Creeps, shape ``(..., n_c)`` [-].
    quadrature : Quadrature
        Rule for the traction integrals.
    step : float
        Relative difference step (floor ``1e-4`` on ``|creep|``) [-].

    Returns
    -------
    state : EquilibriumState
    jacobian : ndarray
        ``d residual_i / d creep_j``, shape ``(..., n_c, n_c)`` [-].
    """
    creep = np.asarray(creep, dtype=float)
    nc = creep.shape[-1]
    h = step * np.maximum(np.abs(creep), 1e-4)
    unit, k = _film_unit(problem), _constants(problem)  # (its sub-batches keep them)
    if compiled.covers(problem, k):
        return _compiled_rows(problem, creep, h, quadrature, (unit, k))
    # row 0: the creeps themselves; row j + 1: creep j perturbed by h_j (one pass for all)
    pert = creep[..., None, :] + h[..., None, :] * _offsets(nc)  # (..., 1 + n_c, n_c)
    wide = problem.expand()
    wide_at = _contact_inputs(wide, pert)
    sg, u, hf = wide_at.spin, wide_at.u_ref, wide_at.film
    c = creep_term(pert)
    at = (slice(None),) * len(problem.shape) + (0,)  # row 0 of the wide axis
    mu, chi, dmu, dchi = lubricated_coefficients(
        ContactState(
            c[at],
            sg[at],
            problem.ax,
            problem.ay,
            problem.p_max,
            problem.load,
            problem.radius,
            u[at],
            hf[at],
        ),
        problem.fluid,
        _asperities(problem),
        quadrature,
        derivatives=True,
    )
    ex = lambda v: v[..., None, :]  # noqa: E731
    delta = np.empty(c.shape + (dmu.shape[-1],))
    delta[..., 0] = c - ex(c[at])
    delta[..., 1] = sg - ex(sg[at])
    delta[..., 2] = np.log((u * ex(hf[at])) / (ex(u[at]) * hf))  # d log u - d log h
    if dmu.shape[-1] == 4:  # a lubrication model's own film dependence (§16)
        delta[..., 3] = np.log(hf / ex(hf[at]))
    mu_p = ex(mu) + (dmu[..., None, :, :] * delta).sum(axis=-1)
    chi_p = ex(chi) + (dchi[..., None, :, :] * delta).sum(axis=-1)
    mu_p[at], chi_p[at] = mu, chi
    wide_state = _balances(wide, pert, wide_at, mu_p, chi_p)
    state = EquilibriumState(
        **{
            name: v[at] if getattr(v, "ndim", 0) >= len(at) else v
            for name, v in vars(wide_state).items()
        }
    )
    res = wide_state.residual
    jac = (res[..., 1:, :] - res[..., :1, :]) / h[..., :, None]  # (..., j, i)
    return state, np.swapaxes(jac, -1, -2)


def _compiled_rows(problem: EquilibriumProblem, creep, h, quadrature, memos):
    """`evaluate_with_jacobian` (``h``: the creeps' steps), or `evaluate` (``h`` None: a
    Jacobian of None) by the compiled kernels (`ballcvt.equilibrium.compiled.evaluate_rows`)."""
    fields, res = compiled.evaluate_rows(
        problem, creep, h, quadrature, memos + (_asperities(problem),)
    )
    state = object.__new__(EquilibriumState)  # every field given: no __init__ to run
    state.__dict__.update(fields)
    return state, None if h is None else compiled.jacobian_rows(res, h)


@lru_cache(maxsize=8)
def _offsets(nc: int) -> np.ndarray:
    """Row 0: no perturbation; row ``j + 1``: creep ``j`` perturbed (read-only)."""
    out = np.concatenate([np.zeros((1, nc)), np.eye(nc)])
    out.flags.writeable = False
    return out


@dataclass(frozen=True)
class ContactInputs:
    """What the traction law is evaluated at, from a creep vector (Eqs. 7-14, 56).

    Attributes
    ----------
    omega_s : ndarray
        Ball speed about its axis [rad/s].
    omega : ndarray
        Signed body speeds about ``j`` [rad/s].
    spin : ndarray
        Spin coefficients [-].
    u_ref : ndarray
        Body surface speed [m/s].
    film : ndarray
        Central film thickness [m].
    """

    omega_s: np.ndarray
    omega: np.ndarray
    spin: np.ndarray
    u_ref: np.ndarray
    film: np.ndarray


def _contact_inputs(problem: EquilibriumProblem, creep) -> ContactInputs:
    """Speeds, spins, surface speeds and film thicknesses at the creeps (Eqs. 7-14, 67)."""
    lay = problem.layout
    omega_s, omega = body_speeds(lay, problem.tilt, creep, problem.input_speed, problem.rho)
    sigma = spin(lay, problem.tilt, omega_s, omega, problem.sz)
    u_ref = np.abs(omega) * problem.radius
    unit = _film_unit(problem)
    film = unit * np.abs(u_ref * entrainment_factor(creep)) ** SPEED_EXPONENT
    return ContactInputs(omega_s, omega, sigma, u_ref, film)


def _film_unit(problem: EquilibriumProblem):
    """Eq. 56 at 1 m/s, kept on the problem and carried to its sub-batches
    (`EquilibriumProblem.memo`), to be multiplied by the speed term (`SPEED_EXPONENT`)
    [m]."""
    fl = problem.fluid
    return problem.memo(
        "film_unit_speed",
        lambda: central_film_thickness(
            fl.viscosity,
            fl.pressure_viscosity_coefficient,
            problem.reduced_modulus,
            problem.rx,
            1.0,
            problem.load,
            problem.ay / problem.ax,
        ),
        carried=True,
    )


def _constants(problem: EquilibriumProblem) -> dict:
    """`_balance_constants`, kept on the problem and carried to its sub-batches."""
    return problem.memo("balances", lambda: _balance_constants(problem), carried=True)


def _balance_constants(problem: EquilibriumProblem) -> dict:
    """The creep-independent factors of `_balances` (kept on the problem, `memo`)."""
    pb, lay, des = problem, problem.layout, problem.design
    rs, n, bm = des.roller_radius, des.n_rollers, des.bearings
    idler_thrust = n * pb.load * np.abs(lay.z_j)
    return {
        "kappa_load": lay.kappa * pb.load,
        "load_radius": pb.load * pb.radius,
        "rs_rho": rs * pb.rho,
        "rs_sz": rs * pb.sz,
        "gyro": bool(np.any(pb.gyro_factor)),
        "idler_load_torque": np.where(
            lay.is_idler, load_dependent_torque(idler_thrust, des.idler_bearing_diameter, bm), 0.0
        ),
        "roller_scale": pb.clamp_force * rs,
        "scale": pb.torque_scale[..., None],
        "roller_drag": np.sum(pb.roller_drag, axis=-1),
        "shaft_drags": _drag_magnitudes(pb),
        "no_drag": np.zeros(pb.shape),
    }


def _drag_magnitudes(problem: EquilibriumProblem) -> DragMagnitudes | None:
    """The problem's shaft and between-disc drag magnitudes, None if all are zero."""
    pb = problem
    if not (np.any(pb.input_drag) or np.any(pb.output_drag) or np.any(pb.disc_drag)):
        return None
    return DragMagnitudes(
        pb.drag_kinds, pb.roller_drag, pb.input_drag, pb.output_drag, pb.disc_drag
    )


def _solved_drags(k: dict, omega):
    """Input and output shaft drags at the solved disc speeds, summed over the kinds
    (`shaft_drags`: each follows its speed, the disc bearing the discs' relative speed)."""
    if k["shaft_drags"] is None:
        return k["no_drag"], k["no_drag"]
    m0, m2 = shaft_drags(k["shaft_drags"], omega[..., 0], omega[..., -1])
    return m0.sum(axis=-1), m2.sum(axis=-1)


def _balances(problem: EquilibriumProblem, creep, at: ContactInputs, mu, chi) -> EquilibriumState:
    """Forces, moments, bearing torques and residuals from the contact coefficients."""
    omega_s, omega = at.omega_s, at.omega
    pb, lay, des, fl = problem, problem.layout, problem.design, problem.fluid
    k = _constants(pb)
    rs, n = des.roller_radius, des.n_rollers
    force = k["kappa_load"] * mu
    moment = -chi * k["load_radius"]
    # (array methods, not np.sum: this runs at every Newton iteration, on few points)
    m_s = (k["rs_rho"] * force + pb.sz * moment).sum(axis=-1)
    m_u = (pb.rho * moment - k["rs_sz"] * force).sum(axis=-1)
    f_sum = -force.sum(axis=-1)
    axle = np.empty(f_sum.shape + (2,))
    axle[..., 0] = 0.5 * (f_sum + 2.0 * m_u / rs)
    axle[..., 1] = 0.5 * (f_sum - 2.0 * m_u / rs)
    bm, nu = des.bearings, fl.kinematic_viscosity
    # with the carrier turning, the axle ends also carry the gyroscopic moment (§13)
    bearing_load = np.hypot(axle, (pb.gyro_factor * omega_s)[..., None]) if k["gyro"] else axle
    t_bls = 2.0 * speed_dependent_torque(
        omega_s, des.roller_bearing_diameter, nu, bm
    ) + load_dependent_torque(bearing_load, des.roller_bearing_diameter, bm).sum(axis=-1)
    t_bl = np.where(
        lay.is_idler,
        speed_dependent_torque(omega, des.idler_bearing_diameter, nu, bm) + k["idler_load_torque"],
        0.0,
    )
    body = n * (-force * pb.radius - moment * lay.z_j)
    scale = k["scale"]
    res = np.empty(body.shape)
    # parasitic drags (zero without design.parasitic, docs/model.md §12): churning on the
    # ball's spin like its axle bearings; the output shaft's drag adds to the load torque
    res[..., 0] = (m_s - np.sign(omega_s) * (t_bls + k["roller_drag"])) / k["roller_scale"]
    res[..., 1:-1] = ((body - np.sign(omega) * t_bl) / scale)[..., 1:-1]
    input_drag, output_drag = _solved_drags(k, omega)
    if pb.torque_weights == (0.0, 1.0):
        res[..., -1] = (body[..., -1] - (pb.output_torque + output_drag)) / scale[..., 0]
    else:  # the torque condition a T_0 + b T_2 = target of a planetary mode (§13)
        a, b = pb.torque_weights
        t0 = -body[..., 0] + input_drag
        t2 = body[..., -1] - output_drag
        res[..., -1] = (a * t0 + b * t2 - pb.output_torque) / scale[..., 0]
    return EquilibriumState(
        creep=creep,
        omega_s=omega_s,
        omega=omega,
        spin=at.spin,
        u_ref=at.u_ref,
        film=at.film,
        mu=mu,
        chi=chi,
        force=force,
        moment=moment,
        body_torque=body,
        axle_reactions=axle,
        roller_bearing_torque=t_bls,
        idler_bearing_torque=t_bl,
        residual=res,
        input_drag=input_drag,
        output_drag=output_drag,
    )


def balancing_output_torque(problem: EquilibriumProblem, state: EquilibriumState):
    """The output torque ``T_2 = T_body,2 - T_drag,2`` that balances the output disc at
    ``state`` [N m], whatever the problem's own torque condition (docs/model.md §5, §13);
    ``T_drag,2`` at the solved speeds (`EquilibriumState.output_drag`)."""
    return state.body_torque[..., -1] - state.output_drag


def carrier_reaction_torque(problem: EquilibriumProblem, state: EquilibriumState):
    """Torque about ``j`` applied to the carrier from outside, from the balls' axles [N m].

    The carrier holds each ball's axle: it takes ``-F_Ra``, ``-F_Rb`` along ``i`` at the
    bearings ``R_c k +- (r_S / 2) s`` (the lever arm of Eqs. 19/34), and the friction torques
    of the ball bearings (about ``s``) and of the idler bearings (about ``j``) react on it.
    The gyroscopic forces along ``u`` and the centrifugal force have no moment about ``j``.
    So the torque the balls and idlers exert on the carrier is
    ``n [-R_c (F_Ra + F_Rb) + (r_S / 2) sin(gamma) (F_Ra - F_Rb)
    + sign(omega_S) T_BLS cos(gamma)] + sum sign(Omega) T_BL``, and the carrier's applied
    torque is minus that (docs/model.md §13). It equals ``T_2 - T_0``, the balance of the
    three shafts, at any equilibrium (tested): a check of the model's moment balances.
    """
    des = problem.design
    rs, n = des.roller_radius, des.n_rollers
    rc = rs * (1.0 + des.aspect_ratio)
    fa, fb = state.axle_reactions[..., 0], state.axle_reactions[..., 1]
    g = problem.tilt
    inner = n * (
        -rc * (fa + fb)
        + 0.5 * rs * np.sin(g) * (fa - fb)
        + np.sign(state.omega_s) * state.roller_bearing_torque * np.cos(g)
    )
    inner = inner + np.sum(np.sign(state.omega) * state.idler_bearing_torque, axis=-1)
    return -inner
