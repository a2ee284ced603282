"""The drive as a planetary (docs/model.md §13): the ideal overall ratio of each operating
mode, and batches of points and capacities per mode, as tables."""

from __future__ import annotations

import numpy as np
import pandas as pd

from ..model.kinematics import ideal_ratio, ratio_range
from ..model.modes import MEMBERS, OperatingMode
from ..params.drive import Drive
from ..solvers.options import SolverOptions
from ..solvers.planetary import ModePoint
from ..solvers.planetary_batch import PROBE, limit_load_batch, limit_load_search, solve_mode_batch
from ..solvers.planetary_pinned import relative_ratio
from ..status import Status

__all__ = ["OperatingMode", "mode_kinematics", "mode_curves", "mode_capacity", "mode_map"]


def _options(drive) -> SolverOptions:
    return getattr(drive, "options", None) or SolverOptions()


def mode_kinematics(design, modes, tilts) -> pd.DataFrame:
    """Ideal overall ratio (no creep) of each mode against the tilt (Eq. 4, Willis).

    Parameters
    ----------
    design : Design
        Geometry.
    modes : sequence of OperatingMode
        The modes (one column each, named by ``mode.label``).
    tilts : array_like
        Tilts [rad]; those whose ideal ratio lies outside the usable range are dropped.

    Returns
    -------
    DataFrame
        ``tilt_deg`` [deg], ``ratio`` (``tau_ID``) [-] and, per mode, the driven member's
        speed over the driver's [-].
    """
    lo, hi = ratio_range(design)
    tilts = np.asarray(tilts, dtype=float)
    tau = ideal_ratio(tilts, design.theta0, design.theta2, design.aspect_ratio)
    keep = (tau >= lo) & (tau <= hi)
    tilts, tau = tilts[keep], tau[keep]
    out = {"tilt_deg": np.degrees(tilts), "ratio": tau}
    for mode in modes:
        out[mode.label] = mode.speeds(1.0, tau, check=False)[mode.driven]
    return pd.DataFrame(out)


def mode_curves(
    drive, mode: OperatingMode, ratios, loads, *, driver_speed: float, clamp_force: float
) -> pd.DataFrame:
    """Points of one mode over the ratio at several load torques that brake the driven member.

    The sign of each load is that of the driven member's speed at zero load.

    Parameters
    ----------
    drive : Drive or Variator
        Design, fluid, idler architecture and (optionally) solver ``options``.
    mode : OperatingMode
        Held and driving members.
    ratios : array_like
        Ideal ratios ``tau_ID`` relative to the carrier [-].
    loads : sequence of float
        Load torques of the driven member [N m] (magnitudes).
    driver_speed : float
        Driver speed [rad/s].
    clamp_force : float
        ``F_N0`` [N] (constant clamping).

    Returns
    -------
    DataFrame
        One row per (load, ratio): ``mode`` (label), ``load_torque`` [N m], ``ratio``,
        ``status`` (0 converged), ``overall_ratio`` (driven over driver speed) [-],
        ``eta`` [-], ``circulation`` (power through the contacts over the input power) [-],
        ``carrier_speed`` [rad/s], ``max_creep`` [-].
    """
    ratios = np.asarray(ratios, dtype=float)
    here, opts = Drive(drive.design, drive.fluid, drive.architecture), _options(drive)

    def at(load):
        return solve_mode_batch(
            here, mode, ModePoint(ratios, load, driver_speed, clamp_force), opts
        )

    brake = at(0.0).braking_direction(mode)
    drn, drv = MEMBERS.index(mode.driven), MEMBERS.index(mode.driver)
    rows = []
    for load in loads:
        got = at(brake * load)
        with np.errstate(divide="ignore", invalid="ignore"):
            rows.append(
                pd.DataFrame(
                    {
                        "mode": mode.label,
                        "load_torque": load,
                        "ratio": ratios,
                        "status": got.status,
                        "overall_ratio": got.speeds[drn] / got.speeds[drv],
                        "eta": got.eta,
                        "circulation": got.circulating_power / got.input_power,
                        "carrier_speed": got.speeds[MEMBERS.index("carrier")],
                        "max_creep": got.max_creep,
                    }
                )
            )
    return pd.concat(rows, ignore_index=True)


