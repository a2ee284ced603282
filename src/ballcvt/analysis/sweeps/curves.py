"""The curves of a sweep: one ratio and speed each, solved over the torque axis.

This is the work a sweep hands to its worker processes: the limiting torques (under the
clamping law), then every torque with continuation from the last solution, then every
reported quantity at the converged points.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ...equilibrium.problem import build_problem
from ...equilibrium.residual import evaluate
from ...model.clamping import axial_force
from ...model.traction.base import has_multiple_equilibria
from ...params.drive import Drive
from ...performance.efficiency import efficiency, loss_breakdown, power_losses
from ...performance.validity import validity
from ...solvers.clamped import solve_clamped, with_clamp
from ...solvers.limit import LimitSearch, bisection_steps, limit_search
from ...solvers.newton import initial_creep, solve_batch, solve_from, solve_near
from ...solvers.optimal_batch import optimal_forces
from ...solvers.optimal_capacity import capacity_search
from ...solvers.options import SolverOptions
from ...status import Status
from .variables import CONTACT_VARIABLES, LOSS_KINDS, POINT_VARIABLES

__all__ = [
    "OperatingRows",
    "solve_curves",
    "limit_search_curves",
    "derived",
    "solve_column",
    "at_optimal_forces",
]


@dataclass(frozen=True)
class OperatingRows:
    """Rows of operating conditions to solve over the output torque: the curves of a sweep,
    or scattered points (one row each). Picklable: sent to worker processes.

    Attributes
    ----------
    drive : Drive
        Design, fluid and idler architecture.
    ratio, input_speed : ndarray
        Ideal ratio [-] and input speed [rad/s] of each row, ``(m,)``.
    clamp_force : ndarray or None
        ``F_N0`` [N] of each row under the constant law (``law`` None); under the optimal
        law, a force near each row's optimum to start its search from (NaN: none), or None.
    law : clamping law or None
        A law other than constant (`ballcvt.model.clamping`).
    options : SolverOptions
        Solver options.
    creep_limit : float
        ``C_lim`` of the limiting torque [-].
    """

    drive: Drive
    ratio: np.ndarray
    input_speed: np.ndarray
    clamp_force: np.ndarray | None = None
    law: Any = None
    options: SolverOptions = SolverOptions()
    creep_limit: float = 0.1

    @classmethod
    def of(
        cls,
        drive: Drive,
        ratio,
        input_speed,
        clamp_force=None,
        law=None,
        options: SolverOptions = SolverOptions(),
        creep_limit: float | None = None,
    ) -> OperatingRows:
        """Rows from array-likes: ``clamp_force`` [N] broadcast to the rows (ignored under
        a law other than the optimal one, which starts its search there),
        ``creep_limit`` the design's by default."""
        ratio, speed = (np.atleast_1d(np.asarray(a, dtype=float)) for a in (ratio, input_speed))
        force = None
        if law is None or (law.optimises and clamp_force is not None):
            force = np.broadcast_to(np.asarray(clamp_force, dtype=float), ratio.shape)
            force = force.astype(float)
        c_lim = drive.design.creep_limit if creep_limit is None else float(creep_limit)
        return cls(drive, ratio, speed, force, law, options, c_lim)

    @property
    def size(self) -> int:
        return int(self.ratio.size)

    @property
    def optimal(self) -> bool:
        """Whether the clamping force is the efficiency-optimal one (an optimisation)."""
        return self.law is not None and self.law.optimises

    def take(self, index) -> OperatingRows:
        """The rows ``index``."""
        force = None if self.clamp_force is None else self.clamp_force[index]
        return replace(
            self, ratio=self.ratio[index], input_speed=self.input_speed[index], clamp_force=force
        )

    def problem(self, rows, torque, force):
        """The equilibrium problem of rows ``rows`` at ``torque`` [N m] and ``force`` [N]."""
        d = self.drive
        return build_problem(
            d.design,
            d.fluid,
            d.architecture,
            self.ratio[rows],
            torque,
            force,
            self.input_speed[rows],
        )


