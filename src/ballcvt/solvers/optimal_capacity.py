"""The optimal clamping law's traction capacity (docs/model.md §11).

The optimiser may pick any clamping force from ``min_force`` up to the force of the
pressure limit ``F_p``, so its capacity is the largest limiting torque over that range.
The limiting torque rises with the force while the traction carries the torque, but not
without end: at very large forces the spin and the rolling losses grow faster, and near
the Roelands viscosity limit (the bound of ``F_p`` when ``max_pressure`` is ``inf``) the
equilibrium no longer exists, so the limit may peak below ``F_p`` (an isothermal drive
whose spin losses grow with the force: harden task 2026:4546 peaks at 68 kN, ``F_p`` 97
kN). Where the limit is still rising at ``F_p`` (larger there than at ``F_p (1 -
EDGE)``), ``F_p`` is the answer (`_rising_at_top`; since session 25). Elsewhere the search
is bounded and deterministic: the limiting torques at `GRID` forces in
geometric progression from ``min_force`` to ``F_p`` and one more at ``F_p (1 - EDGE)``,
then `ZOOM` rounds of `ZOOM_GRID` forces between the neighbours of the best one (each
round narrows the bracket fourfold: the force to some 1e-3 of itself, the torque, flat at
its maximum, to about 1e-7). Where the best is ``F_p`` (the limit still rising there) it is
kept exactly, except under a traction law with more than one equilibrium (the thermal
law): there the limit, the fold of the branch from zero torque, can peak and fall again
below ``F_p`` (past the peak of the traction curves), and was noisy near it (a
continuation step failing at the solver's tolerance ended the branch early), so the best
force is refined, ``F_p`` staying a candidate, and the force must not depend on the batch
(a table and `limit_torque` gave 30.8 and 233 N m on task 2026:124). The points are
searched in one batch with every point's Newton iterates its own to the bit
(``SolverOptions.split_min`` 1, no predictor stage: the kernels with and without the
derivatives round apart in the last bit, and which one evaluated a point near its solution
depended on its batch); each was searched alone before session 37, a fifth of Table I's
thermal optimal sweep. Under the torque condition on ``T_2`` the fold is the walk's along the
branch and the climb's in a held creep, smooth in the force (to 1e-8 whatever the batch,
`ballcvt.model.traction.base.THERMAL_RESIDUAL_FLOOR`), and a limit still rising at
``F_p`` by more than `RISE` of itself keeps ``F_p`` there too (since session 30: Table
I's thermal optimal sweep scanned and refined ``F_p`` in 63 more limit searches per curve
and kept it every time).
"""

from __future__ import annotations

import sys
from dataclasses import replace

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..errors import InputError
from ..model.traction.base import has_multiple_equilibria
from .branch_path import walks
from .clamped import pressure_bound_force, with_clamp
from .limit import LimitSearch, limit_search
from .options import SolverOptions

__all__ = [
    "capacity_basis",
    "capacity_search",
    "capacity_force",
    "force_range_top",
    "EDGE",
    "GRID",
    "ZOOM",
    "ZOOM_GRID",
    "RISE",
]

#: Forces of the first scan, from ``min_force`` to ``F_p`` (one more at ``F_p (1 - EDGE)``).
GRID = 9
#: Relative step below ``F_p`` [-] of the scan's last force but one: where the limit there
#: is the larger, it falls towards ``F_p`` and its peak below is refined.
EDGE = 1e-3
#: Refinement rounds around the best force.
ZOOM = 6
#: Forces of each refinement round (between the best force's neighbours).
ZOOM_GRID = 9
#: Relative rise of the limit [-] from ``F_p (1 - EDGE)`` to ``F_p`` above which a law with
#: more than one equilibrium keeps ``F_p`` (module docstring): a hundred times the fold's
#: noise across batches (1e-8), under a hundredth of the rise where the limit still climbs
#: with the force (6e-4 to 8e-4 on Table I's thermal drive at 2000 rpm).
RISE = 1e-6


