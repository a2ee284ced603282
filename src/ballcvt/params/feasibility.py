"""Geometric feasibility: a design that cannot be built is refused (docs/model.md §10).

Each check derives from the contact layout of docs/model.md §1 (ball centre at radius
``r_S (1 + k)``, contact normals at the angles ``theta_0``, ``theta_2``, ``alpha``) and raises
`InputError` naming the quantity, its value and the allowed range. `check_design` holds for
both architectures and runs whenever a `Design` is built or loaded; `check_architecture` adds
what only one idler layout needs and runs whenever a variator or a contact layout is built.
"""

from __future__ import annotations

import math

from ..errors import InputError

__all__ = ["check_design", "check_architecture", "max_balls", "tilt_limits", "usable_tilt_range"]


def max_balls(aspect_ratio: float, roller_radius: float, min_gap: float) -> int:
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
    """Refuse a `Design` that cannot be built (both architectures; Eqs. F1-F3).

    Parameters
    ----------
    d : Design
        The design to check.

    Raises
    ------
    InputError
        On the first violated bound.
    """
    rs, g = d.roller_radius, d.min_ball_gap
    n_max = max_balls(d.aspect_ratio, rs, g)
    if d.n_rollers > n_max:  # Eq. F1
        raise InputError(
            "n_rollers",
            d.n_rollers,
            f"<= {n_max} (balls of radius {rs:g} m on a circle of radius "
            f"{rs * (1 + d.aspect_ratio):g} m with gaps >= min_ball_gap = {g:g} m)",
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
            f"disc contacts at least min_ball_gap = {g:g} m apart along the axis "
            f"(r_S (sin theta0 + sin theta2) = {sep:.3g} m)",
        )
    if d.roller_bearing_diameter >= 2.0 * rs:  # Eq. F3
        raise InputError(
            "roller_bearing_diameter",
            d.roller_bearing_diameter,
            f"< 2 r_S = {2 * rs:g} m (the axle bearing sits inside the ball)",
        )


def check_architecture(d, architecture: str) -> None:
    """Refuse a design that cannot be built with ``architecture`` (Eqs. F4-F6).

    Parameters
    ----------
    d : Design
        The design.
    architecture : {"double", "single"}
        Idler layout.

    Raises
    ------
    InputError
        On the first violated bound.
    """
    rs, g = d.roller_radius, d.min_ball_gap
    if architecture == "double":
        sep = 2.0 * rs * math.sin(d.alpha)  # Eq. F5
        if sep < g:
            need = math.degrees(math.asin(min(1.0, g / (2.0 * rs))))
            raise InputError(
                "alpha_deg",
                d.alpha_deg,
                f">= {need:.4g} deg for two idlers (their contacts 2 r_S sin(alpha) "
                f"apart must be at least min_ball_gap = {g:g} m)",
            )
        lo, hi = usable_tilt_range(d)
        # Eq. F4: the idlers' rolling radii rho = -cos(gamma -/+ alpha) keep their sign over
        # the usable tilt range (the discs' vanish only at the Eq. 6 limits themselves)
        if lo <= d.alpha - math.pi / 2 or hi >= math.pi / 2 - d.alpha:
            raise InputError(
                "alpha_deg",
                d.alpha_deg,
                f"< {90 - math.degrees(max(-lo, hi)):.4g} deg (an idler's rolling "
                "radius would vanish within the usable tilt range)",
            )
        idler_radius = rs * (1.0 + d.aspect_ratio - math.cos(d.alpha))
    else:
        idler_radius = rs * d.aspect_ratio
    if d.idler_bearing_diameter >= 2.0 * idler_radius:  # Eq. F6
        raise InputError(
            "idler_bearing_diameter",
            d.idler_bearing_diameter,
            f"< {2 * idler_radius:.4g} m, the {architecture} idler's diameter at its contacts",
        )


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