def mode_capacity(
    drive, mode: OperatingMode, ratios, *, driver_speed: float, clamp_force: float
) -> np.ndarray:
    """Largest load torque of the driven member with every ``|C| <= creep_limit`` [N m].

    Parameters are those of `mode_curves`; NaN where even zero load is not admissible.
    """
    ratios = np.asarray(ratios, dtype=float)
    return limit_load_batch(
        Drive(drive.design, drive.fluid, drive.architecture),
        mode,
        ModePoint(ratios, 0.0, driver_speed, clamp_force),
        _options(drive),
    )


def _start_creeps(zero, top, probe, share) -> np.ndarray:
    """Starting creeps ``(n_c, ratios, loads)`` [-] of a map's grid at the shares
    ``share`` ``(ratios, loads)`` of each ratio's limit, from its creeps at zero load and
    at the limit (``zero``, ``top``: `ModeBatch`) and the held search's first load
    (``probe``: its share of the limit and creeps, `LoadSearch.probe`, NaN where none).

    Per contact the rational (Padé [1/1]) interpolant ``C(0) + a s / (1 - b s)`` in the
    share ``s`` through the three; linear in ``s`` where there is no probe, or where the
    interpolant has a pole within ``[0, 1]`` or the creep does not grow one way. A disc
    creep rises steeply next to the capacity (Table I, disc 0 held, 300 rpm, ratio 0.71:
    0.033 at 0.85 of the limit, 0.090 at 0.99): linear interpolation started the grid's
    solves at up to twice their creeps, their ratios 3 % off at the median; the
    interpolant, 0.3 % (the mode's 10 x 10 map a tenth faster, issue 26).
    """
    c0, dt = zero.creep[:, :, None], (top.creep - zero.creep)[:, :, None]
    sp, dp = probe[0][None, :, None], probe[1][:, :, None] - c0
    with np.errstate(divide="ignore", invalid="ignore"):
        b = (dt * sp - dp) / (sp * (dt - dp))
        curved = c0 + dt * (1.0 - b) * share / (1.0 - b * share)
    ok = np.isfinite(curved) & (np.abs(b) < 1.0) & (np.sign(dp) == np.sign(dt)) & (sp < 1.0)
    return np.where(ok, curved, c0 + share * dt)


def _grid(drive, mode, grid, driver, solved):
    """`solve_mode_batch` of a map's grid ``(ratio, load, limit)`` (arrays ``(ratios,
    loads)``; ``driver``: ``(driver_speed, clamp_force)``; ``solved``: the options and the
    batches at zero load and at the limit, per ratio, and the held search's first loads,
    `LoadSearch.probe`), flat.

    A load above its capacity by more than the bisection's bracket (`PROBE`) is not
    solved: it is beyond the limit (status 1, its figures NaN), as the carrier-held map
    leaves the torques above its limit (`ballcvt.analysis.sweeps.grid`): most of a map's
    Newton iterations in a mode went to those loads, each run to its last iteration, and
    then to the point solver (issue 26). The others start from the creeps interpolated in
    the load between zero load and the limit (`_start_creeps`), and the actual ratio they
    give (`ballcvt.solvers.planetary_pinned.relative_ratio`).
    """
    ratio, load, limit = np.broadcast_arrays(*grid)
    options, (zero, top, probe) = solved
    share = np.abs(load) / limit  # (NaN where there is no limit: the cold start)
    x = _start_creeps(zero, top, (probe[0] / limit[:, 0], probe[1]), share)
    solve = np.flatnonzero(~(np.abs(load) > limit * (1.0 + PROBE)).ravel())
    point = ModePoint(ratio.ravel()[solve], load.ravel()[solve], *driver)
    x = x.reshape(x.shape[0], -1)[:, solve]
    start = (relative_ratio(point.ratio, x.T), x)
    got = solve_mode_batch(drive, mode, point, options, start=start)
    return got.expand(solve, ratio.size, Status.BEYOND_LIMIT)


