"""The curves of a sweep: one ratio and speed each, solved over the torque axis.

This is the work a sweep hands to its worker processes: the limiting torques (under the
clamping law), then every torque with continuation from the last solution, then every
reported quantity at the converged points.
"""

from __future__ import annotations

import numpy as np

from ...equilibrium.problem import build_problem
from ...equilibrium.residual import evaluate
from ...errors import TractionLimitError
from ...model.clamping import axial_force
from ...performance.efficiency import efficiency, loss_breakdown, power_losses
from ...performance.validity import validity
from ...solvers.clamped import capacity_basis, solve_clamped, with_clamp
from ...solvers.limit import LimitSearch, limit_search
from ...solvers.newton import initial_creep, solve_batch
from ...solvers.optimal_clamp import ClampCase, clamp_optimum
from .variables import CONTACT_VARIABLES, LOSS_KINDS, POINT_VARIABLES

__all__ = ["solve_curves", "limit_torques", "derived", "solve_column", "at_optimal_forces"]


def solve_curves(
    design,
    fluid,
    architecture,
    clamp_force,
    input_speed,
    ratio,
    torque,
    options,
    creep_limit,
    limit=None,
    law=None,
    callback=None,
):
    """Solve the curves ``(clamp_force[i], input_speed[i], ratio[i])`` over ``torque``.

    ``limit``: the curves' limiting torques if already known, or their
    `ballcvt.solvers.limit.LimitSearch` (else computed here).
    ``law``: a clamping law other than constant (then ``clamp_force`` is ignored and the
    force the law sets at each point is returned as ``clamp_force``, ``(m, n_T)``).

    When the limit search ran here (or was handed over), every point within the limits is
    solved in one batch, each started from the creeps interpolated in torque between the
    curve's solution at its limit and the creeps at zero torque (or the solver's cold
    start); otherwise (bare limits given, the optimal law) torque by torque, each started
    from the last solution (continuation).

    Returns a dict of arrays ``(m, n_T)`` or ``(m, n_T, n_c)`` (and ``limit_torque``,
    ``(m,)``) with the variables of `ballcvt.analysis.sweeps.variables`; run in worker processes.
    """
    m, nt = ratio.size, torque.size
    optimal = law is not None and law.optimises
    base, search = limit_search_curves(
        design,
        fluid,
        architecture,
        ratio,
        input_speed,
        clamp_force,
        law,
        options,
        creep_limit,
        callback,
        limit,
    )
    limit = search.torque if search is not None else limit
    nc = base.layout.n_contacts
    state = {
        "creep": np.full((m, nt, nc), np.nan),
        "force": np.broadcast_to(base.clamp_force[:, None], (m, nt)).copy(),
        # points within the limit start as "not converged" (2) until solved
        "status": np.where(torque[None, :] <= np.nan_to_num(limit, nan=-1.0)[:, None], 2, 1),
        "iterations": np.zeros((m, nt), dtype=int),
        "residual": np.full((m, nt), np.nan),
    }
    if search is not None and not optimal:
        i, k = np.nonzero(state["status"] == 2)
        lim = search.torque[i]
        share = np.divide(torque[k], lim, out=np.zeros(lim.size), where=lim > 0)[:, None]
        zero = np.where(np.isnan(search.creep_zero), initial_creep(base), search.creep_zero)
        x0 = zero[i] + share * (search.creep[i] - zero[i])
        pb, sol = _solve_points(
            state, design, fluid, architecture, ratio, torque, input_speed, law, options, i, k, x0
        )
        stray = _off_branch(state, i, k, sol, creep_limit)
        if stray.size:  # another equilibrium than the one reached from T_2 = 0
            _continue_from_below(
                state,
                design,
                fluid,
                architecture,
                ratio,
                torque,
                input_speed,
                law,
                options,
                i[stray],
                k[stray],
                zero,
                creep_limit,
            )
            solved = None  # evaluated again in `derived`
        else:
            solved = (pb.take(sol.converged), sol.state.take(sol.converged))
        for _ in range(nt) if callback is not None else ():
            callback()
    else:
        x, solved = None, None
        for k in range(nt):
            i = np.flatnonzero(state["status"][:, k] == 2)
            if i.size:
                _, sol = _solve_points(
                    state,
                    design,
                    fluid,
                    architecture,
                    ratio,
                    torque,
                    input_speed,
                    law,
                    options,
                    i,
                    np.full(i.size, k),
                    None if x is None else x[i],
                )
                if x is None:
                    x = np.broadcast_to(sol.state.creep[:1], (m, nc)).copy()
                good = sol.converged
                x[i[good]] = sol.state.creep[good]
            if callback is not None:
                callback()
    creep, force, status = state["creep"], state["force"], state["status"]
    out = {
        "limit_torque": limit,
        "eta_at_limit": _eta_at(
            design,
            fluid,
            architecture,
            base.clamp_force,
            input_speed,
            ratio,
            limit,
            options,
            None if optimal else law,
            None if search is None else search.creep,
        ),
        "status": status.astype(np.int8),
        "iterations": state["iterations"],
        "residual_norm": state["residual"],
    }
    out.update(
        derived(
            design,
            fluid,
            architecture,
            force,
            input_speed,
            ratio,
            torque,
            creep,
            status,
            options,
            solved,
        )
    )
    if law is not None:
        out["clamp_force"] = np.where(status == 0, force, np.nan)
    return out


