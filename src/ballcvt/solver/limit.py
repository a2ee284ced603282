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
from .clamped import pressure_bound_force, solve_clamped, with_clamp
from .point import SolverOptions, solve_point

__all__ = ["limit_torque", "limit_torque_batch", "solve_admissible", "Admissibility",
           "traction_ceiling_torque", "saturated_traction", "bisection_steps", "LIMIT_RTOL"]


#: Default relative width of the final torque bracket of the limit bisections.
LIMIT_RTOL = 1e-4
#: Most bisection steps of `limit_torque_batch` (a bracket of 2^-60 of the ceiling).
MAX_BISECTIONS = 60


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
                 options: SolverOptions = SolverOptions(), rtol: float = LIMIT_RTOL,
                 law=None) -> float:
    """Largest admissible output torque of a single operating point [N m].

    `limit_torque_batch` on one point, so that a point, a sweep and a map give the same
    limit; when there is none, the cause is diagnosed and raised.

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
    law : clamping law, optional
        A law whose force follows the torque (`ballcvt.clamping`); by default the
        problem's constant ``clamp_force``.

    Returns
    -------
    float

    Raises
    ------
    NoEquilibriumError
        If no admissible equilibrium exists even at zero output torque.
    """
    torque = float(limit_torque_batch(problem, creep_limit, options, rtol, law=law))
    if not np.isnan(torque):
        return torque
    zero = replace(problem, output_torque=np.asarray(0.0))
    if _follows_torque(law):
        zero, best = solve_clamped(zero, law, lambda p, x: solve_point(p, options, x))
        if float(zero.clamp_force) > float(pressure_bound_force(zero, zero.design.max_pressure)):
            raise NoEquilibriumError(
                f"no admissible equilibrium even at zero output torque: the {law.name} law's "
                f"clamping force {float(zero.clamp_force):.4g} N already exceeds the pressure "
                f"limit max_pressure = {zero.design.max_pressure:g} Pa")
    else:
        best = solve_point(zero, options)
    where = (f"ratio {float(problem.ratio):g}, clamp_force {float(problem.clamp_force):g} N, "
             f"input speed {float(problem.input_speed):g} rad/s")
    if best.converged:
        why = (f"its creep {float(np.max(np.abs(best.state.creep))):.3g} already exceeds "
               f"creep_limit {creep_limit:g}: the drive's own spin and bearing drag use up "
               "its traction")
    else:
        why = ("the traction this clamping force can transmit at this speed does not carry "
               f"the drive's own drag; raise clamp_force ({best.message})")
    raise NoEquilibriumError(f"no admissible equilibrium even at zero output torque "
                             f"({where}): {why}")


@dataclass(frozen=True)
class Admissibility:
    """Outcome of `solve_admissible`; arrays have the batch shape ``(n,)``.

    Attributes
    ----------
    problem : EquilibriumProblem
        The points at the forces their clamping law set.
    ok : ndarray of bool
        Converged with every ``|C| <= creep_limit`` (and, under a torque-following law,
        every peak pressure within ``design.max_pressure``).
    converged : ndarray of bool
        The equilibrium (and clamping equation) converged.
    creep : ndarray
        Final creeps, ``(n, n_c)``.
    """

    problem: EquilibriumProblem
    ok: np.ndarray
    converged: np.ndarray
    creep: np.ndarray


