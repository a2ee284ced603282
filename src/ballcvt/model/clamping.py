"""Clamping laws: where the input-contact normal load ``F_N0`` comes from (docs/model.md §11).

A clamping law is a named, pluggable piece. Every law answers one question: the clamping
force ``F_N0`` [N] at given disc torques. The solver treats a law whose force depends on
the solved input torque (``implicit``) as part of the equilibrium; the others are
evaluated before it. Adding a law means adding a class here (and its tests); the solver,
the sweeps and the CLI take any object with this interface:

* ``name`` (str), ``implicit`` (bool: depends on the input torque ``T_0``);
* ``clamp_force(design, input_torque, output_torque)`` -> ``F_N0`` [N];
* ``output_torque_bound(design, clamp_force, ratio)`` -> the largest ``T_2`` [N m] at which
  the law's force stays at or below ``clamp_force`` (the capacity search's upper end).

The efficiency-optimal clamp is not a force law but an optimisation; `OptimalClamp` names
it and `ballcvt.solvers.optimal_clamp` carries it out.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..params.models import Design
from ..registry import CLAMP_LAWS as REGISTRY

__all__ = ["ConstantClamp", "CamClamp", "OptimalClamp", "CLAMP_LAWS", "axial_force", "clamp_law"]

#: The law names accepted by `clamp_law`, the CLI and the cycle runner.
CLAMP_LAWS = ("constant", "cam", "optimal")


def axial_force(design: Design, clamp_force):
    """Axial thrust on each disc ``F_D0 = n F_N0 sin(theta_0)`` [N] (docs/model.md §1).

    Parameters
    ----------
    design : Design
        Drive geometry.
    clamp_force : array_like
        Input-contact normal load ``F_N0`` [N].

    Returns
    -------
    ndarray or float
        Disc thrust [N]; the output disc carries the same (``F_N2 sin theta_2 =
        F_N0 sin theta_0``, Eq. 29).
    """
    return design.n_rollers * np.asarray(clamp_force, dtype=float) * math.sin(design.theta0)


@dataclass(frozen=True)
class ConstantClamp:
    """The paper's test rig: a fixed ``F_N0`` (the default law).

    Parameters
    ----------
    force : float
        Input-contact normal load ``F_N0`` > 0 [N].
    """

    force: float
    name: str = "constant"
    implicit: bool = False

    def clamp_force(self, design: Design, input_torque, output_torque):
        """``F_N0`` [N], the same at every torque; shape of the torques."""
        shape = np.broadcast_shapes(np.shape(input_torque), np.shape(output_torque))
        return np.full(shape, float(self.force))

    def output_torque_bound(self, design: Design, clamp_force, ratio):
        """Every torque if ``force <= clamp_force``, none otherwise [N m]."""
        return np.where(self.force <= np.asarray(clamp_force, float), np.inf, 0.0)


@dataclass(frozen=True)
class CamClamp:
    """Torque-sensing loading cam (ball ramp) with a preload spring.

    The thrust is ``F_ax = F_pre + |T| / (r_m tan(phi + atan(mu_r)))``, with ``T`` the
    torque of the disc the cam sits on: the power-screw relation for a load raised by the
    torque (Budynas and Nisbett, Shigley's Mechanical Engineering Design, 10th ed., 2015,
    Eq. 8-1, with the friction angle ``atan(mu_r)``); loading cams of traction drives after
    Loewenthal and Zaretsky, "Design of traction drives", NASA RP-1154 (1985). The clamping
    force is ``F_N0 = F_ax / (n sin theta_0)`` (docs/model.md §1, §11).

    Parameters
    ----------
    preload : float
        Spring preload ``F_pre`` >= 0 [N].
    ramp_angle : float
        Ramp angle ``phi`` [rad], in (0, pi/3).
    mean_radius : float
        Mean radius of the ramp ``r_m`` > 0 [m].
    friction : float
        Ramp friction coefficient ``mu_r`` >= 0 [-].
    disc : {"input", "output"}
        Disc whose torque the cam senses; "input" makes the force depend on the solved
        input torque (solved with the equilibrium).
    """

    preload: float
    ramp_angle: float
    mean_radius: float
    friction: float
    disc: str = "output"
    name: str = "cam"

    def __post_init__(self):
        if self.disc not in ("input", "output"):
            raise InputError("cam.disc", self.disc, "'input' or 'output'")

    @classmethod
    def from_design(cls, design: Design) -> CamClamp:
        """The cam of ``design.cam`` (`InputError` if the design has none)."""
        cam = design.cam
        if cam is None:
            raise InputError(
                "design.cam",
                None,
                "a [design.cam] table (preload, ramp_angle_deg, mean_radius, friction, disc)",
                message=f"clamping law 'cam' needs a loading cam: the design "
                f"'{design.name}' has no [design.cam] table (docs/model.md §11)",
            )
        return cls(cam.preload, cam.ramp_angle, cam.mean_radius, cam.friction, cam.disc)

    @property
    def implicit(self) -> bool:
        """True when the cam senses the input torque, which the equilibrium determines."""
        return self.disc == "input"

    @property
    def gain(self) -> float:
        """Thrust per unit disc torque ``1 / (r_m tan(phi + atan(mu_r)))`` [1/m]."""
        return 1.0 / (self.mean_radius * math.tan(self.ramp_angle + math.atan(self.friction)))

    def thrust(self, torque):
        """Axial thrust ``F_ax`` [N] for a disc torque [N m] of either sign."""
        return self.preload + self.gain * np.abs(np.asarray(torque, dtype=float))

    def clamp_force(self, design: Design, input_torque, output_torque):
        """``F_N0`` [N] at the given disc torques [N m]."""
        torque = input_torque if self.implicit else output_torque
        return self.thrust(torque) / (design.n_rollers * math.sin(design.theta0))

    def output_torque_bound(self, design: Design, clamp_force, ratio):
        """Largest ``T_2`` [N m] whose cam force stays at or below ``clamp_force``.

        For an input-disc cam this uses ``T_2 <= T_0 / tau_ID`` (power cannot grow), so
        it is an upper bound, not the exact torque.
        """
        thrust = axial_force(design, clamp_force)
        torque = np.maximum(thrust - self.preload, 0.0) / self.gain
        ratio = np.asarray(ratio, dtype=float)
        return torque / ratio if self.implicit else np.broadcast_to(torque, ratio.shape)


@dataclass(frozen=True)
class OptimalClamp:
    """The clamping force of maximum efficiency at each point (`ballcvt.solvers.optimal_clamp`).

    Parameters
    ----------
    creep_limit : float, optional
        ``C_lim`` [-]; the design's by default.
    max_pressure : float, optional
        Largest Hertz peak pressure [Pa]; the design's by default.
    """

    creep_limit: float | None = None
    max_pressure: float | None = None
    name: str = "optimal"
    implicit: bool = False


for _law in (ConstantClamp, CamClamp, OptimalClamp):
    REGISTRY.register(_law, name=_law.name)


def clamp_law(law, design: Design, clamp_force=None):
    """Resolve a law given by name or object, with the force of the constant law.

    Parameters
    ----------
    law : str, law object or None
        ``"constant"`` (or None), ``"cam"`` (the design's ``[design.cam]``),
        ``"optimal"``, or a law object.
    design : Design
        Drive (for the cam's parameters).
    clamp_force : float, optional
        ``F_N0`` [N] of the constant law; must not be given with another law.

    Returns
    -------
    ConstantClamp, CamClamp, OptimalClamp or the object given
    """
    if law is None or law == "constant":
        if clamp_force is None:
            raise InputError(
                "clamp_force",
                None,
                "a value [N] for the constant clamping law "
                "(or choose another clamp_law: " + ", ".join(CLAMP_LAWS[1:]) + ")",
            )
        return ConstantClamp(float(clamp_force))
    if clamp_force is not None:
        raise InputError(
            "clamp_force",
            clamp_force,
            f"not given with clamp_law "
            f"{getattr(law, 'name', law)!r} (the law sets the clamping force)",
        )
    if isinstance(law, str):
        if law == "cam":
            return CamClamp.from_design(design)
        if law == "optimal":
            return OptimalClamp()
        raise InputError("clamp_law", law, "one of: " + ", ".join(CLAMP_LAWS))
    return law
