"""``ballcvt map``: efficiency map (ratio x output torque) as data and figure."""

from __future__ import annotations

import sys

import numpy as np

from ...api import MapGrid, to_csv, to_netcdf
from ...files import check_output_dir
from . import options as o


def add_parser(subparsers) -> None:
    """Add ``map`` and its options."""
    p = o.sub(
        subparsers,
        "map",
        "efficiency map (ratio x output torque) as data and figure",
        "Efficiency over ideal ratio x output torque at one clamping force and speed, "
        "with the limiting-torque curve: map.png, map.svg, map.nc (NetCDF-4, CF) and "
        "map.csv in --out. Points beyond the limit have status 1.",
        "ballcvt map --out map_dir --clamp 2000 --speed 2000 --n-ratio 31 --n-torque 35",
    )
    o.add(p, "arch", *o.CLAMP_OPTIONS, "speed", *o.FLUID_OPTIONS)
    o.out(p, "ballcvt-map")
    o.grid_options(
        p, n_ratio=31, n_torque=35, most=1000, torque_max="1.02 x the largest limiting torque"
    )
    o.run_options(p)


def run(args) -> int:
    """Compute the map; write map.nc, map.csv and the figure; print a summary."""
    grid = MapGrid(tuple(args.ratio_range), args.n_ratio, args.torque_max, args.n_torque)
    out = check_output_dir(args.out)
    v = o.variator(args)
    ds = v.efficiency_map(
        grid,
        input_speed_rpm=o.rpm(args.speed),
        **o.law(args),
        workers=args.workers,
        progress=o.show(args),
    )
    _write(ds, out, args)
    if args.quiet:
        return 0
    st = ds.status.values
    o.emit(
        f"wrote {out}/map.png, map.svg, map.nc, map.csv ({v.design.name}): "
        f"{int((st == 0).sum())} of {st.size} points converged within the limit, "
        f"{int((st == 1).sum())} beyond the limiting torque, {int((st == 2).sum())} not "
        f"converged; {int((ds.warnings.values != 0).sum())} with validity warnings; max eta "
        f"{float(ds.eta.max()):.4f}; {ds.attrs['run_time_s']:.1f} s on "
        f"{args.workers} worker(s)"
    )
    if (st == 1).sum() > st.size / 2:
        print(
            f"note: most points lie beyond the limiting torque (max "
            f"{float(np.nanmax(ds.limit_torque.values)):.1f} N m); lower --torque-max",
            file=sys.stderr,
        )
    return 0


def _write(ds, out, args) -> None:
    """map.nc, map.csv and the figure (map.png, map.svg) in ``out``."""
    import matplotlib

    matplotlib.use("Agg")  # the CLI writes files only
    from ...plotting import efficiency_map, save

    to_netcdf(ds, out / "map.nc")
    to_csv(ds, out / "map.csv")
    one = ds.squeeze(drop=True)
    save(
        efficiency_map(
            one.ratio.values,
            one.output_torque.values,
            one.eta.values,
            one.limit_torque.values,
            f"{ds.attrs['design_name']}\nEfficiency map, {args.arch} idler, "
            f"{o.clamp_label(args)}, {args.speed:g} rpm",
            limit_eta=one.eta_at_limit.values,
        ),
        out,
        "map",
    )
