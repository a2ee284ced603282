"""``ballcvt map``: efficiency map (ratio x output torque) as data and figure."""

from __future__ import annotations

import sys

import numpy as np

from ...api import MapGrid, to_csv, to_netcdf
from ...files import check_output_dir
from ...units import deg_to_rad
from . import options as o
from .modes import add_mode_options, mode_of
from .oil_option import add_oil_option
from .point import add_tilt_rate


def add_parser(subparsers) -> None:
    """Add ``map`` and its options."""
    p = o.sub(
        subparsers,
        "map",
        "efficiency map (ratio x output torque) as data and figure",
        "Efficiency over ideal ratio x output torque at one clamping force and speed, "
        "with the limiting-torque curve: map.png, map.svg, map.nc (NetCDF-4, CF) and "
        "map.csv in --out. Points beyond the limit have status 1. With --life, the "
        "system fatigue life L10 of every point (variable l10_hours [h]) and its "
        "contours at the decades of hours (docs/life.md). With --shift-effort, the moment "
        "per ball that holds the tilt, the moment to tilt the balls at --tilt-rate and the "
        "moment about the balls' skew axes (holding_moment, shift_moment, shifter_moment, "
        "skew_moment [N m], docs/model.md section 17) "
        "and their figure shift_effort.png.",
        "ballcvt map --out map_dir --clamp 2000 --speed 2000 --n-ratio 31 --n-torque 35",
    )
    o.add(p, "arch", *o.CLAMP_OPTIONS, "speed", *o.FLUID_OPTIONS, "life", "life-model", "material")
    p.add_argument(
        "--shift-effort",
        action="store_true",
        help="add the holding, tilt-direct shift and skew-axis moments of every point "
        "(docs/model.md section 17)",
    )
    add_tilt_rate(p)
    o.out(p, "ballcvt-map")
    o.grid_options(
        p, n_ratio=31, n_torque=35, most=1000, torque_max="1.02 x the largest limiting torque"
    )
    o.run_options(p)
    add_oil_option(p, "balance")
    add_mode_options(p, "the torques are the driven member's load torques")


def run(args) -> int:
    """Compute the map; write map.nc, map.csv and the figure; print a summary."""
    grid = MapGrid(tuple(args.ratio_range), args.n_ratio, args.torque_max, args.n_torque)
    out = check_output_dir(args.out)
    v = o.variator(args)
    mode = mode_of(args)
    ds = v.efficiency_map(
        grid,
        input_speed_rpm=o.rpm(args.speed),
        **o.law(args),
        workers=args.workers,
        progress=o.show(args),
        mode=mode,
    )
    if args.life:
        ds = v.map_life(ds, life_model=args.life_model, material=args.material)
    if args.shift_effort:
        ds = v.map_shift_effort(ds, tilt_rate=deg_to_rad(args.tilt_rate or 0.0))
    _write(ds, out, args)
    if args.quiet:
        return 0
    st = ds.status.values
    if not mode.is_default:
        o.emit(_mode_summary(ds, out, v.design.name))
        return 0
    o.emit(
        f"wrote {out}/map.png, map.svg, map.nc, map.csv ({v.design.name}): "
        f"{int((st == 0).sum())} of {st.size} points converged within the limit, "
        f"{int((st == 1).sum())} beyond the limiting torque, {int((st == 2).sum())} not "
        f"converged; {int((ds.warnings.values != 0).sum())} with validity warnings; max eta "
        f"{float(ds.eta.max()):.4f}; {ds.attrs['run_time_s']:.1f} s on "
        f"{args.workers} worker(s)"
    )
    if args.shift_effort:
        o.emit(
            f"shift effort at {args.tilt_rate or 0.0:g} deg/s: shift moment up to "
            f"{float(np.nanmax(np.abs(ds.shift_moment.values))):.4g} N m per ball, "
            f"{float(np.nanmax(np.abs(ds.shifter_moment.values))):.4g} N m at the shifter; "
            f"{int(np.nansum(ds.shift_saturated.values))} point(s) with a contact saturated; "
            f"wrote {out}/shift_effort.png, shift_effort.svg"
        )
    if (st == 1).sum() > st.size / 2:
        print(
            f"note: most points lie beyond the limiting torque (max "
            f"{float(np.nanmax(ds.limit_torque.values)):.1f} N m); lower --torque-max",
            file=sys.stderr,
        )
    return 0


def _write(ds, out, args) -> None:
    """map.nc, the figure (map.png, map.svg) and map.csv in ``out``."""
    import matplotlib

    matplotlib.use("Agg")  # the CLI writes files only
    from ...plotting import efficiency_map, save, shift_effort_map

    to_netcdf(ds, out / "map.nc")
    one = _for_figure(ds.squeeze(drop=True))
    save(
        efficiency_map(
            one.ratio.values,
            one.output_torque.values,
            one.eta.values,
            one.limit_torque.values,
            f"{ds.attrs.get('design_name', o.variator(args).design.name)}\nEfficiency map, "
            f"{args.arch} idler, {o.clamp_label(args)}, {args.speed:g} rpm"
            + (f"\n{ds.attrs['mode']}" if "mode" in ds.attrs else ""),
            limit_eta=one.eta_at_limit.values,
            life=one.l10_hours.transpose("ratio", "output_torque").values if args.life else None,
        ),
        out,
        "map",
    )
    if args.shift_effort:
        save(
            shift_effort_map(
                one.ratio.values,
                one.output_torque.values,
                one.shift_moment.transpose("ratio", "output_torque").values,
                one.limit_torque.values,
                f"{ds.attrs.get('design_name', '')}\nShift moment per ball at "
                f"{args.tilt_rate or 0.0:g} deg/s (tilt-direct), {args.speed:g} rpm",
            ),
            out,
            "shift_effort",
        )
    # last: the CSV writer's library (polars, ~35 MB) then loads after the figure's peak
    to_csv(ds, out / "map.csv")


#: Most ratios and torques a figure draws: a larger map is drawn on every k-th of them
#: (ends kept). Its triangulated contours would otherwise cost gigabytes and a long SVG
#: for no visible difference (a 1000 x 1000 map: 2 million triangles on 860 pixels).
FIGURE_POINTS = 250


def _for_figure(one):
    """``one`` thinned to at most `FIGURE_POINTS` ratios and torques (the data files
    keep every point)."""
    pick = {}
    for dim in ("ratio", "output_torque"):
        n = one.sizes.get(dim, 1)
        if n > FIGURE_POINTS:
            pick[dim] = np.unique(np.round(np.linspace(0, n - 1, FIGURE_POINTS)).astype(int))
    return one.isel(pick) if pick else one


def _mode_summary(ds, out, design: str) -> str:
    """The summary line of a map in a planetary mode."""
    st = ds.status.values
    return (
        f"wrote {out}/map.png, map.svg, map.nc, map.csv ({design}; {ds.attrs['mode']}, "
        f"torques are the load torques of the driven member): {int((st == 0).sum())} of "
        f"{st.size} points converged within the limit, {int((st == 1).sum())} beyond it, "
        f"{int((st == 2).sum())} not converged, {int((st == 3).sum())} with speeds out of "
        f"range; max eta {float(ds.eta.max()):.4f}"
    )