def _off_branch(state, i, k, sol, creep_limit):
    """Points of one batch that converged with a creep beyond ``creep_limit`` although
    their torque is within the limit: where the traction can fall with the creep (the
    thermal law, docs/model.md §14) a second equilibrium exists past the peak of the
    traction curve, and Newton reached it. They go back to "not converged" (indices into
    the batch)."""
    big = np.max(np.abs(sol.state.creep), axis=-1) > creep_limit * (1.0 + 1e-9)
    stray = np.flatnonzero(sol.converged & big)
    state["status"][i[stray], k[stray]] = 2
    state["creep"][i[stray], k[stray]] = np.nan
    return stray


def _continue_from_below(
    state,
    design,
    fluid,
    architecture,
    ratio,
    torque,
    input_speed,
    law,
    options,
    i,
    k,
    zero,
    creep_limit,
):
    """Solve the points ``(i, k)`` torque by torque up their curves, each from the last
    admissible solution below it (from ``zero``, the creeps at ``T_2 = 0``, at first):
    the equilibrium reached continuously from no load. Points that still end past the
    creep limit stay "not converged"."""
    for kk in np.unique(k):
        sel = k == kk
        ii = i[sel]
        below = state["status"][ii, :kk] == 0
        last = (
            np.where(below.any(axis=1), kk - 1 - np.argmax(below[:, ::-1], axis=1), -1)
            if kk > 0
            else np.full(ii.size, -1)
        )
        x0 = np.where((last >= 0)[:, None], state["creep"][ii, np.maximum(last, 0)], zero[ii])
        _, sol = _solve_points(
            state,
            design,
            fluid,
            architecture,
            ratio,
            torque,
            input_speed,
            law,
            options,
            ii,
            np.full(ii.size, kk),
            x0,
        )
        _off_branch(state, ii, np.full(ii.size, kk), sol, creep_limit)


def _solve_points(
    state, design, fluid, architecture, ratio, torque, input_speed, law, options, i, k, x0
):
    """Solve the points ``(curve i[j], torque k[j])`` in one batch; record them in
    ``state`` and return the problem (at the forces used) and the batch solution."""
    pb = build_problem(
        design, fluid, architecture, ratio[i], torque[k], state["force"][i, k], input_speed[i]
    )
    pb, sol = solve_column(pb, law, options, x0)
    good = sol.converged
    state["force"][i, k] = pb.clamp_force
    state["creep"][i[good], k[good]] = sol.state.creep[good]
    state["status"][i[good], k[good]] = 0
    state["iterations"][i, k] = sol.iterations
    state["residual"][i, k] = sol.residual_norm
    return pb, sol


def limit_search_curves(
    design,
    fluid,
    architecture,
    ratio,
    input_speed,
    clamp_force,
    law,
    options,
    creep_limit,
    callback=None,
    limit=None,
):
    """Limit search of the curves ``(ratio[i], input_speed[i])`` under a clamping law.

    As `limit_torques`, but returns the `ballcvt.solvers.limit.LimitSearch` (limits and
    the creeps at zero torque and at the limits); ``limit`` may be one already made, or
    bare torques (then None is returned in its place).
    """
    start = np.ones(ratio.size) if law is not None else clamp_force
    base = build_problem(design, fluid, architecture, ratio, 0.0, start, input_speed)
    base, follows, creep_limit = capacity_basis(base, law, creep_limit)
    if isinstance(limit, LimitSearch):
        return base, limit
    if limit is not None:
        return base, None
    return base, limit_search(base, creep_limit, options, callback=callback, law=follows)


def limit_torques(
    design,
    fluid,
    architecture,
    ratio,
    input_speed,
    clamp_force,
    law,
    options,
    creep_limit,
    callback=None,
    limit=None,
):
    """Limiting torques of the curves ``(ratio[i], input_speed[i])`` under a clamping law.

    Parameters
    ----------
    design, fluid, architecture
        The drive.
    ratio, input_speed : ndarray
        Ideal ratios [-] and input speeds [rad/s] of the curves, shape ``(m,)``.
    clamp_force : ndarray or None
        ``F_N0`` [N] of the constant law (``law`` None).
    law : clamping law or None
        A torque-following law (``cam``), ``optimal`` (the limit at the largest force
        within the pressure limit, which the optimiser may pick), or None (constant).
    options : SolverOptions
        Solver options.
    creep_limit : float
        ``C_lim`` [-] (the optimal law's own, if it has one, wins).
    callback : callable, optional
        Called after each step of the limit search.
    limit : ndarray, optional
        Limits already known (returned as they are).

    Returns
    -------
    (EquilibriumProblem, ndarray)
        The curves at zero torque (at the constant force, or the optimal law's bound)
        and their limiting torques [N m] (NaN where none).
    """
    base, search = limit_search_curves(
        design,
        fluid,
        architecture,
        ratio,
        input_speed,
        clamp_force,
        law,
        options,
        creep_limit,
        callback,
        limit,
    )
    return base, (limit if search is None else search.torque)


