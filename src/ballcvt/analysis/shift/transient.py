"""The shift transient: tilt ``gamma(t)`` from one ratio to another (docs/shifting.md).

Three ways to drive it (`MECHANISMS`):

- ``"skew"``: skew-steered; the carrier skews every axle by ``zeta`` and the balls tilt at
  the rate that rolls without side slip, ``gamma_dot = omega_b cos(gamma) tan(zeta)``
  (`ballcvt.model.shift_kinematics.skew_tilt_rate`); the skew is removed (``zeta -> 0``,
  through the actuator lag) when the target is reached (a terminal event);
- ``"tilt-rate"``: tilt-direct at a commanded rate;
- ``"actuator-moment"``: tilt-direct under a moment about the tilt axes (all balls); the
  rate solves ``M = n (M_hold + M_shift(gamma_dot))`` (Brent's method) with a moment model.

Each command may follow its set value with a first-order lag ``t_lag``. The ODE is solved
with `scipy.integrate.solve_ivp` (RK45); the input speed is held (the drive line's inertia
is not integrated) and every output sample is the quasi-static steady point at its ratio.
"""

from __future__ import annotations

import warnings
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np

from ...errors import InputError
from ...model.kinematics import check_ratio, ideal_ratio, tilt_from_ratio, usable_tilt_range
from ...model.layout import ContactLayout
from ...model.shift_kinematics import ball_spin_speed, skew_tilt_rate
from ...params.models import Design
from .result import ShiftResult
from .sampling import sample_shift

__all__ = [
    "MECHANISMS",
    "MomentModel",
    "LinearViscousMoments",
    "ShiftCommand",
    "ShiftDrive",
    "run_shift",
]

#: The shift mechanisms and the unit of their command value.
MECHANISMS = {"skew": "rad", "tilt-rate": "rad/s", "actuator-moment": "N m"}


class MomentModel(Protocol):
    """``(ratio, output_torque, tilt_rate, input_speed) -> (holding, shift)``: the moment
    per ball about its tilt axis that holds the ratio, and the extra moment to tilt at
    ``tilt_rate`` [N m] (ratio [-], torque [N m], rates [rad/s])."""

    def __call__(
        self, ratio: float, output_torque: float, tilt_rate: float, input_speed: float
    ) -> tuple[float, float]: ...


@dataclass(frozen=True)
class LinearViscousMoments:
    """A PLACEHOLDER moment model, for tests only: a constant holding moment and a shift
    moment linear in the tilt rate, ``damping gamma_dot`` [N m per ball].

    It has no physics of the contacts (the side-slip traction of docs/shifting.md): never
    use it for a number a user reads. `ballcvt.api.shift` uses the contact model's
    ``Variator.shift_moments`` when the build has it, and no moments otherwise.
    """

    holding: float = 0.0  # [N m] per ball
    damping: float = 1.0  # [N m s/rad] per ball

    def __call__(self, ratio, output_torque, tilt_rate, input_speed):  # noqa: D102
        return self.holding, self.damping * tilt_rate


@dataclass(frozen=True)
class ShiftCommand:
    """What drives a shift.

    Attributes
    ----------
    mechanism : str
        A key of `MECHANISMS`.
    value : float
        Its size > 0: the skew [rad], the tilt rate [rad/s] or the actuator moment about
        the tilt axes of all balls [N m]; the sign follows the shift's direction.
    lag : float
        First-order time constant of the actuator [s] (0: the command acts at once).
    samples : int
        Output samples over the shift (a quarter more after it while a skew decays).
    max_time : float
        Longest shift integrated before it is refused as never arriving [s].
    """

    mechanism: str
    value: float
    lag: float = 0.0
    samples: int = 51
    max_time: float = 60.0

    def check(self) -> ShiftCommand:
        """Self, or `InputError` naming the bad field."""
        if self.mechanism not in MECHANISMS:
            raise InputError("mechanism", self.mechanism, "one of " + ", ".join(MECHANISMS))
        unit = MECHANISMS[self.mechanism]
        if not (np.isfinite(self.value) and self.value > 0):
            why = (
                " (zero skew keeps the ratio: the shift never arrives)" if self.value == 0 else ""
            )
            raise InputError(self.mechanism, self.value, f"> 0 {unit}{why}")
        if self.mechanism == "skew" and self.value >= np.radians(10.0):
            raise InputError("skew", np.degrees(self.value), "< 10 deg (a small skew angle)")
        if not (np.isfinite(self.lag) and self.lag >= 0):
            raise InputError("actuator_lag", self.lag, ">= 0 s")
        if not 3 <= int(self.samples) <= 10_000:
            raise InputError("samples", self.samples, "3-10000")
        if not (np.isfinite(self.max_time) and self.max_time > 0):
            raise InputError("max_time", self.max_time, "> 0 s")
        return self


