"""Beyond the paper: the Table I drive as a planetary (docs/model.md §13).

`planetary_section` computes the section of the reproduction report "Beyond the paper:
planetary modes": the overall ratio against the tilt in each mode, efficiency and
circulating power against the ratio at three load torques, the capacity per mode, and the
effect of the balls' centrifugal force and gyroscopic moment. The paper's part of the
report does not depend on it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..analysis.sweeps.export import write_table
from ..model.kinematics import ideal_ratio, ratio_range
from ..model.modes import MEMBERS, OperatingMode
from ..plotting.figures import line_panels, save
from ..solvers.planetary import ModePoint
from ..solvers.planetary_batch import limit_load_batch, solve_mode_batch

__all__ = ["PlanetaryData", "planetary_section", "MODES", "ALL_MODES", "DRIVER_SPEED", "LOADS"]

#: The modes shown (the paper's first). The modes that drive the carrier from a disc spin
#: it at ``tau / (tau - 1)`` or ``1 / (1 - tau)`` times the driver speed, beyond the speed at
#: which the heavy Table I balls (0.88 kg) leave the idler over most of the range: they
#: appear in the kinematics figure only.
MODES = (
    OperatingMode("carrier", "disc0"),
    OperatingMode("disc0", "carrier"),
    OperatingMode("disc2", "carrier"),
)
#: Every mode, for the kinematics figure.
ALL_MODES = MODES + (
    OperatingMode("carrier", "disc2"),
    OperatingMode("disc2", "disc0"),
    OperatingMode("disc0", "disc2"),
)
#: Driver speed [rad/s] (955 rpm): the carrier stays below the speed at which the balls'
#: centrifugal force unloads the idler at 2 kN (198.8 rad/s) over most of the range.
DRIVER_SPEED = 100.0
#: Load torques of the driven member [N m].
LOADS = (10.0, 20.0, 30.0)


@dataclass(frozen=True)
class PlanetaryData:
    """The section's tables (one row per point) and figure and CSV paths."""

    kinematics: pd.DataFrame
    curves: pd.DataFrame
    capacity: pd.DataFrame
    effects: pd.DataFrame
    files: list


def planetary_section(v, clamp_force: float, out, quick: bool = False) -> PlanetaryData:
    """Compute the planetary section on variator ``v`` and write its figures and CSVs.

    Parameters
    ----------
    v : Variator
        The drive (constant clamping force ``clamp_force`` [N]).
    out : path-like
        Output directory.
    quick : bool
        Coarse grids.
    """
    d = v.design
    lo, hi = ratio_range(d)
    ratios = np.linspace(max(lo, 0.5), min(hi, 1.9), 8 if quick else 29)
    kin = _kinematics(d)
    rows = []
    for mode in MODES:
        # the load brakes the driven member: the sign of its speed at zero load
        brake = solve_mode_batch(
            v, mode, ModePoint(ratios, 0.0, DRIVER_SPEED, clamp_force), v.options
        ).braking_direction(mode)
        drn, drv = MEMBERS.index(mode.driven), MEMBERS.index(mode.driver)
        for load in LOADS:
            got = solve_mode_batch(
                v, mode, ModePoint(ratios, brake * load, DRIVER_SPEED, clamp_force), v.options
            )
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
    curves = pd.concat(rows, ignore_index=True)
    capacity = pd.DataFrame(
        {
            "ratio": ratios,
            **{
                mode.label: limit_load_batch(
                    v, mode, ModePoint(ratios, 0.0, DRIVER_SPEED, clamp_force), v.options
                )
                for mode in MODES
            },
        }
    )
    effects = _effects(v, clamp_force)
    files = _figures(kin, curves, capacity, out)
    for name, frame, units in (
        ("planet_kinematics", kin, {"tilt_deg": "deg", "overall_ratio": "1"}),
        (
            "planet_curves",
            curves,
            {
                "load_torque": "N m",
                "overall_ratio": "1",
                "circulation": "1",
                "carrier_speed": "rad/s",
                "max_creep": "1",
            },
        ),
        ("planet_capacity", capacity, {m.label: "N m" for m in MODES}),
        ("planet_effects", effects, {}),
    ):
        files.append(write_table(frame, out / f"{name}.csv", units))
    return PlanetaryData(kin, curves, capacity, effects, files)


