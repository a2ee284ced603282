"""Exceptions with messages a user can act on.

Every error names the quantity, the value it had and the allowed range, in one line,
so that the command-line interface can print it as is (exit status 2).
"""

from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType

__all__ = [
    "BallCVTError",
    "InputError",
    "TractionLimitError",
    "ConvergenceError",
    "NoEquilibriumError",
    "ResultChecksumWarning",
    "UnitHintWarning",
]


class BallCVTError(Exception):
    """Base class of every error ballcvt raises on purpose.

    ``phrases`` maps a quantity's name (``input_speed``) to the words of the message that
    state it in SI units (``"input speed 209.44 rad/s"``), so that a front end can restate
    the message in the terms its user typed (`restated`; the command line says
    ``--speed 2000 rpm``).
    """

    phrases: Mapping[str, str] = MappingProxyType({})

    def restated(self, terms: Mapping[str, str]) -> str:
        """The message with each phrase of a quantity in ``terms`` replaced by its text.

        Parameters
        ----------
        terms : Mapping[str, str]
            Quantity name -> the text to say instead (e.g. ``{"input_speed": "--speed
            2000 rpm"}``); quantities without a phrase are ignored.
        """
        text = str(self)
        for name, phrase in self.phrases.items():
            if name in terms:
                text = text.replace(phrase, terms[name])
        return text


class InputError(BallCVTError, ValueError):
    """An input quantity is outside its allowed range.

    Parameters
    ----------
    quantity : str
        Name of the quantity (as the user wrote it, e.g. ``clamp_force``).
    value : object
        The offending value.
    allowed : str
        Human-readable allowed range, e.g. ``"> 0 N"``.
    message : str, optional
        Full one-line message, when the standard wording does not fit (a missing key).
    """

    def __init__(self, quantity: str, value: object, allowed: str, message: str | None = None):
        self.quantity = quantity
        self.value = value
        self.allowed = allowed
        super().__init__(
            message or f"{quantity} = {_fmt(value)} is out of range: allowed {allowed}"
        )


class TractionLimitError(InputError):
    """The requested output torque exceeds the traction capacity of the drive."""

    def __init__(self, value: float, limit: float, context: str = "", allowed: str = ""):
        # allowed: the admissible torques as text when they are not 0 to ``limit``
        self.limit_torque = limit
        BallCVTError.__init__(
            self,
            f"output_torque = {_fmt(value)} N m exceeds the traction capacity"
            + (
                f" {limit:.4g} N m{context}: allowed 0 <= output_torque <= {limit:.4g} N m"
                if not allowed
                else f"{context}: allowed output_torque {allowed}"
            ),
        )
        self.quantity, self.value = "output_torque", value
        self.allowed = allowed or f"<= {limit:.4g} N m"


class ConvergenceError(BallCVTError, RuntimeError):
    """The equilibrium solver did not converge; never returned silently."""


class NoEquilibriumError(ConvergenceError):
    """No admissible equilibrium exists even at zero output torque.

    The traction the clamping force can transmit does not carry the drive's own bearing and
    spin drag (e.g. a clamping force of a few newtons); the message names the conditions.

    Parameters
    ----------
    message : str
        The one-line message.
    phrases : Mapping[str, str], optional
        The words of ``message`` stating each quantity (`BallCVTError.phrases`).
    """

    def __init__(self, message: str, phrases: Mapping[str, str] | None = None):
        super().__init__(message)
        self.phrases = MappingProxyType(dict(phrases or {}))


def _fmt(value: object) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    return repr(value) if isinstance(value, str) else str(value)


class BallCVTDeprecationWarning(FutureWarning):
    """A public name, module path or option was renamed: the message gives the new one.

    A `FutureWarning` so that users see it by default (Python hides a plain
    `DeprecationWarning` outside ``__main__``).
    """


class ResultChecksumWarning(UserWarning):
    """A saved result no longer matches the checksum ballcvt stored with it.

    Its numbers were edited (or damaged) after ballcvt computed them: they load, but are not
    what ballcvt computed. Also issued, with ``modified`` false, for a file saved before
    results carried a checksum (its numbers cannot be checked).
    """

    def __init__(self, message: str, modified: bool = True):
        super().__init__(message)
        self.modified = modified


class UnitHintWarning(UserWarning):
    """A value that looks like a unit mistake (an angular speed in rpm given in rad/s, a
    contact angle in radians given in degrees): it is used as given, and the message names
    the likely intended input."""
