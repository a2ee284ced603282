"""Inertia of the balls when the carrier turns: centrifugal force, gyroscopic moment
(docs/model.md §13).

With the carrier held (the paper's drive) both vanish. Pure functions, SI units.
"""

from __future__ import annotations

import numpy as np

from ..params.models import Design
from .layout import ContactLayout

__all__ = ["roller_mass", "centrifugal_force", "idler_share", "gyro_factor", "max_carrier_speed"]


def roller_mass(design: Design) -> float:
    """Mass of one ball, a solid sphere of the design's material [kg]."""
    return design.material.density * 4.0 / 3.0 * np.pi * design.roller_radius**3


def centrifugal_force(design: Design, carrier_speed):
    """Centrifugal force on one ball, ``m omega_c^2 R_c``, ``R_c = r_S (1 + k)`` [N]
    (docs/model.md §13), along ``+k``."""
    wc = np.asarray(carrier_speed, dtype=float)
    return roller_mass(design) * wc**2 * design.roller_radius * (1.0 + design.aspect_ratio)


def idler_share(layout: ContactLayout, design: Design) -> np.ndarray:
    """Normal load each contact loses per newton of outward radial force on the ball
    (docs/model.md §13): the idler contacts carry the radial balance, ``1 / (2 cos(alpha))``
    each for the double idler and 1 for the single one; the discs' loads are set by the
    axial balance and do not change. The architecture gives it (`ContactLayout.radial_share`).
    """
    return layout.radial_share


def gyro_factor(design: Design, tilt, carrier_speed):
    """``I omega_c sin(gamma) / r_S`` [kg m/s], ``I = 2 m r_S^2 / 5``.

    With the carrier turning the ball's spin axis ``s`` precesses about ``j``, and its
    angular momentum ``I (omega_c j + omega_S s)`` changes at ``I omega_c omega_S j x s =
    -I omega_c omega_S sin(gamma) i``: a moment about ``i`` that only forces along ``u`` at
    the two axle bearings can supply. They sit ``r_S / 2`` from the centre (the lever arm
    of Eqs. 19/34), so each carries ``I omega_c omega_S sin(gamma) / r_S`` (docs/model.md
    §13): this factor times ``omega_S`` [N].
    """
    inertia = 0.4 * roller_mass(design) * design.roller_radius**2
    return inertia * np.asarray(carrier_speed, dtype=float) * np.sin(tilt) / design.roller_radius


def max_carrier_speed(design: Design, layout: ContactLayout, clamp_force):
    """Carrier speed at which the balls' centrifugal force unloads the idler contacts
    [rad/s] (docs/model.md §13)."""
    share = idler_share(layout, design)[layout.is_idler]
    f_max = np.min(
        np.asarray(clamp_force, dtype=float)[..., None]
        * layout.load_factor[layout.is_idler]
        / share,
        axis=-1,
    )
    return np.sqrt(
        f_max / (roller_mass(design) * design.roller_radius * (1.0 + design.aspect_ratio))
    )
