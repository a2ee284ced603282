"""The efficiency-optimal clamp: not a force law but an optimisation (docs/model.md §11).

`OptimalClamp` names it and carries its limits and search settings;
`ballcvt.solvers.optimal_clamp` carries it out.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from .base import ClampLaw

__all__ = ["OptimalClamp"]


@dataclass(frozen=True)
class OptimalClamp(ClampLaw):
    """The clamping force of maximum efficiency at each point (`ballcvt.solvers.optimal_clamp`).

    At zero output torque (no efficiency to maximise) it is the least force from
    ``min_force`` that holds the no-load drag within the creep limit.

    Parameters
    ----------
    creep_limit : float, optional
        ``C_lim`` [-]; the design's by default.
    max_pressure : float, optional
        Largest Hertz peak pressure [Pa]; the design's by default; ``inf``: no pressure
        limit (the efficiency, falling at large forces, places the optimum).
    min_force : float
        Smallest clamping force searched [N].
    grid : int
        Clamping forces on the search's initial geometric grid.
    xtol : float
        Absolute tolerance on the optimal force [N].
    """

    creep_limit: float | None = None
    max_pressure: float | None = None
    name: str = "optimal"
    implicit: bool = False
    min_force: float = 100.0
    grid: int = 24
    xtol: float = 1.0
    optimises: ClassVar[bool] = True
