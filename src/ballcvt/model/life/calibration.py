"""Lundberg-Palmgren life of a radially loaded deep-groove ball bearing, and the
calibration of the material constants against a published load rating (docs/life.md §6).

The calibration is done once, against the ISO 281 basic dynamic load rating of a 6206
deep-groove ball bearing (20.3 kN in the SKF catalogue): at ``F_r = C`` the bearing
lives ``10^6`` revolutions of its inner ring. ``steel_52100.toml`` stores the result;
``tests/test_life_calibration.py`` checks that it reproduces.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...params.material import FatigueMaterial
from ..hertz import hertz_contact
from .combine import miner_life, system_l10
from .contact import contact_l10

__all__ = ["BallBearing", "BEARING_6206", "RATING_6206", "ball_bearing_l10", "calibrate_constants"]

#: Angular elements of the load zone (the life agrees with the closed form to 1e-11).
_ELEMENTS = 2000


@dataclass(frozen=True)
class BallBearing:
    """Internal geometry of a single-row deep-groove ball bearing (zero clearance).

    Attributes
    ----------
    ball_diameter : float
        ``D`` [m].
    n_balls : int
        ``Z`` [-].
    pitch_diameter : float
        ``d_m`` [m].
    inner_conformity, outer_conformity : float
        Groove radius over ball diameter ``f_i``, ``f_o`` [-].
    """

    ball_diameter: float
    n_balls: int
    pitch_diameter: float
    inner_conformity: float
    outer_conformity: float


#: 6206: nine 3/8 in balls on a 46 mm pitch circle ((30 + 62) / 2 mm; SKF catalogue and
#: Harris and Kotzalas, Rolling Bearing Analysis, 5th ed., Example 2.2), groove radii
#: 0.52 D and 0.53 D (the conformities ISO 281 Table 2 assumes).
BEARING_6206 = BallBearing(9.525e-3, 9, 46.0e-3, 0.52, 0.53)
#: Basic dynamic load rating of the 6206 (SKF catalogue, 6206 / 6206-2RS1) [N].
RATING_6206 = 20.3e3


def _race_contacts(bearing: BallBearing, loads, material: FatigueMaterial, inner: bool):
    """Hertz semi-axes (transverse, rolling) and track length of one raceway."""
    d, dm = bearing.ball_diameter, bearing.pitch_diameter
    sign = -1.0 if inner else 1.0
    rx = d * (dm + sign * d) / (2.0 * dm)  # ball against the race in the rolling plane
    f = bearing.inner_conformity if inner else bearing.outer_conformity
    ry = f * d / (2.0 * f - 1.0)  # ball in the groove
    ax, ay, _, _ = hertz_contact(loads, rx, ry, material.reduced_modulus)
    return ay, ax, np.pi * (dm + sign * d)


def ball_bearing_l10(
    bearing: BallBearing, radial_load, material: FatigueMaterial, model="lundberg-palmgren"
):
    """``L10`` of a radially loaded ball bearing from contact lives [10^6 revolutions].

    Inner ring turning, outer ring fixed, zero clearance: ``Q(psi) = Q_max
    cos(psi)^(3/2)`` over ``|psi| < 90 deg`` with ``F_r = Z Q_max J_r``, ``J_r =
    (1/2 pi) int cos(psi)^(5/2) dpsi = 0.2288`` (Stribeck; Harris and Kotzalas, 5th ed.,
    §7.4). A point of the turning inner race meets every ``Q(psi)``: Miner's rule over
    the load zone (Lundberg and Palmgren's cubic mean load). Each element of the fixed
    outer race carries its own ``Q(psi)``: the elements are in series (`system_l10`).
    A point of the inner race is overrolled ``Z (1 + gamma) / 2`` times per revolution,
    one of the outer ``Z (1 - gamma) / 2`` times (``gamma = D / d_m``); the two races
    are in series.

    Parameters
    ----------
    bearing : BallBearing
        Geometry.
    radial_load : float
        ``F_r`` [N].
    material : FatigueMaterial
        Fatigue and elastic constants.
    model : str
        Life model (``ballcvt.registry.LIFE_MODELS``).

    Returns
    -------
    float
        ``L10`` [10^6 revolutions of the inner ring].
    """
    psi = (np.arange(_ELEMENTS) + 0.5) / _ELEMENTS * np.pi - 0.5 * np.pi
    shape = np.cos(psi) ** 1.5
    j_r = np.sum(shape * np.cos(psi)) / (2.0 * _ELEMENTS)  # (1/2pi) int over |psi| < pi/2
    loads = radial_load / (bearing.n_balls * j_r) * shape
    gamma = bearing.ball_diameter / bearing.pitch_diameter
    share = np.full(_ELEMENTS, 0.5 / _ELEMENTS)  # d psi / 2 pi of each element
    a, b, length = _race_contacts(bearing, loads, material, inner=True)
    inner = miner_life(share, contact_l10(loads, a, b, length, material, model))
    inner = inner / (0.5 * bearing.n_balls * (1.0 + gamma))
    a, b, length = _race_contacts(bearing, loads, material, inner=False)
    outer_elements = contact_l10(loads, a, b, length * share, material, model)
    outer = system_l10(outer_elements, material.weibull_slope)
    outer = outer / (0.5 * bearing.n_balls * (1.0 - gamma))
    return float(system_l10([inner, outer], material.weibull_slope)) / 1e6


def calibrate_constants(
    material: FatigueMaterial, bearing: BallBearing = BEARING_6206, rating: float = RATING_6206
) -> tuple[float, float]:
    """The Lundberg-Palmgren and Zaretsky constants that give ``bearing`` the rating
    ``rating``: ``L10(F_r = C) = 10^6`` inner-ring revolutions (ISO 281:2007 §3.5).

    Every life scales as ``constant^(1/e)``, so one evaluation with the material's
    constants rescales them: ``A = A_0 (1 / L10_0)^e``.

    Returns
    -------
    lp_constant, zaretsky_constant : float
        [Pa^c m^(3-h)] and [Pa^(n e - 2) m^3].
    """
    e = material.weibull_slope
    lp = ball_bearing_l10(bearing, rating, material, "lundberg-palmgren")
    zaretsky = ball_bearing_l10(bearing, rating, material, "zaretsky")
    return material.lp_constant * lp**-e, material.zaretsky_constant * zaretsky**-e