def mode_map(
    drive, mode: OperatingMode, ratios, loads, *, driver_speed: float, clamp_force: float
):
    """Efficiency map of one mode over ideal ratio x load torque, with its capacity curve.

    The batched counterpart of the carrier-held efficiency map (``ballcvt map``): one
    `solve_mode_batch` over the whole grid, the capacity by `limit_load_batch`. The loads
    brake the driven member (sign as in `mode_curves`).

    Parameters
    ----------
    drive : Drive or Variator
        Design (its ``creep_limit`` bounds the capacity), fluid, idler architecture and
        (optionally) solver ``options``.
    mode : OperatingMode
        Held and driving members.
    ratios : array_like
        Ideal ratios ``tau_ID`` relative to the carrier [-].
    loads : array_like or int
        Load torques of the driven member [N m] (magnitudes), or their number, evenly
        spaced up to 1.02 x the largest capacity (as the carrier-held map).
    driver_speed : float
        Driver speed [rad/s].
    clamp_force : float
        ``F_N0`` [N] (constant clamping).

    Returns
    -------
    xarray.Dataset
        On ``ratio`` x ``output_torque`` (the load torque magnitude [N m]): ``eta`` [-]
        (power out over power in), ``status`` (`ballcvt.status.Status`: 0 converged, 1
        beyond the creep limit or with no equilibrium above the capacity, 2 no
        equilibrium, 3 speeds out of range), ``loss`` [W],
        ``overall_ratio`` [-], ``carrier_speed`` [rad/s], ``max_creep`` [-]; on ``ratio``:
        ``limit_torque`` [N m] and ``eta_at_limit`` [-].
    """
    import xarray as xr

    ratios = np.asarray(ratios, dtype=float)
    here, opts = Drive(drive.design, drive.fluid, drive.architecture), _options(drive)
    zero = solve_mode_batch(here, mode, ModePoint(ratios, 0.0, driver_speed, clamp_force), opts)
    brake = zero.braking_direction(mode)
    search = limit_load_search(
        here, mode, ModePoint(ratios, brake, driver_speed, clamp_force), opts, zero=zero
    )
    limit, at_limit = search
    if np.ndim(loads) == 0:
        top = 1.02 * float(np.nanmax(limit)) if np.isfinite(limit).any() else 1.0
        loads = np.linspace(top / int(loads), top, int(loads))
    loads = np.asarray(loads, dtype=float)
    r, t = np.meshgrid(ratios, loads, indexing="ij")
    got = _grid(here, mode, (r, brake[:, None] * t, limit[:, None]), (driver_speed, clamp_force),
                (opts, (zero, at_limit, search.probe)))  # fmt: skip
    drn, drv = MEMBERS.index(mode.driven), MEMBERS.index(mode.driver)
    shape = r.shape
    # no equilibrium beyond the capacity: that load is beyond the limit, as in the default map
    status = got.status.reshape(shape).copy()
    status[(status == Status.NOT_CONVERGED) & (t > limit[:, None])] = Status.BEYOND_LIMIT
    with np.errstate(divide="ignore", invalid="ignore"):
        overall = got.speeds[drn] / got.speeds[drv]
    grid = ("ratio", "output_torque")
    ds = xr.Dataset(
        {
            "eta": (grid, got.eta.reshape(shape), {"units": "1"}),
            "status": (grid, status),
            "loss": (grid, got.loss.reshape(shape), {"units": "W"}),
            "overall_ratio": (grid, overall.reshape(shape), {"units": "1"}),
            "carrier_speed": (
                grid,
                got.speeds[MEMBERS.index("carrier")].reshape(shape),
                {"units": "rad/s"},
            ),
            "max_creep": (grid, got.max_creep.reshape(shape), {"units": "1"}),
            "limit_torque": ("ratio", limit, {"units": "N m"}),
            "eta_at_limit": ("ratio", at_limit.eta, {"units": "1"}),
        },
        coords={"ratio": ratios, "output_torque": loads},
        attrs={
            "mode": mode.label,
            "held": mode.held,
            "driver": mode.driver,
            "held_speed": mode.held_speed,
            "driver_speed": float(driver_speed),
            "clamp_force": float(clamp_force),
        },
    )
    ds["output_torque"].attrs.update(units="N m", long_name="load torque of the driven member")
    return ds