def solve_admissible(problem: EquilibriumProblem, creep_limit: float,
                     options: SolverOptions = SolverOptions(), law=None,
                     x0=None) -> Admissibility:
    """Solve a 1-D batch and say which points lie within the traction capacity.

    Newton alone first; the point solver only for the points whose Newton run failed
    without its creeps running past the limit (a failure of the method, not of the
    equilibrium). A point whose Newton run fails with its creeps beyond the limit is
    beyond the capacity at once. This is the admissibility test of the limiting torque
    (docs/model.md §8, §11), so a point is admissible exactly when its torque is at most
    the limit.

    Parameters
    ----------
    problem : EquilibriumProblem
        Operating points, 1-D batch.
    creep_limit : float
        ``C_lim`` [-].
    options : SolverOptions
        Solver options.
    law : clamping law, optional
        A torque-following law (`ballcvt.clamping`); by default the problem's forces.
    x0 : array_like, optional
        Starting creeps ``(n, n_c)``.

    Returns
    -------
    Admissibility
    """
    law = law if _follows_torque(law) else None
    if law is not None:
        def solve(pb, x, fallback):
            return solve_clamped(pb, law, lambda p, y: solve_batch(p, options, y, fallback), x)
    else:
        def solve(pb, x, fallback):
            return pb, solve_batch(pb, options, x, fallback=fallback)
    pb, sol = solve(problem, x0, False)
    big = np.max(np.abs(sol.state.creep), axis=-1)
    conv, creep = sol.converged.copy(), sol.state.creep.copy()
    unsure = np.flatnonzero(~conv & ~(big > creep_limit))
    if unsure.size:
        _, again = solve(pb.take(unsure), None if x0 is None else np.asarray(x0)[unsure], True)
        conv[unsure], creep[unsure] = again.converged, again.state.creep
    ok = conv & (np.max(np.abs(creep), axis=-1) <= creep_limit)
    if law is not None:
        ok &= pb.clamp_force <= pressure_bound_force(pb, pb.design.max_pressure) * (1 + 1e-12)
    return Admissibility(pb, ok, conv, creep)


def _follows_torque(law) -> bool:
    """Whether ``law`` sets a torque-dependent force (else the problem's force is used)."""
    return law is not None and getattr(law, "name", "constant") != "constant"


def limit_torque_batch(problem: EquilibriumProblem, creep_limit: float,
                       options: SolverOptions = SolverOptions(), rtol: float = LIMIT_RTOL,
                       callback=None, law=None) -> np.ndarray:
    """Limiting output torque of every point of a batch (its ``output_torque`` is ignored).

    The same bisection as `limit_torque`, run on all points at once with the batched
    Newton solver, each trial started from the point's last admissible creeps. A trial
    counts as admissible only if it converges with every ``|C| <= creep_limit``. A trial
    whose Newton run fails with its creeps beyond the limit counts as beyond it at once
    (the common case above the limit, kept cheap); one that fails with its creeps within
    the limit goes to the point solver, as in `limit_torque`.

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
    law : clamping law, optional
        A law whose force follows the torque (`ballcvt.clamping`). Its force grows with
        the torque, so the capacity is also bounded by the peak pressure: a trial counts as
        admissible only if its force keeps every contact at or below
        ``design.max_pressure`` (docs/model.md §11). By default the problem's constant
        ``clamp_force``.

    Returns
    -------
    ndarray
        Limiting torques [N m], shape ``(...)``; NaN where even ``T_2 = 0`` is inadmissible.
    """
    flat = problem.flat()
    law = law if _follows_torque(law) else None
    if law is not None:
        f_cap = pressure_bound_force(flat, flat.design.max_pressure)
        hi = np.minimum(law.output_torque_bound(flat.design, f_cap, flat.ratio),
                        traction_ceiling_torque(with_clamp(flat, f_cap)))
    else:
        hi = traction_ceiling_torque(flat)

    def admissible(index, torque, x0):
        got = solve_admissible(replace(flat.take(index), output_torque=torque), creep_limit,
                               options, law, x0)
        return got.ok, got.creep

    ok0, best = admissible(np.arange(flat.size), np.zeros(flat.size), None)
    lo = np.zeros(flat.size)
    # bisect until every bracket is narrow: a loose ceiling (extreme designs) needs more
    # than the bisection_steps() of a typical one
    steps = bisection_steps(rtol)
    for step in range(MAX_BISECTIONS):
        active = np.flatnonzero(ok0 & ((step < steps) | (hi - lo > rtol * hi)))
        if active.size == 0:
            break
        mid = 0.5 * (lo[active] + hi[active])
        ok, x = admissible(active, mid, best[active])
        lo[active] = np.where(ok, mid, lo[active])
        hi[active] = np.where(ok, hi[active], mid)
        best[active] = np.where(ok[:, None], x, best[active])
        if callback is not None and step < steps:
            callback()
    return np.where(ok0, lo, np.nan).reshape(problem.shape)
