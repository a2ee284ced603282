"""Fatigue life over a duty cycle by Miner's rule (docs/life.md).

Each step that ran (status 0) consumes the fraction ``D_i = dt_i / L10_i`` of the system
life it would have if it lasted forever (``L10_i`` the system L10 of that step [s]);
Miner's rule adds them, ``D = sum D_i`` per pass over the cycle, and the drive lasts
``1 / D`` passes: ``T / D`` hours of this cycle (``T`` its duration) and, when the cycle
gives a vehicle speed, ``1 / D`` times its distance. Each element's Miner life is its own
sum over the steps. Idle steps wear nothing; steps without a solution (beyond the
capacity, not converged, braking) are not counted, and the summary says how long they
last.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ...model.life import miner_damage, miner_life
from ...params.drive import Drive
from ...solvers.options import SolverOptions
from ...status import Status
from ...units import rpm_to_rad_s
from ..cycles import CycleResult
from ..sweeps.curves import OperatingRows
from ..sweeps.points import evaluate_points
from .core import HOUR, LifeSettings
from .point import SolvedPoints, creep_life

__all__ = ["cycle_life"]


def cycle_life(
    drive,
    result: CycleResult,
    settings: LifeSettings | None = None,
    distance: float | None = None,
) -> CycleResult:
    """The cycle run ``result`` with its fatigue life (Miner's rule over the steps).

    Parameters
    ----------
    drive : Drive or Variator
        The drive that ran the cycle (with its solver ``options`` if it has them).
    result : CycleResult
        From `ballcvt.analysis.cycles.run_cycle`.
    settings : LifeSettings, optional
        Life model and material.
    distance : float, optional
        Distance covered by one pass of the cycle [m] (`Cycle.distance` when the cycle
        carries a vehicle speed); gives the life in kilometres.

    Returns
    -------
    CycleResult
        ``result`` with the step columns ``l10_hours`` (system L10 of the step [h]),
        ``damage`` (Miner damage of the step, per pass [-]) and ``limiting_element``, and
        ``summary["life"]``: ``damage_per_pass``, ``l10_hours``, ``l10_passes``,
        ``l10_km`` (None without a distance), ``limiting_element``, ``elements`` (each
        one's Miner life ``l10_hours`` [h]), ``model``, ``steps_not_counted`` and their ``time_s``.
    """
    s = (settings or LifeSettings()).check()
    steps = result.steps.copy()
    ran = np.asarray(steps["status"] == Status.CONVERGED)
    idx = np.flatnonzero(ran)
    hours = np.full(len(steps), np.nan)
    limiting = np.full(len(steps), "", dtype=object)
    elements: dict[str, dict] = {}
    dt = np.asarray(steps["duration"], dtype=float)
    if idx.size:
        got, element_hours = _step_lives(drive, steps.iloc[idx], s)
        hours[idx], limiting[idx] = got
        for name, h in element_hours.items():  # repetitions of the cycle, in hours
            repeats = float(miner_life(dt[idx] / HOUR, h))
            elements[name] = {"l10_hours": repeats * float(np.sum(dt)) / HOUR}
    idle = np.asarray(steps["flag"] == "idle")
    damage = np.where(idle, 0.0, np.nan)
    with np.errstate(divide="ignore"):
        damage[idx] = dt[idx] / (HOUR * hours[idx])
    steps["l10_hours"], steps["damage"], steps["limiting_element"] = hours, damage, limiting
    total = float(miner_damage(dt[idx] / HOUR, hours[idx]))
    lost = ~(idle | ran)
    passes = 1.0 / total if total > 0 else float("inf")
    life = {
        "model": s.model,
        "material": s.material.name if s.material else "",
        "damage_per_pass": total,
        "l10_passes": passes,
        "l10_hours": passes * float(np.sum(dt)) / HOUR,
        "l10_km": None if distance is None else passes * distance / 1e3,
        "distance_per_pass_km": None if distance is None else distance / 1e3,
        "limiting_element": min(elements, key=lambda k: elements[k]["l10_hours"])
        if elements
        else "",
        "elements": elements,
        "steps_not_counted": int(lost.sum()),
        "time_not_counted_s": float(np.sum(dt[lost])),
    }
    return replace(result, steps=steps, summary={**result.summary, "life": life})


def _step_lives(drive, steps, settings: LifeSettings):
    """((system hours, limiting element), element hours) of solved cycle steps, re-solved at
    the force each used (a constant force reproduces the clamping law's point)."""
    here = Drive(drive.design, drive.fluid, drive.architecture)
    options = getattr(drive, "options", None) or SolverOptions()
    ratio = np.asarray(steps["ratio"], dtype=float)
    w0 = rpm_to_rad_s(np.asarray(steps["input_speed_rpm"], dtype=float))
    force = np.asarray(steps["clamp_force"], dtype=float)
    t2 = np.asarray(steps["output_torque"], dtype=float)
    rows = OperatingRows.of(here, ratio, w0, clamp_force=force, options=options)
    creep = evaluate_points(rows, t2)["creep"]
    points = SolvedPoints(here, ratio, t2, force, w0, creep)
    hours, limiting, got = creep_life(points, settings, options.quadrature)
    each = {}
    if got is not None:
        ok = points.solved
        for name, e in got.elements.items():
            full = np.full(ok.size, np.nan)
            full[ok] = e.l10_hours
            each[name] = full
    return (hours, limiting), each