def solve_curves(curves: OperatingRows, torque, limit=None, callback=None) -> dict:
    """Solve the rows of ``curves`` over ``torque`` [N m].

    ``limit``: the curves' limiting torques if already known, or their
    `ballcvt.solvers.limit.LimitSearch` (else computed here). Under a clamping law other
    than constant the force the law sets at each point is returned as ``clamp_force``,
    ``(m, n_T)``.

    A point is beyond the capacity (status 1) when its torque lies outside every admissible
    interval of its curve (`LimitSearch.admits`; bare limits: above the limit).

    When the limit search ran here (or was handed over), every point within the limits is
    solved in one batch, each started from the creeps interpolated in torque between the
    curve's solution at its limit and the creeps at zero torque (or the solver's cold
    start), or, after a capacity scan (a torque-following law), between the scan's two
    torques around it, without the predictor stage (`LimitSearch.start_between`: within
    1 % of the solution); under the optimal law every point is searched on its own, all in one batch;
    otherwise (bare limits given) torque by torque, each started from the last solution
    (continuation).

    Returns a dict of arrays ``(m, n_T)`` or ``(m, n_T, n_c)`` (and ``limit_torque``,
    ``(m,)``) with the variables of `ballcvt.analysis.sweeps.variables`; run in worker
    processes.
    """
    m, nt = curves.size, torque.size
    base, search = limit_search_curves(curves, callback, limit)
    if search is not None:  # within an admissible interval (a cam's need not start at 0)
        limit, within = search.torque, search.admits(torque)
    else:
        within = torque[None, :] <= np.nan_to_num(limit, nan=-1.0)[:, None]
    state = {
        "creep": np.full((m, nt, base.layout.n_contacts), np.nan),
        "force": np.broadcast_to(base.clamp_force[:, None], (m, nt)).copy(),
        # points within the limit start as "not converged" until solved
        "status": np.where(within, Status.NOT_CONVERGED, Status.BEYOND_LIMIT),
        "iterations": np.zeros((m, nt), dtype=int),
        "residual": np.full((m, nt), np.nan),
    }
    if search is not None or curves.optimal:
        if curves.optimal:
            solved = _solve_optimal(state, curves, torque)
        else:
            solved = _solve_from_limits(state, curves, torque, search, base)
        for _ in range(nt) if callback is not None else ():
            callback()
    else:
        solved = None
        _solve_upwards(state, curves, torque, callback)
    creep, force, status = state["creep"], state["force"], state["status"]
    out = {
        "limit_torque": limit,
        "eta_at_limit": _eta_at(
            curves,
            base.clamp_force,
            limit,
            None if curves.optimal else curves.law,
            None if search is None else search.creep,
        ),
        "status": status.astype(np.int8),
        "iterations": state["iterations"],
        "residual_norm": state["residual"],
    }
    out.update(derived(curves, force, torque, creep, status, solved))
    if curves.law is not None:
        out["clamp_force"] = np.where(status == Status.CONVERGED, force, np.nan)
    return out


