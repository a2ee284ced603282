"""Output samples of a shift: kinematics, moments and the quasi-static point at each
(docs/shifting.md)."""

from __future__ import annotations

from typing import Any

import numpy as np

from ...errors import BallCVTError
from ...model.kinematics import ideal_ratio
from ...model.shift_kinematics import side_slip
from ...units import rad_s_to_rpm
from .result import ShiftResult

__all__ = ["sample_shift"]


def _times(phases, samples: int) -> list[np.ndarray]:
    """Sample times of each phase: ``samples`` over the shift, a quarter of them after."""
    first = phases[0]
    out = [np.linspace(first.t[0], first.t[-1], samples)]
    for sol in phases[1:]:
        out.append(np.linspace(sol.t[0], sol.t[-1], max(3, samples // 4))[1:])
    return out


def _kinematics(dyn: Any, phases, target: float) -> dict[str, np.ndarray]:
    """Time, tilt, command state and rates at the samples."""
    rows: list[tuple] = []
    for k, (sol, times) in enumerate(zip(phases, _times(phases, dyn.command.samples))):
        goal = target if k == 0 else 0.0
        for t in times:
            y = sol.sol(t)
            rows.append((t, y[0], y[1], *dyn.rates(y, goal)))
    t, gamma, c, gamma_dot, c_dot = (np.array(col) for col in zip(*rows))
    return {"t": t, "gamma": gamma, "c": c, "gamma_dot": gamma_dot, "c_dot": c_dot}


def _moments(dyn: Any, k: dict[str, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Holding and shift moment per ball at the samples (NaN without a model); under skew
    steering the balls roll without side slip and the shift moment is zero."""
    n = k["t"].size
    skew = dyn.command.mechanism == "skew"
    if dyn.drive.moments is None:
        return np.full(n, np.nan), (np.zeros(n) if skew else np.full(n, np.nan))
    pairs = [dyn.moments(g, 0.0 if skew else r) for g, r in zip(k["gamma"], k["gamma_dot"])]
    hold, shift = (np.array(col) for col in zip(*pairs))
    return hold, (np.zeros(n) if skew else shift)


def _points(dyn: Any, ratio: np.ndarray) -> dict[str, np.ndarray]:
    """The quasi-static point at each sampled ratio (NaN where there is none)."""
    cols: dict[str, list] = {
        "input_torque_Nm": [],
        "output_speed_rpm": [],
        "eta": [],
        "power_loss_W": [],
        "converged": [],
    }
    for r in ratio:
        try:
            p = dyn.drive.point(float(r))
            vals = (p.input_torque, rad_s_to_rpm(p.output_speed), p.eta, p.losses["total"], True)
        except BallCVTError:
            vals = (np.nan, np.nan, np.nan, np.nan, False)
        for key, v in zip(cols, vals):
            cols[key].append(v)
    return {key: np.array(v) for key, v in cols.items()}


def sample_shift(dyn: Any, phases, target: float, ratios: tuple[float, float]) -> ShiftResult:
    """The `ShiftResult` of an integrated shift (``dyn``: the transient's dynamics)."""
    import pandas as pd

    d, drive, cmd = dyn.drive.design, dyn.drive, dyn.command
    k = _kinematics(dyn, phases, target)
    skew = k["c"] if cmd.mechanism == "skew" else np.zeros_like(k["t"])
    skew_rate = k["c_dot"] if cmd.mechanism == "skew" else 0.0
    omega_b = dyn.ball_speed(k["gamma"])
    slip = side_slip(drive.layout, k["gamma"], omega_b, skew, k["gamma_dot"], skew_rate)
    ratio = ideal_ratio(k["gamma"], d.theta0, d.theta2, d.aspect_ratio)
    hold, shift = _moments(dyn, k)
    frame = pd.DataFrame(
        {
            "time_s": k["t"],
            "tilt_deg": np.degrees(k["gamma"]),
            "ratio": ratio,
            "skew_deg": np.degrees(skew),
            "tilt_rate_deg_s": np.degrees(k["gamma_dot"]),
            "ball_speed_rad_s": omega_b,
            **{f"side_slip_{c}": slip[:, i] for i, c in enumerate(drive.layout.names)},
            "holding_moment_Nm": hold,
            "shift_moment_Nm": shift,
            "shifter_moment_Nm": d.n_rollers * (hold + shift),
            **_points(dyn, ratio),
        }
    )
    return _result(dyn, frame, phases, ratios)


def _result(dyn: Any, frame, phases, ratios: tuple[float, float]) -> ShiftResult:
    """Integrals, peak and notes of the sampled shift."""
    cmd, drive = dyn.command, dyn.drive
    t = frame["time_s"].to_numpy()
    loss = float(np.trapezoid(frame["power_loss_W"].to_numpy(), t))
    dissipation = (
        drive.design.n_rollers * frame["shift_moment_Nm"] * np.radians(frame["tilt_rate_deg_s"])
    )
    work = float(np.trapezoid(dissipation.to_numpy(), t))
    moment = np.abs(frame["shifter_moment_Nm"].to_numpy())
    notes = [
        f"input speed held at {rad_s_to_rpm(drive.input_speed):.4g} rpm (the drive line's "
        "inertia is not integrated); each sample is the steady point at its ratio",
    ]
    if drive.moments is None:
        notes.append(
            "no shift-moment model in this build (Variator.shift_moments): the moment "
            "columns, the peak shift moment and the shift work are unknown (NaN)"
        )
    if not frame["converged"].all():
        notes.append(f"{int((~frame['converged']).sum())} samples have no steady point")
    return ShiftResult(
        mechanism=cmd.mechanism,
        from_ratio=float(ratios[0]),
        to_ratio=float(ratios[1]),
        final_ratio=float(frame["ratio"].iloc[-1]),
        samples=frame,
        shift_time_s=float(phases[0].t[-1]),
        peak_shift_moment_Nm=float(np.max(moment)) if np.isfinite(moment).all() else np.nan,
        loss_energy_J=loss,
        shift_work_J=work,
        energy_lost_J=loss + work,
        inputs={
            "mechanism_value": cmd.value,
            "mechanism_unit": {"skew": "rad", "tilt-rate": "rad/s"}.get(cmd.mechanism, "N m"),
            "actuator_lag_s": cmd.lag,
            "samples": cmd.samples,
            "max_time_s": cmd.max_time,
            "input_speed_rpm": rad_s_to_rpm(drive.input_speed),
            "output_torque_Nm": drive.output_torque,
            "n_balls": drive.design.n_rollers,
            **drive.labels,
        },
        notes=tuple(notes),
    )
