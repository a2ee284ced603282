"""The one-point search of the optimal clamping force (docs/model.md §11).

For a ratio and output torque, find the clamping force ``F_N0`` that maximises the overall
efficiency subject to every ``|C| <= C_lim`` (traction capacity) and every Hertz peak
pressure ``<= p_lim`` (``design.max_pressure``).

Method. The peak pressure grows as ``F_N0^(1/3)`` (Hertz), so the pressure limit is an
upper bound ``F_p`` in closed form. The efficiency is evaluated on a geometric grid of
clamping forces up to ``F_p`` in one batched solve; the lowest feasible force ``F_c`` (creep
limit) is located by bisection between the last infeasible and the first feasible grid
point; the maximum is then refined by bounded Brent search (`scipy.optimize
.minimize_scalar`) on the feasible bracket around the best grid point, or taken from the
batched search (`ballcvt.solvers.optimal_batch`) when it found it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..equilibrium.problem import build_problem
from ..errors import InputError, TractionLimitError
from ..model.clamping import OptimalClamp
from ..params.models import Design, Fluid
from ..performance.efficiency import efficiency
from .newton import solve_batch
from .optimal_capacity import capacity_force, force_range_top
from .options import SolverOptions
from .refusal import CREEP_RTOL

__all__ = ["ClampCase", "ClampOptimum", "search_optimum", "SEARCH_SETTINGS"]


@dataclass(frozen=True)
class ClampOptimum:
    """Result of `ballcvt.solvers.optimal_clamp.clamp_optimum`.

    Attributes
    ----------
    clamp_force : float
        Optimal ``F_N0`` [N].
    eta : float
        Overall efficiency there [-].
    max_creep : float
        Largest ``|C|`` there [-].
    max_pressure : float
        Largest Hertz peak pressure there [Pa].
    bounds : tuple of float
        Feasible clamping-force range ``(F_c, F_p)`` found [N].
    active : str
        ``"creep"``, ``"pressure"`` or ``"none"``: the constraint the optimum sits on.
    """

    clamp_force: float
    eta: float
    max_creep: float
    max_pressure: float
    bounds: tuple[float, float]
    active: str


@dataclass(frozen=True)
class ClampCase:
    """One operating point whose clamping force is sought.

    Attributes
    ----------
    design, fluid : Design, Fluid
        Parameter sets.
    architecture : str
        Idler architecture (``"double"``, ``"single"``).
    ratio : float
        Ideal speed ratio [-].
    output_torque : float
        Output torque ``T_2`` > 0 [N m].
    input_speed : float
        Input speed [rad/s].
    """

    design: Design
    fluid: Fluid
    architecture: str
    ratio: float
    output_torque: float
    input_speed: float


#: The fields of `OptimalClamp` that set the search (the deprecated positional order).
SEARCH_SETTINGS = ("creep_limit", "max_pressure", "min_force", "grid", "xtol")

#: Largest ratio of the search grid's ceiling to its floor [-]: a wider feasible range is
#: searched a span at a time, the ceiling growing by this factor while the best grid point
#: is the top one (or none is feasible), up to the pressure bound. Without a pressure limit
#: (``max_pressure = inf``) the efficiency, falling at large forces, places the optimum.
_SPAN = 1e3


def _limits(case: ClampCase, law: OptimalClamp) -> tuple[float, float]:
    """``(C_lim [-], p_lim [Pa])`` of the search, checked with the torque."""
    c_lim = case.design.creep_limit if law.creep_limit is None else float(law.creep_limit)
    p_lim = case.design.max_pressure if law.max_pressure is None else float(law.max_pressure)
    if not case.output_torque >= 0:
        raise InputError("output_torque", case.output_torque, ">= 0 N m")
    if not 0 < c_lim < 1:
        raise InputError("creep_limit", c_lim, "0 < creep_limit < 1")
    if not p_lim > 0:
        raise InputError("max_pressure", p_lim, "> 0 Pa (inf for no pressure limit)")
    return c_lim, p_lim


@dataclass(frozen=True)
class _Search:
    """Solves the case at given clamping forces (one batched solve per call)."""

    case: ClampCase
    c_lim: float
    options: SolverOptions

    def __call__(self, forces) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(score, max |C| [-], max p_max [Pa])`` at ``forces`` [N]: the score is the
        overall efficiency (Eq. 38) where the point converges within the creep limit,
        ``-inf`` elsewhere."""
        c = self.case
        forces = np.atleast_1d(np.asarray(forces, dtype=float))
        pb = build_problem(
            c.design, c.fluid, c.architecture, c.ratio, c.output_torque, forces, c.input_speed
        )
        sol = solve_batch(pb, self.options)
        creep = np.max(np.abs(sol.state.creep), axis=-1)
        # the margin of a solved point on the creep limit (a limiting torque is pinned
        # there to the solver's tolerance): the force carrying the limit stays feasible
        ok = sol.converged & (creep <= self.c_lim * (1.0 + CREEP_RTOL))
        eta = efficiency(pb, sol.state).overall
        return np.where(ok, eta, -np.inf), creep, np.max(pb.p_max, axis=-1)

    def feasible(self, force: float) -> bool:
        """Whether ``force`` [N] carries the torque within the creep limit."""
        return bool(np.isfinite(self(force)[0][0]))


