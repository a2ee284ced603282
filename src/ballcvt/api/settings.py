"""Parameter objects of the `Variator` methods, and the grids of maps and tables.

`Variator.solve`, `Variator.sweep` and `Variator.run_cycle` take what is computed (ratio,
torque, clamping, speed) as arguments and *how* it is computed (capacity check, workers,
progress bar, strategy, ...) as one frozen settings object. The old keyword arguments keep
working: each fills the field of the same name (`merge_settings`), on top of ``settings``
if both are given.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from typing import Any, TypeVar

import numpy as np

from ..errors import InputError
from ..model.modes import OperatingMode
from ..units import rpm_to_rad_s

__all__ = [
    "SolveSettings",
    "SweepSettings",
    "CycleSettings",
    "MapGrid",
    "TableGrid",
    "merge_settings",
]

S = TypeVar("S")


@dataclass(frozen=True)
class SolveSettings:
    """How `Variator.solve` solves one point.

    Attributes
    ----------
    check_capacity : bool
        Refuse a torque beyond the traction capacity with `TractionLimitError` (default).
    mode : OperatingMode, optional
        The variator as a planetary (docs/model.md §13); the paper's drive by default.
    oil_temperature : {"fixed", "balance"} or float, optional
        The oil's bulk temperature (docs/model.md §15); None (default): the drive file's
        ``[models] oil_temperature``, else ``"fixed"``. ``"fixed"``: the fluid as
        given, ``"balance"`` (the housing's steady heat balance, ``[design.thermal]``) or a
        temperature [K] (the fluid there, `ballcvt.model.oil.fluid_at`).
    """

    check_capacity: bool = True
    mode: OperatingMode | None = None
    oil_temperature: str | float | None = None


@dataclass(frozen=True)
class SweepSettings:
    """How `Variator.sweep` evaluates a grid.

    Attributes
    ----------
    architecture : str or sequence of str, optional
        The variator's own by default; e.g. ``("double", "single")``.
    creep_limit : float, optional
        ``C_lim`` of the limiting torque [-]; the design's by default.
    limit_torque : array_like, LimitCurve or LimitSearch, optional
        Limiting torques already known at these conditions [N m].
    workers : int
        Processes to use.
    progress : bool, optional
        Progress bar (default: when stderr is a terminal).
    label : str, optional
        What the progress bar says it computes.
    oil_temperature : {"fixed", "balance"} or float, optional
        As in `SolveSettings`: under ``"balance"`` each point at its own heat balance
        (`ballcvt.analysis.oil_sweep`), the dataset gaining ``oil_temperature`` [K].
    """

    architecture: Any = None
    creep_limit: float | None = None
    limit_torque: Any = None
    workers: int = 1
    progress: bool | None = None
    label: str | None = None
    oil_temperature: str | float | None = None


@dataclass(frozen=True)
class CycleSettings:
    """How `Variator.run_cycle` picks the ratio and runs the steps.

    Attributes
    ----------
    strategy : {"target-input-speed", "max-efficiency"}, optional
        How the ratio is chosen; None: ``target-input-speed`` when a target input speed
        is given, else ``max-efficiency`` (`ballcvt.analysis.cycle_request`).
    target_input_speed, target_input_speed_rpm : float, optional
        Input speed held by ``target-input-speed`` [rad/s] or [rpm] (at most one; that
        strategy only).
    candidates : int, optional
        Ratios tried per step by ``max-efficiency`` (that strategy only; 9 when None).
    ratio_range : (float, float), optional
        Ratios any strategy may use [-] (default: the usable range).
    progress : bool, optional
        Progress bar (default: when stderr is a terminal).
    workers : int
        Processes to solve the steps on.
    oil_temperature : {"fixed", "transient"} or float, optional
        The oil's bulk temperature (docs/model.md §15); None (default): ``"transient"``
        for a drive file naming ``[models] oil_temperature = "balance"`` with a
        ``thermal_mass``, else ``"fixed"``. ``"fixed"``: the fluid as given,
        ``"transient"`` (the housing's lumped transient over the cycle,
        ``[design.thermal]`` with its ``thermal_mass``) or a temperature [K].
    initial_oil_temperature : float, optional
        Oil temperature at the cycle's start [K] (``transient``; default: the ambient).
    """

    strategy: str | None = None
    target_input_speed: float | None = None
    target_input_speed_rpm: float | None = None
    candidates: int | None = None
    ratio_range: Any = None
    progress: bool | None = None
    workers: int = 1
    oil_temperature: str | float | None = None
    initial_oil_temperature: float | None = None

    def target(self) -> float | None:
        """The target input speed [rad/s], from whichever unit was given."""
        if self.target_input_speed is not None and self.target_input_speed_rpm is not None:
            raise InputError(
                "target_input_speed",
                self.target_input_speed,
                "at most one of target_input_speed [rad/s] or target_input_speed_rpm [rpm]",
            )
        if self.target_input_speed_rpm is not None:
            return rpm_to_rad_s(self.target_input_speed_rpm)
        return self.target_input_speed


def merge_settings(cls: type[S], settings: S | None, legacy: dict, where: str) -> S:
    """``settings`` (default ``cls()``) with the fields given as old keyword arguments.

    Parameters
    ----------
    cls : type
        The settings class.
    settings : cls or None
        Settings given with ``settings=``.
    legacy : dict
        Keyword arguments of the old signature; each must name a field of ``cls``.
    where : str
        The method, for the message of an unknown keyword.

    Raises
    ------
    TypeError
        An unknown keyword, as Python says for any function.
    """
    names = {f.name for f in fields(cls)}  # type: ignore[arg-type]
    for key in legacy:
        if key not in names:
            raise TypeError(f"{where}() got an unexpected keyword argument {key!r}")
    base = cls() if settings is None else settings
    return replace(base, **legacy) if legacy else base  # type: ignore[type-var]


@dataclass(frozen=True)
class MapGrid:
    """Ratio x output-torque grid of `Variator.efficiency_map` (``ballcvt map``).

    Attributes
    ----------
    ratio_range : (float, float)
        Smallest and largest ideal ratio [-], ``0 < MIN < MAX``.
    n_ratio : int
        Ratios, evenly spaced.
    torque_max : float, optional
        Largest output torque [N m]; default 1.02 x the largest limiting torque
        (`Variator.efficiency_map`) or that torque (`Variator.lookup_table`).
    n_torque : int
        Torques, evenly spaced (from ``torque_max / n_torque`` in a map, from 0 in a table).
    """

    ratio_range: tuple[float, float] = (0.5, 2.0)
    n_ratio: int = 31
    torque_max: float | None = None
    n_torque: int = 35

    def __post_init__(self):
        lo, hi = self.ratio_range
        if not 0 < lo < hi:
            raise InputError("ratio_range", f"{lo:g} {hi:g}", "0 < MIN < MAX")
        if self.torque_max is not None and not self.torque_max > 0:
            raise InputError("torque_max", self.torque_max, "> 0 N m")

    def ratios(self) -> np.ndarray:
        """The ideal ratios of the grid [-]."""
        return np.linspace(*self.ratio_range, self.n_ratio)


@dataclass(frozen=True)
class TableGrid(MapGrid):
    """Ratio x input-speed x output-torque grid of `Variator.lookup_table` (``ballcvt table``).

    Attributes
    ----------
    ratio_range, n_ratio, torque_max, n_torque
        As in `MapGrid` (torques start at 0).
    speed_range_rpm : (float, float)
        Smallest and largest input speed [rpm], ``0 < MIN < MAX``.
    n_speed : int
        Input speeds, evenly spaced.
    """

    n_ratio: int = 16
    n_torque: int = 20
    speed_range_rpm: tuple[float, float] = (500.0, 4000.0)
    n_speed: int = 5

    def __post_init__(self):
        w_lo, w_hi = self.speed_range_rpm
        if not 0 < w_lo < w_hi or not math.isfinite(w_hi):
            raise InputError("speed_range", f"{w_lo:g} {w_hi:g}", "0 < MIN < MAX rpm")
        super().__post_init__()

    def speeds_rpm(self) -> np.ndarray:
        """The input speeds of the grid [rpm]."""
        return np.linspace(*self.speed_range_rpm, self.n_speed)
