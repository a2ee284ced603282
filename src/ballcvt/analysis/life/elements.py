"""The parts whose rolling-contact fatigue sets a drive's life, and what loads each one.

Every track and every support bearing of the drive is one life *element* (docs/life.md):

* the **disc tracks** (``input_disc``, ``output_disc``): one track per disc, overrun by
  every ball, so ``n`` stress cycles per disc revolution relative to the carrier;
* the **idler tracks** (``idler_a``/``idler_b``, or ``idler``): ``n`` stress cycles per
  idler revolution relative to the carrier;
* the **ball tracks** (``ball_input``, ``ball_idler_a``, ...): on each of the ``n`` balls,
  one track per contact, one stress cycle per ball revolution about its axle;
* the **support bearings** with a catalogue rating in the design (``[design.bearings]``):
  the two bearings of each ball axle (``roller_bearing_a``/``_b``, radial loads ``|F_Ra|``,
  ``|F_Rb|``, turning at ``omega_S``), each double idler's bearing (thrust
  ``F_Da = n F_Na sin(alpha)``, docs/model.md §1, §4) and the thrust bearing between the
  discs (the disc thrust ``n F_N0 sin(theta_0)`` at ``|omega_0 - omega_2|``).

Speeds are relative to the carrier (in a planetary mode: the carrier-frame point), so the
stress-cycle rates hold in every mode. Arrays carry the operating points on their first
axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...model.architectures import contact_layout
from ...model.kinematics import rolling_radius
from ...params.models import Design

__all__ = [
    "LifeInputs",
    "TrackElement",
    "BearingElement",
    "track_elements",
    "bearing_elements",
    "rated_viscosity",
]


@dataclass(frozen=True)
class LifeInputs:
    """What the fatigue lives of a batch of ``m`` solved points need (SI units).

    Attributes
    ----------
    design : Design
    architecture : str
    load, semi_x, semi_y : ndarray
        Normal load [N] and contact semi-axes, rolling and transverse [m], ``(m, n_c)``.
    body_speed : ndarray
        Signed speed of the disc or idler of each contact relative to the carrier
        [rad/s], ``(m, n_c)``.
    roller_speed : ndarray
        Ball speed about its axle ``omega_S`` [rad/s], ``(m,)``.
    axle_reactions : ndarray
        ``(F_Ra, F_Rb)`` on each ball axle [N], ``(m, 2)``.
    axial_force : ndarray
        Axial thrust on each disc [N], ``(m,)``.
    tilt : ndarray
        Ball tilt [rad], ``(m,)``.
    kinematic_viscosity : float
        Of the fluid, ``eta_0 / rho``, for the bearings' ``a_ISO`` [m^2/s].
    """

    design: Design
    architecture: str
    load: np.ndarray
    semi_x: np.ndarray
    semi_y: np.ndarray
    body_speed: np.ndarray
    roller_speed: np.ndarray
    axle_reactions: np.ndarray
    axial_force: np.ndarray
    tilt: np.ndarray
    kinematic_viscosity: float

    @classmethod
    def of_result(cls, result) -> LifeInputs:
        """From one `ballcvt.results.point.OperatingResult` (``m = 1``)."""
        c = list(result.contacts.values())

        def row(key):
            return np.array([[getattr(x, key) for x in c]], dtype=float)

        return cls(
            result.design,
            result.architecture,
            row("normal_load"),
            row("semi_axis_x"),
            row("semi_axis_y"),
            row("body_speed"),
            np.array([result.roller_speed], dtype=float),
            np.array([result.axle_reactions], dtype=float),
            np.array([result.axial_force], dtype=float),
            np.array([result.tilt], dtype=float),
            result.fluid.kinematic_viscosity,
        )

    @classmethod
    def of_state(cls, problem, state, axial_force) -> LifeInputs:
        """From a 1-D batch of equilibrium problems and their states at the solution
        (`ballcvt.equilibrium`), carrier held; ``axial_force`` [N], ``(m,)``."""
        return cls(
            problem.design,
            problem.layout.architecture,
            np.asarray(problem.load, dtype=float),
            np.asarray(problem.ax, dtype=float),
            np.asarray(problem.ay, dtype=float),
            np.asarray(state.omega, dtype=float),
            np.asarray(state.omega_s, dtype=float),
            np.asarray(state.axle_reactions, dtype=float).reshape(-1, 2),
            np.asarray(axial_force, dtype=float),
            np.asarray(problem.tilt, dtype=float),
            problem.fluid.kinematic_viscosity,
        )


@dataclass(frozen=True)
class TrackElement:
    """A rolling track: ``count`` identical tracks under the same contact.

    Attributes
    ----------
    name, body : str
        Element name and the body it is on (``disc``, ``idler``, ``ball``).
    count : int
        Identical tracks in the drive (``n`` for the ball tracks, else 1).
    load, semi_major, semi_minor : ndarray
        Contact load [N] and semi-axes transverse to and along the rolling direction
        (the contact's ``semi_axis_y`` and ``semi_axis_x``) [m], ``(m,)``.
    track_length : ndarray
        Circumference of the track [m], ``(m,)``.
    cycle_rate : ndarray
        Stress cycles per second of one track [1/s], ``(m,)``.
    """

    name: str
    body: str
    count: int
    load: np.ndarray
    semi_major: np.ndarray
    semi_minor: np.ndarray
    track_length: np.ndarray
    cycle_rate: np.ndarray


@dataclass(frozen=True)
class BearingElement:
    """``count`` identical rolling bearings under the same load.

    Attributes
    ----------
    name : str
    count : int
    rating : float
        Basic dynamic load rating ``C`` [N].
    load : ndarray
        Dynamic equivalent load ``P`` [N], ``(m,)``.
    speed : ndarray
        Revolutions per second of the bearing's rings relative to each other [1/s], ``(m,)``.
    fatigue_limit : float or None
        Fatigue load limit ``C_u`` [N], for ``a_ISO``.
    diameter : float or None
        Mean diameter [m], for the rated viscosity of ``a_ISO``.
    """

    name: str
    count: int
    rating: float
    load: np.ndarray
    speed: np.ndarray
    fatigue_limit: float | None = None
    diameter: float | None = None


#: Element names of the tracks on the discs and idlers, by contact name.
_BODY_TRACK = {"input": "input_disc", "output": "output_disc"}


def track_elements(x: LifeInputs) -> list[TrackElement]:
    """Every track of the drive: one on each disc and idler, one per contact on each ball.

    Track lengths: ``2 pi r_c`` on a disc or idler (``r_c`` the contact's distance from the
    main axis, Eq. 2) and ``2 pi r_S |rho_c|`` on the ball (its rolling radius, Eq. 1).
    """
    d = x.design
    layout = contact_layout(d, x.architecture)
    n, r_s = d.n_rollers, d.roller_radius
    rho = np.abs(rolling_radius(layout, x.tilt))  # (m, n_c)
    ball_rate = np.abs(x.roller_speed) / (2.0 * math.pi)
    out = []
    for j, name in enumerate(layout.names):
        body = "idler" if layout.is_idler[j] else "disc"
        on_body = np.full(ball_rate.shape, 2.0 * math.pi * r_s * layout.radius[j])
        common = (x.load[:, j], x.semi_y[:, j], x.semi_x[:, j])
        out.append(
            TrackElement(
                _BODY_TRACK.get(name, name),
                body,
                1,
                *common,
                on_body,
                n * np.abs(x.body_speed[:, j]) / (2.0 * math.pi),
            )
        )
        out.append(
            TrackElement(
                f"ball_{name}", "ball", n, *common, 2.0 * math.pi * r_s * rho[:, j], ball_rate
            )
        )
    return out


def bearing_elements(x: LifeInputs) -> tuple[list[BearingElement], list[str]]:
    """The support bearings with a rating in ``design.bearings``, and a note for each one
    left out (no rating given, or no load to wear it)."""
    d, b = x.design, x.design.bearings
    out: list[BearingElement] = []
    notes = []
    rev = 1.0 / (2.0 * math.pi)
    if b.roller_bearing_rating is None:
        notes.append("ball-axle bearings left out: no roller_bearing_rating in [design.bearings]")
    else:
        for i, side in enumerate("ab"):
            out.append(
                BearingElement(
                    f"roller_bearing_{side}",
                    d.n_rollers,
                    b.roller_bearing_rating,
                    np.abs(x.axle_reactions[:, i]),
                    np.abs(x.roller_speed) * rev,
                    b.roller_bearing_fatigue_limit,
                    d.roller_bearing_diameter,
                )
            )
    out += _idler_bearings(x, notes)
    if b.disc_bearing_rating is None:
        notes.append("disc thrust bearing left out: no disc_bearing_rating in [design.bearings]")
    else:
        slip = np.abs(x.body_speed[:, 0] - x.body_speed[:, -1]) * rev
        bore = None if d.parasitic is None else d.parasitic.disc_bearing_diameter or None
        load = np.abs(x.axial_force)
        limit = b.disc_bearing_fatigue_limit
        out.append(
            BearingElement("disc_bearing", 1, b.disc_bearing_rating, load, slip, limit, bore)
        )
    return out, notes


def _idler_bearings(x: LifeInputs, notes: list[str]) -> list[BearingElement]:
    """Each double idler's bearing, loaded by its thrust ``n F_Na sin(alpha)``; the single
    idler's bearing carries no load (docs/model.md §1) and is left out with a note."""
    d = x.design
    rating = d.bearings.idler_bearing_rating
    layout = contact_layout(d, x.architecture)
    idlers = [j for j in range(layout.n_contacts) if layout.is_idler[j]]
    if rating is None:
        notes.append("idler bearings left out: no idler_bearing_rating in [design.bearings]")
        return []
    thrust = [d.n_rollers * x.load[:, j] * abs(layout.z_j[j]) for j in idlers]
    if not any(np.any(t > 0) for t in thrust):
        notes.append("idler bearing left out: it carries no load (single idler, radial balance)")
        return []
    return [
        BearingElement(
            f"idler_bearing_{layout.names[j].removeprefix('idler_')}",
            1,
            rating,
            t,
            np.abs(x.body_speed[:, j]) / (2.0 * math.pi),
            d.bearings.idler_bearing_fatigue_limit,
            d.idler_bearing_diameter,
        )
        for j, t in zip(idlers, thrust)
    ]


def rated_viscosity(speed, diameter):
    """Rated kinematic viscosity ``nu_1`` of a bearing (ISO 281:2007 §9.3.3, Fig. 13).

    ``nu_1 = 45000 n^-0.83 d_m^-0.5`` below 1000 rpm, ``4500 n^-0.5 d_m^-0.5`` above
    (``n`` in rpm, ``d_m`` in mm, ``nu_1`` in mm^2/s).

    Parameters
    ----------
    speed : array_like
        Revolutions per second of the bearing [1/s] (> 0).
    diameter : float
        Mean diameter ``d_m`` [m].

    Returns
    -------
    ndarray
        ``nu_1`` [m^2/s].
    """
    n = 60.0 * np.asarray(speed, dtype=float)
    dm = 1e3 * diameter
    with np.errstate(divide="ignore"):
        nu1 = np.where(n < 1000.0, 45000.0 * n**-0.83, 4500.0 * n**-0.5) / np.sqrt(dm)
    return 1e-6 * nu1