def _solve_from_limits(state, curves: OperatingRows, torque, search: LimitSearch, base):
    """Every point within the limits in one batch, started between the creeps at zero
    torque and at the limit; returns the converged points' (problem, state), or None when
    some had to be solved again from below."""
    i, k = np.nonzero(state["status"] == Status.NOT_CONVERGED)
    lim = search.torque[i]
    share = np.divide(torque[k], lim, out=np.zeros(lim.size), where=lim > 0)[:, None]
    zero = np.where(np.isnan(search.creep_zero), initial_creep(base), search.creep_zero)
    x0 = zero[i] + share * (search.creep[i] - zero[i])
    near = search.start_between(i, torque[k])  # a capacity scan's or a walk's creeps
    if near is not None:
        x0 = np.where(np.isnan(near), x0, near)
    # (under a law with more than one equilibrium, at a constant force each solve starts
    # between the equilibria its curve's walk met below the limit (since session 36,
    # without the predictor stage: the thermal sweep 10 % faster; between the creeps at
    # zero torque and at the limit, with it, before) and is kept where it lies on the
    # branch below the limit, `on_branch`; under a torque-following law each starts from
    # its scan's creeps and is kept where it is not past a fold, `solve_from`: before
    # session 33 each was followed from zero torque at its own force)
    on_constant = has_multiple_equilibria(base.fluid) and curves.law is None
    predict = near is None
    below = search.creep[i] if on_constant else None
    pb, sol = _solve_points(state, curves, torque, (i, k), x0, predict, below)
    stray = _off_branch(state, (i, k), sol, curves.creep_limit)
    if stray.size:  # another equilibrium than the one reached from T_2 = 0
        _continue_from_below(state, curves, torque, (i[stray], k[stray]), zero)
        return None  # evaluated again in `derived`
    return pb.take(sol.converged), sol.state.take(sol.converged)


def _solve_optimal(state, curves: OperatingRows, torque):
    """Every point within the limits at its own optimal force, searched all at once (the
    search starts each point from its own guess: no continuation along the curve);
    returns the converged points' (problem, state)."""
    i, k = np.nonzero(state["status"] == Status.NOT_CONVERGED)
    if not i.size:
        return None
    pb, sol = _solve_points(state, curves, torque, (i, k), None)
    return pb.take(sol.converged), sol.state.take(sol.converged)


def _solve_upwards(state, curves: OperatingRows, torque, callback) -> None:
    """Torque by torque up the curves, each point from the last solution (continuation)."""
    x = None
    for k in range(torque.size):
        i = np.flatnonzero(state["status"][:, k] == Status.NOT_CONVERGED)
        if i.size:
            _, sol = _solve_points(
                state, curves, torque, (i, np.full(i.size, k)), None if x is None else x[i]
            )
            if x is None:
                x = np.broadcast_to(sol.state.creep[:1], (curves.size, sol.state.creep.shape[-1]))
                x = x.copy()
            good = sol.converged
            x[i[good]] = sol.state.creep[good]
        if callback is not None:
            callback()


def _off_branch(state, points, sol, creep_limit):
    """Points of one batch that converged with a creep beyond ``creep_limit`` although
    their torque is within the limit: where the traction can fall with the creep (the
    thermal law, docs/model.md §14) a second equilibrium exists past the peak of the
    traction curve, and Newton reached it. They go back to "not converged" (indices into
    the batch)."""
    i, k = points
    big = np.max(np.abs(sol.state.creep), axis=-1) > creep_limit * (1.0 + 1e-9)
    stray = np.flatnonzero(sol.converged & big)
    state["status"][i[stray], k[stray]] = Status.NOT_CONVERGED
    state["creep"][i[stray], k[stray]] = np.nan
    return stray


def _continue_from_below(state, curves: OperatingRows, torque, points, zero):
    """Solve the ``points`` (curve, torque index) torque by torque up their curves, each
    from the last admissible solution below it (from ``zero``, the creeps at ``T_2 = 0``,
    at first): the equilibrium reached continuously from no load. Points that still end
    past the creep limit stay "not converged"."""
    i, k = points
    for kk in np.unique(k):
        ii = i[k == kk]
        below = state["status"][ii, :kk] == Status.CONVERGED
        last = (
            np.where(below.any(axis=1), kk - 1 - np.argmax(below[:, ::-1], axis=1), -1)
            if kk > 0
            else np.full(ii.size, -1)
        )
        x0 = np.where((last >= 0)[:, None], state["creep"][ii, np.maximum(last, 0)], zero[ii])
        at = (ii, np.full(ii.size, kk))
        _, sol = _solve_points(state, curves, torque, at, x0)
        _off_branch(state, at, sol, curves.creep_limit)


