"""Kinematics: ratio and tilt, rolling radii, body speeds and spin (Eqs. 1, 3-14).

Pure functions of NumPy arrays. Per-contact arrays have the contacts on the last axis;
tilt and speeds broadcast over the leading axes. Spin follows docs/model.md §2 in
vector form, which reproduces Eqs. 11-14 (with the Eq. 7 typo ``omega_1 -> omega_2``).
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from ..errors import InputError
from ..params.models import Design
from .layout import ContactLayout

__all__ = [
    "ideal_ratio",
    "tilt_from_ratio",
    "tilt_limits",
    "usable_tilt_range",
    "ratio_range",
    "check_ratio",
    "rolling_radius",
    "spin_axis_projection",
    "body_speeds",
    "spin",
    "creep_term",
    "entrainment_factor",
]


def _tau0(theta0, theta2, k):
    return (1.0 + k + np.cos(theta0)) / (1.0 + k + np.cos(theta2))


def ideal_ratio(tilt, theta0, theta2, k):
    """Ideal speed ratio ``tau_ID(gamma)`` (Eq. 4).

    Parameters
    ----------
    tilt : array_like
        Ball-axis tilt ``gamma`` [rad].
    theta0, theta2 : float
        Input and output contact angles [rad].
    k : float
        Aspect ratio ``r_1 / r_S`` [-].

    Returns
    -------
    ndarray
        ``tau_ID = tau_0 cos(theta2 - gamma) / cos(theta0 + gamma)`` [-].
    """
    tilt = np.asarray(tilt, dtype=float)
    return _tau0(theta0, theta2, k) * np.cos(theta2 - tilt) / np.cos(theta0 + tilt)


def tilt_from_ratio(ratio, theta0, theta2, k):
    """Tilt for an ideal ratio: the closed-form inverse of Eq. 4 (docs/model.md §2).

    ``gamma = atan((q cos(theta0) - cos(theta2)) / (q sin(theta0) + sin(theta2)))``,
    ``q = tau_ID / tau_0``.

    Parameters
    ----------
    ratio : array_like
        Ideal speed ratio ``tau_ID`` > 0 [-].
    theta0, theta2 : float
        Contact angles [rad].
    k : float
        Aspect ratio [-].

    Returns
    -------
    ndarray
        Tilt ``gamma`` [rad].
    """
    q = np.asarray(ratio, dtype=float) / _tau0(theta0, theta2, k)
    return np.arctan((q * np.cos(theta0) - np.cos(theta2)) / (q * np.sin(theta0) + np.sin(theta2)))


def tilt_limits(theta0, theta2) -> tuple[float, float]:
    """Geometric tilt limits of Eq. 6, where ``tau_ID`` reaches 0 or infinity.

    Parameters
    ----------
    theta0, theta2 : float
        Input and output contact angles [rad].

    Returns
    -------
    tuple of float
        ``(gamma_min, gamma_max)`` [rad].
    """
    return max(-theta0, theta2 - math.pi / 2), min(theta2, math.pi / 2 - theta0)


def usable_tilt_range(d) -> tuple[float, float]:
    """Usable tilt range: ``tilt_safety_factor`` times the Eq. 6 limits (Fig. 3) [rad]."""
    lo, hi = tilt_limits(d.theta0, d.theta2)
    return d.tilt_safety_factor * lo, d.tilt_safety_factor * hi


@lru_cache(maxsize=64)
def ratio_range(design: Design) -> tuple[float, float]:
    """Usable ratio range: Eq. 6 limits times ``design.tilt_safety_factor`` (Fig. 3).

    Returns
    -------
    tuple of float
        ``(tau_min, tau_max)`` [-].
    """
    lo, hi = usable_tilt_range(design)
    args = (design.theta0, design.theta2, design.aspect_ratio)
    return float(ideal_ratio(lo, *args)), float(ideal_ratio(hi, *args))


def check_ratio(design: Design, ratio) -> None:
    """Raise `InputError` if any ``ratio`` is outside `ratio_range`."""
    lo, hi = ratio_range(design)
    r = np.asarray(ratio, dtype=float)
    bad = ~((r >= lo * (1 - 1e-12)) & (r <= hi * (1 + 1e-12)))
    if np.any(bad):
        value = float(r[bad].flat[0]) if r.ndim else float(r)
        raise InputError(
            "ratio",
            value,
            f"{lo:.4g} <= ratio <= {hi:.4g} (tilt within "
            f"{design.tilt_safety_factor:g} x the Eq. 6 limits)",
        )


def spin_axis_projection(layout: ContactLayout, tilt):
    """``s . z_c`` with ``s = cos(gamma) j - sin(gamma) k`` (docs/model.md §1) [-]."""
    g = np.asarray(tilt, dtype=float)[..., None]
    return np.cos(g) * layout.z_j - np.sin(g) * layout.z_k


def rolling_radius(layout: ContactLayout, tilt):
    """Signed rolling radius of the ball at each contact over ``r_S`` (Eq. 1).

    ``rho_c = (s x z_c) . i = cos(gamma) z_c.k + sin(gamma) z_c.j``; ``r_Sc = r_S |rho_c|``.
    Positive where the ball surface moves along ``+i`` for ``omega_S > 0``.

    Parameters
    ----------
    layout : ContactLayout
    tilt : array_like
        Tilt ``gamma`` [rad], shape ``(...)``.

    Returns
    -------
    ndarray
        Shape ``(..., n_contacts)`` [-].
    """
    g = np.asarray(tilt, dtype=float)[..., None]
    return np.cos(g) * layout.z_k + np.sin(g) * layout.z_j


def body_speeds(layout: ContactLayout, tilt, creep, input_speed, rho=None):
    """Ball speed and the signed speeds of the bodies about ``j`` (Eqs. 3, 7).

    Parameters
    ----------
    layout : ContactLayout
    tilt : array_like
        Tilt [rad], shape ``(...)``.
    creep : array_like
        Creep coefficients (Eq. 7) per contact, shape ``(..., n_contacts)`` [-].
    input_speed : array_like
        Input disc speed ``omega_0`` [rad/s], shape ``(...)``.
    rho : array_like, optional
        `rolling_radius` at ``tilt``, if already known [-].

    Returns
    -------
    omega_s : ndarray
        Ball spin speed about ``s``, ``omega_0 r_0 (1 - C_0) / r_S0``, shape ``(...)`` [rad/s].
    omega : ndarray
        Signed body speed ``Omega_c`` about ``j`` for every contact; index 0 is ``omega_0``,
        shape ``(..., n_contacts)`` [rad/s].
    """
    rho = rolling_radius(layout, tilt) if rho is None else rho
    creep = np.asarray(creep, dtype=float)
    w0 = np.asarray(input_speed, dtype=float)
    omega_s = w0 * layout.radius[0] * (1.0 - creep[..., 0]) / rho[..., 0]
    omega = omega_s[..., None] * rho * (1.0 - creep) / layout.radius
    omega[..., 0] = w0  # the input disc turns at omega_0 (broadcasts over the batch)
    return omega_s, omega


def spin(layout: ContactLayout, tilt, omega_s, omega, sz=None):
    """Spin coefficients ``sigma_c = (omega_S s - Omega_c j) . z_c / |Omega_c|`` (Eqs. 10-14).

    Parameters
    ----------
    layout : ContactLayout
    tilt : array_like
        Tilt [rad], shape ``(...)``.
    omega_s : array_like
        Ball speed [rad/s], shape ``(...)``.
    omega : array_like
        Signed body speeds [rad/s], shape ``(..., n_contacts)``.
    sz : array_like, optional
        `spin_axis_projection` at ``tilt``, if already known [-].

    Returns
    -------
    ndarray
        Spin coefficients, shape ``(..., n_contacts)`` [-].
    """
    sz = spin_axis_projection(layout, tilt) if sz is None else sz
    omega = np.asarray(omega, dtype=float)
    return (np.asarray(omega_s)[..., None] * sz - omega * layout.z_j) / np.abs(omega)


def creep_term(creep):
    """Gross sliding over the body surface speed, the creep term of Eq. 55 [-].

    Input contact: ``C_0``; others: ``C / (1 - C)``.
    """
    creep = np.asarray(creep, dtype=float)
    out = creep / (1.0 - creep)
    out[..., 0] = creep[..., 0]
    return out


def entrainment_factor(creep):
    """Mean entrainment speed over ``|Omega_c| r_c`` (Eq. 56 bracket) [-].

    Input: ``1 - C/2``; others: ``(1 - C/2) / (1 - C)``.
    """
    creep = np.asarray(creep, dtype=float)
    out = (1.0 - 0.5 * creep) / (1.0 - creep)
    out[..., 0] = 1.0 - 0.5 * creep[..., 0]
    return out
