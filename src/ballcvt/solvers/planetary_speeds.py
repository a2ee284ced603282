"""The members' speeds of a planetary mode and the actual ratio its creeps give
(docs/model.md §13): what `ballcvt.solvers.planetary` and its batched and held-creep
searches share."""

from __future__ import annotations

import numpy as np

from ..model.architectures import contact_layout
from ..model.inertia import max_carrier_speed
from ..model.modes import OperatingMode

__all__ = ["carrier_speed_bound", "member_speeds", "relative_ratio"]


def carrier_speed_bound(drive, mode: OperatingMode, clamp_force: float) -> float:
    """The carrier speed [rad/s] above which the balls' centrifugal force lifts them off
    the idler (`ballcvt.model.inertia.max_carrier_speed`), or ``inf`` for a mode without
    it."""
    if not mode.centrifugal:
        return np.inf
    layout = contact_layout(drive.design, drive.architecture)
    return float(max_carrier_speed(drive.design, layout, clamp_force))


def member_speeds(mode: OperatingMode, driver_speed, tau, bound: float):
    """The members' speeds [rad/s] at the relative ratio ``tau`` (`OperatingMode.speeds`,
    unchecked) and whether each point's are in range: the discs turn relative to the
    carrier, and the carrier turns below ``bound`` (`carrier_speed_bound`)."""
    sp = mode.speeds(driver_speed, tau, check=False)
    rel = sp["disc0"] - sp["carrier"]
    ok = (
        np.isfinite(rel)
        & (np.abs(rel) > 0)
        & np.isfinite(sp["carrier"])
        & (np.abs(sp["carrier"]) < bound)
    )
    return sp, ok


def relative_ratio(ideal, creep) -> np.ndarray:
    """The actual relative ratio ``omega_2 / omega_0`` of the carrier-frame creeps ``creep``
    ``(n, n_c)`` at the ideal ratio ``ideal`` [-]: ``tau_ID (1 - C_0) (1 - C_2)`` (the disc
    contacts' creeps as `ballcvt.equilibrium.residual` defines them, Eqs. 7-9), a first
    pass's ratio from guessed creeps."""
    creep = np.asarray(creep, dtype=float)
    return np.asarray(ideal, dtype=float) * (1.0 - creep[:, 0]) * (1.0 - creep[:, -1])
