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

from dataclasses import dataclass, fields

import numpy as np

from .._compat import warn_renamed
from ..equilibrium.problem import build_problem
from ..errors import InputError, TractionLimitError
from ..model.clamping import OptimalClamp
from ..params.models import Design, Fluid
from ..performance.efficiency import efficiency
from .newton import solve_batch
from .options import SolverOptions

__all__ = ["ClampCase", "ClampOptimum", "clamp_optimum", "optimal_clamp_force"]


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


def optimal_clamp_force(*args, **kwargs) -> ClampOptimum:
    """Deprecated: ``optimal_clamp_force(design, fluid, architecture, ratio, output_torque,
    input_speed, options, creep_limit, max_pressure, min_force, grid, xtol)`` is
    `clamp_optimum` of a `ClampCase`, the limits and settings in an `OptimalClamp`."""
    warn_renamed(
        "optimal_clamp_force(design, fluid, ...)",
        "clamp_optimum(ClampCase(design, fluid, ...), OptimalClamp(...), options)",
    )
    names = tuple(f.name for f in fields(ClampCase)) + ("options",) + _SEARCH
    kw = {**dict(zip(names, args)), **kwargs}
    case = ClampCase(*(kw.pop(f.name) for f in fields(ClampCase)))
    options = kw.pop("options", SolverOptions())
    return clamp_optimum(case, OptimalClamp(**kw), options)


_SEARCH = ("creep_limit", "max_pressure", "min_force", "grid", "xtol")


def _limits(case: ClampCase, law: OptimalClamp) -> tuple[float, float]:
    """``(C_lim [-], p_lim [Pa])`` of the search, checked with the torque."""
    c_lim = case.design.creep_limit if law.creep_limit is None else float(law.creep_limit)
    p_lim = case.design.max_pressure if law.max_pressure is None else float(law.max_pressure)
    if not case.output_torque > 0:
        raise InputError("output_torque", case.output_torque, "> 0 N m")
    if not 0 < c_lim < 1:
        raise InputError("creep_limit", c_lim, "0 < creep_limit < 1")
    if not p_lim > 0:
        raise InputError("max_pressure", p_lim, "> 0 Pa")
    return c_lim, p_lim


def clamp_optimum(
    case: ClampCase, law: OptimalClamp = OptimalClamp(), options: SolverOptions = SolverOptions()
) -> ClampOptimum:
    """Clamping force of maximum efficiency under the creep and pressure limits.

    Parameters
    ----------
    case : ClampCase
        The operating point (design, fluid, architecture, ratio [-], output torque
        [N m], input speed [rad/s]).
    law : OptimalClamp
        The limits (``creep_limit`` [-], ``max_pressure`` [Pa]: the design's when None)
        and the search settings (``min_force`` [N], ``grid``, ``xtol`` [N]).
    options : SolverOptions
        Solver options.

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
    design, fluid, architecture = case.design, case.fluid, case.architecture
    ratio, output_torque, input_speed = case.ratio, case.output_torque, case.input_speed
    min_force, grid, xtol = law.min_force, law.grid, law.xtol
    c_lim, p_lim = _limits(case, law)

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
