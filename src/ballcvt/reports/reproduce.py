"""`reproduce`: recompute every result figure and stated number of the paper, with a report.

Run from the command line as ``ballcvt reproduce --out DIR [--quick]``. Writes into DIR:
``figNN.png/.svg/.csv`` for Figs. 3, 5, 7-13, ``map.*``, the sweeps as NetCDF
(``data/*.nc``), ``claims.csv``, ``report.md`` and ``report.html`` (figures inline), and,
beyond the paper, the planetary section's ``planet_*.png/.svg/.csv``.
"""

from __future__ import annotations

import platform
import sys
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from scipy.optimize import minimize_scalar
from tqdm.auto import tqdm

from .._version import __version__
from ..analysis import traction_ceiling, write_table
from ..analysis.sweeps import to_netcdf
from ..api import PAPER_POINT, Variator
from ..files import check_output_dir
from ..units import rpm_to_rad_s
from .claims import paper_claims
from .figures import FIGURES, FigureData
from .planetary import planetary_section
from .report import Findings, RunInfo, write_report

__all__ = ["reproduce", "Reproduction", "GRIDS"]

#: The paper's operating point of its figures (Sec. 4).
RPM = PAPER_POINT.input_speed_rpm
CLAMP = PAPER_POINT.clamp_force

#: Grid sizes: (full, quick).
GRIDS = {
    "torque": (57, 9),
    "ratio": (61, 7),
    "map_ratio": (31, 7),
    "map_torque": (35, 8),
    "envelope": (24, 5),
}


@dataclass(frozen=True)
class Reproduction:
    """What `reproduce` wrote and found."""

    out: Path
    files: list
    claims: list
    run_time: float


def _grid(name, quick):
    return GRIDS[name][1 if quick else 0]


def _torques(n, top=180.0):
    return np.unique(np.concatenate([[0.0, 1.0, 2.5], np.linspace(5.0, top, n - 3)]))


def compute(
    quick: bool = False,
    workers: int = 1,
    progress: bool | None = None,
    traction_law: str | None = None,
    drive: Variator | None = None,
):
    """Run every sweep the figures need; returns (FigureData, Fig. 11 peak).

    ``traction_law`` replaces the paper's isothermal law (docs/model.md §14) in every sweep;
    ``drive`` replaces the Table I drive (its design, fluid and law) altogether.

    Every sweep and the Fig. 8c envelope run on ``workers`` processes, each with a labelled
    progress bar.
    """
    v = Variator(traction_law=traction_law) if drive is None else drive
    speed = rpm_to_rad_s(RPM)
    torque = _torques(_grid("torque", quick))
    common: dict[str, Any] = {"input_speed": speed, "workers": workers, "progress": progress}
    torque_curves = v.sweep(
        ratio=[0.5, 1.0, 2.0],
        output_torque=torque,
        clamp_force=CLAMP,
        label="Figs. 7, 9: efficiency and creep vs torque",
        **common,
    )
    clamps = [1000.0, 1500.0, 2000.0, 2500.0, 3000.0]
    clamp_curves = v.sweep(
        ratio=1.0,
        output_torque=_torques(_grid("torque", quick), 260.0),
        clamp_force=clamps,
        label="Fig. 8: efficiency at five clamps",
        **common,
    )
    env_t = np.unique(np.concatenate([np.linspace(5.0, 250.0, _grid("envelope", quick)), [40.0]]))
    envelope = pd.DataFrame(_envelope(v, env_t, speed, workers, progress))
    ratio = np.unique(np.concatenate([np.linspace(0.5, 2.0, _grid("ratio", quick)), [1.0]]))
    ratio_curves = v.sweep(
        ratio=ratio,
        output_torque=[20.0, 40.0, 60.0],
        clamp_force=CLAMP,
        architecture=("double", "single"),
        label="Figs. 10-13: vs ratio",
        **common,
    )
    emap = v.sweep(
        ratio=np.linspace(0.5, 2.0, _grid("map_ratio", quick)),
        output_torque=np.linspace(2.0, 170.0, _grid("map_torque", quick)),
        clamp_force=CLAMP,
        label="efficiency map",
        **common,
    )
    data = FigureData(v.design, torque_curves, clamp_curves, envelope, ratio_curves, emap)
    return data, _fig11_peak(v, ratio_curves)


def _envelope_row(v, torque, speed):
    o = v.optimal_clamp_force(1.0, torque, input_speed=speed)
    return {
        "output_torque": torque,
        "clamp_force": o.clamp_force,
        "eta": o.eta,
        "max_creep": o.max_creep,
        "max_pressure": o.max_pressure,
        "active_constraint": o.active,
    }