def force_range_top(problem: EquilibriumProblem, p_lim: float, min_force: float) -> np.ndarray:
    """The top ``F_p`` [N] of the optimiser's force range ``[min_force, F_p]`` at every point.

    ``F_p`` is the force whose peak Hertz pressure reaches ``p_lim`` (`pressure_bound_force`,
    Eqs. 48-50: ``p_max ~ F^(1/3)``). Every path of the optimal law (its solve, the limiting
    torque, a map, a table, a sweep, a cycle) refuses a point whose range is empty alike.

    Raises
    ------
    InputError
        ``max_pressure``, where ``F_p <= min_force`` (the peak pressure at ``min_force``
        already exceeds ``p_lim``), naming that pressure and what to change.
    """
    top = np.broadcast_to(pressure_bound_force(problem, p_lim), problem.shape)
    empty = ~(top > min_force)
    if np.any(empty):
        k = np.unravel_index(int(np.argmax(empty)), problem.shape)
        p_max = np.broadcast_to(np.max(problem.p_max, axis=-1), problem.shape)[k]
        force = np.broadcast_to(problem.clamp_force, problem.shape)[k]
        p_at_min = float(p_max * (min_force / force) ** (1.0 / 3.0))
        ratio = float(np.broadcast_to(problem.ratio, problem.shape)[k])
        raise InputError(
            "max_pressure",
            p_lim,
            f"> {p_at_min:.3g} Pa, the peak pressure at the optimal law's min_force = "
            f"{min_force:g} N (ratio {ratio:g}): raise max_pressure or lower min_force",
        )
    return np.array(top, dtype=float)


def _searches(flat: EquilibriumProblem, forces: np.ndarray, c_lim: float, options) -> LimitSearch:
    """The limit search of each point at each of its ``forces`` ``(n, k)`` [N]: one batch
    of ``n k`` rows in C order (`ballcvt.solvers.limit.limit_search`)."""
    n, k = forces.shape
    rows = np.repeat(np.arange(n), k)
    return limit_search(with_clamp(flat.take(rows), forces.ravel()), c_lim, options)


def _limits(flat: EquilibriumProblem, forces: np.ndarray, c_lim: float, options) -> np.ndarray:
    """Limiting torques ``(n, k)`` [N m] of each point at each of its ``forces``, ``-inf``
    where there is none."""
    got = _searches(flat, forces, c_lim, options).torque
    return np.where(np.isfinite(got), got, -np.inf).reshape(forces.shape)


def capacity_force(
    problem: EquilibriumProblem, p_lim: float, creep_limit: float, floor: float, options
) -> np.ndarray:
    """The clamping force [N] of the largest limiting torque within ``[floor, F_p]``.

    Parameters
    ----------
    problem : EquilibriumProblem
        Operating points (any batch shape; torque and force ignored).
    p_lim : float
        Pressure limit [Pa] (``inf``: the Roelands limit bounds the force).
    creep_limit : float
        ``C_lim`` [-].
    floor : float
        Least force [N] (the law's ``min_force``).
    options : SolverOptions
        Solver options.

    Returns
    -------
    ndarray
        Forces [N], the batch shape of ``problem``; ``F_p`` where no force has a limit.
    """
    return _capacity(problem, p_lim, creep_limit, floor, options)[0]


def _capacity(problem, p_lim, creep_limit, floor, options):
    """`capacity_force`, and the limit search of the flattened points at those forces
    when every one is ``F_p`` with its limit still rising there (`_rising_at_top`'s
    own), else None."""
    flat = problem.flat()
    top = force_range_top(problem, p_lim, floor).reshape(-1)
    if has_multiple_equilibria(problem.fluid):  # the same force whatever the batch
        options = replace(options, split_min=1, predictor_min_points=sys.maxsize)
    out, at_top = _search(flat, top, floor, creep_limit, options)
    return out.reshape(problem.shape), at_top


def _search(flat, top: np.ndarray, floor: float, creep_limit: float, options):
    """`capacity_force` of the 1-D batch ``flat`` (forces ``(n,)`` [N]): ``F_p`` where the
    limit still rises there (`_rising_at_top`), else the scan and its refinement; and
    the limit search at ``F_p`` where every point's limit rises there (else None)."""
    multiple = has_multiple_equilibria(flat.fluid)
    if multiple and not walks(flat):
        return _scan(flat, top, floor, creep_limit, options), None
    out = top.copy()
    rising, at_top = _rising_at_top(flat, top, creep_limit, options, RISE if multiple else 0.0)
    rest = np.flatnonzero(~rising)
    if rest.size:
        out[rest] = _scan(flat.take(rest), top[rest], floor, creep_limit, options)
        at_top = None
    return out, at_top


