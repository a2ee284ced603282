"""Equilibrium of the variator as a planetary (docs/model.md §13).

With the carrier turning, the model of §§1-12 holds in the carrier's frame: the contacts
see the speeds relative to the carrier. A mode (`ballcvt.model.modes.OperatingMode`) gives the
driver's speed and the driven member's load torque; the relative input speed then depends
on the actual ratio ``tau_R`` (creep included) through Willis' relation, and the load torque
sets the condition ``a T_0 + b T_2 = target`` that closes the last balance. The speeds are
found by a fixed point on ``tau_R`` (it depends on the speeds only through the film
thickness and the bearing drag: two or three passes), each pass a warm-started solve.

Before the passes, `coupled_creeps` solves the creeps with the ratio following them:
Newton's iteration with each point's carrier-frame problem rebuilt, before every
evaluation, at the ratio its current creeps give (`relative_ratio`: ``tau_ID (1 - C_0)(1 -
C_2)``). Where it converges, its creeps are the fixed point's (the ratio they give is the
one their problem was built at), found in one Newton run where the passes took three to
seven, each a Newton run of its own (issue 26). Its Jacobian leaves out the ratio's
dependence on the creeps (a weak one away from the capacity, the fixed point's slope some
1e-3), which Broyden's update of the last Jacobian near the solution
(`ballcvt.solvers.secant`) takes in. The passes then go on from its answer and confirm it,
in one evaluation where it converged; a point it leaves goes through the passes from its
start (a map's interpolated one, or the cold start) as before.

Where the relative input speed is negative the problem is solved mirrored: all speeds and
torques change sign together and the creeps stay (the shear stress and the bearing drags
are odd in the speeds, the centrifugal force even, the gyroscopic force odd in each of the
two speeds whose product it carries).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..equilibrium.problem import CarrierFrame, EquilibriumProblem, OperatingInputs, make_problem
from ..equilibrium.residual import balancing_output_torque
from ..errors import ConvergenceError, InputError
from ..model.architectures import contact_layout
from ..model.modes import OperatingMode, resolve_mode
from ..model.traction.base import has_multiple_equilibria
from ..params.drive import Drive
from .newton import _newton, initial_creep
from .newton_step import residual_norm
from .options import at_residual_floor
from .planetary_speeds import carrier_speed_bound, member_speeds, relative_ratio
from .point import PointSolution, SolverOptions, solve_point

__all__ = [
    "ModePoint",
    "carrier_speed_bound",
    "member_speeds",
    "relative_ratio",
    "coupled_creeps",
    "couples",
    "COUPLED_ITERATIONS",
    "COUPLED_PATIENCE",
    "ModeSolution",
    "solve_mode",
    "carrier_frame_problem",
    "ratio_tolerance",
    "ratio_settles",
    "next_ratio",
    "RatioPasses",
    "RATIO_TOL",
    "SECANT_STEPS",
    "RATIO_PER_TOL",
    "RATIO_NOISE_RTOL",
]

#: Relative tolerance of the fixed point on the actual ratio.
RATIO_TOL = 1e-13
#: The same, as a share of the solver's tolerance [-], under a traction law whose residual
#: floor raises that tolerance (`ballcvt.solvers.options.at_residual_floor`): each pass's
#: solve is then exact only to the floor, and the ratio jitters from pass to pass (harden
#: task 2029:982 under the thermal law: ~2.5e-12 relative, so 1e-13 was never met and the
#: point was refused or not by chance).
RATIO_PER_TOL = 0.1


#: Relative change of the actual ratio [-] below which a fixed point whose change stopped
#: shrinking has reached the noise floor of its solves (`ratio_settles`): under the thermal
#: law each pass's solve follows the branch from zero torque again and lands anywhere
#: within the law's residual floor, so the ratio jittered by ~1e-9 from pass to pass, ten
#: times the tolerance, and a load settled or not by chance (harden task 2706:113: a
#: capacity bisection stopped at 19.61 N m, its first bracket, where loads to 23 N m
#: settle within the creep limit). The steps of a contraction shrink every pass, so a
#: step that does not lies at that floor, far below this bound (as the clamp's
#: `ballcvt.solvers.clamped.CLAMP_NOISE_RTOL`).
RATIO_NOISE_RTOL = 1e-7


#: Change of the ratio between two passes, in tolerances of the fixed point
#: (`ratio_tolerance`), from which its slope is measured [-] (`next_ratio`): the solves'
#: noise lies within the tolerance (some 1e-9 of the ratio under the thermal law, whose
#: tolerance its floor raises), and a smaller change keeps the last slope measured. At
#: 1e5 (a change of 1e-8 of the ratio under the isothermal law) a slope measured far
#: from the fixed point, where the map is not yet linear, was kept for its last passes,
#: and they converged at a rate of 0.47 instead of at once.
SLOPE_STEPS = 1e3
#: Change of the ratio, in tolerances of the fixed point, down to which `next_ratio` takes
#: the secant step [-]; below it, at the solves' noise, the plain one, whose changes
#: `ratio_settles`' noise rule reads. A pass right after a secant step is not settled by
#: that rule (the callers pass ``last = inf``): a secant step's slope can be off, and the
#: change grow again (harden tasks 3801:445 and 3801:26826 of a campaign of the modes,
#: session 38: settled so with its ratio 2e-10 from its solve's, the power balance, Eq.
#: 38 = Eq. 39, missed its 1e-12 bound). Nor is the threshold higher: near a capacity
#: the map's slope reaches 0.98 (task 3801:13175, a disc held, 3,844 rpm), and plain
#: steps from 1e-8 did not settle in 30 passes.
SECANT_STEPS = 10.0
#: Bounds on the slope of the map ``tau -> actual ratio`` a `next_ratio` step trusts [-]:
#: at 0.9 (the clamping law's fixed point's, `ballcvt.solvers.clamped.MAX_SLOPE`) the
#: steps of task 3801:13175 (slope 0.98) converged at a rate of 0.8, thirty passes short.
SLOPE_BOUNDS = (-1.0, 0.99)


def next_ratio(tau, new, before, tol):
    """The next ratio of the fixed point ``tau <- g(tau)`` on the actual ratio (Wegstein
    1958, *Accelerating convergence of iterative processes*, Commun. ACM 1(6) 9-13):
    ``tau + (g(tau) - tau) / (1 - s)``, ``s`` the slope of ``g`` measured against the
    previous pass, clipped to `SLOPE_BOUNDS` (the plain step ``g(tau)`` at the first).

    The plain iteration converges at the rate ``|s|``; near the capacity, where the first
    pass lies far from the actual ratio, it took ten to nineteen passes to `RATIO_TOL`,
    each a batched solve of the equilibrium (a third fewer with this step, issue 26).
    Within `SECANT_STEPS` tolerances of the fixed point the step is the plain one.

    Parameters
    ----------
    tau, new : array_like
        The ratio of this pass and ``g(tau)``, the actual ratio its solve gave [-].
    before : tuple or None
        ``(tau, new, slope, secant)`` of the previous pass (this function's second
        return), or None at the first.
    tol : float
        Relative tolerance of the fixed point [-] (`ratio_tolerance`).

    Returns
    -------
    (ndarray, tuple)
        The next ratio [-], and ``(tau, new, slope, secant)`` for the next pass
        (``secant``: whether the step was the secant one).
    """
    tau, new = np.asarray(tau, dtype=float), np.asarray(new, dtype=float)
    slope = np.zeros(np.shape(tau))
    if before is not None:
        t0, n0, slope = before[:3]
        dt = tau - t0
        with np.errstate(divide="ignore", invalid="ignore"):
            measured = (new - n0) / dt
        fresh = np.isfinite(measured) & (np.abs(dt) > SLOPE_STEPS * tol * np.abs(tau))
        slope = np.where(fresh, np.clip(measured, *SLOPE_BOUNDS), slope)
    far = np.abs(new - tau) > SECANT_STEPS * tol * np.abs(tau)
    return np.where(far, tau + (new - tau) / (1.0 - slope), new), (tau, new, slope, far)


class RatioPasses:
    """The fixed point on the actual ratio over a batch of ``n`` points, pass by pass:
    its tolerance (`ratio_tolerance`), each point's last change (``inf`` before the first
    pass and after a secant step, whose pass the noise rule of `ratio_settles` must not
    settle) and the memory of `next_ratio`. Used by the batched passes of
    `ballcvt.solvers.planetary_batch.solve_mode_batch` and of the held-creep capacity
    (`ballcvt.solvers.planetary_pinned`). ``rtol``: a looser relative tolerance [-] (a
    start for another search), never a tighter one."""

    def __init__(self, n: int, options: SolverOptions, fluid, rtol: float | None = None):
        self.tol = max(ratio_tolerance(options, fluid), 0.0 if rtol is None else rtol)
        self.last = np.full(n, np.inf)
        self.memory = (
            np.full(n, np.nan),
            np.full(n, np.nan),
            np.zeros(n),
            np.zeros(n, dtype=bool),
        )

    def settles(self, tau, new, todo) -> np.ndarray:
        """`ratio_settles` of the points ``todo`` (``tau`` ``(n,)``, ``new`` their actual
        ratios)."""
        return ratio_settles(np.abs(new - tau[todo]), self.last[todo], tau[todo], self.tol)

    def step(self, tau, new, todo) -> np.ndarray:
        """`next_ratio` of the points ``todo``: their next ratios; updates the memory and
        the last changes."""
        step, seen = next_ratio(tau[todo], new, tuple(m[todo] for m in self.memory), self.tol)
        for mine, now in zip(self.memory, seen, strict=True):
            mine[todo] = now
        self.last[todo] = np.where(seen[3], np.inf, np.abs(new - tau[todo]))
        return step


def ratio_settles(change, last, tau, tol):
    """Whether the fixed point on the actual ratio has settled, from this pass's change
    ``|new - tau|`` and the last pass's ``last`` (``inf`` at the first) [-], at the
    ratio ``tau`` [-] with the tolerance ``tol`` (`ratio_tolerance`): within ``tol``, or
    within `RATIO_NOISE_RTOL` and no smaller than the last change (the noise floor)."""
    scale = np.abs(tau)
    return (change <= tol * scale) | ((change <= RATIO_NOISE_RTOL * scale) & (change >= last))


def ratio_tolerance(options: SolverOptions, fluid) -> float:
    """Relative tolerance [-] of the fixed point on the actual ratio under ``fluid``'s
    traction law: `RATIO_TOL`, or `RATIO_PER_TOL` times the tolerance raised to the law's
    residual floor where that is larger."""
    tol = at_residual_floor(options, fluid).tol
    return RATIO_TOL if tol == options.tol else max(RATIO_TOL, RATIO_PER_TOL * tol)


@dataclass(frozen=True)
class ModePoint:
    """An operating point of the variator in a planetary mode (arrays broadcast together
    where a batch is solved).

    Attributes
    ----------
    ratio : array_like
        Ideal ratio relative to the carrier ``tau_ID`` [-].
    load_torque : array_like
        Load torque of the driven member (the torque it delivers; applied to it: minus
        that) [N m].
    driver_speed : array_like
        Speed of the driver [rad/s] (signed).
    clamp_force : float
        ``F_N0`` [N] (constant clamping).
    """

    ratio: Any
    load_torque: Any
    driver_speed: Any
    clamp_force: float


@dataclass(frozen=True)
class ModeSolution:
    """Outcome of `solve_mode`.

    Attributes
    ----------
    problem : EquilibriumProblem
        The point in the carrier frame, its input disc turning forward (mirrored where
        the relative input speed is negative), with its output torque the solved ``T_2``
        and the default torque condition: a standard problem at the solution.
    solution : PointSolution
        Creeps and state of ``problem``.
    sign : float
        +1, or -1 where mirrored: physical speeds and torques are ``sign`` times the
        carrier-frame ones.
    speeds : dict of float
        Speeds of ``disc0``, ``disc2``, ``carrier`` [rad/s].
    passes : int
        Solves of the fixed point on the actual ratio.
    """

    problem: EquilibriumProblem
    solution: PointSolution
    sign: float
    speeds: dict
    passes: int


def solve_mode(
    drive: Drive,
    mode: OperatingMode | str,
    point: ModePoint,
    options: SolverOptions = SolverOptions(),
    max_passes: int = 30,
) -> ModeSolution:
    """Solve one operating point of the variator in a planetary mode.

    Parameters
    ----------
    drive : Drive
        Design, fluid and architecture (or any object with them, e.g. a `Variator`).
    mode : OperatingMode or str
        Held, driving and driven members, or a name of `ballcvt.registry.OPERATING_MODES`.
    point : ModePoint
        Ratio, load torque, driver speed and clamping force (scalars).
    options : SolverOptions
        Solver options.
    max_passes : int
        Most passes of the fixed point on the actual ratio.

    Returns
    -------
    ModeSolution

    Raises
    ------
    InputError
        Out-of-range inputs, or a mode and ratio that need an infinite speed.
    ConvergenceError
        If an equilibrium or the fixed point does not converge.
    """
    mode = resolve_mode(mode)
    ratio, driver_speed = float(point.ratio), float(point.driver_speed)
    tau, x, sol, pb = ratio, None, None, None
    fixed = replace(point, load_torque=float(point.load_torque))
    ratio_tol = ratio_tolerance(options, drive.fluid)
    last, before = np.inf, None
    if couples(drive.fluid, mode):  # on to the fixed point at once, as the batches
        tau, x = _coupled_point(drive, mode, fixed, options)
    for passes in range(1, max_passes + 1):  # noqa: B007 (the count is returned)
        speeds = mode.speeds(driver_speed, tau)
        if not abs(float(speeds["disc0"] - speeds["carrier"])) > 0.0:
            raise InputError(
                "driver_speed",
                point.driver_speed,
                f"!= 0: with {mode.label} at "
                f"ratio {ratio:g} the discs would not turn relative to the "
                "carrier",
            )
        pb, sign = carrier_frame_problem(drive, mode, fixed, speeds)
        sign = float(sign)
        sol = solve_point(pb, options, x)
        if not sol.converged and x is not None:
            # the last pass's creeps can be a poor start (the first pass, at the ideal
            # ratio, may land on a far root): retry from the cold start, which is where
            # the batched path's fallback starts (`solve_mode_batch`), so both agree
            sol = solve_point(pb, options)
        if not sol.converged:
            raise ConvergenceError(f"{mode.label}: {sol.message}")
        x = sol.state.creep
        new = float(sol.state.omega[-1] / sol.state.omega[0])
        if ratio_settles(abs(new - tau), last, tau, ratio_tol):
            break
        step, before = next_ratio(tau, new, before, ratio_tol)
        tau, last = float(step), np.inf if before[3] else abs(new - tau)
    else:
        raise ConvergenceError(
            f"{mode.label}: the speeds did not settle in {max_passes} "
            f"passes (actual ratio {tau:.15g})"
        )
    speeds = {m: float(v) for m, v in mode.speeds(driver_speed, new).items()}
    t2 = balancing_output_torque(pb, sol.state)
    standard = replace(pb, output_torque=np.asarray(t2), torque_weights=(0.0, 1.0))
    return ModeSolution(standard, sol, sign, speeds, passes)


def _coupled_point(drive: Drive, mode: OperatingMode, point: ModePoint, options):
    """`solve_mode`'s start: the ratio and creeps of `coupled_creeps` from the cold start
    where it converges (the passes confirm them), else the ideal ratio and no creeps."""
    ratio = float(point.ratio)
    bound = carrier_speed_bound(drive, mode, point.clamp_force)
    if not member_speeds(mode, np.array([point.driver_speed]), np.array([ratio]), bound)[1][0]:
        return ratio, None  # (the passes say why)
    nc = contact_layout(drive.design, drive.architecture).n_contacts
    got, creep, done = coupled_creeps(drive, mode, point, ([ratio], np.full((1, nc), np.nan)),
                                      options)  # fmt: skip
    return (float(got[0]), creep[0]) if done[0] else (ratio, None)


def carrier_frame_problem(drive: Drive, mode: OperatingMode, point: ModePoint, speeds):
    """The point(s) in the carrier frame, mirrored where the relative input speed is
    negative (module docstring).

    Parameters
    ----------
    drive : Drive
        Design, fluid and architecture.
    mode : OperatingMode
        Held, driving and driven members.
    point : ModePoint
        Ratio, load torque and clamping force (arrays broadcast; the driver speed is
        read from ``speeds``).
    speeds : dict of array_like
        Member speeds of `OperatingMode.speeds` [rad/s]; the relative input speed
        ``omega_0 - omega_c`` must not be zero.

    Returns
    -------
    (EquilibriumProblem, ndarray)
        The problem, and ``sign``: +1, or -1 where mirrored.
    """
    a, b, target = mode.torque_condition(point.load_torque)
    relative = np.asarray(speeds["disc0"] - speeds["carrier"], dtype=float)
    sign = np.where(relative > 0, 1.0, -1.0)
    pb = make_problem(
        drive,
        OperatingInputs(point.ratio, sign * target, point.clamp_force, np.abs(relative)),
        CarrierFrame(
            carrier_speed=sign * speeds["carrier"],
            torque_weights=(a, b),
            centrifugal=mode.centrifugal,
            gyroscopic=mode.gyroscopic,
            signed_torque=True,
        ),
    )
    return pb, sign


#: Newton iterations `coupled_creeps` may take [-]: from the cold start it took ten to
#: twelve, from a map's interpolated start three to nine (Table I, a 10 x 10 map of each
#: mode at 300 rpm); near geared neutral, where the fixed point's slope nears 1, it
#: converges slowly, and the passes' secant steps do better.
COUPLED_ITERATIONS = 16
#: Iterations without a lower residual after which a point leaves `coupled_creeps` [-]:
#: where the ratio's dependence on the creeps, left out of the Jacobian, is strong (a
#: load next to the capacity) the iteration stalls, and the passes take the point on. At
#: 2 a point of a map's grid next to the capacity (disc 2 held, the carrier driving) left
#: after six iterations and took four passes more; at 4 it converged in nine (as the
#: torque continuation's `ballcvt.solvers.newton.PATIENCE`).
COUPLED_PATIENCE = 4


def couples(fluid, mode: OperatingMode) -> bool:
    """Whether the fixed point of ``mode`` goes through `coupled_creeps` under ``fluid``'s
    law: not under a law with more than one equilibrium, whose solves follow each point's
    branch from zero torque (`ballcvt.solvers.newton.solve_batch`), nor where the input
    disc's and the carrier's speeds, and so the carrier-frame problem, do not depend on
    the ratio (one of them held, the other driving: the second pass settles at once)."""
    one, two = (mode.speeds(1.0, tau, check=False) for tau in (0.5, 2.0))
    fixed = all(one[m] == two[m] for m in ("disc0", "carrier"))
    return not has_multiple_equilibria(fluid) and not fixed


def coupled_creeps(drive, mode: OperatingMode, point: ModePoint, start, options: SolverOptions):
    """The creeps of points of a mode at the fixed point on the actual ratio, by one Newton
    run with the ratio following the creeps (module docstring).

    Parameters
    ----------
    drive : Drive
        Design, fluid and architecture.
    mode : OperatingMode
        Held and driving members.
    point : ModePoint
        Ratios, loads and driver speeds ``(n,)`` (and the clamping force).
    start : tuple of ndarray
        ``(tau (n,), x (n, n_c))``: the ratios [-] and creeps [-] to start from (NaN
        creeps: the cold start, `ballcvt.solvers.newton.initial_creep`).
    options : SolverOptions
        Solver options (at most `COUPLED_ITERATIONS` iterations; no point solver).

    Returns
    -------
    tau : ndarray
        ``(n,)``: the ratios [-] the creeps give where ``done``.
    x : ndarray
        ``(n, n_c)``: the final creeps [-].
    done : ndarray of bool
        ``(n,)``: converged, at the ratio its creeps give (a point whose ratio would put its
        speeds out of range, or turn the relative input speed, keeps its last ratio, and
        is not done).
    """
    ratio, load, w = (np.broadcast_to(np.asarray(v, dtype=float), np.shape(start[0]))
                      for v in (point.ratio, point.load_torque, point.driver_speed))  # fmt: skip
    tau, x = np.array(start[0], dtype=float), np.array(start[1], dtype=float)
    bound = carrier_speed_bound(drive, mode, point.clamp_force)
    sign = _relative_sign(member_speeds(mode, w, tau, bound)[0])

    def refresh(rows, creep):  # the points ``rows`` at the ratio of their creeps
        new = relative_ratio(ratio[rows], creep)
        speeds, ok = member_speeds(mode, w[rows], new, bound)
        ok &= _relative_sign(speeds) == sign[rows]
        tau[rows] = np.where(ok, new, tau[rows])
        if not ok.all():  # (those keep their last ratio)
            speeds, _ = member_speeds(mode, w[rows], tau[rows], bound)
        at = ModePoint(ratio[rows], load[rows], w[rows], point.clamp_force)
        return carrier_frame_problem(drive, mode, at, speeds)[0]

    opts = at_residual_floor(replace(options, max_iterations=COUPLED_ITERATIONS), drive.fluid)
    flat = refresh(np.arange(tau.size), x)
    x = np.where(np.isnan(x), initial_creep(flat), x)  # (NaN: the cold start)
    iterations = np.zeros(tau.size, dtype=int)
    state = _newton(flat, x, iterations, opts, patience=COUPLED_PATIENCE, refresh=refresh)
    done = residual_norm(state.residual) <= opts.tol
    return tau, x, done & (tau == relative_ratio(ratio, x))


def _relative_sign(speeds) -> np.ndarray:
    """Sign of the relative input speed ``omega_0 - omega_c`` of the members' ``speeds``
    (`member_speeds`)."""
    return np.sign(speeds["disc0"] - speeds["carrier"])
