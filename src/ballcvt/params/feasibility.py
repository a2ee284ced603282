"""Geometric feasibility: a design that cannot be built is refused (docs/model.md §10).

Each check derives from the contact layout of docs/model.md §1 (ball centre at radius
``r_S (1 + k)``, contact normals at the angles ``theta_0``, ``theta_2``, ``alpha``) and raises
`InputError` naming the quantity, its value and the allowed range. `check_design` holds for
every architecture and runs whenever a `Design` is built or loaded; what only one idler
layout needs (Eqs. F4-F6) is checked by its architecture
(`ballcvt.model.architectures.Architecture.check`) whenever a variator or a contact layout
is built, and the tilt limits it reads are in `ballcvt.model.kinematics`.
"""

from __future__ import annotations

import math

from .._compat import moved_names
from ..errors import InputError

__all__ = ["check_design", "max_rollers"]

#: Names that moved to the model layer (answered with a warning).
__getattr__ = moved_names(
    __name__,
    {
        "check_architecture": "ballcvt.model.architectures",
        "tilt_limits": "ballcvt.model.kinematics",
        "usable_tilt_range": "ballcvt.model.kinematics",
        "max_balls": "ballcvt.params.feasibility:max_rollers",
    },
)


def max_rollers(aspect_ratio: float, roller_radius: float, min_gap: float) -> int:
    """Largest number of balls that fit around the carrier (docs/model.md §10, Eq. F1).

    Neighbouring ball centres sit ``2 r_S (1 + k) sin(pi / n)`` apart; they must be at least
    ``2 r_S + g`` apart, so ``sin(pi / n) >= (1 + g / (2 r_S)) / (1 + k)``.

    Parameters
    ----------
    aspect_ratio : float
        ``k = r_1 / r_S`` [-].
    roller_radius : float
        Ball radius ``r_S`` [m].
    min_gap : float
        Smallest clearance between neighbouring balls ``g`` [m].

    Returns
    -------
    int
        ``n_max`` (0 if not even one gap fits on the circle) [-].
    """
    s = (1.0 + min_gap / (2.0 * roller_radius)) / (1.0 + aspect_ratio)
    if s >= 1.0:
        return 1
    return int(math.floor(math.pi / math.asin(s) * (1 + 1e-12)))


def check_design(d) -> None:
    """Refuse a `Design` that cannot be built (every architecture; Eqs. F1-F3).

    Parameters
    ----------
    d : Design
        The design to check.

    Raises
    ------
    InputError
        On the first violated bound.
    """
    rs, g = d.roller_radius, d.min_roller_gap
    n_max = max_rollers(d.aspect_ratio, rs, g)
    if d.n_rollers > n_max:  # Eq. F1
        raise InputError(
            "n_rollers",
            d.n_rollers,
            f"<= {n_max} (balls of radius {rs:g} m on a circle of radius "
            f"{rs * (1 + d.aspect_ratio):g} m with gaps >= min_roller_gap = {g:g} m)",
        )
    if d.n_rollers < 3:
        raise InputError(
            "n_rollers",
            d.n_rollers,
            ">= 3 (fewer balls cannot centre the discs and the idler radially)",
        )
    sep = rs * (math.sin(d.theta0) + math.sin(d.theta2))  # Eq. F2
    if sep < g:
        raise InputError(
            "theta0_deg + theta2_deg",
            f"{d.theta0_deg:g} + {d.theta2_deg:g}",
            f"disc contacts at least min_roller_gap = {g:g} m apart along the axis "
            f"(r_S (sin theta0 + sin theta2) = {sep:.3g} m)",
        )
    if d.roller_bearing_diameter >= 2.0 * rs:  # Eq. F3
        raise InputError(
            "roller_bearing_diameter",
            d.roller_bearing_diameter,
            f"< 2 r_S = {2 * rs:g} m (the axle bearing sits inside the ball)",
        )