def _rising_at_top(flat, top: np.ndarray, creep_limit: float, options, rise: float = 0.0):
    """Whether each point's limiting torque is larger at ``F_p`` than at ``F_p (1 -
    EDGE)`` (by more than ``rise`` of itself [-]): it rises with the force up to its peak
    and falls beyond (module docstring), so a limit still rising at ``F_p`` is largest
    there, and the scan below it would find nothing larger (since session 25: two limits
    instead of ten where the drive is traction-limited up to the pressure bound, the case
    of the built-in drives). Not used under a law with more than one equilibrium where
    the fold is not the walk's (a planetary mode's torque condition), whose limit is noisy
    near its peak. Also returns the limit search at ``F_p`` (`LimitSearch`, one batch with
    the other force's), which a capacity at ``F_p`` reuses (`capacity_search`)."""
    n = flat.size
    got = _searches(flat, np.column_stack([top * (1.0 - EDGE), top]), creep_limit, options)
    lim = np.where(np.isfinite(got.torque), got.torque, -np.inf).reshape(n, 2)
    rising = np.isfinite(lim[:, 1]) & (lim[:, 1] > lim[:, 0] * (1.0 + rise))
    return rising, got.take(np.arange(1, 2 * n, 2))


def _scan(flat, top: np.ndarray, floor: float, creep_limit: float, options) -> np.ndarray:
    """The force of the largest limit among `GRID` forces and ``F_p (1 - EDGE)`` and
    ``F_p``, refined (`_zoom`) where it lies below ``F_p`` (always under a law with more
    than one equilibrium)."""
    low = np.full(top.shape, float(floor))
    share = np.append(np.linspace(0.0, 1.0, GRID), 1.0)
    forces = np.exp(np.log(low)[:, None] + np.log(top / low)[:, None] * share)
    forces[:, -2] = top * (1.0 - EDGE)  # is the limit still rising at F_p?
    forces[:, -1] = top
    lim = _limits(flat, forces, creep_limit, options)
    best = np.argmax(lim, axis=1)
    zoom = best < GRID  # the best force is below F_p: refine it
    if has_multiple_equilibria(flat.fluid):  # the limit may peak and fall, noisily
        zoom[:] = True
    inner = np.flatnonzero(zoom & np.isfinite(lim.max(axis=1)))
    out = top.copy()
    if inner.size:
        out[inner] = _zoom(flat.take(inner), forces[inner], best[inner], creep_limit, options)
    return out


def _zoom(flat, forces, best, creep_limit: float, options) -> np.ndarray:
    """Refine the best force of each row of ``forces`` ``(n, k)`` (ascending) between its
    neighbours: `ZOOM` rounds of `ZOOM_GRID` forces in geometric progression across the
    bracket, the one nearest the best so far replaced by it (it stays a candidate, the
    row ascending), the bracket then the neighbours of the round's best."""
    rows = np.arange(forces.shape[0])
    a = forces[rows, np.maximum(best - 1, 0)]
    b = forces[rows, np.minimum(best + 1, forces.shape[1] - 1)]
    f_best = forces[rows, best]
    share = np.linspace(0.0, 1.0, ZOOM_GRID)
    for _ in range(ZOOM):
        trial = np.exp(np.log(a)[:, None] + np.log(b / a)[:, None] * share)
        near = np.argmin(np.abs(np.log(trial / f_best[:, None])), axis=1)
        trial[rows, near] = f_best
        lim = _limits(flat, trial, creep_limit, options)
        k = np.argmax(lim, axis=1)
        f_best = trial[rows, k]
        a = trial[rows, np.maximum(k - 1, 0)]
        b = trial[rows, np.minimum(k + 1, ZOOM_GRID - 1)]
    return f_best


def capacity_basis(problem: EquilibriumProblem, law, creep_limit: float, options=SolverOptions()):
    """What the limiting torque under ``law`` is searched on: ``(problem, law, creep_limit)``.

    Under ``optimal`` the optimiser may pick any force from ``min_force`` up to the
    pressure bound, so its capacity is that of the constant law at the force of the
    largest limiting torque within the law's (or the design's) ``max_pressure``
    (`capacity_force`), with the law's own ``creep_limit`` if it has one (docs/model.md
    §11). Any other law is returned unchanged.
    """
    return capacity_search(problem, law, creep_limit, options)[:3]


def capacity_search(
    problem: EquilibriumProblem, law, creep_limit: float, options=SolverOptions()
) -> tuple:
    """`capacity_basis`, and the limit search of its ``problem`` (flattened,
    `ballcvt.solvers.limit.LimitSearch`) where the search for the force already made it:
    under ``optimal``, where every point's limit still rises at ``F_p`` (the limits at
    ``F_p`` decided that); None otherwise (then search it, `limit_search`). Returns
    ``(problem, law, creep_limit, search or None)``."""
    if law is None or not law.optimises:
        return problem, law, creep_limit, None
    p_lim = problem.design.max_pressure if law.max_pressure is None else law.max_pressure
    c_lim = creep_limit if law.creep_limit is None else law.creep_limit
    force, search = _capacity(problem, p_lim, c_lim, law.min_force, options)
    return with_clamp(problem, force), None, c_lim, search
