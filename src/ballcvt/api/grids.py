"""Batched limits, efficiency maps and lookup tables of a `Variator` (``ballcvt map``,
``ballcvt table``): the limit search of every curve runs once, sets the default torque
range, and is handed to the sweep (docs/model.md §8)."""

from __future__ import annotations

import sys
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..analysis.oil_sweep import balanced_limits
from ..analysis.sweeps.curves import OperatingRows, limit_search_curves
from ..equilibrium.problem import build_problem
from ..model.oil import fluid_at
from ..params.drive import Drive
from ..solvers.limit import LimitSearch, bisection_steps
from ..units import rpm_to_rad_s
from . import oil
from .settings import MapGrid, SweepSettings, TableGrid

__all__ = ["LimitCurve", "limit_curve", "efficiency_map", "lookup_table"]


@dataclass(frozen=True)
class LimitCurve:
    """Limiting output torques of a batch of (ratio, input speed) curves.

    Attributes
    ----------
    ratio : ndarray
        Ideal ratios [-], ``(m,)``.
    input_speed : ndarray
        Input speeds [rad/s], ``(m,)``.
    search : LimitSearch
        The limit search (torques, and the creeps at zero torque and at the limits), which
        `Variator.sweep` takes as ``limit_torque`` so as not to search again.
    oil_temperature : ndarray, optional
        Under the oil's heat balance, the temperature each curve's limit point produces
        ``(m,)`` [K] (docs/model.md §15); None at the fluid as given.
    """

    ratio: np.ndarray
    input_speed: np.ndarray
    search: LimitSearch
    oil_temperature: np.ndarray | None = None

    @property
    def torque(self) -> np.ndarray:
        """Limiting output torque of each curve [N m] (NaN where none)."""
        return self.search.torque


def _progress_bar(progress: bool | None, total: int, desc: str):
    from tqdm.auto import tqdm

    show = sys.stderr.isatty() if progress is None else progress
    return tqdm(total=total, desc=desc, unit="step", disable=not show)


def limit_curve(variator, ratio, input_speed, clamp: dict, creep_limit, progress) -> LimitCurve:
    """`Variator.limit_curve`: one batched limit search (docs/model.md §8, §11).

    Parameters
    ----------
    variator : Variator
        The drive.
    ratio, input_speed : array_like
        Ideal ratios [-] and input speeds [rad/s]; broadcast together and flattened.
    clamp : dict
        ``clamp_force`` [N] or ``clamp_law`` (as in `Variator.solve`).
    creep_limit : float or None
        ``C_lim`` [-]; the design's by default.
    progress : bool or None
        Progress bar (None: when stderr is a terminal).
    """
    v = variator
    r, w = (np.ravel(a) for a in np.broadcast_arrays(np.asarray(ratio, float), input_speed))
    force = clamp.get("clamp_force")
    law = None if force is not None else v.clamp_law(clamp.get("clamp_law"))
    build_problem(
        v.design, v.fluid, v.architecture, r, 0.0, 1.0 if force is None else force, w
    )  # validates every input
    c_lim = v.design.creep_limit if creep_limit is None else float(creep_limit)
    rows = OperatingRows.of(
        Drive(v.design, v.fluid, v.architecture), r, w, force, law, v.options, c_lim
    )
    if (choice := oil.path_choice(v)) != "fixed":  # each limit at its own oil temperature
        return _oil_limits(v, rows, choice)
    with _progress_bar(progress, bisection_steps(), f"limiting torque at {r.size} points") as bar:
        search = limit_search_curves(rows, bar.update)[1]
    return LimitCurve(r, w, search)


def _oil_limits(variator, rows, choice) -> LimitCurve:
    """`limit_curve` under the oil model ``choice``, not ``"fixed"`` (docs/model.md §15)."""
    if choice == "balance":
        thermal = oil.thermal_of(variator.design)
        _, temperature, search = balanced_limits(rows, thermal)
        return LimitCurve(rows.ratio, rows.input_speed, search, temperature)
    fluid = fluid_at(variator.fluid, float(choice))
    search = limit_search_curves(replace(rows, drive=replace(rows.drive, fluid=fluid)))[1]
    return LimitCurve(rows.ratio, rows.input_speed, search, np.full(rows.size, float(choice)))


def efficiency_map(variator, grid: MapGrid, input_speed_rpm: float, clamp: dict, run: dict):
    """`Variator.efficiency_map` on ``grid`` at one input speed [rpm]; ``run`` holds
    ``workers`` and ``progress``."""
    ratios = grid.ratios()
    w = np.full(ratios.size, rpm_to_rad_s(input_speed_rpm))
    limits = limit_curve(variator, ratios, w, clamp, None, run["progress"])
    top = 1.02 * _largest(limits) if grid.torque_max is None else grid.torque_max
    return variator.sweep(
        ratio=ratios,
        output_torque=np.linspace(top / grid.n_torque, top, grid.n_torque),
        **clamp,
        input_speed_rpm=input_speed_rpm,
        settings=SweepSettings(limit_torque=_handed(limits), label="efficiency map", **run),
    )


def lookup_table(variator, grid: TableGrid, clamp: dict, run: dict):
    """`Variator.lookup_table` on ``grid``; ``run`` holds ``workers`` and ``progress``."""
    ratios, rpm = grid.ratios(), grid.speeds_rpm()
    r_grid, w_grid = (g.ravel() for g in np.meshgrid(ratios, rpm_to_rad_s(rpm)))
    limits = limit_curve(variator, r_grid, w_grid, clamp, None, run["progress"])
    top = _largest(limits) if grid.torque_max is None else grid.torque_max
    return variator.sweep(
        ratio=ratios,
        output_torque=np.linspace(0.0, top, grid.n_torque),
        **clamp,
        input_speed_rpm=rpm,
        settings=SweepSettings(limit_torque=_handed(limits), label="lookup table", **run),
    )


def _handed(limits: LimitCurve) -> LimitCurve | None:
    """The limits a map or table hands to its sweep: none under an oil temperature
    other than the fluid's own (each temperature of the sweep searches its own)."""
    return limits if limits.oil_temperature is None else None


def _largest(limits: LimitCurve) -> float:
    return float(np.nanmax(limits.torque))


def sweep_limit(limit: Any) -> Any:
    """The ``limit_torque`` a sweep takes: a `LimitCurve`'s search, else as given."""
    return limit.search if isinstance(limit, LimitCurve) else limit
