"""Kinematic curves of a drive (no creep): the ideal ratio against the tilt (Eq. 4, Fig. 3)
and the spin coefficients against the ratio (Eqs. 10-14, Fig. 5)."""

from __future__ import annotations

import numpy as np

from ..model.architectures import contact_layout
from ..model.kinematics import body_speeds, ideal_ratio, spin, tilt_from_ratio, tilt_limits

__all__ = ["ratio_tilt_curve", "kinematic_spin"]


def ratio_tilt_curve(
    theta0: float,
    theta2: float,
    aspect_ratio: float,
    *,
    points: int = 401,
    safety_factor: float = 1.0,
):
    """Ideal ratio over the open range of tilts between the Eq. 6 limits (Eq. 4, Fig. 3).

    Parameters
    ----------
    theta0, theta2 : float
        Input and output contact angles [rad].
    aspect_ratio : float
        ``k = r_1 / r_S`` [-].
    points : int
        Tilts from limit to limit, both limits included in the count but left out of the
        curve (``points - 2`` values are returned).
    safety_factor : float
        Fraction of each tilt limit that is usable (``Design.tilt_safety_factor``) [-].

    Returns
    -------
    (ndarray, ndarray, ndarray)
        Tilt ``gamma`` [rad], ideal ratio ``tau_ID`` [-], and whether each tilt lies
        within the safety factor times the limits (bool).
    """
    lo, hi = tilt_limits(theta0, theta2)
    tilt = np.linspace(lo, hi, points)[1:-1]
    ratio = ideal_ratio(tilt, theta0, theta2, aspect_ratio)
    usable = (tilt >= safety_factor * lo) & (tilt <= safety_factor * hi)
    return tilt, ratio, usable


def kinematic_spin(design, architecture: str, ratio) -> dict[str, np.ndarray]:
    """Spin coefficients at zero creep against the ideal ratio (Eqs. 10-14, Fig. 5).

    Parameters
    ----------
    design : Design
        Geometry.
    architecture : str
        ``"double"`` or ``"single"`` idler.
    ratio : array_like
        Ideal ratios ``tau_ID`` [-], shape ``(n,)``.

    Returns
    -------
    dict of ndarray
        Contact name (in the layout's order) -> spin coefficient ``sigma_c`` [-], ``(n,)``.
    """
    ratio = np.asarray(ratio, dtype=float)
    lay = contact_layout(design, architecture)
    tilt = tilt_from_ratio(ratio, design.theta0, design.theta2, design.aspect_ratio)
    ws, w = body_speeds(lay, tilt, np.zeros((ratio.size, lay.n_contacts)), 1.0)
    sg = spin(lay, tilt, ws, w)
    return {name: sg[:, i] for i, name in enumerate(lay.names)}
