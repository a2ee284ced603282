"""The paper's result figures: compute each from the sweeps, write PNG, SVG and CSV.

Each ``fig_*`` function takes the shared data (`FigureData`), writes its files in ``out``
and returns their paths. The data behind every figure is written as CSV with the units in
a header line, so the curves can be laid over the paper's.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
import xarray as xr

from ..analysis import kinematic_spin, ratio_tilt_curve, write_table
from ..params import Design
from ..plotting import LABELS, efficiency_map, line_panels, ratio_vs_tilt, save

__all__ = ["FigureData", "FIGURES"]

STYLES = ["-", "--", "-.", ":", (0, (5, 1, 1, 1, 1, 1))]


@dataclass(frozen=True)
class FigureData:
    """Sweeps the figures are drawn from.

    Attributes
    ----------
    design : Design
    torque_curves : Dataset
        Double idler, ratios 0.5 / 1 / 2, F_N0 = 2 kN, over output torque (Figs. 7, 9).
    clamp_curves : Dataset
        Double idler, ratio 1, several F_N0, over output torque (Fig. 8).
    envelope : DataFrame
        Optimal clamping force and efficiency per torque (Fig. 8c).
    ratio_curves : Dataset
        Both architectures over the ratio at T_2 = 20 / 40 / 60 N m (Figs. 10-13).
    efficiency_map : Dataset
        Double idler, ratio x torque (the map).
    """

    design: Design
    torque_curves: xr.Dataset
    clamp_curves: xr.Dataset
    envelope: pd.DataFrame
    ratio_curves: xr.Dataset
    efficiency_map: xr.Dataset


def _sel(ds, **kw):
    return ds.sel(**kw).squeeze(drop=True)


def fig3(data: FigureData, out: Path):
    """Fig. 3: ideal ratio vs tilt, k = 1, several contact angles, 0.8 safety factor."""
    curves, rows = [], []
    safety = data.design.tilt_safety_factor
    for theta in (30.0, 40.0, 45.0, 50.0, 60.0):
        th = np.radians(theta)
        tilt, ratio, usable = ratio_tilt_curve(th, th, 1.0, points=401, safety_factor=safety)
        curves.append((np.degrees(tilt), ratio, f"theta = {theta:g} deg", usable))
        rows.append(
            pd.DataFrame(
                {
                    "theta_deg": theta,
                    "tilt_deg": np.degrees(tilt),
                    "ratio": ratio,
                    "within_safety": usable,
                }
            )
        )
    write_table(
        pd.concat(rows),
        out / "fig03.csv",
        {"theta_deg": "deg", "tilt_deg": "deg", "ratio": "1", "within_safety": "1"},
    )
    return save(ratio_vs_tilt(curves), out, "fig03") + [out / "fig03.csv"]


def fig5(data: FigureData, out: Path):
    """Fig. 5 a-d: kinematic spin coefficients (zero creep) vs ratio, double idler."""
    ratio = np.geomspace(0.5, 2.0, 121)
    sg = kinematic_spin(data.design, "double", ratio)
    panels: list[dict[str, Any]] = [
        {
            "title": f"({'abcd'[i]}) {name} contact",
            "ylabel": LABELS["spin"],
            "lines": [(ratio, s, "", {})],
        }
        for i, (name, s) in enumerate(sg.items())
    ]
    frame = pd.DataFrame({"ratio": ratio, **{f"spin_{n}": s for n, s in sg.items()}})
    write_table(frame, out / "fig05.csv", {"ratio": "1"})
    fig = line_panels(
        panels, LABELS["ratio"], "Fig. 5: spin coefficients (zero creep), double idler", ncols=4
    )
    return save(fig, out, "fig05") + [out / "fig05.csv"]


def _efficiency_panels(ds, dim, label, extra=None):
    names = [
        ("eta_speed", LABELS["eta_speed"]),
        ("eta_torque", LABELS["eta_torque"]),
        ("eta", LABELS["eta"]),
    ]
    panels = []
    for i, (var, ylabel) in enumerate(names):
        lines = [
            (
                ds.output_torque.values,
                _sel(ds[var], **{dim: v}).values,
                label(v),
                {"ls": STYLES[j % len(STYLES)]},
            )
            for j, v in enumerate(ds[dim].values)
        ]
        if extra and var == "eta":
            lines.append(extra)
        panels.append(
            {
                "title": f"({'abc'[i]})",
                "ylabel": ylabel,
                "lines": lines,
                "ylim": (0.0, 1.0) if var == "eta" else None,
            }
        )
    return panels


def _curve_frame(ds, dim, variables):
    frame = ds[list(variables)].to_dataframe().reset_index()
    keep = [dim, "output_torque", *variables]
    return frame[keep]


def fig7(data: FigureData, out: Path):
    """Fig. 7 a-c: speed, torque and overall efficiency vs T_2 at ratio 0.5, 1, 2."""
    ds = _sel(data.torque_curves, architecture="double")
    panels = _efficiency_panels(ds, "ratio", lambda r: rf"$\tau_{{ID}}$ = {r:g}")
    fig = line_panels(
        panels, LABELS["output_torque"], "Fig. 7: double idler, $F_{N0}$ = 2 kN, 2000 rpm", ncols=3
    )
    frame = _curve_frame(ds, "ratio", ["eta_speed", "eta_torque", "eta", "eta_loss", "status"])
    write_table(frame, out / "fig07.csv", {"output_torque": "N m"})
    return save(fig, out, "fig07") + [out / "fig07.csv"]


def fig8(data: FigureData, out: Path):
    """Fig. 8 a-c: efficiencies vs T_2 for several F_N0 at ratio 1, with the envelope."""
    ds = _sel(data.clamp_curves, architecture="double")
    env = data.envelope
    extra = (
        env.output_torque.values,
        env.eta.values,
        r"envelope (optimal $F_{N0}$)",
        {"color": "k", "lw": 2.2},
    )
    panels = _efficiency_panels(
        ds, "clamp_force", lambda f: rf"$F_{{N0}}$ = {f / 1e3:g} kN", extra
    )
    fig = line_panels(
        panels,
        LABELS["output_torque"],
        "Fig. 8: double idler, $\\tau_{ID}$ = 1, 2000 rpm",
        ncols=3,
    )
    frame = _curve_frame(ds, "clamp_force", ["eta_speed", "eta_torque", "eta", "status"])
    write_table(frame, out / "fig08.csv", {"output_torque": "N m", "clamp_force": "N"})
    write_table(
        env,
        out / "fig08c_envelope.csv",
        {
            "output_torque": "N m",
            "clamp_force": "N",
            "eta": "1",
            "max_creep": "1",
            "max_pressure": "Pa",
        },
    )
    return save(fig, out, "fig08") + [out / "fig08.csv", out / "fig08c_envelope.csv"]


def fig9(data: FigureData, out: Path):
    """Fig. 9 a-d: creep at the four contacts vs T_2, ratios 0.5 / 1 / 2."""
    ds = _sel(data.torque_curves, architecture="double")
    panels = []
    names = ["input", "idler_a", "idler_b", "output"]
    for i, name in enumerate(names):
        c = _sel(ds.creep, contact=name)
        lines = [
            (
                ds.output_torque.values,
                np.abs(_sel(c, ratio=r).values),
                rf"$\tau_{{ID}}$ = {r:g}",
                {"ls": STYLES[j]},
            )
            for j, r in enumerate(ds.ratio.values)
        ]
        panels.append(
            {
                "title": f"({'abcd'[i]}) {name}",
                "ylabel": r"$|C|$ [-]",
                "lines": lines,
                "yscale": "log",
            }
        )
    fig = line_panels(
        panels, LABELS["output_torque"], "Fig. 9: creep, double idler, $F_{N0}$ = 2 kN", ncols=4
    )
    frame = ds.creep.sel(contact=names).to_dataframe().reset_index()
    frame = frame.pivot_table(
        index=["ratio", "output_torque"], columns="contact", values="creep", dropna=False
    ).reset_index()
    frame.columns = [
        str(c) if c in ("ratio", "output_torque") else f"creep_{c}" for c in frame.columns
    ]
    write_table(frame, out / "fig09.csv", {"output_torque": "N m"})
    return save(fig, out, "fig09") + [out / "fig09.csv"]


def _ratio_curves(data, arch, torque):
    return _sel(data.ratio_curves, architecture=arch, output_torque=torque)


def fig10(data: FigureData, out: Path):
    """Fig. 10 a-b: idler creep and spin vs ratio at T_2 = 40 N m, double idler."""
    ds = _ratio_curves(data, "double", 40.0)
    r = ds.ratio.values
    panels = [
        {
            "title": "(a) idler creep",
            "ylabel": LABELS["creep"],
            "lines": [
                (r, _sel(ds.creep, contact=c).values, c, {"ls": s})
                for c, s in (("idler_a", "-"), ("idler_b", "--"))
            ],
        },
        {
            "title": "(b) idler spin",
            "ylabel": LABELS["spin"],
            "lines": [
                (r, _sel(ds.spin, contact=c).values, c, {"ls": s})
                for c, s in (("idler_a", "-"), ("idler_b", "--"))
            ],
        },
    ]
    fig = line_panels(
        panels, LABELS["ratio"], "Fig. 10: double idler, $T_2$ = 40 N m, $F_{N0}$ = 2 kN", ncols=2
    )
    frame = pd.DataFrame(
        {
            "ratio": r,
            **{
                f"{v}_{c}": _sel(ds[v], contact=c).values
                for v in ("creep", "spin")
                for c in ("idler_a", "idler_b")
            },
        }
    )
    write_table(frame, out / "fig10.csv", {"ratio": "1"})
    return save(fig, out, "fig10") + [out / "fig10.csv"]


def fig11(data: FigureData, out: Path):
    """Fig. 11: efficiency vs ratio at T_2 = 40 N m by Eq. 38 and by Eq. 39."""
    ds = _ratio_curves(data, "double", 40.0)
    r = ds.ratio.values
    panels = [
        {
            "title": "",
            "ylabel": LABELS["eta"],
            "lines": [
                (
                    r,
                    ds.eta.values,
                    "Eq. 38 (speed x torque efficiency)",
                    {"lw": 2.5, "alpha": 0.6},
                ),
                (
                    r,
                    ds.eta_loss.values,
                    "Eq. 39 (1 - losses / input power)",
                    {"ls": "--", "color": "k"},
                ),
            ],
        }
    ]
    fig = line_panels(
        panels,
        LABELS["ratio"],
        "Fig. 11: double idler, $T_2$ = 40 N m, $F_{N0}$ = 2 kN, 2000 rpm",
        ncols=1,
    )
    frame = pd.DataFrame({"ratio": r, "eta_eq38": ds.eta.values, "eta_eq39": ds.eta_loss.values})
    write_table(frame, out / "fig11.csv", {"ratio": "1"})
    return save(fig, out, "fig11") + [out / "fig11.csv"]


def fig12(data: FigureData, out: Path):
    """Fig. 12: single-idler creep vs ratio at T_2 = 40 N m (double idler's for scale)."""
    single = _ratio_curves(data, "single", 40.0)
    double = _ratio_curves(data, "double", 40.0)
    r = single.ratio.values
    panels = [
        {
            "title": "",
            "ylabel": r"idler $|C|$ [-]",
            "yscale": "log",
            "lines": [
                (r, np.abs(_sel(single.creep, contact="idler").values), "single idler", {}),
                (
                    r,
                    np.abs(_sel(double.creep, contact="idler_a").values),
                    "double idler, idler a",
                    {"ls": "--"},
                ),
                (
                    r,
                    np.abs(_sel(double.creep, contact="idler_b").values),
                    "double idler, idler b",
                    {"ls": ":"},
                ),
            ],
        }
    ]
    fig = line_panels(panels, LABELS["ratio"], "Fig. 12: idler creep, $T_2$ = 40 N m", ncols=1)
    frame = pd.DataFrame(
        {
            "ratio": r,
            "creep_single_idler": _sel(single.creep, contact="idler").values,
            "creep_double_idler_a": _sel(double.creep, contact="idler_a").values,
            "creep_double_idler_b": _sel(double.creep, contact="idler_b").values,
        }
    )
    write_table(frame, out / "fig12.csv", {"ratio": "1"})
    return save(fig, out, "fig12") + [out / "fig12.csv"]


def fig13(data: FigureData, out: Path):
    """Fig. 13: single vs double idler efficiency vs ratio at T_2 = 20, 40, 60 N m."""
    ds = data.ratio_curves
    r = ds.ratio.values
    lines, cols = [], {"ratio": r}
    for j, t in enumerate(ds.output_torque.values):
        for arch, color in (("double", "C0"), ("single", "C3")):
            eta = _sel(ds.eta, architecture=arch, output_torque=t).values
            lines.append(
                (r, eta, rf"{arch}, $T_2$ = {t:g} N m", {"color": color, "ls": STYLES[j]})
            )
            cols[f"eta_{arch}_T{t:g}"] = eta
    fig = line_panels(
        [{"title": "", "ylabel": LABELS["eta"], "lines": lines}],
        LABELS["ratio"],
        "Fig. 13: single vs double idler, $F_{N0}$ = 2 kN",
        ncols=1,
    )
    write_table(pd.DataFrame(cols), out / "fig13.csv", {"ratio": "1"})
    return save(fig, out, "fig13") + [out / "fig13.csv"]


def fig_map(data: FigureData, out: Path):
    """Efficiency map (ratio x torque) with the limiting-torque curve."""
    ds = _sel(data.efficiency_map, architecture="double")
    fig = efficiency_map(
        ds.ratio.values,
        ds.output_torque.values,
        ds.eta.values,
        ds.limit_torque.values,
        limit_eta=ds.eta_at_limit.values,
        title="Efficiency map, double idler, $F_{N0}$ = 2 kN, 2000 rpm",
    )
    frame = (
        ds[["eta", "status"]]
        .to_dataframe()
        .reset_index()[["ratio", "output_torque", "eta", "status"]]
    )
    write_table(frame, out / "map.csv", {"output_torque": "N m"})
    return save(fig, out, "map") + [out / "map.csv"]


#: Figure name -> (function, caption).
FIGURES = {
    "fig03": (fig3, "Fig. 3: ideal speed ratio vs tilt for several contact angles (k = 1)."),
    "fig05": (fig5, "Fig. 5 a-d: kinematic spin coefficients vs ratio."),
    "fig07": (fig7, "Fig. 7 a-c: speed, torque and overall efficiency vs output torque."),
    "fig08": (
        fig8,
        "Fig. 8 a-c: efficiencies vs torque for several clamping forces, "
        "with the upper envelope (optimal clamping force) in (c).",
    ),
    "fig09": (fig9, "Fig. 9 a-d: creep at the four contacts vs output torque."),
    "fig10": (fig10, "Fig. 10 a-b: idler creep and spin vs ratio, T_2 = 40 N m."),
    "fig11": (fig11, "Fig. 11: efficiency vs ratio by Eq. 38 and Eq. 39, T_2 = 40 N m."),
    "fig12": (fig12, "Fig. 12: single-idler creep vs ratio, T_2 = 40 N m."),
    "fig13": (fig13, "Fig. 13: single vs double idler efficiency, T_2 = 20 / 40 / 60 N m."),
    "map": (fig_map, "Efficiency map with the limiting-torque curve (red)."),
}