def _solve_points(state, curves: OperatingRows, torque, points, x0, predict=True, below=None):
    """Solve the ``points`` (curve ``i[j]``, torque ``k[j]``) in one batch; record them in
    ``state`` and return the problem (at the forces used) and the batch solution
    (``predict``, ``below``: as in `solve_column`)."""
    i, k = points
    pb = curves.problem(i, torque[k], state["force"][i, k])
    pb, sol = solve_column(pb, curves.law, curves.options, x0, predict, below)
    good = sol.converged
    state["force"][i, k] = pb.clamp_force
    state["creep"][i[good], k[good]] = sol.state.creep[good]
    state["status"][i[good], k[good]] = Status.CONVERGED
    state["iterations"][i, k] = sol.iterations
    state["residual"][i, k] = sol.residual_norm
    return pb, sol


def limit_search_curves(curves: OperatingRows, callback=None, limit=None):
    """Limit search of the rows of ``curves`` under their clamping law.

    Parameters
    ----------
    curves : OperatingRows
        The rows (ratio, input speed, constant force or law).
    callback : callable, optional
        Called after each step of the search.
    limit : ndarray or LimitSearch, optional
        A search already made (returned as it is), or bare torques [N m] (then None is
        returned in its place).

    Returns
    -------
    (EquilibriumProblem, LimitSearch or None)
        The rows at zero torque (at the constant force, or the optimal law's bound) and
        the `ballcvt.solvers.limit.LimitSearch`: limiting torques [N m] (NaN where none)
        and the creeps at zero torque and at the limits.
    """
    start = np.ones(curves.size) if curves.law is not None else curves.clamp_force
    base = curves.problem(slice(None), 0.0, start)
    base, follows, creep_limit, search = capacity_search(
        base, curves.law, curves.creep_limit, curves.options
    )
    if isinstance(limit, LimitSearch):
        return base, limit
    if limit is not None:
        return base, None
    if search is not None:  # the optimal law's search for its force made it
        for _ in range(bisection_steps() if callback is not None else 0):
            callback()
        return base, search
    search = limit_search(base, creep_limit, curves.options, callback=callback, law=follows)
    return base, search


def solve_column(pb, law, options, x0, predict=True, below=None):
    """Solve the points of one torque under ``law`` -> (problem at the forces used, sol);
    ``predict``: whether the solves start with the predictor stage (False: ``x0`` is
    already near; under a law with more than one equilibrium Newton from there is kept on
    the branch, `ballcvt.solvers.newton.solve_from`); ``below``: at a constant force,
    creeps on each point's branch at a torque at least its own (both as in
    `ballcvt.solvers.newton.solve_batch`)."""
    if law is None:
        return pb, solve_batch(pb, options, x0, predict=predict, below=below)
    if not law.optimises:
        return solve_clamped(pb, law, lambda p, x: solve_from(p, options, x, predict=predict), x0)
    pb, start = optimal_start(pb, law, options)
    x = initial_creep(pb) if x0 is None else np.broadcast_to(x0, start.shape)
    unknown = np.isnan(start).any(axis=1)
    x = np.where(unknown[:, None], x, start)
    if has_multiple_equilibria(pb.fluid):  # from the search's creeps, as `solve` (since
        return pb, solve_near(pb, options, x)  # session 37; followed from zero torque before)
    return pb, solve_batch(pb, options, x, predict=unknown.any())


def at_optimal_forces(pb, law, options):
    """The points of a 1-D batch at their efficiency-optimal clamping forces (all points
    searched together, `ballcvt.solvers.optimal_batch.optimal_forces`); a point no force
    can carry keeps its force and is flagged by the solve that follows."""
    return optimal_start(pb, law, options)[0]


