"""The double-idler architecture: two idlers touch each ball (the 2017 drive; Sec. II.A).

Contacts ``input, idler_a, idler_b, output``; normals and loads of Eqs. 1-2 and 29
(docs/model.md §1).
"""

from __future__ import annotations

import math

import numpy as np

from ...errors import InputError
from ...params.models import Design
from ...registry import ARCHITECTURES
from ..kinematics import usable_tilt_range
from .base import Architecture, ContactGeometry

__all__ = ["DoubleIdler", "DOUBLE"]


class DoubleIdler(Architecture):
    """Two idlers at ``+-alpha`` from the radial direction (docs/model.md §1)."""

    name = "double"
    contacts = ("input", "idler_a", "idler_b", "output")

    def geometry(self, design: Design) -> ContactGeometry:
        """Contact normals, radii and Eq. 29 load factors [-]."""
        k = design.aspect_ratio
        t0, t2, al = design.theta0, design.theta2, design.alpha
        f2 = np.sin(t0) / np.sin(t2)  # Eq. 29
        fa = np.sin(t0 + t2) / (2.0 * np.cos(al) * np.sin(t2))  # Eq. 29
        # an outward radial force on the ball is carried by the two idlers (§13)
        share = 1.0 / (2.0 * np.cos(design.alpha))
        return ContactGeometry(
            z_j=[-np.sin(t0), -np.sin(al), np.sin(al), np.sin(t2)],
            z_k=[np.cos(t0), -np.cos(al), -np.cos(al), np.cos(t2)],
            radius=[
                1 + k + np.cos(t0),
                1 + k - np.cos(al),
                1 + k - np.cos(al),
                1 + k + np.cos(t2),
            ],
            kappa=[1.0, 1.0, 1.0, -1.0],
            load_factor=[1.0, fa, fa, f2],
            groove_ratio=[
                design.disc_groove_ratio,
                design.idler_groove_ratio,
                design.idler_groove_ratio,
                design.disc_groove_ratio,
            ],
            radial_share=[0.0, share, share, 0.0],
        )

    def idler_radius(self, design: Design) -> float:
        """``r_S (1 + k - cos(alpha))`` [m]."""
        return design.roller_radius * (1.0 + design.aspect_ratio - math.cos(design.alpha))

    def check_layout(self, design: Design) -> None:
        """The two idlers' contacts apart (Eq. F5) and their rolling radii of one sign over
        the usable tilt range (Eq. F4).

        Raises
        ------
        InputError
            On the first violated bound.
        """
        rs, g = design.roller_radius, design.min_roller_gap
        sep = 2.0 * rs * math.sin(design.alpha)  # Eq. F5
        if sep < g:
            need = math.degrees(math.asin(min(1.0, g / (2.0 * rs))))
            raise InputError(
                "alpha_deg",
                design.alpha_deg,
                f">= {need:.4g} deg for two idlers (their contacts 2 r_S sin(alpha) "
                f"apart must be at least min_roller_gap = {g:g} m)",
            )
        lo, hi = usable_tilt_range(design)
        # Eq. F4: the idlers' rolling radii rho = -cos(gamma -/+ alpha) keep their sign over
        # the usable tilt range (the discs' vanish only at the Eq. 6 limits themselves)
        if lo <= design.alpha - math.pi / 2 or hi >= math.pi / 2 - design.alpha:
            raise InputError(
                "alpha_deg",
                design.alpha_deg,
                f"< {90 - math.degrees(max(-lo, hi)):.4g} deg (an idler's rolling "
                "radius would vanish within the usable tilt range)",
            )


DOUBLE = ARCHITECTURES.register(DoubleIdler())