@dataclass(frozen=True)
class ShiftDrive:
    """The drive a shift runs on.

    Attributes
    ----------
    design : Design
    layout : ContactLayout
        Of the design's architecture.
    input_speed : float
        Input disc speed ``omega_0`` relative to the carrier, held [rad/s].
    output_torque : float
        ``T_2`` [N m].
    point : callable
        ``point(ratio)``: the steady `OperatingResult` at an ideal ratio (a `BallCVTError`
        where there is none).
    moments : MomentModel, optional
        Holding and shift moments; without one the moment columns are NaN and an
        ``actuator-moment`` shift is refused.
    labels : Mapping
        What the result's ``inputs`` repeat (drive, clamping).
    """

    design: Design
    layout: ContactLayout
    input_speed: float
    output_torque: float
    point: Callable[[float], Any]
    moments: MomentModel | None = None
    labels: dict = field(default_factory=dict)


@dataclass(frozen=True)
class _Dynamics:
    """The right-hand side: state ``(gamma, c)``, ``c`` the lagged command (skew [rad],
    tilt rate [rad/s] or moment [N m])."""

    drive: ShiftDrive
    command: ShiftCommand

    def ball_speed(self, tilt):
        return ball_spin_speed(self.drive.layout, tilt, self.drive.input_speed)

    def rates(self, y, target: float) -> tuple[float, float]:
        """``(gamma_dot, c_dot)`` at state ``y`` toward the command ``target``."""
        gamma, c = float(y[0]), float(y[1])
        lag = self.command.lag
        c_dot = (target - c) / lag if lag > 0 else 0.0
        if self.command.mechanism == "skew":
            return float(skew_tilt_rate(self.ball_speed(gamma), gamma, c)), c_dot
        if self.command.mechanism == "tilt-rate":
            return c, c_dot
        return self.rate_under(gamma, c), c_dot

    def moments(self, gamma: float, rate: float) -> tuple[float, float]:
        d = self.drive
        assert d.moments is not None
        ratio = float(ideal_ratio(gamma, d.design.theta0, d.design.theta2, d.design.aspect_ratio))
        h, s = d.moments(ratio, d.output_torque, rate, d.input_speed)
        return float(h), float(s)

    def rate_under(self, gamma: float, moment: float) -> float:
        """The tilt rate at which ``n (M_hold + M_shift) = moment`` [rad/s]: the secant
        method from rest (two or three moment evaluations in the linear range), else
        Brent's method over ``|gamma_dot| <= 10 |omega_b|``."""
        from scipy.optimize import brentq, root_scalar

        n = self.drive.design.n_rollers
        excess = lambda r: n * sum(self.moments(gamma, r)) - moment  # noqa: E731
        top = 10.0 * abs(float(self.ball_speed(gamma)))
        step = 1e-3 * top
        with warnings.catch_warnings():  # a secant that diverges (saturation) says so
            warnings.simplefilter("ignore", RuntimeWarning)
            guess = root_scalar(excess, x0=0.0, x1=step, method="secant", xtol=1e-13, maxiter=20)
        if guess.converged and abs(guess.root) <= top:
            return float(guess.root)
        lo, hi = excess(-top), excess(top)
        if lo * hi > 0:
            raise InputError(
                "actuator_moment",
                moment,
                f"between {n * sum(self.moments(gamma, -top)):.4g} and "
                f"{n * sum(self.moments(gamma, top)):.4g} N m at tilt "
                f"{np.degrees(gamma):.3g} deg (beyond, the side forces saturate and the "
                "tilt rate is set by the inertia of the balls, not modelled)",
            )
        return float(brentq(excess, -top, top, xtol=1e-12, rtol=1e-10))