def optimal_start(pb, law, options, guess=None, creep=None):
    """`at_optimal_forces` and the creeps the search found there, ``(n, n_c)`` [-] (NaN
    rows where it has none); ``guess``: forces near the optima [N] to start from, and
    ``creep`` the creeps there (as in `ballcvt.solvers.optimal_batch.optimal_forces`)."""
    got = optimal_forces(pb, law, options, guess=guess, creep=creep)
    return with_clamp(pb, np.where(got.refused, pb.clamp_force, got.force)), got.creep


def _eta_at(curves: OperatingRows, clamp_force, torque, law=None, x0=None):
    """Overall efficiency (Eq. 38) at one torque per curve (NaN where there is none);
    ``x0``: starting creeps per curve (the limit search's, at these torques)."""
    eta = np.full(curves.size, np.nan)
    ok = np.flatnonzero(np.isfinite(torque))
    if ok.size:
        pb = curves.problem(ok, torque[ok], clamp_force[ok])
        options = curves.options
        start = None if x0 is None else x0[ok]
        if start is not None and law is None:  # the limit search's own solutions
            # (under a law with more than one equilibrium, Newton from them is kept where it
            # stays on the branch below them, `on_branch`: until session 35 each was
            # followed from zero torque, 7 % of Table I's thermal sweep)
            sol = solve_batch(pb, options, start, predict=False, below=start)
        else:  # from them where known (under the thermal law: kept on the branch)
            known = start is not None and bool(np.isfinite(start).all())
            pb, sol = solve_column(pb, law, options, start, predict=not known)
        eta[ok] = np.where(sol.converged, efficiency(pb, sol.state).overall, np.nan)
    return eta


def derived(curves: OperatingRows, clamp_force, torque, creep, status, solved=None):
    """Every reported quantity at the converged points (NaN elsewhere); ``clamp_force``
    has the shape ``(m, n_T)`` of the points, ``torque`` is ``(n_T,)`` or ``(m, n_T)``.

    ``solved``: the problem and state of exactly the converged points, in C order,
    when the solve already has them (else they are evaluated here)."""
    m, nt, nc = creep.shape
    i, k = np.nonzero(status == Status.CONVERGED)
    values = {name: np.full((m, nt), np.nan) for name in POINT_VARIABLES}
    values.update({name: np.full((m, nt, nc), np.nan) for name in CONTACT_VARIABLES})
    values["losses"] = np.full((m, nt, len(LOSS_KINDS)), np.nan)
    values["warnings"] = np.zeros((m, nt), dtype=np.int8)
    if i.size == 0:
        return values
    if solved is None:
        torque = np.broadcast_to(torque, (m, nt))  # one axis for all, or per point
        pb = curves.problem(i, torque[i, k], clamp_force[i, k])
        st = evaluate(pb, creep[i, k], curves.options.quadrature)
    else:
        pb, st = solved
    for name, v in _point_values(curves, pb, st).items():
        values[name][i, k] = v
    return values


def _point_values(curves: OperatingRows, pb, st) -> dict:
    """The reported quantities of solved points (`ballcvt.analysis.sweeps.variables`)."""
    loss = power_losses(pb, st)
    eff = efficiency(pb, st, loss)
    valid = validity(pb, st)
    kinds = loss_breakdown(loss)
    return {
        "eta": eff.overall,
        "eta_loss": eff.from_losses,
        "eta_speed": eff.speed,
        "eta_torque": eff.torque,
        "input_torque": st.input_torque,
        "actual_ratio": st.omega[:, -1] / st.omega[:, 0],
        "tilt_deg": np.degrees(pb.tilt),
        "axial_force": axial_force(curves.drive.design, pb.clamp_force),
        "creep": st.creep,
        "spin": st.spin,
        "mu": st.mu,
        "chi": st.chi,
        "p_max": pb.p_max,
        "film_thickness": st.film,
        "normal_load": pb.load,
        "creep_loss": loss.creep,
        "spin_loss": loss.spin,
        "lambda_ratio": valid.lambda_ratio,
        "losses": np.stack([kinds[kind] for kind in LOSS_KINDS], axis=-1),
        "warnings": valid.flags,
    }
