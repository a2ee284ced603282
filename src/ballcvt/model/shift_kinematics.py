"""Shift kinematics: tilt rate under a skewed axle, side slip at the contacts
(docs/shifting.md).

A ball's axle is oriented by its tilt ``gamma`` (in the meridian plane, docs/model.md §1)
and its skew ``zeta``, a rotation of the axle about ``-k`` (the radial line through the
ball centre): ``s' = cos(gamma) (cos(zeta) j + sin(zeta) i) - sin(gamma) k``. In the
carrier frame the ball turns at ``omega_b`` about ``s'`` while its axle frame turns at
``-gamma_dot R(zeta) i - zeta_dot k``. Every body the ball touches (discs, idlers) turns
about ``j``, so its surface moves along ``i`` only; the side slip at a contact is the
ball's surface speed along the lateral direction ``e_c = z_c x i`` over its rolling speed
along ``i``. Because ``z_c x (i x z_c) = i`` for every contact normal ``z_c`` in the
meridian plane, the lateral speed is ``-r_S (w . i)`` at every contact at once: the side
slip vanishes at all contacts together when the ball's angular velocity ``w`` has no
component along ``i``, i.e. at ``gamma_dot = omega_b cos(gamma) tan(zeta)`` (to first
order in the skew, ``omega_b zeta cos(gamma)``, the rate of the Fallbrook skew-control
patents' kinematics). Pure functions, SI units, contacts on the last axis.
"""

from __future__ import annotations

import numpy as np

from .kinematics import body_speeds
from .layout import ContactLayout

__all__ = [
    "ball_spin_speed",
    "ball_angular_velocity",
    "skew_tilt_rate",
    "side_slip",
]


def ball_spin_speed(layout: ContactLayout, tilt, input_speed):
    """Ball speed about its axle in the carrier frame, without creep (Eq. 3 with ``C = 0``).

    Parameters
    ----------
    layout : ContactLayout
    tilt : array_like
        Tilt ``gamma`` [rad].
    input_speed : array_like
        Input disc speed ``omega_0`` relative to the carrier [rad/s].

    Returns
    -------
    ndarray
        ``omega_b = omega_0 r~_0 / rho_0(gamma)`` [rad/s] (docs/model.md §2).
    """
    tilt = np.asarray(tilt, dtype=float)
    creep = np.zeros((*tilt.shape, layout.n_contacts))
    omega_b, _ = body_speeds(layout, tilt, creep, input_speed)
    return omega_b


def ball_angular_velocity(tilt, ball_speed, skew, tilt_rate, skew_rate=0.0):
    """The ball's angular velocity in the carrier frame, components on ``(i, j, k)``.

    ``w = omega_b s' - gamma_dot (cos(zeta) i - sin(zeta) j) - zeta_dot k``, the spin about
    the skewed axle ``s'`` plus the turning of the axle frame (tilt about the skewed tilt
    axis, skew about ``-k``; docs/shifting.md, Eq. S2).

    Parameters
    ----------
    tilt, ball_speed, skew, tilt_rate, skew_rate : array_like
        ``gamma`` [rad], ``omega_b`` [rad/s], ``zeta`` [rad], ``gamma_dot`` and
        ``zeta_dot`` [rad/s]; broadcast together.

    Returns
    -------
    ndarray
        Shape ``(..., 3)``: ``(w.i, w.j, w.k)`` [rad/s].
    """
    g, wb, z, gd, zd = np.broadcast_arrays(
        *(np.asarray(a, dtype=float) for a in (tilt, ball_speed, skew, tilt_rate, skew_rate))
    )
    wi = wb * np.cos(g) * np.sin(z) - gd * np.cos(z)
    wj = wb * np.cos(g) * np.cos(z) + gd * np.sin(z)
    wk = -wb * np.sin(g) - zd
    return np.stack([wi, wj, wk], axis=-1)


def skew_tilt_rate(ball_speed, tilt, skew):
    """The tilt rate at which a skewed ball rolls without side slip (docs/shifting.md, S4).

    Parameters
    ----------
    ball_speed : array_like
        ``omega_b`` [rad/s] (`ball_spin_speed`).
    tilt, skew : array_like
        ``gamma`` and ``zeta`` [rad].

    Returns
    -------
    ndarray
        ``gamma_dot = omega_b cos(gamma) tan(zeta)`` [rad/s]; ``omega_b zeta cos(gamma)``
        to first order in ``zeta``.
    """
    return np.asarray(ball_speed) * np.cos(tilt) * np.tan(skew)


def side_slip(layout: ContactLayout, tilt, ball_speed, skew, tilt_rate, skew_rate=0.0):
    """Side slip at every contact: lateral sliding speed over rolling speed (Eq. S3).

    The ball surface speed at contact ``c`` is ``r_S w x z_c``; the bodies it touches turn
    about ``j`` and move along ``i`` only, so the sliding across the rolling direction is
    the ball's speed along ``e_c = z_c x i``. Positive for a tilt rate that increases
    ``gamma``; with no skew ``s_c = gamma_dot r_S / U_c``, ``U_c = |omega_b| r_S |rho_c|``.

    Parameters
    ----------
    layout : ContactLayout
    tilt, ball_speed, skew, tilt_rate, skew_rate : array_like
        As in `ball_angular_velocity`; broadcast together (shape ``(...)``).

    Returns
    -------
    ndarray
        Side slip ``s_c`` per contact, shape ``(..., n_contacts)`` [-].
    """
    w = ball_angular_velocity(tilt, ball_speed, skew, tilt_rate, skew_rate)[..., None, :]
    zc = np.stack([np.zeros_like(layout.z_j), layout.z_j, layout.z_k], axis=-1)
    e_c = np.cross(zc, [1.0, 0.0, 0.0])  # lateral direction z_c x i, in the meridian plane
    surface = np.cross(w, zc)  # ball surface speed over r_S at each contact
    lateral = np.sum(surface * e_c, axis=-1)
    rolling = surface[..., 0]
    return lateral / np.abs(rolling)
