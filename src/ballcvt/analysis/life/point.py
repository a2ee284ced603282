"""The fatigue life of one solved point, and of a batch of points given by their creeps."""

from __future__ import annotations

from types import MappingProxyType

import numpy as np

from ...equilibrium.problem import build_problem
from ...equilibrium.residual import evaluate
from ...model.clamping import axial_force
from ...model.traction.quadrature import Quadrature
from ...params.drive import Drive
from .core import LifeArrays, LifeSettings, life_arrays
from .elements import LifeInputs
from .result import ElementLife, LifeResult

__all__ = ["point_life", "creep_life", "SolvedPoints"]


def point_life(result, settings: LifeSettings | None = None) -> LifeResult:
    """Fatigue life of a solved operating point (docs/life.md).

    Parameters
    ----------
    result : OperatingResult or PlanetaryResult
        The point (in a planetary mode its carrier-frame point, ``result.relative``: the
        stress cycles count the speeds relative to the carrier).
    settings : LifeSettings, optional
        Life model and material (Lundberg-Palmgren on AISI 52100 by default).

    Returns
    -------
    LifeResult
    """
    s = (settings or LifeSettings()).check()
    point = getattr(result, "relative", result)
    got = life_arrays(LifeInputs.of_result(point), s)
    elements = {
        name: ElementLife(
            e.kind,
            e.body,
            e.count,
            float(e.l10_cycles[0]),
            float(e.cycle_rate[0]),
            float(e.l10_hours[0]),
            float(e.load[0]),
        )
        for name, e in got.elements.items()
    }
    assert s.material is not None
    return LifeResult(
        elements=MappingProxyType(elements),
        l10_hours=float(got.l10_hours[0]),
        limiting_element=str(got.limiting()[0]),
        model=s.model,
        material=s.material.name,
        weibull_slope=got.weibull_slope,
        notes=got.notes,
        point=MappingProxyType(
            {
                "ratio": point.ratio,
                "output_torque": point.output_torque,
                "clamp_force": point.clamp_force,
                "input_speed_rpm": point.input_speed_rpm,
            }
        ),
    )


class SolvedPoints:
    """A 1-D batch of solved points of one drive, carrier held: their inputs and creeps.

    Parameters
    ----------
    drive : Drive
    ratio, output_torque, clamp_force, input_speed : array_like
        ``(m,)``: ideal ratio [-], ``T_2`` [N m], ``F_N0`` [N], ``omega_0`` [rad/s].
    creep : array_like
        The solved creeps, ``(m, n_c)`` [-] (NaN rows: points without a solution).
    """

    def __init__(self, drive: Drive, ratio, output_torque, clamp_force, input_speed, creep):
        self.drive = drive
        arrays = np.broadcast_arrays(
            *(np.asarray(a, dtype=float) for a in (ratio, output_torque, clamp_force, input_speed))
        )
        self.inputs = tuple(np.ravel(a) for a in arrays)
        self.creep = np.asarray(creep, dtype=float).reshape(self.inputs[0].size, -1)

    @property
    def solved(self) -> np.ndarray:
        """Which points have a solution (finite creeps)."""
        return np.all(np.isfinite(self.creep), axis=-1) & np.isfinite(self.inputs[2])


def creep_life(
    points: SolvedPoints,
    settings: LifeSettings | None = None,
    quadrature: Quadrature | None = None,
) -> tuple[np.ndarray, np.ndarray, LifeArrays | None]:
    """System L10 [h] and limiting element of each point of a batch (NaN and ``""`` where a
    point has no solution), and the lives of the solved points.

    The balances are evaluated once at the solved creeps (`ballcvt.equilibrium.evaluate`)
    for the axle reactions and the body speeds the solution implies.
    """
    s = (settings or LifeSettings()).check()
    ok = points.solved
    m = ok.size
    hours, limiting = np.full(m, np.nan), np.full(m, "", dtype=object)
    if not ok.any():
        return hours, limiting, None
    d = points.drive
    ratio, torque, force, speed = (a[ok] for a in points.inputs)
    pb = build_problem(d.design, d.fluid, d.architecture, ratio, torque, force, speed)
    st = evaluate(pb, points.creep[ok], quadrature or Quadrature())
    got = life_arrays(LifeInputs.of_state(pb, st, axial_force(d.design, force)), s)
    hours[ok] = got.l10_hours
    limiting[ok] = got.limiting()
    return hours, limiting, got
