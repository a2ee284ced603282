"""`ShiftResult`: a shift transient as a time series and its summary (docs/shifting.md)."""

from __future__ import annotations

import json
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..._version import __version__
from ...files import atomic_write_text, strict_json, write_json

__all__ = ["ShiftResult", "SUMMARY_KEYS"]

#: The summary keys of `ShiftResult.to_dict` (and of ``ballcvt shift --json``).
SUMMARY_KEYS = (
    "mechanism",
    "from_ratio",
    "to_ratio",
    "final_ratio",
    "shift_time_s",
    "peak_shift_moment_Nm",
    "loss_energy_J",
    "shift_work_J",
    "energy_lost_J",
)


@dataclass(frozen=True)
class ShiftResult:
    """A shift from one ratio to another over time (SI units; column names carry theirs).

    Attributes
    ----------
    mechanism : str
        ``"skew"`` (skew-steered), ``"tilt-rate"`` (tilt-direct at a commanded rate) or
        ``"actuator-moment"`` (tilt-direct under a moment).
    from_ratio, to_ratio, final_ratio : float
        Start, target and last sampled ideal ratio ``tau_ID`` [-] (the last differs from
        the target by the overshoot of a skew removed with a lag).
    samples : pandas.DataFrame
        One row per output sample: ``time_s``, ``tilt_deg``, ``ratio``, ``skew_deg``,
        ``tilt_rate_deg_s``, ``ball_speed_rad_s``, ``side_slip_<contact>``,
        ``holding_moment_Nm`` and ``shift_moment_Nm`` (per ball), ``shifter_moment_Nm``
        (all balls), ``input_torque_Nm``, ``output_speed_rpm``, ``eta``,
        ``power_loss_W`` and ``converged`` (the quasi-static point at that ratio).
    shift_time_s : float
        Time to reach the target ratio [s].
    peak_shift_moment_Nm : float
        Largest ``|shifter_moment_Nm|`` over the shift [N m] (NaN without a moment model).
    loss_energy_J, shift_work_J, energy_lost_J : float
        Trapezoid integrals over the samples of the power losses, of the side-slip
        dissipation ``n M_shift gamma_dot`` (tilt-direct; zero under skew steering), and
        their sum [J]; NaN where a sample has no solution or the moments are unknown.
    inputs : Mapping
        The command, the operating point and the drive.
    notes : tuple of str
        What the numbers do not include, one line each.
    version : str
        ballcvt version that computed the result.
    """

    mechanism: str
    from_ratio: float
    to_ratio: float
    final_ratio: float
    samples: Any
    shift_time_s: float
    peak_shift_moment_Nm: float
    loss_energy_J: float
    shift_work_J: float
    energy_lost_J: float
    inputs: Mapping[str, Any] = field(default_factory=dict)
    notes: tuple[str, ...] = ()
    version: str = __version__

    def to_dict(self) -> dict[str, Any]:
        """The summary, the inputs and the notes (no time series), JSON-ready."""
        out = {key: getattr(self, key) for key in SUMMARY_KEYS}
        return {
            **out,
            "inputs": dict(self.inputs),
            "notes": list(self.notes),
            "version": self.version,
        }

    def to_json(self) -> str:
        """`to_dict` as strict JSON text (NaN written ``null``)."""
        clean, _ = strict_json(self.to_dict())
        return json.dumps(clean, indent=2, allow_nan=False)

    def to_csv(self, path) -> Path:
        """Write the time series as CSV, atomically (through `ballcvt.files`)."""
        return atomic_write_text(path, self.samples.to_csv(index=False))

    def save(self, out) -> list[Path]:
        """Write ``shift.csv`` and ``summary.json`` into the folder ``out``."""
        out = Path(out)
        return [self.to_csv(out / "shift.csv"), write_json(out / "summary.json", self.to_dict())]

    def __repr__(self) -> str:
        moment = self.peak_shift_moment_Nm
        peak = "unknown" if not np.isfinite(moment) else f"{moment:.4g} N m"
        return (
            f"ShiftResult({self.mechanism}: {self.from_ratio:g} -> {self.to_ratio:g} in "
            f"{self.shift_time_s:.4g} s, peak shift moment {peak}, energy lost "
            f"{self.energy_lost_J:.4g} J, {len(self.samples)} samples)"
        )
