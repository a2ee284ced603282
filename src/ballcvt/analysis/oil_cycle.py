"""A duty cycle with the oil's temperature: the housing's lumped transient (docs/model.md §15).

``C dT/dt = P_loss(t, T) - h A (T - T_amb)`` is integrated over the steps with the loss held
over each step (the exact exponential update, `ballcvt.model.oil.transient_step`: stable at
any step length), the loss of a step evaluated at the temperature the step starts at
(explicit in the fluid's temperature dependence, which is slow beside ``C / (h A)``).

The steps are solved batched, as every cycle: the whole cycle is run (`run_cycle`) with the
fluid at a few bulk temperatures `GRID_STEP` apart, each run only when the temperature
reaches it; a step at ``T`` between two of them takes their rows interpolated linearly in
``T`` (the flag and status of the nearer; a step that failed at either takes the nearer's
row as it is). The temperature never jumps a grid interval in one step unnoticed: every
step reads the two runs around its own temperature.
"""

from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..errors import InputError
from ..model.clamping import clamp_law as resolve_law
from ..model.oil import C_TO_K, MAX_OIL_TEMPERATURE, fluid_at, transient_step
from .cycle_files import Cycle
from .cycle_request import CycleRequest
from .cycles import CycleResult, _summary, run_cycle

__all__ = ["OilTransient", "run_cycle_with_oil", "GRID_STEP"]

#: Spacing of the bulk temperatures the cycle is solved at [K].
GRID_STEP = 1.0


@dataclass(frozen=True)
class OilTransient:
    """The oil's model over a cycle.

    Attributes
    ----------
    thermal : ThermalModel
        The housing (``[design.thermal]``, with its ``thermal_mass``).
    initial_temperature : float, optional
        At the cycle's start [K]; the ambient when None.
    fixed_temperature : float, optional
        Run the whole cycle with the fluid at this temperature instead [K].
    """

    thermal: Any
    initial_temperature: float | None = None
    fixed_temperature: float | None = None


def run_cycle_with_oil(drive, cycle: Cycle, request: CycleRequest, oil: OilTransient):
    """`run_cycle` with the oil's temperature: fixed at ``oil.fixed_temperature``, or the
    lumped transient (module docstring).

    Returns
    -------
    CycleResult
        Its steps gain ``oil_temperature_C`` (at each step's start) [C]; its summary
        ``oil_temperature`` (the model, the initial, maximum and final temperatures [C],
        the time constant [s] and the temperatures the cycle was solved at).
    """
    start = _time.perf_counter()
    if oil.fixed_temperature is not None:
        res = run_cycle(
            replace(drive, fluid=fluid_at(drive.fluid, oil.fixed_temperature)), cycle, request
        )
        res.steps["oil_temperature_C"] = oil.fixed_temperature - C_TO_K
        t_c = oil.fixed_temperature - C_TO_K
        res.summary["oil_temperature"] = {"model": "given", "max_C": t_c, "final_C": t_c}
        return res
    thermal = oil.thermal
    t0 = (
        thermal.ambient_temperature if oil.initial_temperature is None else oil.initial_temperature
    )
    runs: dict[int, CycleResult] = {}

    def run(j: int):
        if j not in runs:
            hot = replace(drive, fluid=fluid_at(drive.fluid, t0 + j * GRID_STEP))
            runs[j] = run_cycle(hot, cycle, request)
        return runs[j].steps

    temps = np.empty(cycle.size + 1)
    temps[0] = t0
    rows = []
    durations = cycle.durations
    for k in range(cycle.size):
        x = (temps[k] - t0) / GRID_STEP
        j = math.floor(x)
        w = x - j
        row = _blend(run(j).iloc[k], run(j + 1).iloc[k], w)
        rows.append(row)
        loss = 0.0 if row["flag"] == "idle" or not row["status"] == 0 else float(row["loss_total"])
        temps[k + 1] = transient_step(temps[k], loss, float(durations[k]), thermal)
        if temps[k + 1] > MAX_OIL_TEMPERATURE:
            raise InputError(
                "oil_temperature",
                "transient",
                "a cycle the housing keeps below 150 C",
                message=f"the oil passes 150 C at t = {cycle.time[k]:.0f} s (loss "
                f"{loss:.4g} W, h A = {thermal.conductance:.4g} W/K): beyond the fluid's data",
            )
    import pandas as pd

    steps = pd.DataFrame(rows).reset_index(drop=True)
    steps["oil_temperature_C"] = temps[:-1] - C_TO_K
    base = runs[0].summary
    law = resolve_law(request.clamp_law, drive.design, request.clamp_force)
    summary = _summary(
        drive,
        cycle,
        steps,
        base["strategy"],
        law,
        request.resolve(cycle).target_input_speed,
        _time.perf_counter() - start,
    )
    summary["workers"] = base["workers"]
    summary["oil_temperature"] = {
        "model": "transient",
        "initial_C": t0 - C_TO_K,
        "max_C": float(np.max(temps)) - C_TO_K,
        "final_C": float(temps[-1]) - C_TO_K,
        "time_constant_s": thermal.time_constant,
        "solved_at_C": sorted(t0 + j * GRID_STEP - C_TO_K for j in runs),
    }
    return CycleResult(steps=steps, summary=summary)


def _blend(lo, hi, w: float):
    """The row ``(1 - w) lo + w hi`` (numbers), the nearer's flag and status; the nearer
    row as it is where either failed."""
    near = lo if w < 0.5 else hi
    if lo["status"] != hi["status"] or lo["flag"] != hi["flag"] or near["status"] != 0:
        return near.copy()
    out = near.copy()
    for key, a in lo.items():
        if key in ("flag", "status", "time", "duration"):
            continue
        if isinstance(a, float | np.floating):
            out[key] = (1.0 - w) * a + w * hi[key]
    return out
