"""The single-idler architecture: one cylindrical idler (the original patent; Sec. II.B).

Contacts ``input, idler, output``; the idler touches each ball at its point nearest the
axis, normal ``-k``, load from the radial balance (docs/model.md §1).
"""

from __future__ import annotations

import numpy as np

from ...params.models import Design
from ...registry import ARCHITECTURES
from .base import Architecture, ContactGeometry

__all__ = ["SingleIdler", "SINGLE"]


class SingleIdler(Architecture):
    """One cylindrical idler of radius ``r_1 = k r_S`` (docs/model.md §1)."""

    name = "single"
    contacts = ("input", "idler", "output")

    def geometry(self, design: Design) -> ContactGeometry:
        """Contact normals, radii and load factors (radial balance) [-]."""
        k = design.aspect_ratio
        t0, t2 = design.theta0, design.theta2
        f2 = np.sin(t0) / np.sin(t2)  # Eq. 29
        f1 = np.cos(t0) + f2 * np.cos(t2)  # radial balance
        return ContactGeometry(
            z_j=[-np.sin(t0), 0.0, np.sin(t2)],
            z_k=[np.cos(t0), -1.0, np.cos(t2)],
            radius=[1 + k + np.cos(t0), k, 1 + k + np.cos(t2)],
            kappa=[1.0, 1.0, -1.0],
            load_factor=[1.0, f1, f2],
            groove_ratio=[
                design.disc_groove_ratio,
                design.single_idler_groove_ratio,
                design.disc_groove_ratio,
            ],
            # the one idler carries an outward radial force on the ball whole (§13)
            radial_share=[0.0, 1.0, 0.0],
        )

    def idler_radius(self, design: Design) -> float:
        """``k r_S`` [m]."""
        return design.roller_radius * design.aspect_ratio


SINGLE = ARCHITECTURES.register(SingleIdler())
