"""Duty-cycle files: a CSV time series with the units in the header (docs/cycles.md).

Two kinds of cycle are read:

* **output side** (a vehicle or a load): ``time``, ``output_speed``, ``output_torque``;
  a strategy picks the ratio at each step;
* **input side** (a test rig): ``time``, ``input_speed``, ``input_power``, and optionally
  ``ratio`` (the commanded ideal ratio; without it the ``max-efficiency`` strategy picks
  one); the output torque follows from the input power.

Either kind may add ``vehicle_speed`` (the speed of the vehicle the drive moves): the
cycle's distance, for a fatigue life in kilometres (docs/life.md).

Column names carry their unit in brackets, e.g. ``output_speed [rpm]``; the accepted
units are listed in `UNITS`. Values are converted to SI on reading.
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..units import QUANTITY_UNITS, parse_header, unit_factor

__all__ = ["Cycle", "read_cycle", "cycle_from_arrays", "UNITS", "KINDS", "STRATEGIES"]

#: How a duty-cycle run picks the ratio (`ballcvt.analysis.cycles.run_cycle`).
STRATEGIES = ("target-input-speed", "max-efficiency")

#: The quantity of each column (its accepted units: `ballcvt.units.QUANTITY_UNITS`).
QUANTITIES = {
    "time": "time",
    "output_speed": "angular_speed",
    "input_speed": "angular_speed",
    "output_torque": "torque",
    "input_power": "power",
    "ratio": "dimensionless",
    "vehicle_speed": "speed",
}
#: Accepted units per column: unit -> factor to SI.
UNITS = {column: dict(QUANTITY_UNITS[q]) for column, q in QUANTITIES.items()}
#: The column sets of the two kinds of cycle (``ratio`` is optional on the input side).
KINDS = {
    "output": ("time", "output_speed", "output_torque"),
    "input": ("time", "input_speed", "input_power"),
}


@dataclass(frozen=True)
class Cycle:
    """A duty cycle in SI units (arrays of one length ``n``).

    Attributes
    ----------
    kind : {"output", "input"}
        Which side of the drive the cycle prescribes.
    time : ndarray
        Sample times, strictly increasing [s].
    output_speed, output_torque : ndarray or None
        Output-side cycle: ``omega_2`` >= 0 [rad/s] and ``T_2`` [N m] (negative: braking,
        which the model does not cover and flags).
    input_speed, input_power, ratio : ndarray or None
        Input-side cycle: ``omega_0`` >= 0 [rad/s], input power [W], and the commanded
        ideal ratio [-] (optional).
    vehicle_speed : ndarray or None
        Speed of the vehicle the drive moves (optional, either kind) [m/s]: gives the
        distance of the cycle, and a fatigue life in kilometres.
    name : str
        Where it came from.
    """

    kind: str
    time: np.ndarray
    output_speed: np.ndarray | None = None
    output_torque: np.ndarray | None = None
    input_speed: np.ndarray | None = None
    input_power: np.ndarray | None = None
    ratio: np.ndarray | None = None
    name: str = "cycle"
    vehicle_speed: np.ndarray | None = None

    @property
    def size(self) -> int:
        """Number of steps."""
        return self.time.size

    @property
    def durations(self) -> np.ndarray:
        """Time each sample stands for [s]: half the intervals on each side (the sum is
        the cycle's duration)."""
        t = self.time
        if t.size == 1:
            return np.zeros(1)
        edges = np.concatenate([[t[0]], 0.5 * (t[1:] + t[:-1]), [t[-1]]])
        return np.diff(edges)

    def take(self, index) -> Cycle:
        """The steps ``index`` (a slice or an index array) as a cycle of their own."""
        steps = {f.name: getattr(self, f.name) for f in fields(self)}
        return replace(
            self, **{k: v[index] for k, v in steps.items() if isinstance(v, np.ndarray)}
        )

    @property
    def distance(self) -> float | None:
        """Distance covered, ``sum v_i dt_i`` [m]; None without a ``vehicle_speed``."""
        if self.vehicle_speed is None:
            return None
        return float(np.sum(self.vehicle_speed * self.durations))


def cycle_from_arrays(*, time, name: str = "cycle", **columns) -> Cycle:
    """A validated `Cycle` from SI arrays (one of the two column sets of `KINDS`).

    Parameters
    ----------
    time : array_like
        Sample times [s].
    name : str
        Where the cycle came from.
    **columns : array_like or None
        The other columns by name (`QUANTITIES`), in SI units: ``output_speed``,
        ``output_torque``, ``input_speed``, ``input_power``, ``ratio``, ``vehicle_speed``
        (None: not given).
    """
    unknown = sorted(set(columns) - set(QUANTITIES))
    if unknown:
        raise InputError("cycle column", unknown[0], "one of " + ", ".join(QUANTITIES))
    given = {k: v for k, v in {"time": time, **columns}.items() if v is not None}
    kind = next((k for k, cols in KINDS.items() if all(c in given for c in cols)), None)
    if kind is None or (kind == "output" and {"input_speed", "input_power"} & set(given)):
        raise InputError(
            "cycle columns",
            ", ".join(given),
            "time with output_speed and "
            "output_torque, or time with input_speed and input_power "
            "(and optionally ratio)",
        )
    arrays = {}
    for key, value in given.items():
        arr = np.atleast_1d(np.asarray(value, dtype=float))
        if arr.ndim != 1 or arr.size == 0 or arr.size != np.size(given["time"]):
            raise InputError(key, arr.shape, "a 1-D column as long as time")
        bad = np.flatnonzero(~np.isfinite(arr))
        if bad.size:
            raise InputError(key, float(arr[bad[0]]), f"finite numbers (step {bad[0]})")
        arrays[key] = arr
    t = arrays["time"]
    if t.size > 1 and np.any(np.diff(t) <= 0):
        i = int(np.flatnonzero(np.diff(t) <= 0)[0]) + 1
        raise InputError("time", float(t[i]), f"strictly increasing (step {i})")
    for key in ("output_speed", "input_speed", "vehicle_speed"):
        if key in arrays and np.any(arrays[key] < 0):
            i = int(np.flatnonzero(arrays[key] < 0)[0])
            raise InputError(
                key, float(arrays[key][i]), f">= 0 (step {i}; the drive does not reverse)"
            )
    if "ratio" in arrays and np.any(arrays["ratio"] <= 0):
        i = int(np.flatnonzero(arrays["ratio"] <= 0)[0])
        raise InputError("ratio", float(arrays["ratio"][i]), f"> 0 (step {i})")
    return Cycle(kind=kind, name=name, **arrays)


def read_cycle(path: str | Path) -> Cycle:
    """Read and validate a cycle CSV file (see the module docstring).

    Raises
    ------
    InputError
        Unreadable file, unknown or duplicated column, unknown unit, a non-number, time
        not increasing, negative speed: one line naming the column (and step).
    """
    import pandas as pd

    path = Path(path)
    try:
        frame = pd.read_csv(path, comment="#", skipinitialspace=True)
    except (OSError, UnicodeDecodeError, pd.errors.ParserError, pd.errors.EmptyDataError) as exc:
        raise InputError(
            "cycle file",
            str(path),
            "a readable CSV file",
            message=f"cycle file {path}: cannot be read as CSV ({type(exc).__name__})",
        ) from None
    columns = {}
    for header in frame.columns:
        name, unit = parse_header(header)
        if name not in UNITS:
            raise InputError(
                "cycle column",
                str(header),
                "one of " + ", ".join(f"{k} [{'|'.join(u)}]" for k, u in UNITS.items()),
                message=f"cycle file {path}: unknown column '{header}' (known: "
                + ", ".join(UNITS)
                + ", each with its unit in brackets)",
            )
        if not unit:
            raise InputError(
                f"{name} unit",
                "(none)",
                " or ".join(UNITS[name]),
                message=f"cycle file {path}: column '{header}' needs its unit "
                f"in brackets, one of: " + ", ".join(UNITS[name]),
            )
        factor = unit_factor(unit, QUANTITIES[name], str(header), f"cycle file {path}")
        if name in columns:
            raise InputError(
                "cycle column",
                name,
                "each column once",
                message=f"cycle file {path}: column '{name}' appears twice",
            )
        values = pd.to_numeric(frame[header], errors="coerce").to_numpy(dtype=float)
        bad = np.flatnonzero(np.isnan(values))
        if bad.size:
            raise InputError(
                name,
                str(frame[header].iloc[bad[0]]),
                "a number",
                message=f"cycle file {path}: '{header}' at data row {bad[0] + 1} is not a number",
            )
        columns[name] = values * factor
    return cycle_from_arrays(name=path.name, **columns)
