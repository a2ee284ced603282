"""Validity warnings: where a solved point lies outside the model's assumptions.

A warning never changes a result; it says which assumption the point strains
(docs/model.md §10). Each kind is one bit of an integer flag, so that a sweep stores one
``warnings`` value per point (CF ``flag_masks``) and a result lists the messages.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..equilibrium.residual import EquilibriumState
from ..model.film import minimum_film_thickness
from ..model.kinematics import entrainment_factor
from ..model.lubrication import LUBRICATION_MODELS, asperities

__all__ = [
    "WARNINGS",
    "LAMBDA_MIXED",
    "HERTZ_SIZE_LIMIT",
    "Validity",
    "validity",
    "warning_messages",
    "flag_names",
]

#: Warning kinds and their bits.
WARNINGS = {
    "mixed_lubrication": 1,
    "pressure_above_limit": 2,
    "large_contact": 4,
    "speed_beyond_fluid_data": 8,
}

#: Film thickness ratio below which the contact runs in mixed lubrication: the asperities
#: touch and the full-film traction law no longer holds (Tallian 1967; Hamrock, Schmid and
#: Jacobson, *Fundamentals of Machine Elements*, 3rd ed. (2014), Sec. 13.9).
LAMBDA_MIXED = 3.0

#: Largest semi-axis over the ball radius for the half-space assumption of Hertz theory
#: (the contact small against the bodies' radii; Johnson, *Contact Mechanics* (1985) §4.1).
HERTZ_SIZE_LIMIT = 0.1


@dataclass(frozen=True)
class Validity:
    """Validity figures of solved points.

    Attributes
    ----------
    lambda_ratio : ndarray
        Film thickness ratio ``h_min / sigma`` per contact, ``(..., n_c)`` [-].
    entrainment_speed : ndarray
        Mean rolling speed per contact, ``(..., n_c)`` [m/s].
    flags : ndarray of int
        Bitwise OR of the `WARNINGS` that hold, ``(...)``.
    asperity_fraction : ndarray
        Fraction of the normal load the asperities carry, ``(..., n_c)`` (zero under the
        full-film model; docs/model.md §15) [-].
    film_parameter : ndarray
        ``h / sigma`` of the lubrication model, ``h`` the central film at the film's
        share of the load, ``(..., n_c)`` [-].
    """

    lambda_ratio: np.ndarray
    entrainment_speed: np.ndarray
    flags: np.ndarray
    asperity_fraction: np.ndarray
    film_parameter: np.ndarray


def validity(problem: EquilibriumProblem, state: EquilibriumState) -> Validity:
    """Check solved points against the model's assumptions (docs/model.md §10).

    Parameters
    ----------
    problem : EquilibriumProblem
        The points.
    state : EquilibriumState
        Their solved state.

    Returns
    -------
    Validity
    """
    des, fl = problem.design, problem.fluid
    speed = state.u_ref * entrainment_factor(state.creep)
    h_min = minimum_film_thickness(
        fl.viscosity,
        fl.pressure_viscosity_coefficient,
        problem.reduced_modulus,
        problem.rx,
        speed,
        problem.load,
        problem.ay / problem.ax,
    )
    lam = h_min / des.surface_roughness
    size = np.maximum(problem.ax, problem.ay) / des.roller_radius
    flags = np.zeros(problem.shape, dtype=np.int64)
    for name, hit in (
        ("mixed_lubrication", lam < LAMBDA_MIXED),
        ("pressure_above_limit", problem.p_max > des.max_pressure),
        ("large_contact", size > HERTZ_SIZE_LIMIT),
        ("speed_beyond_fluid_data", speed > fl.max_rolling_speed),
    ):
        flags |= np.asarray(hit).any(axis=-1) * WARNINGS[name]
    asp = asperities(des)
    share = LUBRICATION_MODELS.get(asp.model).sharing
    frac, film_parameter = share(state.film, problem.load, problem.ax, problem.ay, asp)
    return Validity(
        lambda_ratio=lam,
        entrainment_speed=speed,
        flags=flags,
        asperity_fraction=frac,
        film_parameter=film_parameter,
    )


def flag_names(flags) -> list[str]:
    """Names of the warnings set in ``flags`` (an int or a 0-d integer array)."""
    return [name for name, bit in WARNINGS.items() if int(flags) & bit]


def warning_messages(
    problem: EquilibriumProblem, valid: Validity, names: tuple[str, ...]
) -> list[str]:
    """One line per warning of a single point, naming the contact and the figure.

    Parameters
    ----------
    problem : EquilibriumProblem
        One point (batch shape ``()``).
    valid : Validity
        Its validity figures.
    names : tuple of str
        Contact names.

    Returns
    -------
    list of str
    """
    des, fl = problem.design, problem.fluid
    out = []
    lam = np.asarray(valid.lambda_ratio)
    speed = np.asarray(valid.entrainment_speed)
    size = np.maximum(problem.ax, problem.ay) / des.roller_radius
    for name in flag_names(valid.flags):
        if name == "mixed_lubrication":
            i = int(np.argmin(lam))
            share = float(np.max(valid.asperity_fraction))
            out.append(
                f"mixed_lubrication: film thickness ratio h_min/sigma = {lam[i]:.3g} < "
                f"{LAMBDA_MIXED:g} at the {names[i]} contact (surface_roughness "
                f"{des.surface_roughness:.3g} m): asperities touch, "
                + (
                    f"carrying up to {100 * share:.2g} % of a contact's load (mixed "
                    "lubrication model, docs/model.md §16)"
                    if share > 0
                    else "outside the full-film traction law"
                )
            )
        elif name == "pressure_above_limit":
            i = int(np.argmax(problem.p_max))
            out.append(
                f"pressure_above_limit: Hertz peak pressure {problem.p_max[i] / 1e9:.3g} "
                f"GPa at the {names[i]} contact exceeds max_pressure "
                f"{des.max_pressure / 1e9:.3g} GPa"
            )
        elif name == "large_contact":
            i = int(np.argmax(size))
            out.append(
                f"large_contact: contact semi-axis {size[i]:.3g} x the ball radius at "
                f"the {names[i]} contact (> {HERTZ_SIZE_LIMIT:g}): beyond the "
                "small-contact assumption of Hertz theory"
            )
        else:
            i = int(np.argmax(speed))
            out.append(
                f"speed_beyond_fluid_data: rolling speed {speed[i]:.3g} m/s at the "
                f"{names[i]} contact exceeds the fluid data's max_rolling_speed "
                f"{fl.max_rolling_speed:g} m/s"
            )
    return out