def _grid(search: _Search, f_p: float, law: OptimalClamp) -> tuple[np.ndarray, np.ndarray]:
    """The geometric grid of forces from ``min_force`` up to at most ``F_p`` [N] and its
    scores: its ceiling is ``min(F_p, _SPAN min_force)``, raised by `_SPAN` (up to ``F_p``)
    while the best grid point is the top one, or none is feasible and the creep still
    falls with the force."""
    top = min(f_p, law.min_force * _SPAN)
    while True:
        forces = np.geomspace(law.min_force, top, law.grid)
        eta, creep, _ = search(forces)
        if np.isfinite(eta).any():
            at_top = int(np.argmax(eta)) == law.grid - 1
        else:
            at_top = bool(creep[-1] < creep[-2])
        if top >= f_p or not at_top:
            return forces, eta
        top = min(f_p, top * _SPAN)


def _creep_bound(search: _Search, forces: np.ndarray, first: int, xtol: float) -> float:
    """Lowest feasible force ``F_c`` [N]: by bisection between the last infeasible and the
    first feasible grid point (``forces[first]``)."""
    if first == 0:
        return float(forces[0])
    lo, hi = forces[first - 1], forces[first]
    while hi - lo > xtol:
        mid = 0.5 * (lo + hi)
        if search.feasible(mid):
            hi = mid
        else:
            lo = mid
    return float(hi)


def _refine(search: _Search, forces: np.ndarray, eta: np.ndarray, f_c: float, xtol: float):
    """The efficiency maximum [N] by bounded Brent search around the best grid point."""
    best = int(np.argmax(eta))
    a = max(f_c, forces[max(best - 1, 0)])
    b = forces[min(best + 1, forces.size - 1)]
    if b - a <= xtol:
        return float(a)
    from scipy.optimize import minimize_scalar  # loaded when needed (0.4 s import)

    def loss(force):  # a force whose point fails scores below every efficiency (>= 0)
        eta = search(force)[0][0]
        return -eta if np.isfinite(eta) else 1.0

    res = minimize_scalar(loss, bounds=(a, b), method="bounded", options={"xatol": xtol})
    return float(res.x)


def _capacity_candidate(search: _Search, ref, limits) -> tuple[np.ndarray, np.ndarray]:
    """The force of the largest limiting torque (`capacity_force`, at ``limits`` =
    ``(p_lim [Pa], min_force [N])``) and its score: near the capacity the one force that
    carries the torque may fall between the grid's points."""
    force = capacity_force(ref, limits[0], search.c_lim, limits[1], search.options)
    forces = np.atleast_1d(np.asarray(force, dtype=float))
    return forces, search(forces)[0]


def search_optimum(
    case: ClampCase,
    law: OptimalClamp = OptimalClamp(),
    options: SolverOptions = SolverOptions(),
    found: float | None = None,
) -> ClampOptimum:
    """Clamping force of maximum efficiency under the creep and pressure limits, searched
    for one point: a grid of forces, the creep-limit force by bisection, the maximum by
    Brent's search (or ``found``).

    ``case``, ``law`` and ``options``, the result and the errors are those of
    `ballcvt.solvers.optimal_clamp.clamp_optimum`, which calls it (and the batched
    search's reference and fallback, `ballcvt.solvers.optimal_batch`).

    Parameters
    ----------
    found : float, optional
        The optimum [N] found by the batched search (`ballcvt.solvers.optimal_batch`):
        taken for the Brent search's.
    """
    c_lim, p_lim = _limits(case, law)
    search = _Search(case, c_lim, options)
    # Pressure bound: p_max ~ F^(1/3) for every contact (loads proportional to F_N0).
    ref = build_problem(
        case.design, case.fluid, case.architecture, case.ratio, 0.0, 1000.0, case.input_speed
    )
    f_p = float(force_range_top(ref, p_lim, law.min_force))  # refused where empty
    forces, eta = _grid(search, f_p, law)
    if not np.isfinite(eta).any():  # at the capacity only its own force may carry it
        forces, eta = _capacity_candidate(search, ref, (p_lim, law.min_force))
    feasible = np.isfinite(eta)
    if not feasible.any():
        raise TractionLimitError(
            float(case.output_torque),
            float("nan"),
            f" at ratio {case.ratio:g} for any clamping force up to the pressure limit "
            f"({forces[-1]:.0f} N)",
        )
    first = int(np.argmax(feasible))
    f_c = _creep_bound(search, forces, first, law.xtol)
    if case.output_torque == 0:
        candidates = np.array([f_c])
    else:
        best = float(forces[int(np.argmax(eta))])
        top = _refine(search, forces, eta, f_c, law.xtol) if found is None else found
        candidates = np.array([top, f_c, best])
    etas, creep, pmax = search(candidates)
    k = int(np.argmax(etas))
    f_opt = float(candidates[k])
    active = (
        "creep"
        if abs(f_opt - f_c) <= 2 * law.xtol and first > 0
        else "pressure"
        if abs(f_opt - f_p) <= 2 * law.xtol
        else "none"
    )
    return ClampOptimum(
        clamp_force=f_opt,
        eta=float(etas[k]),
        max_creep=float(creep[k]),
        max_pressure=float(pmax[k]),
        bounds=(float(f_c), float(forces[-1])),
        active=active,
    )
