"""The variator as a three-shaft planetary (docs/model.md §13).

The members are disc 0, disc 2 and the carrier (the ball axles' cage); the idlers run free.
Every contact relation of the model holds for speeds relative to the carrier, so with
``omega_c`` the carrier speed the variator imposes (Willis' relation of a planetary)

    ``omega_2 - omega_c = tau (omega_0 - omega_c)``,

``tau`` the actual ratio relative to the carrier (``tau_ID`` without creep, Eq. 8 with it).
An `OperatingMode` names the member held (speed zero, or any given speed: a free
differential) and the driver (speed given); the third member is driven, and its load
torque is given. In steady state the torques applied
to the three members from outside sum to zero, and the carrier's follows from the discs'.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..registry import OPERATING_MODES

__all__ = [
    "MEMBERS",
    "OperatingMode",
    "relative_ratio_coefficients",
    "member_torques",
    "resolve_mode",
    "DEFAULT_MODE",
]

#: The three shafts of the planetary.
MEMBERS = ("disc0", "disc2", "carrier")


def relative_ratio_coefficients(ratio):
    """Coefficients ``c`` of ``c_0 omega_0 + c_2 omega_2 + c_c omega_c = 0``.

    Willis' relation ``omega_2 - omega_c = tau (omega_0 - omega_c)`` written as a linear
    form: ``c_0 = -tau``, ``c_2 = 1``, ``c_c = tau - 1``.

    Parameters
    ----------
    ratio : array_like
        Ratio relative to the carrier ``tau`` [-].

    Returns
    -------
    dict of ndarray
        Keyed by member name [-].
    """
    tau = np.asarray(ratio, dtype=float)
    return {"disc0": -tau, "disc2": np.ones_like(tau), "carrier": tau - 1.0}


@dataclass(frozen=True)
class OperatingMode:
    """Which member is held and which drives; the third is driven.

    Attributes
    ----------
    held : {"carrier", "disc0", "disc2"}
        The member held at zero speed. ``carrier`` is the paper's CVT (the default);
        ``disc0`` or ``disc2`` make a single-input single-output planetary CVT, whose
        output passes through zero (geared neutral) where ``tau = 1``.
    driver : {"disc0", "disc2", "carrier"}
        The member whose speed is given.
    centrifugal : bool
        Include the balls' centrifugal force ``m omega_c^2 R_c`` (it unloads the idler
        contacts; docs/model.md §13). No effect with the carrier held.
    gyroscopic : bool
        Include the balls' gyroscopic moment ``I omega_c omega_S sin(gamma)`` (carried by
        the axle ends, it loads the ball bearings). No effect with the carrier held.
    held_speed : float
        Speed of the ``held`` member [rad/s]: 0 holds it; any other value makes the
        drive a free differential (two speeds and one torque given).
    """

    held: str = "carrier"
    driver: str = "disc0"
    centrifugal: bool = True
    gyroscopic: bool = True
    held_speed: float = 0.0

    def __post_init__(self):
        for name in ("held", "driver"):
            value = getattr(self, name)
            if value not in MEMBERS:
                raise InputError(name, value, "one of: " + ", ".join(MEMBERS))
        if not np.isfinite(self.held_speed):
            raise InputError("held_speed", self.held_speed, "finite (rad/s)")
        if self.driver == self.held:
            raise InputError(
                "driver", self.driver, f"a member other than the held one ({self.held})"
            )

    @property
    def driven(self) -> str:
        """The member whose load torque is given."""
        return next(m for m in MEMBERS if m not in (self.held, self.driver))

    @property
    def is_default(self) -> bool:
        """The paper's drive: carrier held, disc 0 drives, disc 2 driven."""
        return self.held == "carrier" and self.driver == "disc0" and self.held_speed == 0.0

    @property
    def label(self) -> str:
        """E.g. ``"disc2 held, carrier drives disc0"``."""
        held = (
            "held"
            if self.held_speed == 0.0
            else f"at {self.held_speed:g} rad/s (free differential)"
        )
        return f"{self.held} {held}, {self.driver} drives {self.driven}"

    def speeds(self, driver_speed, ratio, check: bool = True) -> dict:
        """Speeds of the three members [rad/s].

        Parameters
        ----------
        driver_speed : array_like
            Speed of the driver [rad/s] (signed, about ``j``).
        ratio : array_like
            Ratio relative to the carrier ``tau`` [-].

        Returns
        -------
        dict of ndarray
            ``disc0``, ``disc2``, ``carrier`` [rad/s].

        check : bool
            Raise where a speed would be infinite (else it is returned as ``inf``).

        Raises
        ------
        InputError
            Where the driven member would need an infinite speed (its coefficient in
            Willis' relation vanishes: e.g. the carrier driven from disc 0 with disc 2
            held at ``tau = 1``).
        """
        c = relative_ratio_coefficients(ratio)
        w = np.asarray(driver_speed, dtype=float)
        den = c[self.driven]
        if not check:  # batches: infinite speeds become inf or NaN
            den = np.where(np.abs(den) < 1e-9, 0.0, den)
        elif np.any(np.abs(den) < 1e-9):
            bad = (
                float(np.asarray(ratio, dtype=float)[np.abs(den) < 1e-9].flat[0])
                if np.ndim(ratio)
                else float(ratio)
            )
            raise InputError(
                "ratio",
                bad,
                f"!= 1: with {self.held} held and {self.driver} "
                f"driving, the {self.driven} would turn infinitely fast there",
            )
        shape = np.broadcast(w, den).shape
        out = {
            self.held: np.full(shape, self.held_speed),
            self.driver: np.broadcast_to(w, shape).astype(float),
            self.driven: _divide(-(c[self.driver] * w + c[self.held] * self.held_speed), den),
        }
        return {m: out[m] for m in MEMBERS}

    def torque_condition(self, load_torque):
        """The condition ``a T_0 + b T_2 = target`` that the driven load sets.

        ``T_0`` is the torque applied to disc 0 and ``T_2`` the load torque of disc 2
        (docs/model.md §5); the carrier's applied torque is ``T_2 - T_0``. A driven
        member's load torque ``L`` (the torque it delivers to its load) is applied to it
        as ``-L``.

        Returns
        -------
        (a, b, target) : (float, float, ndarray)
        """
        load = np.asarray(load_torque, dtype=float)
        return {
            "disc2": (0.0, 1.0, load),
            "disc0": (1.0, 0.0, -load),
            "carrier": (-1.0, 1.0, -load),
        }[self.driven]


