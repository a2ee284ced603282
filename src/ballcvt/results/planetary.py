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
        are computed with disc 0 as the input; `variator_efficiency` gives them by the way
        the power actually crosses the variator.
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
            ("input member", self.input_member, ""),
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
    def input_member(self) -> str:
        """The member(s) through which power enters the drive, largest first, joined by
        ``+`` (e.g. ``carrier``, or ``carrier+disc2`` where the load overhauls the driven
        member); ``none`` at rest."""
        return _members(self.powers, 1.0)

    @property
    def output_member(self) -> str:
        """The member(s) through which power leaves the drive (as `input_member`);
        ``none`` where all the power in is dissipated."""
        return _members(self.powers, -1.0)

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
        """``1 - losses / power in`` [-]; equals `eta` to round-off (clipped to [0, 1]
        where that round-off would leave it, e.g. with no power out)."""
        p_in = self.input_power
        return min(max(1.0 - self.loss / p_in, 0.0), 1.0) if p_in > 0 else math.nan

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
        (as on the rig), ``disc2 -> disc0`` (reversed) or ``into both discs (dissipated)``,
        and whether it circulates (more power through the contacts than through the
        driver)."""
        ins = _members(self.disc_powers, 1.0)
        way = {"disc0": "disc0 -> disc2", "disc2": "disc2 -> disc0"}.get(
            ins, "into both discs (dissipated)"
        )
        circ = self.circulating_power > abs(self.input_power) * (1 + 1e-9)
        return way + (" (circulating)" if circ else "")

    @property
    def disc_powers(self) -> dict[str, float]:
        """Power into the variator through each disc in the carrier frame [W] (mirroring
        negates both factors, so these are the physical relative powers)."""
        rel = self.relative
        return {
            "disc0": rel.input_torque * rel.input_speed,
            "disc2": -rel.output_torque * rel.output_speed,
        }

    @property
    def variator_efficiency(self) -> dict[str, float]:
        """The variator's efficiencies between its discs in the carrier frame, by the
        way the power crosses it (`power_flow`) [-], each in [0, 1].

        ``eta`` is power out over power in of the two discs (Eq. 38 with the input the disc
        that takes power in); ``speed`` and ``torque`` are Eq. 9 and Eq. 37 the same way
        (the inverses of ``relative``'s where the power flows from disc 2 to disc 0; NaN
        where both discs take power in, and then ``eta`` is 0), clipped to [0, 1] against
        round-off at zero load."""
        rel, ins = self.relative, _members(self.disc_powers, 1.0)
        p_in = sum(max(p, 0.0) for p in self.disc_powers.values())
        eta = sum(max(-p, 0.0) for p in self.disc_powers.values()) / p_in if p_in > 0 else math.nan
        if ins == "disc0":
            speed, torque = rel.eta_speed, rel.eta_torque
        elif ins == "disc2":
            speed, torque = _inverse(rel.eta_speed), _inverse(rel.eta_torque)
        else:
            speed = torque = math.nan
        return {"eta": eta, "speed": _unit(speed), "torque": _unit(torque)}

    def to_dict(self) -> dict[str, Any]:
        """Plain data: the carrier-frame keys of `OperatingResult.to_dict` plus the
        planetary ones."""
        out = self.relative.to_dict()
        # the carrier-frame figures with disc 0 as the input (for `from_dict`); the
        # top-level efficiencies are the drive's, by the way its power flows
        out["carrier_frame_efficiency"] = {k: out[k] for k in _EFFICIENCY_KEYS}
        var = self.variator_efficiency
        out.update(
            eta=self.eta,
            eta_loss=self.eta_loss,
            eta_speed=var["speed"],
            eta_torque=var["torque"],
            variator_eta=var["eta"],
            input_member=self.input_member,
            output_member=self.output_member,
        )
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
        rest = {k: v for k, v in data.items() if k not in keys}
        rest.update(data.get("carrier_frame_efficiency") or {})  # absent before 0.1.1
        rel = OperatingResult.from_dict(rest, source)
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


#: The efficiency keys of `OperatingResult.to_dict`, kept in a planetary result's
#: ``carrier_frame_efficiency`` (disc 0 as the input).
_EFFICIENCY_KEYS = ("eta", "eta_loss", "eta_speed", "eta_torque")


def _members(powers: Mapping[str, float], sign: float) -> str:
    """Members whose power has ``sign`` (+1 in, -1 out), largest first, joined by ``+``;
    powers below 1e-12 of the largest count as zero."""
    scale = max((abs(p) for p in powers.values()), default=0.0)
    names = sorted(
        (m for m, p in powers.items() if sign * p > 1e-12 * scale), key=lambda m: -sign * powers[m]
    )
    return "+".join(names) or "none"


def _unit(value: float) -> float:
    """``value`` clipped to [0, 1] (round-off at zero load or speed), NaN kept."""
    return min(max(value, 0.0), 1.0) if not math.isnan(value) else value


def _inverse(value: float) -> float:
    return 1.0 / value if value else math.nan


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
