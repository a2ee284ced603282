"""The shift transient on `Variator` (``ballcvt shift``; docs/shifting.md)."""

from __future__ import annotations

import math
from typing import Any

from ..errors import InputError
from ..model.architectures import contact_layout
from ..params.models import Design, Fluid
from ..solvers.options import SolverOptions
from ..units import rad_s_to_rpm
from .hints import one_speed

__all__ = ["ShiftMethods", "default_moment_model"]

#: The keywords of `ShiftMethods.shift` passed on to `Variator.solve`.
_POINT_KEYS = ("clamp_force", "clamp_law", "input_speed", "input_speed_rpm")
#: The keywords of `ShiftMethods.shift` that set the transient (`ShiftCommand`).
_SHIFT_KEYS = ("actuator_lag", "moment_model", "samples", "max_time")


def default_moment_model(variator, clamp: dict):
    """The holding and shift moments of the contact model (``Variator.shift_moments``,
    docs/model.md §17) as a `ballcvt.analysis.shift.MomentModel` at the clamping
    ``clamp``."""
    moments = variator.shift_moments

    def model(ratio, output_torque, tilt_rate, input_speed):
        rpm = rad_s_to_rpm(input_speed)
        m = moments(ratio, output_torque, tilt_rate=tilt_rate, input_speed_rpm=rpm, **clamp)
        return m.holding_moment, m.shift_moment

    return model


def _command(skew_deg, tilt_rate_deg_s, actuator_moment, options: dict):
    """The `ShiftCommand` of exactly one of the three mechanisms."""
    from ..analysis.shift import ShiftCommand

    given = {
        "skew": skew_deg,
        "tilt-rate": tilt_rate_deg_s,
        "actuator-moment": actuator_moment,
    }
    named = [k for k, v in given.items() if v is not None]
    if len(named) != 1:
        raise InputError(
            "mechanism",
            ", ".join(named) or "none",
            "exactly one of skew_deg, tilt_rate_deg_s or actuator_moment",
        )
    value = float(given[named[0]])  # type: ignore[arg-type]
    name, unit = {
        "skew": ("skew_deg", "deg"),
        "tilt-rate": ("tilt_rate_deg_s", "deg/s"),
        "actuator-moment": ("actuator_moment", "N m"),
    }[named[0]]
    if not (math.isfinite(value) and value > 0):
        why = ": zero skew holds the ratio, the shift never arrives" if value == 0 else ""
        raise InputError(name, value, f"> 0 {unit}{why} (the direction follows the ratios)")
    if named[0] == "skew" and value >= 10.0:
        raise InputError(name, value, "< 10 deg (a small skew angle)")
    if named[0] != "actuator-moment":
        value = math.radians(value)
    kept = {k: options[k] for k in ("samples", "max_time") if k in options}
    lag = float(options.get("actuator_lag", 0.0))
    return ShiftCommand(named[0], value, lag, **kept).check()


class ShiftMethods:
    """The shift method `Variator` inherits (its fields are declared here for typing)."""

    design: Design
    fluid: Fluid
    architecture: str
    options: SolverOptions

    def shift(
        self,
        from_ratio: float,
        to_ratio: float,
        output_torque: float,
        *,
        skew_deg: float | None = None,
        tilt_rate_deg_s: float | None = None,
        actuator_moment: float | None = None,
        **options: Any,
    ):
        """Shift from one ideal ratio to another over time (docs/shifting.md).

        Parameters
        ----------
        from_ratio, to_ratio : float
            Start and target ideal ratio ``tau_ID`` [-], within `ratio_range`.
        output_torque : float
            ``T_2`` during the shift [N m].
        skew_deg : float, optional
            Skew-steered: the skew angle of the axles [deg] (> 0, < 10; its sign follows
            the shift's direction); the balls tilt at ``omega_b cos(gamma) tan(zeta)``.
        tilt_rate_deg_s : float, optional
            Tilt-direct at this tilt rate [deg/s] (> 0).
        actuator_moment : float, optional
            Tilt-direct under this moment about the tilt axes of all balls [N m]; the
            rate follows from the moment balance with the contact model's moments.
        **options
            The point's ``clamp_force`` or ``clamp_law`` and ``input_speed`` [rad/s] or
            ``input_speed_rpm`` (as in `solve`; the input speed is held over the shift);
            the transient's ``actuator_lag`` (first-order time constant [s], 0 by
            default), ``samples`` (51), ``max_time`` (60 s) and ``moment_model`` (a
            `ballcvt.analysis.shift.MomentModel`; default the contact model's
            ``shift_moments`` when the build has it, else none: moments unknown).

        Returns
        -------
        ShiftResult
            The time series (``samples``), ``shift_time_s``, ``peak_shift_moment_Nm``,
            ``energy_lost_J`` and the inputs.
        """
        from ..analysis.shift import ShiftDrive, run_shift

        unknown = sorted(set(options) - set(_POINT_KEYS) - set(_SHIFT_KEYS))
        if unknown:
            raise InputError(unknown[0], options[unknown[0]], ", ".join(_POINT_KEYS + _SHIFT_KEYS))
        command = _command(skew_deg, tilt_rate_deg_s, actuator_moment, options)
        speed = one_speed(options.get("input_speed"), options.get("input_speed_rpm"))
        if not (math.isfinite(speed) and speed > 0):
            raise InputError("input_speed", speed, "> 0 rad/s and finite")
        clamp = {k: options[k] for k in ("clamp_force", "clamp_law") if options.get(k) is not None}
        rpm = rad_s_to_rpm(speed)  # the points in rpm: no second unit hint per sample
        model = options.get("moment_model") or default_moment_model(self, clamp)
        drive = ShiftDrive(
            self.design,
            contact_layout(self.design, self.architecture),
            speed,
            float(output_torque),
            lambda r: self.solve(r, output_torque, input_speed_rpm=rpm, **clamp),  # type: ignore[attr-defined]
            model,
            {
                "design": self.design.name,
                "architecture": self.architecture,
                "clamp": {k: str(v) for k, v in clamp.items()},
            },
        )
        return run_shift(drive, command, float(from_ratio), float(to_ratio))