def _kinematics(design) -> pd.DataFrame:
    """Ideal overall ratio (no creep) against the tilt in every mode."""
    lo, hi = ratio_range(design)
    tilts = np.linspace(-1.0, 1.0, 201)
    tau = ideal_ratio(tilts, design.theta0, design.theta2, design.aspect_ratio)
    keep = (tau >= lo) & (tau <= hi)
    tilts, tau = tilts[keep], tau[keep]
    out = {"tilt_deg": np.degrees(tilts), "ratio": tau}
    for mode in ALL_MODES:
        sp = mode.speeds(1.0, tau, check=False)
        out[mode.label] = sp[mode.driven]
    return pd.DataFrame(out)


def _effects(v, clamp_force) -> pd.DataFrame:
    """One point (disc 2 held, the carrier at 150 rad/s, tau_ID = 1.5, 20 N m) with the
    balls' centrifugal force and gyroscopic moment on and off."""
    rows = []
    for cf, gy in ((False, False), (True, False), (False, True), (True, True)):
        mode = OperatingMode("disc2", "carrier", centrifugal=cf, gyroscopic=gy)
        r = v.solve(1.5, 20.0, clamp_force=clamp_force, input_speed=150.0, mode=mode)
        idler = next(c for name, c in r.relative.contacts.items() if name.startswith("idler"))
        rows.append(
            {
                "centrifugal": "on" if cf else "off",
                "gyroscopic": "on" if gy else "off",
                "idler load [N]": f"{idler.normal_load:.0f}",
                "idler p_max [GPa]": f"{idler.p_max / 1e9:.3f}",
                "ball bearing loss [W]": f"{r.relative.losses['roller_bearings']:.2f}",
                "total loss [W]": f"{r.loss:.2f}",
                "efficiency": f"{r.eta:.4f}",
            }
        )
    return pd.DataFrame(rows)


def _figures(kin, curves, capacity, out) -> list:
    files = []
    lines = [
        (
            kin.tilt_deg.values,
            np.where(np.abs(kin[m.label].values) <= 3, kin[m.label].values, np.nan),
            m.label,
            None,
        )
        for m in ALL_MODES
    ]
    fig = line_panels(
        [
            {
                "ylabel": "overall ratio, driven / driver [1]",
                "lines": lines,
                "title": "ideal (no creep); within +-3",
                "ylim": (-3.1, 3.1),
            }
        ],
        "tilt [deg]",
        "Planetary modes: overall ratio vs tilt",
    )
    files += save(fig, out, "planet_ratio")
    panels = []
    for mode in MODES:
        sub = curves[curves["mode"] == mode.label]
        panels.append(
            {
                "ylabel": "efficiency, power out / power in [1]",
                "title": mode.label,
                "ylim": (0, 1),
                "lines": [
                    (g.overall_ratio.values, g.eta.values, f"{load:g} N m", None)
                    for load, g in sub.groupby("load_torque")
                ],
            }
        )
    fig = line_panels(
        panels,
        "overall ratio, driven / driver [1]",
        f"Planetary modes: efficiency vs overall ratio (driver "
        f"{DRIVER_SPEED * 30 / math.pi:.0f} rpm; the load brakes the driven "
        "member)",
        ncols=3,
    )
    files += save(fig, out, "planet_efficiency")
    panels = [
        {
            "ylabel": "power through the contacts / shaft power [1]",
            "title": mode.label,
            "yscale": "log",
            "lines": [
                (g.ratio.values, g.circulation.values, f"{load:g} N m", None)
                for load, g in curves[curves["mode"] == mode.label].groupby("load_torque")
            ],
        }
        for mode in MODES
    ]
    fig = line_panels(
        panels, r"ideal ratio $\tau_{ID}$ [1]", "Planetary modes: circulating power", ncols=3
    )
    files += save(fig, out, "planet_circulation")
    fig = line_panels(
        [
            {
                "ylabel": "limiting load torque of the driven member [N m]",
                "lines": [
                    (capacity.ratio.values, capacity[m.label].values, m.label, None) for m in MODES
                ],
            }
        ],
        r"ideal ratio $\tau_{ID}$ [1]",
        "Planetary modes: capacity per mode",
    )
    files += save(fig, out, "planet_capacity")
    return files