def member_torques(input_torque, output_torque) -> dict:
    """Torques applied to the three members from outside [N m] (sum zero).

    Parameters
    ----------
    input_torque : array_like
        ``T_0``, applied to disc 0 [N m].
    output_torque : array_like
        ``T_2``, the load torque of disc 2 (applied to it: ``-T_2``) [N m].

    Returns
    -------
    dict of ndarray
        ``disc0 = T_0``, ``disc2 = -T_2``, ``carrier = T_2 - T_0`` [N m].
    """
    t0 = np.asarray(input_torque, dtype=float)
    t2 = np.asarray(output_torque, dtype=float)
    return {"disc0": t0, "disc2": -t2, "carrier": t2 - t0}


def _divide(num, den):
    with np.errstate(divide="ignore", invalid="ignore"):
        return num / den


def resolve_mode(mode: OperatingMode | str | None) -> OperatingMode:
    """The `OperatingMode` that ``mode`` names.

    Parameters
    ----------
    mode : OperatingMode, str or None
        A mode, a name of `ballcvt.registry.OPERATING_MODES` (e.g. ``"carrier_held"``,
        ``"disc2_held_carrier_drives"``), or None for the paper's drive.

    Returns
    -------
    OperatingMode

    Raises
    ------
    InputError
        For an unknown name.
    """
    if mode is None:
        return DEFAULT_MODE
    if isinstance(mode, OperatingMode):
        return mode
    return OPERATING_MODES.get(mode)


#: The paper's drive: carrier held, disc 0 drives, disc 2 driven.
DEFAULT_MODE = OPERATING_MODES.register(OperatingMode(), name="carrier_held")
# every other held/driver pair of the three members, named ``<held>_held_<driver>_drives``
for _held in MEMBERS:
    for _driver in MEMBERS:
        if _driver != _held and (_held, _driver) != ("carrier", "disc0"):
            OPERATING_MODES.register(
                OperatingMode(_held, _driver), name=f"{_held}_held_{_driver}_drives"
            )
