"""Limiting output torque (docs/model.md §8).

The traction law saturates (``mu -> a + tau_L0 A / F_N``), so creep runs away over a
narrow torque band instead of stopping at a sharp maximum. The limiting torque is the
largest ``T_2`` with a converged equilibrium and every ``|C| <= C_lim``. It is found by
bisection on ``T_2``, each trial started from the solution at the highest torque known
to be admissible (continuation).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..errors import NoEquilibriumError
from .batch import solve_batch
from .point import PointSolution, SolverOptions, solve_point

__all__ = ["LimitSolution", "limit_torque", "limit_torque_batch", "traction_ceiling_torque",
           "saturated_traction", "bisection_steps", "LIMIT_RTOL"]


@dataclass(frozen=True)
class LimitSolution:
    """Limiting torque and the admissible equilibrium just below it.

    Attributes
    ----------
    torque : float
        Limiting output torque [N m].
    solution : PointSolution
        Equilibrium at ``torque``.
    critical_contact : int
        Index of the contact whose creep reaches the limit first.
    bracket : tuple of float
        Final ``(admissible, inadmissible)`` torques [N m].
    """

    torque: float
    solution: PointSolution
    critical_contact: int
    bracket: tuple[float, float]


#: Default relative width of the final torque bracket of the limit bisections.
LIMIT_RTOL = 1e-4


def bisection_steps(rtol: float = LIMIT_RTOL) -> int:
    """Bisection steps of `limit_torque_batch` for a relative bracket ``rtol``."""
    return int(np.ceil(np.log2(1.0 / rtol))) + 1


def saturated_traction(problem: EquilibriumProblem) -> np.ndarray:
    """Traction ceiling ``mu_max = a + tau_L0 pi a_x a_y / F_N`` of every contact [-].

    ``|tau| <= tau_L = tau_L0 + a p`` and the pressure integrates to ``F_N`` over the
    ellipse, so ``|mu| <= mu_max`` (Eqs. 53-54, 57).
    """
    fl = problem.fluid
    area = np.pi * problem.ax * problem.ay
    return fl.limiting_shear_slope + fl.limiting_shear_stress * area / problem.load


def traction_ceiling_torque(problem: EquilibriumProblem) -> np.ndarray:
    """Upper bound on ``T_2`` from the saturated traction of the disc contacts [N m].

    With the spin moment bounded like the traction (`saturated_traction`), the output
    torque cannot exceed ``n F_N r_c (1 + sin(theta)) mu_max`` at the output contact, nor
    that of the input contact over ``tau_ID`` (power cannot grow: ``T_2 <= T_0 / tau_ID``).
    Shape ``(...)``, the batch shape of ``problem``.
    """
    cap = (problem.design.n_rollers * problem.load * problem.radius
           * saturated_traction(problem) * (1 + np.abs(problem.layout.z_j)))
    return np.minimum(cap[..., -1], cap[..., 0] / problem.ratio)


def limit_torque(problem: EquilibriumProblem, creep_limit: float,
                 options: SolverOptions = SolverOptions(),
                 rtol: float = LIMIT_RTOL) -> LimitSolution:
    """Largest admissible output torque of a single operating point.

    Parameters
    ----------
    problem : EquilibriumProblem
        Operating point (its ``output_torque`` is ignored).
    creep_limit : float
        ``C_lim``, the largest admissible ``|C|`` [-].
    options : SolverOptions
        Solver options.
    rtol : float
        Relative width of the final torque bracket [-].

    Returns
    -------
    LimitSolution
    """
    def at(torque, x0):
        sol = solve_point(replace(problem, output_torque=np.asarray(float(torque))), options, x0)
        ok = sol.converged and float(np.max(np.abs(sol.state.creep))) <= creep_limit
        return ok, sol

    ok, best = at(0.0, None)
    if not ok:
        where = (f"ratio {float(problem.ratio):g}, clamp_force {float(problem.clamp_force):g} N, "
                 f"input speed {float(problem.input_speed):g} rad/s")
        if best.converged:
            why = (f"its creep {float(np.max(np.abs(best.state.creep))):.3g} already exceeds "
                   f"creep_limit {creep_limit:g}: the drive's own spin and bearing drag use up "
                   "its traction")
        else:
            why = ("the traction this clamping force can transmit does not carry the drive's "
                   f"own drag; raise clamp_force ({best.message})")
        raise NoEquilibriumError(f"no admissible equilibrium even at zero output torque "
                                 f"({where}): {why}")
    lo, hi = 0.0, float(traction_ceiling_torque(problem))
    while True:
        ok, sol = at(hi, best.state.creep)
        if not ok:
            break
        lo, best, hi = hi, sol, 2.0 * hi
    while hi - lo > rtol * hi:
        mid = 0.5 * (lo + hi)
        ok, sol = at(mid, best.state.creep)
        if ok:
            lo, best = mid, sol
        else:
            hi = mid
    critical = int(np.argmax(np.abs(best.state.creep)))
    return LimitSolution(torque=lo, solution=best, critical_contact=critical, bracket=(lo, hi))


def limit_torque_batch(problem: EquilibriumProblem, creep_limit: float,
                       options: SolverOptions = SolverOptions(), rtol: float = LIMIT_RTOL,
                       callback=None) -> np.ndarray:
    """Limiting output torque of every point of a batch (its ``output_torque`` is ignored).

    The same bisection as `limit_torque`, run on all points at once with the batched
    Newton solver, each trial started from the point's last admissible creeps. A trial
    counts as admissible only if Newton converges with every ``|C| <= creep_limit``
    (no per-point fallback, so a trial Newton cannot converge counts as beyond the limit).

    Parameters
    ----------
    problem : EquilibriumProblem
        Operating points, batch shape ``(...)``.
    creep_limit : float
        ``C_lim`` [-].
    options : SolverOptions
        Solver options.
    rtol : float
        Relative width of the final torque brackets [-].
    callback : callable, optional
        Called with no argument after each bisection step (progress bars).

    Returns
    -------
    ndarray
        Limiting torques [N m], shape ``(...)``; NaN where even ``T_2 = 0`` is inadmissible.
    """
    flat = problem.flat()

    def admissible(torque, x0):
        sol = solve_batch(replace(flat, output_torque=torque), options, x0, fallback=False)
        ok = sol.converged & (np.max(np.abs(sol.state.creep), axis=-1) <= creep_limit)
        return ok, sol.state.creep

    ok0, best = admissible(np.zeros(flat.size), None)
    lo, hi = np.zeros(flat.size), traction_ceiling_torque(flat)
    for _ in range(bisection_steps(rtol)):
        mid = 0.5 * (lo + hi)
        ok, x = admissible(mid, best)
        lo = np.where(ok, mid, lo)
        hi = np.where(ok, hi, mid)
        best = np.where(ok[:, None], x, best)
        if callback is not None:
            callback()
    return np.where(ok0, lo, np.nan).reshape(problem.shape)
