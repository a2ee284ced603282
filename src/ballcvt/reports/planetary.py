"""Beyond the paper: the Table I drive as a planetary (docs/model.md §13).

`planetary_section` computes the section of the reproduction report "Beyond the paper:
planetary modes": the overall ratio against the tilt in each mode, efficiency and
circulating power against the ratio at three load torques, the capacity per mode, and the
effect of the balls' centrifugal force and gyroscopic moment. The paper's part of the
report does not depend on it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from ..analysis import (
    OperatingMode,
    mode_capacity,
    mode_curves,
    mode_kinematics,
    write_table,
)
from ..plotting import line_panels, save
from ..units import rad_s_to_rpm

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
    lo, hi = v.ratio_range
    ratios = np.linspace(max(lo, 0.5), min(hi, 1.9), 8 if quick else 29)
    kin = mode_kinematics(v.design, ALL_MODES, np.linspace(-1.0, 1.0, 201))
    at = {"driver_speed": DRIVER_SPEED, "clamp_force": clamp_force}
    curves = pd.concat(
        [mode_curves(v, mode, ratios, LOADS, **at) for mode in MODES], ignore_index=True
    )
    capacity = pd.DataFrame(
        {"ratio": ratios, **{mode.label: mode_capacity(v, mode, ratios, **at) for mode in MODES}}
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
        f"{rad_s_to_rpm(DRIVER_SPEED):.0f} rpm; the load brakes the driven "
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
