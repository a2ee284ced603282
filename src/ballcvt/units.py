"""Unit conversions: the one place that knows what an rpm or a degree is.

Every conversion is written the way the package always computed it (``rpm * pi / 30``,
in that order), so that the results are the same to the last bit wherever it is used.
Files ballcvt reads carry units in their column headers (``load [kN]``): `parse_header`
splits them and `unit_factor` / `convert` turn a value into SI or refuse a unit it does
not know (`QUANTITY_UNITS`), naming the column and the accepted units.

A leaf: imports no physics.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = [
    "rpm_to_rad_s",
    "rad_s_to_rpm",
    "deg_to_rad",
    "rad_to_deg",
    "celsius_to_kelvin",
    "kelvin_to_celsius",
    "ZERO_CELSIUS",
    "RAD_S_PER_RPM",
    "QUANTITY_UNITS",
    "parse_header",
    "unit_factor",
    "convert",
]

#: One revolution per minute in rad/s.
RAD_S_PER_RPM = math.pi / 30.0


#: 0 C in kelvin.
ZERO_CELSIUS = 273.15


def celsius_to_kelvin(temperature_c: float) -> float:
    """Temperature [C] -> [K]."""
    return float(temperature_c) + ZERO_CELSIUS


def kelvin_to_celsius(temperature: float) -> float:
    """Temperature [K] -> [C]."""
    return float(temperature) - ZERO_CELSIUS


def rpm_to_rad_s(speed_rpm):
    """Angular speed [rpm] -> [rad/s] (``rpm * pi / 30``); scalars stay scalars."""
    if isinstance(speed_rpm, (int, float)):
        return float(speed_rpm) * math.pi / 30.0
    return np.asarray(speed_rpm, dtype=float) * math.pi / 30.0


def rad_s_to_rpm(speed):
    """Angular speed [rad/s] -> [rpm] (``rad/s * 30 / pi``); scalars stay scalars."""
    if isinstance(speed, (int, float)):
        return float(speed) * 30.0 / math.pi
    return np.asarray(speed, dtype=float) * 30.0 / math.pi


def deg_to_rad(angle_deg):
    """Angle [deg] -> [rad]."""
    if isinstance(angle_deg, (int, float)):
        return math.radians(angle_deg)
    return np.radians(np.asarray(angle_deg, dtype=float))


def rad_to_deg(angle):
    """Angle [rad] -> [deg]."""
    if isinstance(angle, (int, float)):
        return math.degrees(angle)
    return np.degrees(np.asarray(angle, dtype=float))


# --- units in file headers ------------------------------------------------------------
#: SI prefixes accepted before a unit that takes them (``u`` and ``µ`` both mean micro).
PREFIXES = {"G": 1e9, "M": 1e6, "k": 1e3, "": 1.0, "m": 1e-3, "u": 1e-6, "µ": 1e-6, "n": 1e-9}


def _prefixed(unit: str, prefixes: str = "GMkmuµn") -> dict[str, float]:
    return {p + unit: f for p, f in PREFIXES.items() if p == "" or p in prefixes}


#: Quantity -> accepted unit -> factor to its SI unit (the first entry).
QUANTITY_UNITS: dict[str, dict[str, float]] = {
    "force": _prefixed("N"),
    "pressure": _prefixed("Pa"),
    "length": _prefixed("m", "kmun") | {"µm": 1e-6},
    "speed": {"m/s": 1.0, "mm/s": 1e-3, "km/s": 1e3, "km/h": 1.0 / 3.6},
    "torque": {
        f"{p}{sep}m": f
        for p, f in (("", 1.0), ("k", 1e3), ("M", 1e6))
        for sep in ("N ", "N", "N*", "N.", "N·")
    }
    | {"N mm": 1e-3, "Nmm": 1e-3},
    "power": _prefixed("W", "GMkmu"),
    "time": _prefixed("s", "mun") | {"min": 60.0, "h": 3600.0},
    "angular_speed": {"rad/s": 1.0, "rpm": RAD_S_PER_RPM, "rev/min": RAD_S_PER_RPM,
                      "1/min": RAD_S_PER_RPM},
    "angle": {"rad": 1.0, "deg": math.pi / 180.0, "°": math.pi / 180.0},
    "dimensionless": {"1": 1.0, "-": 1.0, "": 1.0},
}  # fmt: skip


def parse_header(header: str) -> tuple[str, str | None]:
    """Split a column header ``"name [unit]"`` into ``(name, unit)``; ``unit`` is None
    when the header has no brackets (an empty pair of brackets gives ``""``)."""
    text = str(header).strip()
    if text.endswith("]") and "[" in text:
        name, _, unit = text[:-1].partition("[")
        return name.strip(), unit.strip()
    return text, None


def unit_factor(unit: str, quantity: str, column: str = "column", source: str = "") -> float:
    """Factor that converts a value in ``unit`` to the SI unit of ``quantity`` [-].

    Parameters
    ----------
    unit : str
        As written in a header, e.g. ``"kN"``, ``"rpm"``, ``"N m"``.
    quantity : str
        A key of `QUANTITY_UNITS` (``force``, ``pressure``, ``length``, ``speed``,
        ``torque``, ``power``, ``time``, ``angular_speed``, ``angle``, ``dimensionless``).
    column, source : str
        The column's header and the file it is in, for the message.

    Raises
    ------
    InputError
        An unknown unit, naming the column, the unit and the accepted ones.
    """
    from .errors import InputError

    accepted = QUANTITY_UNITS[quantity]
    unit = " ".join(unit.split())
    if unit not in accepted:
        first: dict[float, str] = {}  # one spelling per factor: "N m", not also "Nm"
        for name, factor in accepted.items():
            first.setdefault(factor, name)
        allowed = ", ".join(first.values())
        raise InputError(
            column,
            unit,
            allowed,
            message=f"{source + ': ' if source else ''}column '{column}': unit [{unit}] is not one ballcvt knows for "
            f"{quantity.replace('_', ' ')}: allowed {allowed}",
        )
    return accepted[unit]


def convert(values, unit: str, quantity: str, column: str = "column", source: str = ""):
    """``values`` in ``unit`` converted to the SI unit of ``quantity`` (``values * factor``,
    see `unit_factor`; an array stays an array)."""
    factor = unit_factor(unit, quantity, column, source)
    return values * factor if factor != 1.0 else values
