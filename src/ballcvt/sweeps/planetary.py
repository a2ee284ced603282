"""Planetary modes over many points, batched through the fast solver (docs/model.md §13).

`solve_mode_batch` is `ballcvt.solver.planetary.solve_mode` on a batch: every pass of the
fixed point on the actual ratio is one batched solve. `limit_load_batch` finds the capacity
per mode by bisection on the load.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..equilibrium.problem import build_problem, max_carrier_speed
from ..equilibrium.residual import evaluate
from ..geometry.layout import contact_layout
from ..modes import MEMBERS, OperatingMode, member_torques
from ..performance.efficiency import power_losses
from ..solver.batch import solve_batch
from ..solver.limit import traction_ceiling_torque
from ..solver.planetary import RATIO_TOL
from ..solver.point import SolverOptions

__all__ = ["ModeBatch", "solve_mode_batch", "limit_load_batch", "MODE_STATUS"]


#: Status codes of `solve_mode_batch` (as in a sweep, plus 3).
MODE_STATUS = {0: "converged within the traction capacity", 1: "beyond the traction capacity",
               2: "not converged", 3: "speeds out of range (infinite, none relative to the "
               "carrier, or a carrier fast enough to unload the idler)"}


@dataclass(frozen=True)
class ModeBatch:
    """Outcome of `solve_mode_batch`; arrays ``(n,)`` (speeds and torques ``(3, n)`` in
    the order of `ballcvt.modes.MEMBERS`), NaN where ``status`` is not 0."""

    status: np.ndarray
    speeds: np.ndarray
    torques: np.ndarray
    loss: np.ndarray
    actual_ratio: np.ndarray
    max_creep: np.ndarray
    circulating_power: np.ndarray

    @property
    def powers(self) -> np.ndarray:
        """Power into the drive through each member [W], ``(3, n)``."""
        return self.torques * self.speeds

    @property
    def eta(self) -> np.ndarray:
        """Power out over power in [-] (as `PlanetaryResult.eta`)."""
        p = self.powers
        p_in = np.sum(np.maximum(p, 0.0), axis=0)
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(p_in > 0, np.sum(np.maximum(-p, 0.0), axis=0) / p_in, np.nan)


def solve_mode_batch(design, fluid, architecture: str, mode: OperatingMode, ratio,
                     load_torque, driver_speed, clamp_force: float,
                     options: SolverOptions = SolverOptions(), max_passes: int = 30
                     ) -> ModeBatch:
    """`solve_mode` on a batch of points, batched through the fast solver.

    ``ratio``, ``load_torque`` and ``driver_speed`` broadcast to ``(n,)``. Every pass of the
    fixed point on the actual ratio is one `solve_batch` of the points not yet settled.
    Points whose speeds are out of range are flagged (status 3), not raised; points whose
    creeps exceed ``design.creep_limit`` are flagged 1.
    """
    ratio, load, w = (np.ravel(v) for v in np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (ratio, load_torque, driver_speed))))
    n = ratio.size
    a, b, target = mode.torque_condition(load)
    w_max = float(max_carrier_speed(design, contact_layout(design, architecture),
                                    clamp_force)) if mode.centrifugal else np.inf
    status = np.full(n, 2)
    tau, x = ratio.copy(), np.full((n, contact_layout(design, architecture).n_contacts),
                                   np.nan)
    creep = x.copy()
    settled = np.zeros(n, dtype=bool)
    for _ in range(max_passes):
        sp = mode.speeds(w, tau, check=False)
        rel = sp["disc0"] - sp["carrier"]
        ok = (np.isfinite(rel) & (np.abs(rel) > 0) & np.isfinite(sp["carrier"])
              & (np.abs(sp["carrier"]) < w_max))
        status[~ok & ~settled] = 3
        todo = np.flatnonzero(ok & ~settled)
        if todo.size == 0:
            break
        sign = np.where(rel[todo] > 0, 1.0, -1.0)
        pb = build_problem(design, fluid, architecture, ratio[todo], sign * target[todo],
                           clamp_force, np.abs(rel[todo]), carrier_speed=sign * sp["carrier"][todo],
                           torque_weights=(a, b), centrifugal=mode.centrifugal,
                           gyroscopic=mode.gyroscopic, signed_torque=True)
        x0 = x[todo]
        sol = solve_batch(pb, options, None if np.isnan(x0).any() else x0)
        x[todo] = sol.state.creep
        new = sol.state.omega[:, -1] / sol.state.omega[:, 0]
        done = ~sol.converged | (np.abs(new - tau[todo]) <= RATIO_TOL * np.abs(tau[todo]))
        status[todo[~sol.converged]] = 2
        fin = todo[done & sol.converged]
        status[fin] = 0
        creep[fin] = sol.state.creep[done & sol.converged]
        settled[todo[done]] = True
        tau[todo] = np.where(sol.converged, new, tau[todo])
    # the converged points once more, in one batch, for their torques and losses
    good = np.flatnonzero(status == 0)
    speeds = np.full((3, n), np.nan)
    torques = np.full((3, n), np.nan)
    loss, circ, big = (np.full(n, np.nan) for _ in range(3))
    if good.size:
        sp = mode.speeds(w[good], tau[good], check=False)
        rel = sp["disc0"] - sp["carrier"]
        sign = np.where(rel > 0, 1.0, -1.0)
        pb = build_problem(design, fluid, architecture, ratio[good], sign * target[good],
                           clamp_force, np.abs(rel), carrier_speed=sign * sp["carrier"],
                           torque_weights=(a, b), centrifugal=mode.centrifugal,
                           gyroscopic=mode.gyroscopic, signed_torque=True)
        st = evaluate(pb, creep[good], options.quadrature)
        t2 = st.body_torque[:, -1] - np.sum(pb.output_drag, axis=-1)
        mt = member_torques(sign * st.input_torque, sign * t2)
        for i, m in enumerate(MEMBERS):
            speeds[i, good] = sp[m]
            torques[i, good] = mt[m]
        loss[good] = power_losses(pb, st).total
        circ[good] = np.abs(st.input_torque * np.abs(rel))
        big[good] = np.max(np.abs(creep[good]), axis=-1)
        status[good[big[good] > design.creep_limit]] = 1
    keep = status == 0
    return ModeBatch(status, np.where(keep, speeds, np.nan), np.where(keep, torques, np.nan),
                     np.where(keep, loss, np.nan), np.where(keep, tau, np.nan),
                     np.where(keep, big, np.nan), np.where(keep, circ, np.nan))


def limit_load_batch(design, fluid, architecture: str, mode: OperatingMode, ratio,
                     driver_speed, clamp_force: float, options: SolverOptions = SolverOptions(),
                     rtol: float = 1e-3, max_steps: int = 40) -> np.ndarray:
    """Largest load torque of the driven member with every ``|C| <= creep_limit``.

    The load brakes the driven member: its sign is that of the driven speed at zero load
    (positive at geared neutral). Bracketed by doubling from the carrier-frame traction
    ceiling, then bisected to ``rtol`` on all ratios at once (`solve_mode_batch`).

    Returns
    -------
    ndarray
        ``|L|`` at the limit [N m], ``(n,)``; NaN where even zero load is not admissible or
        the speeds are out of range.
    """
    ratio = np.ravel(np.asarray(ratio, dtype=float))
    n = ratio.size

    def admissible(load):
        return solve_mode_batch(design, fluid, architecture, mode, ratio, load, driver_speed,
                                clamp_force, options).status == 0

    zero = solve_mode_batch(design, fluid, architecture, mode, ratio, 0.0, driver_speed,
                            clamp_force, options)
    direction = np.where(np.nan_to_num(zero.speeds[MEMBERS.index(mode.driven)]) < 0, -1.0,
                         1.0)
    ok0 = zero.status == 0
    hi = traction_ceiling_torque(build_problem(design, fluid, architecture, ratio, 0.0,
                                               clamp_force, 1.0))
    lo = np.zeros(n)
    for _ in range(12):                         # double until beyond the capacity
        up = admissible(direction * hi) & ok0
        if not up.any():
            break
        lo = np.where(up, hi, lo)
        hi = np.where(up, 2.0 * hi, hi)
    for _ in range(max_steps):
        if np.all(~ok0 | (hi - lo <= rtol * hi)):
            break
        mid = 0.5 * (lo + hi)
        up = admissible(direction * mid)
        lo, hi = np.where(up, mid, lo), np.where(up, hi, mid)
    return np.where(ok0, lo, np.nan)