def _integrate(dyn: _Dynamics, y0, span: tuple[float, float], target: float, goal=None):
    """`solve_ivp` from ``y0`` over ``span``; terminal events: the usable tilt limits, and
    the tilt ``goal`` when given."""
    from scipy.integrate import solve_ivp

    lo, hi = usable_tilt_range(dyn.drive.design)

    def limit(t, y):
        return (y[0] - lo) * (hi - y[0])

    limit.terminal = True  # type: ignore[attr-defined]
    events: list = [limit]
    if goal is not None:

        def reach(t, y):
            return y[0] - goal

        reach.terminal = True  # type: ignore[attr-defined]
        events.append(reach)
    return solve_ivp(
        lambda t, y: dyn.rates(y, target),
        span,
        y0,
        method="RK45",
        events=events,
        dense_output=True,
        rtol=1e-9,
        atol=1e-12,
    )


def _command_target(dyn: _Dynamics, g1: float, g2: float) -> float:
    """The signed command: its size toward the target (a skew also by the ball's turn)."""
    direction = np.sign(g2 - g1)
    if dyn.command.mechanism == "skew":
        direction *= np.sign(float(dyn.ball_speed(g1)))
    return float(direction * dyn.command.value)


def _phases(dyn: _Dynamics, g1: float, g2: float, ratios: tuple[float, float]):
    """The solutions of the shift and, for a skew removed with a lag, of its decay."""
    cmd = dyn.command
    target = _command_target(dyn, g1, g2)
    y0 = [g1, 0.0 if cmd.lag > 0 else target]
    first = _integrate(dyn, y0, (0.0, cmd.max_time), target, goal=g2)
    if first.t_events[1].size == 0:
        d = dyn.drive.design
        reached = float(ideal_ratio(first.y[0, -1], d.theta0, d.theta2, d.aspect_ratio))
        how = (
            "leaves the usable tilt range"
            if first.t_events[0].size
            else f"is still short of it after max_time {cmd.max_time:g} s"
        )
        raise InputError(
            cmd.mechanism,
            cmd.value,
            "a command that reaches the target",
            message=f"the shift {ratios[0]:g} -> {ratios[1]:g} never arrives: the ratio "
            f"reaches {reached:.4g} and {how} (a larger {cmd.mechanism}, or a longer "
            "max_time)",
        )
    phases = [first]
    if cmd.mechanism == "skew" and cmd.lag > 0:
        end = first.t[-1]
        phases.append(_integrate(dyn, first.y[:, -1], (end, end + 5.0 * cmd.lag), 0.0))
    return phases, target


def run_shift(
    drive: ShiftDrive, command: ShiftCommand, from_ratio: float, to_ratio: float
) -> ShiftResult:
    """Integrate a shift and sample it (module docstring; docs/shifting.md).

    Parameters
    ----------
    drive : ShiftDrive
    command : ShiftCommand
    from_ratio, to_ratio : float
        Start and target ideal ratio ``tau_ID`` [-], within the usable range.

    Returns
    -------
    ShiftResult

    Raises
    ------
    InputError
        A ratio out of range or equal start and target, a bad command, a shift that
        never arrives (or leaves the usable tilt range), an actuator moment without a
        moment model or beyond the saturated side forces.
    """
    command.check()
    d = drive.design
    for name, ratio in (("from_ratio", from_ratio), ("to_ratio", to_ratio)):
        try:
            check_ratio(d, ratio)
        except InputError as exc:
            raise InputError(name, ratio, exc.allowed) from None
    if from_ratio == to_ratio:
        raise InputError("to_ratio", to_ratio, f"a ratio other than from_ratio {from_ratio:g}")
    if command.mechanism == "actuator-moment" and drive.moments is None:
        raise InputError(
            "actuator_moment",
            command.value,
            "a moment model",
            message="an actuator-moment shift needs the shift moments of the contact "
            "model (Variator.shift_moments), which this build does not have: give a "
            "skew or a tilt rate",
        )
    args = (d.theta0, d.theta2, d.aspect_ratio)
    g1, g2 = (float(tilt_from_ratio(r, *args)) for r in (from_ratio, to_ratio))
    dyn = _Dynamics(drive, command)
    phases, target = _phases(dyn, g1, g2, (from_ratio, to_ratio))
    return sample_shift(dyn, phases, target, (from_ratio, to_ratio))
