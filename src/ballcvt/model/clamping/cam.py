"""The loading-cam clamping law: a torque-sensing ball ramp with a preload spring
(docs/model.md §11)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...errors import InputError
from ...params.models import Design
from .base import ClampLaw, axial_force

__all__ = ["CamClamp"]


@dataclass(frozen=True)
class CamClamp(ClampLaw):
    """Torque-sensing loading cam (ball ramp) with a preload spring.

    The thrust is ``F_ax = F_pre + |T| / (r_m tan(phi + atan(mu_r)))`` (on loading), with ``T`` the
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
    branch : {"loading", "unloading"}
        Side of the ramp friction's hysteresis: "loading" (the torque rose to its value:
        the friction resists the ramp's climb, ``tan(phi + atan(mu_r))``, the default)
        or "unloading" (the torque fell to it: the cam stays clamped until the friction
        is overcome, ``tan(phi - atan(mu_r))``, a larger thrust at the same torque; the
        power-screw relation for lowering a load, Budynas and Nisbett, Eq. 8-2). In
        steady running the two cam halves turn together: the ramp friction dissipates
        nothing, it only sets which force holds.
    """

    preload: float
    ramp_angle: float
    mean_radius: float
    friction: float
    disc: str = "output"
    name: str = "cam"
    branch: str = "loading"

    def __post_init__(self):
        if self.disc not in ("input", "output"):
            raise InputError("cam.disc", self.disc, "'input' or 'output'")
        if self.branch not in ("loading", "unloading"):
            raise InputError("cam.branch", self.branch, "'loading' or 'unloading'")
        if self.branch == "unloading" and self.ramp_angle <= math.atan(self.friction):
            raise InputError(
                "cam.branch",
                self.branch,
                "'loading' (the ramp self-locks, phi <= atan(mu_r): it never unloads)",
            )

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
        return cls(
            cam.preload, cam.ramp_angle, cam.mean_radius, cam.friction, cam.disc, branch=cam.branch
        )

    @property
    def implicit(self) -> bool:  # type: ignore[override]  # the base default is False
        """True when the cam senses the input torque, which the equilibrium determines."""
        return self.disc == "input"

    @property
    def gain(self) -> float:
        """Thrust per unit disc torque ``1 / (r_m tan(phi +- atan(mu_r)))`` [1/m] (``+``
        loading, ``-`` unloading)."""
        sign = 1.0 if self.branch == "loading" else -1.0
        return 1.0 / (
            self.mean_radius * math.tan(self.ramp_angle + sign * math.atan(self.friction))
        )

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
