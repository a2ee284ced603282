"""Results of an operating point in a planetary mode (docs/model.md §13)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Any

from .._display import html_summary, text_summary
from .._version import __version__
from ..errors import InputError
from ..model.modes import MEMBERS, OperatingMode, member_torques
from ..units import rad_s_to_rpm
from .io import JsonFile, read_result
from .point import OperatingResult

__all__ = ["PlanetaryResult", "make_planetary_result"]


@dataclass(frozen=True)
class PlanetaryResult:
    """An operating point of the variator as a planetary (SI units).

    Attributes
    ----------
    mode : OperatingMode
        Held, driving and driven members.
    relative : OperatingResult
        The point in the carrier frame, its input disc turning forward: creeps, spins,
        pressures, films, contact forces, losses and validity warnings. Its efficiencies
        are those of the variator between its discs in that frame; with the power flowing
        from disc 2 to disc 0 there (`power_flow`) that efficiency is ``1 / eta``.
    sign : float
        +1, or -1 where the carrier-frame point is mirrored (docs/model.md §13): the
        physical relative speeds and torques are ``sign`` times ``relative``'s.
    speeds : Mapping[str, float]
        Speed of ``disc0``, ``disc2``, ``carrier`` [rad/s].
    torques : Mapping[str, float]
        Torque applied to each member from outside [N m] (they sum to zero).
    load_torque : float
        The driven member's load torque, as given [N m].
    driver_speed : float
        The driver's speed, as given [rad/s].
    passes : int
        Solves of the fixed point on the actual ratio.
    version : str
        ballcvt version.
    """

    mode: OperatingMode
    relative: OperatingResult
    sign: float
    speeds: Mapping[str, float]
    torques: Mapping[str, float]
    load_torque: float
    driver_speed: float
    passes: int
    version: str = __version__

    def _summary(self) -> tuple[str, list]:
        rows = [
            ("overall ratio", self.overall_ratio, "-"),
            ("torque ratio", self.torque_ratio, "-"),
            ("efficiency", self.eta, "-"),
            ("power flow", self.power_flow, ""),
            ("geared neutral", self.geared_neutral, ""),
        ]
        for m in ("disc0", "disc2", "carrier"):
            rows.append(
                (
                    m,
                    f"{rad_s_to_rpm(self.speeds[m]):.5g} rpm, {self.torques[m]:.4g} N m",
                    "",
                )
            )
        rows.append(("losses", self.loss, "W"))
        return f"PlanetaryResult: {self.mode.label}", rows

    def __repr__(self) -> str:
        return text_summary(*self._summary())

    def _repr_html_(self) -> str:
        return html_summary(*self._summary())

    def to_dataframe(self):
        """Per-contact quantities in the carrier frame (`OperatingResult.to_dataframe`)."""
        return self.relative.to_dataframe()

    @property
    def powers(self) -> dict[str, float]:
        """Power into the drive through each member, ``torque x speed`` [W]."""
        return {m: self.torques[m] * self.speeds[m] for m in MEMBERS}

    @property
    def input_power(self) -> float:
        """Power into the drive: the sum of the members' positive powers [W] (the driver's,
        unless the load overhauls it)."""
        return sum(max(p, 0.0) for p in self.powers.values())

    @property
    def output_power(self) -> float:
        """Power out of the drive: the sum of the members' negative powers, negated [W]."""
        return sum(max(-p, 0.0) for p in self.powers.values())

    @property
    def loss(self) -> float:
        """Power lost in the drive, from the carrier frame [W] (equals
        ``input_power - output_power`` to the residual, docs/model.md §13)."""
        return self.relative.losses["total"]

    @property
    def overall_ratio(self) -> float:
        """Driven over driver speed (signed) [-]."""
        return self.speeds[self.mode.driven] / self.speeds[self.mode.driver]

    @property
    def torque_ratio(self) -> float:
        """Driven member's load torque over the driver's torque [-]: the figure that
        stays meaningful at geared neutral, where the output speed is zero."""
        t = self.torques[self.mode.driver]
        return self.load_torque / t if t else math.nan

    @property
    def eta(self) -> float:
        """Power out over power in [-] (whichever members carry them; NaN with no power
        in, e.g. at rest)."""
        return self.output_power / self.input_power if self.input_power > 0 else math.nan

    @property
    def eta_loss(self) -> float:
        """``1 - losses / power in`` [-]; equals `eta` to round-off."""
        return 1.0 - self.loss / self.input_power if self.input_power > 0 else math.nan

    @property
    def geared_neutral(self) -> bool:
        """Whether the driven member is (nearly) at rest: ``|overall ratio| < 1e-3``. There
        the efficiency is zero whatever the losses; read `torque_ratio` instead."""
        return abs(self.overall_ratio) < 1e-3

    @property
    def circulating_power(self) -> float:
        """Power through the traction contacts: disc 0's power in the carrier frame [W]."""
        rel = self.relative
        return abs(rel.input_torque * rel.input_speed)

    @property
    def power_flow(self) -> str:
        """How the power crosses the variator in the carrier frame: ``disc0 -> disc2``
        (as on the rig) or ``disc2 -> disc0`` (reversed), and whether it circulates
        (more power through the contacts than through the driver)."""
        forward = self.relative.input_power > 0  # mirroring negates both factors
        way = "disc0 -> disc2" if forward else "disc2 -> disc0"
        circ = self.circulating_power > abs(self.input_power) * (1 + 1e-9)
        return way + (" (circulating)" if circ else "")

    def to_dict(self) -> dict[str, Any]:
        """Plain data: the carrier-frame keys of `OperatingResult.to_dict` plus the
        planetary ones."""
        out = self.relative.to_dict()
        out.update(
            mode={
                "held": self.mode.held,
                "driver": self.mode.driver,
                "driven": self.mode.driven,
                "centrifugal": self.mode.centrifugal,
                "gyroscopic": self.mode.gyroscopic,
                "held_speed": self.mode.held_speed,
            },
            mirrored=self.sign < 0,
            load_torque=self.load_torque,
            driver_speed=self.driver_speed,
            passes=self.passes,
            speeds=dict(self.speeds),
            torques=dict(self.torques),
            powers=self.powers,
            overall_ratio=self.overall_ratio,
            torque_ratio=self.torque_ratio,
            geared_neutral=self.geared_neutral,
            carrier_speed=self.speeds["carrier"],
            carrier_torque=self.torques["carrier"],
            overall_eta=self.eta,
            overall_eta_loss=self.eta_loss,
            circulating_power=self.circulating_power,
            power_flow=self.power_flow,
            planetary_version=self.version,
        )
        return out

    to_json = JsonFile.to_json
    save = JsonFile.save

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], source: str = "result") -> PlanetaryResult:
        """Inverse of `to_dict`, validated: the carrier-frame part as an
        `OperatingResult`, and the member torques and speeds against it."""
        keys = ("mode", "mirrored", "load_torque", "driver_speed", "passes", "speeds", "torques")
        missing = [k for k in keys if k not in data]
        if missing:
            raise InputError(
                missing[0],
                None,
                "a value",
                message=f"{source}: required key '{missing[0]}' is missing",
            )
        rel = OperatingResult.from_dict({k: v for k, v in data.items() if k not in keys}, source)
        m = data["mode"]
        mode = OperatingMode(
            m["held"],
            m["driver"],
            bool(m["centrifugal"]),
            bool(m["gyroscopic"]),
            float(m.get("held_speed", 0.0)),
        )
        out = make_planetary_result(
            mode,
            rel,
            -1.0 if data["mirrored"] else 1.0,
            data["speeds"],
            float(data["load_torque"]),
            float(data["driver_speed"]),
            int(data["passes"]),
        )
        for m_ in MEMBERS:
            if not math.isclose(
                float(data["torques"][m_]), out.torques[m_], rel_tol=1e-12, abs_tol=1e-12
            ):
                raise InputError(
                    f"torques.{m_}",
                    data["torques"][m_],
                    f"{out.torques[m_]:.12g}",
                    message=f"{source}: torques.{m_} is inconsistent with the "
                    "carrier-frame result: the file was edited or is "
                    "corrupt",
                )
        return out

    @classmethod
    def load(cls, path: str | Path) -> PlanetaryResult:
        """Read and validate a result written by `save`."""
        return cls.from_dict(*read_result(path))


def make_planetary_result(
    mode: OperatingMode,
    relative: OperatingResult,
    sign: float,
    speeds: Mapping[str, float],
    load_torque: float,
    driver_speed: float,
    passes: int,
) -> PlanetaryResult:
    """Assemble a `PlanetaryResult`; the member torques follow from the carrier frame."""
    torques = {
        m: sign * float(t)
        for m, t in member_torques(relative.input_torque, relative.output_torque).items()
    }
    return PlanetaryResult(
        mode,
        relative,
        float(sign),
        MappingProxyType({m: float(speeds[m]) for m in MEMBERS}),
        MappingProxyType(torques),
        float(load_torque),
        float(driver_speed),
        int(passes),
    )
