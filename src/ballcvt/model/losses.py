"""Parasitic losses beyond the paper: churning, seals, disc thrust bearings (docs/model.md §12).

Off by default (a design without a ``[design.parasitic]`` table has none), so every figure
of the paper is unchanged. All functions are pure, SI in and out, and broadcast.
"""

from __future__ import annotations

import numpy as np

from ..params.models import Design, Fluid

__all__ = [
    "moment_coefficient",
    "windage_torque",
    "seal_torque",
    "thrust_bearing_torque",
    "parasitic_torques",
    "PARASITIC_KINDS",
]

#: Kinds of parasitic loss: the last axis of the shaft drag torques.
PARASITIC_KINDS = ("churning", "seals", "disc_bearings")


def moment_coefficient(reynolds):
    """Moment coefficient ``C_M`` of a body of radius ``r`` spinning in a fluid [-].

    ``C_M = M / (rho omega^2 r^5 / 2)`` as a function of ``Re = omega r^2 / nu``: the
    largest of the creeping-flow sphere, ``16 pi / Re`` (Stokes' torque ``8 pi mu r^3
    omega``, Lamb, Hydrodynamics, 6th ed., 1932, Art. 334), the laminar disc wetted on both
    faces, ``3.87 / Re^(1/2)`` (von Karman 1921, Cochran 1934), and the turbulent disc,
    ``0.146 / Re^(1/5)`` (Schlichting and Gersten, Boundary-Layer Theory, 9th ed., 2017,
    Sec. 5.2.4 and Ch. 22). Using the disc's boundary-layer values for a sphere of the same
    radius is an assumption of ballcvt (docs/model.md §12).

    Parameters
    ----------
    reynolds : array_like
        Rotational Reynolds number ``omega r^2 / nu`` >= 0 [-].

    Returns
    -------
    ndarray
        ``C_M`` [-] (``inf`` at ``Re = 0``, where the torque is zero).
    """
    re = np.asarray(reynolds, dtype=float)
    with np.errstate(divide="ignore"):
        return np.maximum.reduce([16.0 * np.pi / re, 3.87 / np.sqrt(re), 0.146 / re**0.2])


def windage_torque(speed, radius, density, kinematic_viscosity, factor=1.0):
    """Drag torque on a body spinning in oil (churning/windage) [N m].

    ``M = factor C_M(Re) rho omega^2 r^5 / 2`` with `moment_coefficient`.

    Parameters
    ----------
    speed : array_like
        Spin speed ``omega`` [rad/s] (sign ignored).
    radius : array_like
        Body radius ``r`` [m].
    density : float
        Effective density of the surrounding oil-air mixture [kg/m^3].
    kinematic_viscosity : float
        Kinematic viscosity of the oil [m^2/s].
    factor : float
        Multiplier on ``C_M`` (1 for the formulas as published) [-].

    Returns
    -------
    ndarray
        Torque magnitude [N m].
    """
    w = np.abs(np.asarray(speed, dtype=float))
    r = np.asarray(radius, dtype=float)
    re = w * r**2 / kinematic_viscosity
    with np.errstate(invalid="ignore"):
        m = 0.5 * factor * moment_coefficient(re) * density * w**2 * r**5
    return np.where(w > 0, m, 0.0)


def seal_torque(diameter, k1, beta, k2):
    """Friction torque of one contact lip seal ``M = K_S1 d_s^beta + K_S2`` [N m].

    The form of the SKF model of the seals' frictional moment (SKF, Rolling bearings,
    catalogue 17000 EN, 2018, "The SKF model for calculating the frictional moment"), with
    ``d_s`` in mm and ``M`` in N mm; the constants depend on the seal type and size and
    come from its maker.

    Parameters
    ----------
    diameter : float
        Seal counterface diameter ``d_s`` [m].
    k1, beta, k2 : float
        ``K_S1`` [N mm / mm^beta], ``beta`` [-], ``K_S2`` [N mm].

    Returns
    -------
    float
        Torque [N m].
    """
    return 1e-3 * (k1 * (diameter * 1e3) ** beta + k2)


def thrust_bearing_torque(thrust, diameter, friction):
    """Friction torque of a thrust ball bearing ``M = mu F_ax d / 2`` [N m].

    The constant-coefficient estimate of SKF (Rolling bearings, catalogue 17000 EN, 2018,
    "Estimating the frictional moment", ``mu = 0.0013`` for thrust ball bearings).

    Parameters
    ----------
    thrust : array_like
        Axial load ``F_ax`` [N].
    diameter : float
        Bearing bore diameter ``d`` [m].
    friction : float
        Constant friction coefficient ``mu`` [-].

    Returns
    -------
    ndarray
        Torque magnitude [N m].
    """
    return friction * np.abs(np.asarray(thrust, dtype=float)) * diameter / 2.0


def parasitic_torques(design: Design, fluid: Fluid, input_speed, output_speed, ball_speed, thrust):
    """Drag torques of the parasitic losses at given speeds (docs/model.md §12).

    Parameters
    ----------
    design, fluid : Design, Fluid
        The drive; ``design.parasitic`` None gives zeros (the paper's model).
    input_speed, output_speed : array_like
        Disc speeds ``omega_0``, ``omega_2`` [rad/s].
    ball_speed : array_like
        Ball spin speed ``omega_S`` [rad/s].
    thrust : array_like
        Disc axial thrust ``F_ax`` [N].

    Returns
    -------
    ball : ndarray
        Churning torque on each ball about its spin axis [N m], shape ``(...)``.
    input, output : ndarray
        Drag torques on the input and output shafts by kind (`PARASITIC_KINDS`) [N m],
        shape ``(..., 3)``: positive where they oppose the shaft's rotation. The disc
        thrust bearing's torque has opposite signs on the two shafts; its power is
        ``M |omega_0 - omega_2|``.
    """
    shape = np.broadcast_shapes(
        *(np.shape(a) for a in (input_speed, output_speed, ball_speed, thrust))
    )
    par = design.parasitic
    if par is None:
        return np.zeros(shape), np.zeros(shape + (3,)), np.zeros(shape + (3,))
    rho = par.oil_fraction * fluid.density
    nu = fluid.kinematic_viscosity
    ball = windage_torque(ball_speed, design.roller_radius, rho, nu, par.churning_factor)
    seal = (
        seal_torque(par.seal_diameter, par.seal_k1, par.seal_beta, par.seal_k2)
        if par.seal_diameter > 0
        else 0.0
    )

    # the thrust bearing closing the clamping loop between the discs turns at their
    # relative speed: it brakes the faster disc and drives the slower one
    slip = np.sign(np.asarray(input_speed, float) - np.asarray(output_speed, float))
    bearing = slip * thrust_bearing_torque(
        thrust, par.disc_bearing_diameter, par.disc_bearing_friction
    )

    def shaft(speed, sign):
        parts = np.broadcast_arrays(
            windage_torque(speed, par.disc_radius, rho, nu, par.churning_factor),
            np.asarray(seal, dtype=float),
            sign * bearing,
        )
        return np.broadcast_to(np.stack(parts, axis=-1), shape + (3,)).copy()

    return (
        np.broadcast_to(ball, shape).copy(),
        shaft(input_speed, 1.0),
        shaft(output_speed, -1.0),
    )
