"""The outcome of a planetary mode's batched solve (`ballcvt.solvers.planetary_batch`)."""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from ..model.modes import MEMBERS, OperatingMode

__all__ = ["ModeBatch"]


@dataclass(frozen=True)
class ModeBatch:
    """Outcome of `solve_mode_batch`; arrays ``(n,)`` (speeds and torques ``(3, n)`` in
    the order of `ballcvt.model.modes.MEMBERS`), NaN where ``status`` (a
    `ballcvt.status.Status` code) is not ``CONVERGED``; ``losses`` [W] is ``(k, n)``, one
    row per kind of `ballcvt.performance.efficiency.LOSS_KINDS` (``loss`` is its total);
    ``creep`` ``(n_c, n)`` holds the contacts' creeps in the carrier frame [-]."""

    status: np.ndarray
    speeds: np.ndarray
    torques: np.ndarray
    loss: np.ndarray
    actual_ratio: np.ndarray
    max_creep: np.ndarray
    circulating_power: np.ndarray
    losses: np.ndarray
    creep: np.ndarray

    @property
    def powers(self) -> np.ndarray:
        """Power into the drive through each member [W], ``(3, n)``."""
        return self.torques * self.speeds

    @property
    def input_power(self) -> np.ndarray:
        """Power into the drive: the sum of the members' positive powers [W]."""
        return np.sum(np.maximum(self.powers, 0.0), axis=0)

    @property
    def eta(self) -> np.ndarray:
        """Power out over power in [-] (as `PlanetaryResult.eta`)."""
        p_in = self.input_power
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(p_in > 0, np.sum(np.maximum(-self.powers, 0.0), axis=0) / p_in, np.nan)

    def expand(self, index, size: int, status: int) -> ModeBatch:
        """The batch of ``size`` points with these at ``index`` and every other point
        at ``status``, its figures NaN."""

        def full(values):
            out = np.full(np.shape(values)[:-1] + (size,), np.nan)
            out[..., index] = values
            return out

        codes = np.full(size, int(status))
        codes[index] = self.status
        return ModeBatch(codes, *(full(getattr(self, f.name)) for f in fields(self)[1:]))

    def braking_direction(self, mode: OperatingMode) -> np.ndarray:
        """Sign of a load that brakes the driven member: that of its speed in this batch
        (solved at zero load), +1 where it is zero or unknown."""
        return np.where(np.nan_to_num(self.speeds[MEMBERS.index(mode.driven)]) < 0, -1.0, 1.0)
