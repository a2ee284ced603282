"""The oil's heat balance on the batched paths: sweeps, maps, tables, limit curves
(docs/model.md §15).

Each point of a batch runs at its own bulk oil temperature, the root of
``P_loss(T) = h A (T - T_amb)`` (`ballcvt.api.oil.balance` for one point). The batched
solver holds one fluid per batch, so the batch is solved on a *ladder* of common
temperatures ``T_amb, T_amb + dT, ...`` (`NODE_STEP` apart, up while any point's losses
exceed what the housing rejects at the top rung, at most to `MAX_OIL_TEMPERATURE`), and
each point's balance is found between the rungs:

* its excess ``e_k = P_loss(T_k) - h A (T_k - T_amb)`` at the rungs is interpolated by the
  Lagrange polynomial through up to six rungs about its first change of sign (three below
  the bracket's upper rung, two above: a quintic), whose root in the bracketing interval is
  the point's temperature;
* every quantity of the point (efficiency, losses, creeps, forces, ...) is the same
  polynomial's value at that temperature (Lagrange weights over the same rungs); counts
  and codes (status, warnings, iterations) are those of the rung nearest to it.

A point not solved at a rung before its balance (beyond the limiting torque there, or not
converged) keeps that rung's status and is NaN; a point whose losses outgrow the housing
up to `MAX_OIL_TEMPERATURE` has no balance (a runaway) and is ``status`` 2 (not
converged), NaN.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ..model.oil import MAX_OIL_TEMPERATURE, fluid_at
from ..params.models import Fluid
from ..status import Status

__all__ = [
    "NODE_STEP",
    "LIMIT_STEP",
    "runaways_at_top",
    "runaway_status",
    "Ladder",
    "climb",
    "balance_weights",
    "interpolate",
    "nearest",
    "bracketing",
    "lagrange",
]

#: Spacing of the ladder's temperatures [K]. The efficiency is only once differentiable in
#: the temperature (the mixed-lubrication tables are cubic Hermite pieces in lambda), so
#: the interpolation's error falls with the spacing, not faster: on harden task 0:13 (a
#: random hub-based design with its oil balance) a table's efficiencies agreed with
#: `Variator.solve`'s to 5.3e-6 at 2.5 K and to 5.6e-9 at 1 K (docs/model.md §15).
NODE_STEP = 1.0
#: Spacing of the limit points' ladder [K] (1e-4 relative: the limit searches' own
#: bracket, `ballcvt.solvers.limit.LIMIT_RTOL`; limit points climb far).
LIMIT_STEP = 10.0
#: Rungs of a point's stencil below its bracket's upper rung and above it: a quintic.
BELOW, ABOVE = 3, 2
#: Bisection steps on a point's interpolated excess (the root to 2 K / 2^40).
ROOT_STEPS = 40
#: Outcome of a point: balanced between rungs.
BALANCED = -1
#: Outcome of a point: no balance below `MAX_OIL_TEMPERATURE` (a runaway).
RUNAWAY = -2


@dataclass(frozen=True)
class Ladder:
    """A batch solved at common oil temperatures.

    Attributes
    ----------
    temperatures : ndarray
        The rungs ``(k,)`` [K].
    results : list
        What the batch evaluation returned at each rung.
    excess : ndarray
        ``P_loss - h A (T - T_amb)`` of each point at each rung ``(k, n)`` [W], NaN where
        the point was not solved.
    """

    temperatures: np.ndarray
    results: list
    excess: np.ndarray


def climb(fluid: Fluid, thermal, evaluate: Callable, step: float = NODE_STEP) -> Ladder:
    """Solve a batch on the ladder of oil temperatures from the ambient up.

    Parameters
    ----------
    fluid : Fluid
        The fluid as given (with its viscosity-temperature data).
    thermal : ThermalModel
        The housing (``[design.thermal]``).
    evaluate : callable
        ``evaluate(fluid) -> (result, loss)``: the batch solved with ``fluid``, and the
        total power loss of each point ``(n,)`` [W] (NaN where not solved).
    step : float
        Between the rungs [K].

    Returns
    -------
    Ladder
        The ambient's rung alone where no point has a loss to reject; else the rungs up
        to one past the first where no point's losses exceed the heat rejected, leaving
        out the points whose losses exceed it even at `MAX_OIL_TEMPERATURE` (runaways,
        found by solving there first), and that top rung last.
    """
    ambient, conductance = thermal.ambient_temperature, thermal.conductance

    def rung(t: float):
        result, loss = evaluate(fluid_at(fluid, t))
        return t, result, np.asarray(loss, dtype=float) - conductance * (t - ambient)

    got = [rung(float(ambient))]
    if not np.any(got[0][2] > 0.0):  # nothing to reject: every point at the ambient
        return _ladder(got)
    top = rung(MAX_OIL_TEMPERATURE)
    hopeless = top[2] > 0.0  # losses beyond the housing even with the hottest oil
    if not np.any(got[0][2][~hopeless] > 0.0):  # the rest balance at the ambient
        return _ladder(got + [top])
    settled = 0
    while settled < 1 + ABOVE:  # rungs past the last balance: a whole stencil about it
        t = got[-1][0] + step
        if t >= MAX_OIL_TEMPERATURE:
            break
        got.append(rung(t))
        settled += not np.any(got[-1][2][~hopeless] > 0.0)
    return _ladder(got + [top])


def _ladder(got: list) -> Ladder:
    return Ladder(
        np.array([g[0] for g in got]), [g[1] for g in got], np.array([g[2] for g in got])
    )


def lagrange(nodes: np.ndarray, t: float) -> np.ndarray:
    """The Lagrange basis through ``nodes`` at ``t``."""
    w = np.ones(nodes.size)
    for j in range(nodes.size):
        for m in range(nodes.size):
            if m != j:
                w[j] *= (t - nodes[m]) / (nodes[j] - nodes[m])
    return w


def _root(nodes: np.ndarray, values: np.ndarray, lo: float, hi: float) -> float:
    """The root in ``[lo, hi]`` of the polynomial through ``(nodes, values)``, which is
    positive at ``lo`` and not at ``hi`` (bisection)."""
    for _ in range(ROOT_STEPS):
        mid = 0.5 * (lo + hi)
        if lagrange(nodes, mid) @ values > 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def _point(temps: np.ndarray, e: np.ndarray) -> tuple[int, float, np.ndarray]:
    """``(outcome, T, weights)`` of one point from its excess at the rungs: outcome
    `BALANCED`, `RUNAWAY`, or the rung where it was not solved."""
    k = temps.size
    weights = np.zeros(k)
    for j in range(k):
        if not np.isfinite(e[j]):
            return j, float(temps[j]), weights
        if e[j] <= 0.0:
            break
    else:
        return RUNAWAY, float(temps[-1]), weights
    if j == 0:  # no loss to reject: the oil at the ambient
        weights[0] = 1.0
        return BALANCED, float(temps[0]), weights
    spacing = temps[1] - temps[0]
    top = j
    while (
        top + 1 < min(k, j + 1 + ABOVE)
        and np.isfinite(e[top + 1])
        and temps[top + 1] - temps[top] <= 1.001 * spacing
    ):
        top += 1
    use = np.arange(max(0, j - BELOW), top + 1)
    root = _root(temps[use], e[use], float(temps[j - 1]), float(temps[j]))
    weights[use] = lagrange(temps[use], root)
    return BALANCED, root, weights


def balance_weights(ladder: Ladder) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Each point's balance between the rungs.

    Returns
    -------
    temperature : ndarray
        The oil temperature of each point ``(n,)`` [K] (at a failed point, the rung where
        it failed; at a runaway, the top rung).
    weights : ndarray
        Lagrange weights ``(k, n)`` of the rungs at that temperature (zero at a failed
        point).
    outcome : ndarray
        ``(n,)``: `BALANCED`, `RUNAWAY`, or the index of the rung where the point was not
        solved.
    """
    temps, excess = ladder.temperatures, ladder.excess
    n = excess.shape[1]
    temperature, outcome = np.empty(n), np.empty(n, dtype=int)
    weights = np.zeros((temps.size, n))
    for i in range(n):
        outcome[i], temperature[i], weights[:, i] = _point(temps, excess[:, i])
    return temperature, weights, outcome


