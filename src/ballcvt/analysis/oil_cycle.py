"""A duty cycle with the oil's temperature: the housing's lumped transient (docs/model.md §15).

``C dT/dt = P_loss(t, T) - h A (T - T_amb)`` is integrated over the steps with the loss held
over each step (the exact exponential update, `ballcvt.model.oil.transient_step`: stable at
any step length), the loss of a step evaluated at the temperature the step starts at
(explicit in the fluid's temperature dependence, which is slow beside ``C / (h A)``).

The steps are solved batched, as every cycle: the whole cycle is run (`run_cycle`) with the
fluid at a few bulk temperatures `GRID_STEP` apart, each run only when the temperature
reaches it; a step at ``T`` between two of them takes the rows of the four runs about it
(one below and two above; from the start's run up between the first two) interpolated by
the cubic through them in ``T`` (Lagrange), the flag and status of the nearest. Where the
step failed or changed its flag at any of the four, no interpolation holds (the step's
efficiency can turn steeply where a creep nears its limit: 9e-3 per K on harden task
2719:30, so even the nearer run's row 0.0015 K away was 1.4e-5 off), and the step is solved
alone at its own temperature (`_alone`); where it failed alike at the two runs about it, it
takes the nearer's row as it is. The temperature never jumps a grid interval in one step
unnoticed: every step reads the runs around its own temperature.

Linear interpolation was not enough: on the built-in hub a step's efficiency curves in the
oil's temperature by ``d2 eta / dT2`` ~ -2e-4 1/K^2, so the chord of runs 1 K apart was up
to 2.2e-5 under the step solved at its temperature (``h^2 |eta''| / 8``); the cubic's error
is of the fourth order in the spacing (docs/model.md §15).
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
from .oil_paths import lagrange

__all__ = ["OilTransient", "run_cycle_with_oil", "GRID_STEP"]

#: Spacing of the bulk temperatures the cycle is solved at [K].
GRID_STEP = 1.0
#: The runs a step at ``t0 + (j + w) GRID_STEP`` reads, as offsets from ``j - 1`` (from
#: ``j = 0``, the start's run, they begin there: a warming cycle runs none below it).
STENCIL = (0, 1, 2, 3)


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
    records: dict[int, list] = {}  # each run's steps as rows (read once per step each)

    def run(j: int) -> list:
        if j not in runs:
            hot = replace(drive, fluid=fluid_at(drive.fluid, t0 + j * GRID_STEP))
            runs[j] = run_cycle(hot, cycle, request)
            records[j] = runs[j].steps.to_dict("records")
        return records[j]

    alone = 0  # steps solved alone at their own temperature
    temps = np.empty(cycle.size + 1)
    temps[0] = t0
    rows = []
    durations = cycle.durations
    for k in range(cycle.size):
        x = (temps[k] - t0) / GRID_STEP
        j = math.floor(x)
        low = -1 if j != 0 else 0  # from the start up: the runs from it (none below)
        row = _blend([run(j + low + m)[k] for m in range(len(STENCIL))], x - j - low)
        if row is None:
            row, alone = _alone(drive, cycle, request, (k, temps[k])), alone + 1
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
        "steps_solved_alone": alone,
    }
    return CycleResult(steps=steps, summary=summary)


def _blend(rows: list, x: float):
    """The step's row at ``x`` in [0, 3] over the four `STENCIL` runs ``rows`` (module
    docstring): the cubic through the four where they share its status and flag; the
    nearer of the two about ``x`` as it is where both failed alike; else None (to be
    solved at its own temperature)."""
    i = min(int(x), 2)
    lo, hi = rows[i], rows[i + 1]
    near = lo if x - i < 0.5 else hi
    if _alike(lo, hi) and near["status"] != 0:
        return dict(near)
    if not all(_alike(near, r) for r in rows):
        return None
    weights = lagrange(np.asarray(STENCIL, dtype=float), x)
    out = dict(near)
    for key, a in near.items():
        if key in ("flag", "status", "time", "duration"):
            continue
        if isinstance(a, float | np.floating):
            out[key] = float(sum(c * r[key] for c, r in zip(weights, rows, strict=True)))
    return out


def _alone(drive, cycle: Cycle, request: CycleRequest, at: tuple) -> dict:
    """The row of step ``k`` solved alone with the fluid at ``temperature`` [K] (``at`` =
    ``(k, temperature)``; its time and duration those of the whole cycle's step)."""
    k, temperature = at
    one = cycle.take(slice(k, k + 1))
    settings = replace(request, workers=1, progress=False)
    hot = replace(drive, fluid=fluid_at(drive.fluid, float(temperature)))
    row = run_cycle(hot, one, settings).steps.to_dict("records")[0]
    row.update(time=float(cycle.time[k]), duration=float(cycle.durations[k]))
    return row


def _alike(a, b) -> bool:
    """Whether two runs' rows of a step share their status and flag."""
    return a["status"] == b["status"] and a["flag"] == b["flag"]
