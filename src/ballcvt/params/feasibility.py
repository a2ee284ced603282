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

__all__ = [
    "check_design",
    "check_dependents",
    "design_warnings",
    "disc_contact_radius",
    "max_rollers",
]

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
    check_dependents(d)


def disc_contact_radius(d) -> float:
    """Radius of the disc contacts from the drive's axis, ``r_S (1 + k + cos theta)``, the
    larger of the input (``theta_0``) and output (``theta_2``) discs' (docs/model.md §1;
    a disc contact stays where it is as the balls tilt) [m]."""
    c = max(math.cos(d.theta0), math.cos(d.theta2))
    return d.roller_radius * (1.0 + d.aspect_ratio + c)


def check_dependents(d) -> None:
    """Refuse parameters that depend on the geometry and cannot fit it (docs/drive-files.md).

    The parasitic-loss radii, the seals, the disc bearing and the cam are given in metres,
    so they do not follow an edit of the balls or the aspect ratio: a disc whose outer
    radius lies inside its own contact track is refused here, with the range the geometry
    allows. (The idler bearing is checked by the architecture, Eq. F6.)

    Raises
    ------
    InputError
        Naming the field, its value and the allowed range.
    """
    g = d.min_roller_gap
    r_c = disc_contact_radius(d)
    par = d.parasitic
    if par is not None:
        if par.disc_radius < r_c + g:
            raise InputError(
                "parasitic.disc_radius",
                par.disc_radius,
                f">= {r_c + g:.4g} m (the disc contacts are at r_S (1 + k + cos theta) = "
                f"{r_c:.4g} m, plus min_roller_gap)",
            )
        for name in ("seal_diameter", "disc_bearing_diameter"):
            value = getattr(par, name)
            if value >= 2.0 * r_c:
                raise InputError(
                    f"parasitic.{name}",
                    value,
                    f"< {2 * r_c:.4g} m (inside the disc contacts at radius {r_c:.4g} m)",
                )
    if d.cam is not None and par is not None and d.cam.mean_radius > par.disc_radius:
        raise InputError(
            "cam.mean_radius",
            d.cam.mean_radius,
            f"<= parasitic.disc_radius = {par.disc_radius:g} m (the ramp acts on the back "
            "of the disc)",
        )


def design_warnings(d) -> list[str]:
    """Parameters that fit the geometry but look meant for another design (one line each,
    naming the field and the fix); empty for a consistent design."""
    out = []
    r_c = disc_contact_radius(d)
    par = d.parasitic
    if par is not None and par.disc_radius > r_c + 2.0 * d.roller_radius:
        out.append(
            f"[design.parasitic] disc_radius = {par.disc_radius:g} m is far beyond the disc "
            f"contacts at {r_c:.4g} m (more than a ball diameter): the churning loss is "
            f"overestimated; set it to about {r_c + 0.1 * d.roller_radius:.3g} m"
        )
    return out