def solve_column(pb, law, options, x0):
    """Solve the points of one torque under ``law`` -> (problem at the forces used, sol)."""
    if law is None:
        return pb, solve_batch(pb, options, x0)
    if not law.optimises:
        return solve_clamped(pb, law, lambda p, x: solve_batch(p, options, x), x0)
    pb = at_optimal_forces(pb, law, options)
    return pb, solve_batch(pb, options, x0)


def at_optimal_forces(pb, law, options):
    """The points of a 1-D batch at their efficiency-optimal clamping forces (one
    optimisation per point, batched inside); a point no force can carry keeps its force
    and is flagged by the solve that follows."""
    forces = np.array(pb.clamp_force, dtype=float)
    for j in range(pb.size):
        try:
            case = ClampCase(
                pb.design,
                pb.fluid,
                pb.layout.architecture,
                float(pb.ratio[j]),
                float(pb.output_torque[j]),
                float(pb.input_speed[j]),
            )
            forces[j] = clamp_optimum(case, law, options).clamp_force
        except TractionLimitError:
            pass
    return with_clamp(pb, forces)


def _eta_at(
    design, fluid, arch, clamp_force, input_speed, ratio, torque, options, law=None, x0=None
):
    """Overall efficiency (Eq. 38) at one torque per curve (NaN where there is none);
    ``x0``: starting creeps per curve (the limit search's, at these torques)."""
    eta = np.full(ratio.size, np.nan)
    ok = np.flatnonzero(np.isfinite(torque))
    if ok.size:
        pb = build_problem(
            design, fluid, arch, ratio[ok], torque[ok], clamp_force[ok], input_speed[ok]
        )
        if x0 is not None and law is None:  # the limit search's own solutions
            sol = solve_batch(pb, options, x0[ok], predict=False)
        else:
            pb, sol = solve_column(pb, law, options, None if x0 is None else x0[ok])
        eta[ok] = np.where(sol.converged, efficiency(pb, sol.state).overall, np.nan)
    return eta


def derived(
    design,
    fluid,
    arch,
    clamp_force,
    input_speed,
    ratio,
    torque,
    creep,
    status,
    options,
    solved=None,
):
    """Every reported quantity at the converged points (NaN elsewhere); ``clamp_force``
    has the shape ``(m, n_T)`` of the points, ``torque`` is ``(n_T,)`` or ``(m, n_T)``.

    ``solved``: the problem and state of exactly the converged points, in C order,
    when the solve already has them (else they are evaluated here)."""
    m, nt, nc = creep.shape
    ok = status == 0
    i, k = np.nonzero(ok)
    values = {name: np.full((m, nt), np.nan) for name in POINT_VARIABLES}
    values.update({name: np.full((m, nt, nc), np.nan) for name in CONTACT_VARIABLES})
    values["losses"] = np.full((m, nt, len(LOSS_KINDS)), np.nan)
    values["warnings"] = np.zeros((m, nt), dtype=np.int8)
    if i.size == 0:
        return values
    if solved is None:
        torque = np.broadcast_to(torque, (m, nt))  # one axis for all, or per point
        pb = build_problem(
            design, fluid, arch, ratio[i], torque[i, k], clamp_force[i, k], input_speed[i]
        )
        st = evaluate(pb, creep[i, k], options.quadrature)
    else:
        pb, st = solved
    loss = power_losses(pb, st)
    eff = efficiency(pb, st, loss)
    valid = validity(pb, st)
    point = {
        "eta": eff.overall,
        "eta_loss": eff.from_losses,
        "eta_speed": eff.speed,
        "eta_torque": eff.torque,
        "input_torque": st.input_torque,
        "actual_ratio": st.omega[:, -1] / st.omega[:, 0],
        "tilt_deg": np.degrees(pb.tilt),
        "axial_force": axial_force(design, pb.clamp_force),
    }
    contact = {
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
    }
    for name, v in point.items():
        values[name][i, k] = v
    for name, v in contact.items():
        values[name][i, k] = v
    kinds = loss_breakdown(loss)
    values["losses"][i, k] = np.stack([kinds[kind] for kind in LOSS_KINDS], axis=-1)
    values["warnings"][i, k] = valid.flags
    return values
