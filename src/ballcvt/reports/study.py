"""Report of a design study: figures, the front, the chosen design (docs/studies.md)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..analysis.studies import OBJECTIVES, make_context
from ..api import Variator
from ..params import Design
from ..plotting import maps_figure, parameters_figure, pareto_figure, save
from .report import write_blocks

__all__ = ["study_report"]

#: Grid of the two efficiency maps (ratio x torque points).
MAP_GRID = (12, 12)


def study_report(result, spec, out, quick_maps: bool = False) -> list[Path]:
    """Figures (``study_pareto``, ``study_parameters``, ``study_maps``) and ``report.md``
    / ``report.html`` of a finished study in ``out``; returns the files written."""
    out = Path(out)
    ds = result.dataset
    objectives = list(spec.objectives)
    units = {k: v[0] for k, v in OBJECTIVES.items()}
    files = save(pareto_figure(ds, objectives, units), out, "study_pareto")
    files += save(parameters_figure(ds, list(spec.names), objectives[0]), out, "study_parameters")
    blocks: list[tuple] = [
        ("h1", f"Design study: {spec.study.name}"),
        (
            "p",
            f"{ds.sizes['design']} designs ({spec.study.method}, seed "
            f"{spec.study.seed}), {result.evaluated_now} evaluated in this run, on "
            f"the {spec.study.architecture} idler, base drive `{spec.study.drive}`, "
            f"traction law {spec.study.traction_law or 'of the fluid'}. Objectives: "
            + ", ".join(f"{o} ({s})" for o, s in spec.objectives.items())
            + ".",
        ),
    ]
    counts = result.counts()
    blocks.append(
        ("table", ["status", "designs"], [[k, v] for k, v in counts.items() if k != "reasons"])
    )
    if counts["reasons"]:
        blocks.append(
            (
                "table",
                ["why not evaluated or not feasible", "designs"],
                [[k, v] for k, v in list(counts["reasons"].items())[:12]],
            )
        )
    blocks.append(
        (
            "figure",
            "study_pareto.png",
            "Objectives of the feasible designs, the Pareto front and the chosen design",
        )
    )
    blocks.append(
        (
            "figure",
            "study_parameters.png",
            "The varied parameters: feasible "
            f"designs coloured by {objectives[0]}, infeasible ones as grey crosses, "
            "the front circled in red",
        )
    )
    front = ds.isel(design=np.flatnonzero(ds["pareto"].values))
    cols = list(spec.names) + objectives
    blocks.append(
        (
            "table",
            ["design"] + cols,
            [
                [int(d)] + [f"{float(front[c].values[i]):.4g}" for c in cols]
                for i, d in enumerate(front["design"].values)
            ],
        )
    )
    if result.chosen_design is not None:
        files += _maps(result, spec, out, quick_maps)
        blocks.append(
            (
                "p",
                f"Chosen design: number {int(ds['design'].values[result.chosen])}"
                f" (`chosen_design.toml`, which every command loads with --design).",
            )
        )
        blocks.append(
            (
                "figure",
                "study_maps.png",
                "Efficiency maps of the base drive and "
                "of the chosen design at the study's first clamping force and speed",
            )
        )
    files += write_blocks(out, "report", blocks, f"ballcvt study {spec.study.name}")
    return files


def _maps(result, spec, out, quick):
    """Efficiency maps of the base and the chosen design."""
    ctx = make_context(spec)
    i = result.chosen
    ds = result.dataset
    force = (
        float(ds["clamp_force"].values[i])
        if "clamp_force" in spec.parameters
        else spec.operating.clamp_force
    )
    speed = (
        spec.operating.input_speed_rpm[0]
        if spec.operating.input_speed_rpm
        else spec.operating.target_input_speed_rpm
    )
    base = Variator(Design(**ctx.base), ctx.fluid, spec.study.architecture)
    chosen = Variator(result.chosen_design, ctx.fluid, spec.study.architecture)
    n_r, n_t = (5, 5) if quick else MAP_GRID
    maps, titles = [], []
    for v, what in ((base, "base drive"), (chosen, "chosen design")):
        lo, hi = v.ratio_range
        ratio = np.linspace(max(lo, 0.5), min(hi, 2.0), n_r)
        law = {} if force is not None else {"clamp_law": spec.operating.clamp_law}
        top = 1.05 * max(
            v.limit_torque(
                ratio=float(r), input_speed_rpm=speed, **({"clamp_force": force} if force else law)
            )
            for r in (ratio[0], ratio[-1], 1.0)
        )
        torque = np.linspace(0.05 * top, top, n_t)
        maps.append(
            v.sweep(
                ratio=ratio,
                output_torque=torque,
                input_speed_rpm=speed,
                **({"clamp_force": force} if force else law),
            )
        )
        titles.append(
            f"{what}: {v.design.name[:70]}\nF_N0 "
            f"{'law ' + spec.operating.clamp_law if force is None else f'{force:g} N'}"
            f", {speed:g} rpm"
        )
    return (
        save(maps_figure(*maps, titles), out, "study_maps")
        if all(math.isfinite(float(np.nanmax(m.eta))) for m in maps)
        else []
    )
