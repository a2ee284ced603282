"""The traction capacity over a ratio range, with the constraint that sets it at each ratio
(docs/model.md §8, §11): the Python form of ``ballcvt capacity``."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..solvers.capacity import Capacity

__all__ = ["CapacityCurve", "capacity_curve"]


@dataclass(frozen=True)
class CapacityCurve:
    """Admissible output torques at each ratio of a range.

    Attributes
    ----------
    ratio : ndarray
        Ideal ratios ``tau_ID`` [-], ``(n,)``.
    capacities : tuple of Capacity
        The admissible intervals [N m] at each ratio and what sets each end
        (`Capacity.constraints`).
    """

    ratio: np.ndarray
    capacities: tuple[Capacity, ...]

    @property
    def limit_torque(self) -> np.ndarray:
        """The largest admissible output torque at each ratio [N m] (NaN: none)."""
        return np.array([c.largest for c in self.capacities])

    @property
    def active_constraint(self) -> list[str | None]:
        """What sets the largest admissible torque at each ratio (e.g. ``"creep (output
        contact)"``, ``"pressure (max_pressure 3 GPa)"``, ``"no equilibrium"``)."""
        return [c.active_constraint for c in self.capacities]

    def to_frame(self):
        """One row per ratio: ``ratio`` [-], ``limit_torque`` [N m] (the largest
        admissible; empty when none), ``lowest_torque`` [N m] (the lower end of the first
        interval), ``active_constraint`` (what sets ``limit_torque``),
        ``lower_constraint`` (what sets ``lowest_torque``), ``n_intervals`` and
        ``intervals`` (text, e.g. ``"0 to 41.2 N m"``).

        Returns
        -------
        pandas.DataFrame
        """
        import pandas as pd

        return pd.DataFrame(
            {
                "ratio": self.ratio,
                "limit_torque": self.limit_torque,
                "lowest_torque": [
                    c.intervals[0][0] if c.intervals else np.nan for c in self.capacities
                ],
                "active_constraint": self.active_constraint,
                "lower_constraint": [
                    c.constraints[0][0] if c.constraints else None for c in self.capacities
                ],
                "n_intervals": [len(c.intervals) for c in self.capacities],
                "intervals": [c.describe() for c in self.capacities],
            }
        )


def capacity_curve(variator, ratios, **where) -> CapacityCurve:
    """`Variator.capacity` at each ratio of ``ratios``, with its active constraints.

    Parameters
    ----------
    variator : Variator
        The drive.
    ratios : array_like
        Ideal ratios ``tau_ID`` [-] within the drive's range.
    **where
        ``clamp_force`` [N] or ``clamp_law``, ``input_speed`` [rad/s] or
        ``input_speed_rpm`` [rpm], ``creep_limit`` [-]: as in `Variator.capacity`.

    Returns
    -------
    CapacityCurve

    Examples
    --------
    >>> from ballcvt import Variator
    >>> from ballcvt.api import capacity_curve
    >>> c = capacity_curve(Variator(), [0.5, 1.0, 2.0], clamp_force=2000.0,
    ...                    input_speed_rpm=2000)  # doctest: +SKIP
    >>> c.to_frame()[["ratio", "limit_torque", "active_constraint"]]  # doctest: +SKIP
    """
    r = np.asarray(ratios, dtype=float).reshape(-1)
    return CapacityCurve(r, tuple(variator.capacity(float(x), **where) for x in r))