def interpolate(values: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """``sum_k w_k v_k`` over the rungs (axis 0); NaN where every weight is zero.

    ``values`` ``(k, n, ...)`` at each rung, ``weights`` ``(k, n)`` from
    `balance_weights`; a value at a rung of zero weight does not count (NaN or not).
    """
    w = weights.reshape(weights.shape + (1,) * (values.ndim - weights.ndim))
    used = np.broadcast_to(w != 0.0, values.shape)
    out = np.sum(np.where(used, values, 0.0) * w, axis=0)
    return np.where(np.any(used, axis=0), out, np.nan)


def nearest(values: np.ndarray, ladder: Ladder, temperature, outcome) -> np.ndarray:
    """A count or code (status, warnings, iterations) ``(k, n, ...)`` at each point's rung
    nearest its temperature; a failed point's at its failed rung, a runaway's
    `Status.NOT_CONVERGED` when ``values`` are statuses (else the top rung's)."""
    idx = np.abs(ladder.temperatures[:, None] - temperature[None, :]).argmin(axis=0)
    idx = np.where(outcome >= 0, outcome, idx)
    out = np.take_along_axis(values, idx.reshape((1, -1) + (1,) * (values.ndim - 2)), axis=0)[0]
    return out


def bracketing(ladder: Ladder, temperature) -> tuple[np.ndarray, np.ndarray]:
    """Indices ``(below, above)`` ``(n,)`` of the rungs either side of each temperature
    [K] (both the rung's own at a rung, the end rung's beyond the ladder)."""
    temps = ladder.temperatures
    above = np.clip(np.searchsorted(temps, temperature), 0, temps.size - 1)
    below = np.where(temps[above] <= temperature, above, np.maximum(above - 1, 0))
    return below, above


def runaways_at_top(ladder: Ladder, temperature, weights, outcome) -> None:
    """A runaway takes the top rung (`MAX_OIL_TEMPERATURE`): in place, its temperature
    and weights (a limit point the housing cannot hold below it is taken there)."""
    run = outcome == RUNAWAY
    temperature[run] = ladder.temperatures[-1]
    weights[:, run] = 0.0
    weights[-1, run] = 1.0


def runaway_status(status: np.ndarray, outcome: np.ndarray) -> np.ndarray:
    """``status`` with a runaway point's set to `Status.NOT_CONVERGED`."""
    shape = outcome.shape + (1,) * (status.ndim - 1)
    return np.where(outcome.reshape(shape) == RUNAWAY, Status.NOT_CONVERGED, status)
