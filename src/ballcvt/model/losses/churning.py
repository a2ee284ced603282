"""Churning: the drag of the oil-air mixture on the spinning balls and discs (docs/model.md §12).

Two built-in loss terms of kind ``churning``: ``roller_churning`` on each ball about its spin
axis and ``disc_churning`` on each disc shaft, both read from ``design.parasitic``.
"""

from __future__ import annotations

import numpy as np

from ...registry import LOSS_TERMS
from .base import DragInputs, LossTerm, has_parasitic

__all__ = ["moment_coefficient", "windage_torque", "BALL_CHURNING", "DISC_CHURNING"]


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
    with np.errstate(divide="ignore", over="ignore"):  # inf at (near) rest, as documented
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
    # at rest, or so slow that C_M overflows while omega^2 underflows: no torque
    return np.where(np.isfinite(m), m, 0.0)


def _roller_churning(at: DragInputs):
    """Churning torque on one ball, radius ``r_S`` (`windage_torque`) [N m]."""
    par, fl = at.design.parasitic, at.fluid
    assert par is not None
    rho = par.oil_fraction * fl.density
    return windage_torque(
        at.speed, at.design.roller_radius, rho, fl.kinematic_viscosity, par.churning_factor
    )


def _disc_churning(at: DragInputs):
    """Churning torque on one disc, radius ``disc_radius`` (`windage_torque`) [N m]."""
    par, fl = at.design.parasitic, at.fluid
    assert par is not None
    rho = par.oil_fraction * fl.density
    return windage_torque(
        at.speed, par.disc_radius, rho, fl.kinematic_viscosity, par.churning_factor
    )


_SOURCE = "design.parasitic: oil_fraction, churning_factor (balls); and disc_radius (discs)"
BALL_CHURNING = LOSS_TERMS.register(
    LossTerm("roller_churning", "rollers", _roller_churning, "churning", _SOURCE, has_parasitic)
)
DISC_CHURNING = LOSS_TERMS.register(
    LossTerm("disc_churning", "shafts", _disc_churning, "churning", _SOURCE, has_parasitic)
)
