"""Optimal clamping force: the paper's Fig. 8 remark as a feature.

For a ratio and output torque, find the clamping force ``F_N0`` that maximises the overall
efficiency subject to every ``|C| <= C_lim`` (traction capacity) and every Hertz peak
pressure ``<= p_lim`` (``design.max_pressure``).

Method. The peak pressure grows as ``F_N0^(1/3)`` (Hertz), so the pressure limit is an
upper bound ``F_p`` in closed form. The efficiency is evaluated on a geometric grid of
clamping forces up to ``F_p`` in one batched solve; the lowest feasible force ``F_c`` (creep
limit) is located by bisection between the last infeasible and the first feasible grid
point; the maximum is then refined by bounded Brent search (`scipy.optimize
.minimize_scalar`) on the feasible bracket around the best grid point.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..equilibrium.problem import build_problem
from ..errors import InputError, TractionLimitError
from ..params.models import Design, Fluid
from ..performance.efficiency import efficiency
from .newton import solve_batch
from .options import SolverOptions

__all__ = ["ClampOptimum", "optimal_clamp_force"]


@dataclass(frozen=True)
class ClampOptimum:
    """Result of `optimal_clamp_force`.

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


def optimal_clamp_force(
    design: Design,
    fluid: Fluid,
    architecture: str,
    ratio: float,
    output_torque: float,
    input_speed: float,
    options: SolverOptions = SolverOptions(),
    creep_limit: float | None = None,
    max_pressure: float | None = None,
    min_force: float = 100.0,
    grid: int = 24,
    xtol: float = 1.0,
) -> ClampOptimum:
    """Clamping force of maximum efficiency under the creep and pressure limits.

    Parameters
    ----------
    design, fluid : Design, Fluid
        Parameter sets.
    architecture : {"double", "single"}
        Idler architecture.
    ratio : float
        Ideal speed ratio [-].
    output_torque : float
        Output torque ``T_2`` > 0 [N m].
    input_speed : float
        Input speed [rad/s].
    options : SolverOptions
        Solver options.
    creep_limit : float, optional
        ``C_lim`` [-]; ``design.creep_limit`` by default.
    max_pressure : float, optional
        ``p_lim`` [Pa]; ``design.max_pressure`` by default.
    min_force : float
        Smallest clamping force searched [N].
    grid : int
        Clamping forces on the initial geometric grid.
    xtol : float
        Absolute tolerance on the optimal force [N].

    Returns
    -------
    ClampOptimum

    Raises
    ------
    InputError
        Non-positive torque or limits.
    TractionLimitError
        If no clamping force up to the pressure bound carries the torque.
    """
    c_lim = design.creep_limit if creep_limit is None else float(creep_limit)
    p_lim = design.max_pressure if max_pressure is None else float(max_pressure)
    if not output_torque > 0:
        raise InputError("output_torque", output_torque, "> 0 N m")
    if not 0 < c_lim < 1:
        raise InputError("creep_limit", c_lim, "0 < creep_limit < 1")
    if not p_lim > 0:
        raise InputError("max_pressure", p_lim, "> 0 Pa")

    def evaluate(forces, x0=None):
        forces = np.atleast_1d(np.asarray(forces, dtype=float))
        pb = build_problem(design, fluid, architecture, ratio, output_torque, forces, input_speed)
        sol = solve_batch(pb, options, x0)
        eta = efficiency(pb, sol.state).overall
        creep = np.max(np.abs(sol.state.creep), axis=-1)
        ok = sol.converged & (creep <= c_lim)
        return np.where(ok, eta, -np.inf), creep, np.max(pb.p_max, axis=-1), sol.state.creep

    # Pressure bound: p_max ~ F^(1/3) for every contact (loads proportional to F_N0).
    ref = build_problem(design, fluid, architecture, ratio, 0.0, 1000.0, input_speed)
    f_p = 1000.0 * (p_lim / float(np.max(ref.p_max))) ** 3
    if f_p <= min_force:
        raise InputError(
            "max_pressure",
            p_lim,
            f"a value reached above min_force = "
            f"{min_force:g} N (p_max at {min_force:g} N is "
            f"{np.max(ref.p_max) * (min_force / 1000.0) ** (1 / 3):.3g} Pa)",
        )
    forces = np.geomspace(min_force, f_p, grid)
    eta, *_ = evaluate(forces)
    feasible = np.isfinite(eta)
    if not feasible.any():
        raise TractionLimitError(
            float(output_torque),
            float("nan"),
            f" at ratio {ratio:g} for any clamping force up to the pressure limit ({f_p:.0f} N)",
        )
    first = int(np.argmax(feasible))
    f_c = forces[first]
    if first > 0:  # creep bound by bisection
        lo, hi = forces[first - 1], forces[first]
        while hi - lo > xtol:
            mid = 0.5 * (lo + hi)
            if np.isfinite(evaluate(mid)[0][0]):
                hi = mid
            else:
                lo = mid
        f_c = hi
    best = int(np.nanargmax(np.where(feasible, eta, -np.inf)))
    a = max(f_c, forces[max(best - 1, 0)])
    b = forces[min(best + 1, grid - 1)]
    if b - a > xtol:
        from scipy.optimize import minimize_scalar  # loaded when needed (0.4 s import)

        res = minimize_scalar(
            lambda f: -evaluate(f)[0][0], bounds=(a, b), method="bounded", options={"xatol": xtol}
        )
        f_opt = float(res.x)
    else:
        f_opt = float(a)
    candidates = np.array([f_opt, f_c, forces[best]])
    etas, creep, pmax, _ = evaluate(candidates)
    k = int(np.argmax(etas))
    f_opt = float(candidates[k])
    active = (
        "creep"
        if abs(f_opt - f_c) <= 2 * xtol and first > 0
        else "pressure"
        if abs(f_opt - f_p) <= 2 * xtol
        else "none"
    )
    return ClampOptimum(
        clamp_force=f_opt,
        eta=float(etas[k]),
        max_creep=float(creep[k]),
        max_pressure=float(pmax[k]),
        bounds=(float(f_c), float(f_p)),
        active=active,
    )
