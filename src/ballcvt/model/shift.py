"""Moments about a ball's tilt axis: holding a ratio and tilting the balls (docs/model.md §17).

The tilt axis of a ball passes through its centre perpendicular to the meridian plane that
holds its spin axis ``s`` and the main axis ``j``: it is the rolling direction ``i``
(docs/model.md §1). Tilting by ``+d gamma`` turns the ball about ``-i``
(``s(gamma) = cos gamma j - sin gamma k``), so its angular velocity gains ``-gamma_dot i``.

**Lever arms.** Every contact lies on the ball's sphere, at ``r_S z_c`` from its centre.
The normal load acts along ``z_c`` (through the centre), the traction ``F_c`` along ``i``
and the spin moment about ``z_c``: none has a moment about ``i``. Only a transverse
force does: a force ``F_y`` along the contact's transverse direction
``e_y = kappa_c (i x z_c)`` (the ``y`` of Eq. 55's frame, docs/model.md §17) has the moment
``r_S z_c x F_y e_y = kappa_c r_S F_y i``, lever ``r_S`` exactly. The axle reactions act
along ``i`` and have none either.

**Side slip of a tilt.** The extra angular velocity ``-gamma_dot i`` moves the ball's
surface at each contact by ``-gamma_dot r_S (i x z_c)`` (tangent to the ball and
transverse to the rolling), while the disc's or idler's surface moves along ``i`` only; so
the body slides over the ball laterally at ``gamma_dot r_S`` and the contact's lateral
creep (Eq. 55's frame) is ``s_c = kappa_c gamma_dot r_S / u_c`` (``u_c`` the rolling
speed ``|Omega_c| r_c``).

**Skew.** An axle skewed by a small ``zeta`` about ``-k`` (``s -> s + zeta cos gamma i``)
adds ``omega_S zeta cos gamma i`` to the ball's angular velocity: the pattern of a tilt, so
the side slips of a skewed ball tilting at ``gamma_dot`` are those of the effective tilt rate
``gamma_dot - omega_S zeta cos gamma`` (zero when ``gamma_dot = omega_S zeta cos gamma``,
the skew-steered tilt rate); `tilt_moments` at that rate gives its moment (to first order in
``zeta``).

**Moment about the skew axis.** The skew axis of a ball is ``k`` (radial, in the meridian
plane of ``j``, the centre and every contact normal); ``zeta`` turns the axle about
``-k``. With the traction ``F_c = kappa_c mu_c F_Nc`` along ``+i`` at ``r_S z_c`` and the
spin moment ``T_c = -chi_c F_Nc r_c`` about ``z_c`` (docs/model.md §5), the contacts'
moment on the ball about ``+k`` is
``M_k = sum_c (-r_S (z_c . j) F_c + (z_c . k) T_c)`` (``(z_c x i) . k = -z_c . j``: the
traction's lever is the contact's axial offset ``r_S z_c . j``). A lateral force lies in
the meridian plane, tangent at a point of it: its moment is along ``i``, none about ``k``.
The carrier holds it with the moment ``M_k`` about ``-k``, the direction of increasing
skew (conjugate to ``zeta``: power ``M_k zeta_dot``); ``k = -sin gamma s + cos gamma u``
splits it into the axle bearings' drag about ``s`` and the axle-end couple about ``u``.

**Moment to hold or to tilt.** With ``F_y,c = mu_y,c F_Nc`` on the ball, the moment the
contacts exert about ``-i`` (the direction of increasing ``gamma``) is
``-r_S sum_c kappa_c mu_y,c F_Nc``; the shifter holds or drives the tilt with its
opposite, ``M = r_S sum_c kappa_c mu_y,c F_Nc`` per ball (conjugate to ``gamma``: its
power is ``M gamma_dot``). Sources: the tilt and skew of ball-planetary CVTs, Fallbrook
Technologies' patents (US 8,313,404 and US 8,469,856, skew-based control; US 8,506,452,
skew cam; US 11,174,922, Nichols 2021, tilt gamma and skew zeta); creep forces under
combined creep and spin, Johnson (1985, Contact Mechanics, §8.4).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..params.models import Fluid
from .traction.base import lateral_coefficients
from .traction.contact import ContactState
from .traction.quadrature import Quadrature

__all__ = [
    "tilt_side_slip",
    "tilt_axis_moment",
    "skew_axis_moment",
    "TiltContacts",
    "TiltMoments",
    "tilt_moments",
]

#: A contact is at its lateral traction limit when its lateral force is below this share
#: of its linear-range extrapolation (``(1 - e^-x)/x = 0.5`` at ``x = 1.59``: the force at
#: 80 % of its limit under Eq. 53 with a uniform sliding field).
SATURATION_SHARE = 0.5
#: Lateral creep of the linear-range reference of each contact [-].
LINEAR_SLIP = 1e-7


def tilt_side_slip(tilt_rate, roller_radius, u_ref, kappa):
    """Lateral creep of each contact while the balls tilt at ``tilt_rate`` [-].

    ``s_c = kappa_c gamma_dot r_S / u_c`` (module docstring).

    Parameters
    ----------
    tilt_rate : float or array_like
        ``d gamma / dt`` [rad/s].
    roller_radius : float
        Ball radius ``r_S`` [m].
    u_ref : array_like
        Rolling speed of each contact ``|Omega_c| r_c`` [m/s], ``(..., n_c)``.
    kappa : array_like
        Sign of each contact's traction along ``+i`` (docs/model.md §1), ``(n_c,)``.
    """
    return np.asarray(kappa) * np.asarray(tilt_rate)[..., None] * roller_radius / u_ref


def tilt_axis_moment(mu_y, load, kappa, roller_radius):
    """Moment the shifter applies per ball to hold the contacts' lateral forces [N m].

    ``M = r_S sum_c kappa_c mu_y,c F_Nc`` about the direction of increasing tilt
    (module docstring).

    Parameters
    ----------
    mu_y : array_like
        Lateral traction coefficients (Eq. 55's frame) ``(..., n_c)`` [-].
    load : array_like
        Normal loads ``F_Nc`` ``(..., n_c)`` [N].
    kappa : array_like
        Traction signs of the contacts ``(n_c,)`` [-].
    roller_radius : float
        ``r_S`` [m].
    """
    return roller_radius * np.sum(np.asarray(kappa) * np.asarray(mu_y) * load, axis=-1)


def skew_axis_moment(traction, spin_moment, normal_j, normal_k, roller_radius):
    """Moment of the contacts on a ball about its skew axis ``k`` [N m].

    ``M_k = sum_c (-r_S (z_c . j) F_c + (z_c . k) T_c)`` (module docstring): about the
    outward radial axis ``+k``; the carrier holds the ball with the same moment about the
    direction of increasing skew ``-k``. The lateral forces have no part in it.

    Parameters
    ----------
    traction : array_like
        Traction on the ball along ``+i``, ``F_c = kappa_c mu_c F_Nc`` ``(..., n_c)`` [N].
    spin_moment : array_like
        Spin moment on the ball about ``z_c``, ``T_c = -chi_c F_Nc r_c`` ``(..., n_c)``
        [N m].
    normal_j, normal_k : array_like
        Components ``z_c . j`` and ``z_c . k`` of the outward ball normals ``(n_c,)`` [-].
    roller_radius : float
        ``r_S`` [m].
    """
    lever = -roller_radius * np.asarray(normal_j) * np.asarray(traction)
    return np.sum(lever + np.asarray(normal_k) * np.asarray(spin_moment), axis=-1)


@dataclass(frozen=True)
class TiltContacts:
    """The contacts of solved points and what tilting them needs to know.

    Attributes
    ----------
    state : ContactState
        The contacts at the solved creeps, arrays ``(..., n_c)``.
    kappa : ndarray
        Traction sign of each contact ``(n_c,)`` [-].
    roller_radius : float
        ``r_S`` [m].
    fluid : Fluid
        Traction fluid (its law, with its side-slip form).
    quadrature : Quadrature
        Rule of the traction integrals.
    entry : array_like
        Rolling direction of each contact along Eq. 55's ``x``, ``kappa_c i``:
        ``sign(kappa_c rho_c omega_S)`` (the ball's surface moves at
        ``omega_S r_S rho_c`` along ``i``) [-]; the edge where a Maxwell film enters
        (`ballcvt.model.traction.lateral.lateral_shear_coefficients`).
    normal : tuple of array_like or None
        ``(z_c . j, z_c . k)`` of the contacts' outward normals, ``(n_c,)`` each [-]; None
        (not known): the moments about the skew axis are NaN.
    """

    state: ContactState
    kappa: np.ndarray
    roller_radius: float
    fluid: Fluid
    quadrature: Quadrature = Quadrature()
    entry: Any = 1.0
    normal: Any = None

    def lateral(self, slip):
        """``mu, mu_y, chi`` of the contacts at lateral creeps ``slip`` [-]."""
        return lateral_coefficients(self.state, self.fluid, slip, self.quadrature, self.entry)

    def skew(self, mu, chi):
        """`skew_axis_moment` of the contacts at coefficients ``mu, chi`` [N m]."""
        st = self.state
        load = np.asarray(st.load)
        if self.normal is None:
            return np.full(load.shape[:-1], np.nan)
        traction = self.kappa * np.asarray(mu) * load
        spin_moment = -np.asarray(chi) * load * np.asarray(st.radius)
        return skew_axis_moment(traction, spin_moment, *self.normal, self.roller_radius)


@dataclass(frozen=True)
class TiltMoments:
    """Per-ball moments about the tilt axis (arrays of the points' shape).

    Attributes
    ----------
    holding : ndarray
        Moment to hold the tilt at the steady point [N m].
    shift : ndarray
        Extra moment to tilt at the rate [N m] (the sign of the rate).
    side_slip : ndarray
        Lateral creep of each contact ``(..., n_c)`` [-].
    lateral_force : ndarray
        Lateral force of each contact on the ball along ``e_y`` ``(..., n_c)`` [N].
    saturated : ndarray
        Whether a contact's lateral force is at its traction limit (below
        ``SATURATION_SHARE`` of its linear-range extrapolation).
    skew : ndarray
        Moment about the skew axis at the rate (`skew_axis_moment`; the side slip changes
        the contacts' ``mu`` and ``chi``) [N m]; NaN when the normals are not known.
    """

    holding: np.ndarray
    shift: np.ndarray
    side_slip: np.ndarray
    lateral_force: np.ndarray
    saturated: np.ndarray
    skew: np.ndarray


def tilt_moments(contacts: TiltContacts, tilt_rate) -> TiltMoments:
    """Holding and tilt-direct shift moments of solved points (module docstring).

    The contacts keep their steady creeps, spins, loads and films (quasi-static: the
    steady point's longitudinal creeps are not re-solved with the side slip); each gets
    the lateral creep of the tilt (`tilt_side_slip`), and its lateral force follows from
    the film's law (`lateral_coefficients`, docs/model.md §17).

    Parameters
    ----------
    contacts : TiltContacts
        The solved contacts.
    tilt_rate : float or array_like
        ``d gamma / dt`` [rad/s] (broadcast with the points).

    Returns
    -------
    TiltMoments
    """
    st, k, rs = contacts.state, contacts.kappa, contacts.roller_radius
    load = np.asarray(st.load)
    mu0, mu_y0, chi0 = contacts.lateral(0.0)
    holding = tilt_axis_moment(mu_y0, load, k, rs)
    rate = np.asarray(tilt_rate, dtype=float)
    slip = tilt_side_slip(rate, rs, np.asarray(st.u_ref), k)
    if not np.any(rate):
        zero = np.zeros_like(slip)
        skew = contacts.skew(mu0, chi0)
        return TiltMoments(
            holding, np.zeros_like(holding), zero, mu_y0 * load, zero[..., 0] > 0, skew
        )
    mu, mu_y, chi = contacts.lateral(slip)
    ref = np.sign(slip) * LINEAR_SLIP
    _, mu_lin, _ = contacts.lateral(ref)
    linear = (mu_lin - mu_y0) / np.where(ref != 0.0, ref, 1.0) * slip
    extra = mu_y - mu_y0
    saturated = np.any(np.abs(extra) < SATURATION_SHARE * np.abs(linear), axis=-1)
    shift = tilt_axis_moment(mu_y, load, k, rs) - holding
    return TiltMoments(holding, shift, slip, mu_y * load, saturated, contacts.skew(mu, chi))