def _envelope(v, torques, speed, workers, progress):
    """Fig. 8c: the optimal clamping force at each torque, on ``workers`` processes."""
    show = sys.stderr.isatty() if progress is None else progress
    bar = tqdm(
        total=len(torques), desc="Fig. 8c: optimal-clamp envelope", unit="torque", disable=not show
    )
    with bar:
        if workers > 1:
            with ProcessPoolExecutor(max_workers=workers) as pool:
                futures = [pool.submit(_envelope_row, v, float(t), speed) for t in torques]
                rows = []
                for f in futures:
                    rows.append(f.result())
                    bar.update()
                return rows
        rows = []
        for t in torques:
            rows.append(_envelope_row(v, float(t), speed))
            bar.update()
        return rows


def _fig11_peak(v, ratio_curves):
    """Maximum of eta(ratio) at T_2 = 40 N m: grid maximum refined by bounded Brent."""
    eta = ratio_curves.eta.sel(architecture="double", output_torque=40.0).squeeze(drop=True)
    r = eta.ratio.values
    i = int(np.nanargmax(eta.values))
    lo, hi = r[max(i - 1, 0)], r[min(i + 1, r.size - 1)]

    def neg(x):
        return -v.solve(ratio=x, output_torque=40.0, clamp_force=CLAMP, input_speed_rpm=RPM).eta

    res = minimize_scalar(neg, bounds=(lo, hi), method="bounded", options={"xatol": 1e-3})
    return float(res.x), float(-res.fun)


def reproduce(
    out,
    quick: bool = False,
    workers: int = 1,
    progress: bool | None = None,
    traction_law: str | None = None,
    drive: Variator | None = None,
) -> Reproduction:
    """Recompute the paper's results on the Table I drive and write figures and report.

    Parameters
    ----------
    out : path-like
        Output directory (created).
    quick : bool
        Coarse grids (seconds; for tests and a first look).
    workers : int
        Processes for the sweeps.
    progress : bool, optional
        Progress bars (default: when stderr is a terminal).
    traction_law : str, optional
        A traction law other than the paper's isothermal one (docs/model.md §14): every
        figure and claim is then recomputed under it, and the report says so.
    drive : Variator, optional
        A drive replacing the paper's Table I drive (another design, fluid or creep limit,
        e.g. ``Variator(*open_drive("hub"))``): every figure and claim is recomputed on it
        (the claims still quote the paper's values), and the report names its design and
        fluid. ``traction_law`` is then ignored (the drive's fluid has its own law).

    Returns
    -------
    Reproduction
    """
    start = time.perf_counter()
    out = check_output_dir(out)
    check_output_dir(out / "data")
    data, peak = compute(quick, workers, progress, traction_law, drive)
    files = []
    show = sys.stderr.isatty() if progress is None else progress
    for fn, _ in tqdm(
        FIGURES.values(), desc="figures and data files", unit="figure", disable=not show
    ):
        files += fn(data, out)
    for name in ("torque_curves", "clamp_curves", "ratio_curves", "efficiency_map"):
        files.append(to_netcdf(getattr(data, name), out / "data" / f"{name}.nc"))
    v = Variator(traction_law=traction_law) if drive is None else drive
    design, fluid = v.design, v.fluid
    claims = paper_claims(data, peak)
    frame = pd.DataFrame([c.__dict__ for c in claims])
    files.append(write_table(frame, out / "claims.csv", {}))
    ceiling = traction_ceiling(v, 1.0, clamp_force=CLAMP, input_speed=rpm_to_rad_s(RPM))
    with tqdm(
        total=1, desc="beyond the paper: planetary modes", unit="section", disable=not show
    ) as bar:
        planet = planetary_section(v, CLAMP, out, quick)
        bar.update()
    files += planet.files
    run_time = time.perf_counter() - start
    files += write_report(
        out,
        Findings(data, claims, ceiling, peak),
        RunInfo(quick, run_time, _inputs(design, fluid, quick, workers)),
        planetary=planet,
    )
    return Reproduction(out=out, files=files, claims=claims, run_time=run_time)


def _inputs(design, fluid, quick, workers):
    return {
        "design": design.name,
        "fluid": fluid.name,
        "operating point": f"F_N0 = {CLAMP:g} N, omega_0 = {RPM:g} rpm (Figs. 7, 9-13)",
        "model options (the paper's figures)": (
            "constant clamping force (clamp law 'constant'), "
            + (
                "isothermal traction (Eqs. 51-66)"
                if fluid.traction_law == "isothermal"
                else f"{fluid.traction_law} traction law (docs/model.md §14), NOT the paper's "
                "isothermal law"
            )
            + ", carrier held, no parasitic losses (the paper's model; the Table I file's "
            "example cam is not used)"
        ),
        "model options (planetary section)": "as above, with the carrier turning and the "
        "balls' centrifugal force and gyroscopic moment "
        "(docs/model.md §13)",
        "creep limit": f"{design.creep_limit:g}",
        "max pressure (clamp optimisation)": f"{design.max_pressure / 1e9:g} GPa",
        "grids": "quick (coarse)" if quick else "full",
        "worker processes": str(workers),
        "ballcvt": __version__,
        "python": platform.python_version(),
        "machine": f"{platform.machine()}, {platform.system()}",
    }
