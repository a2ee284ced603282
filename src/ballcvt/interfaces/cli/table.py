"""``ballcvt table``: lookup tables (ratio x input speed x torque) for system simulation."""

from __future__ import annotations

from ...api import TableGrid, to_netcdf, write_tables
from ...files import check_output_dir
from . import options as o
from .oil_option import add_oil_option


def add_parser(subparsers) -> None:
    """Add ``table`` and its options."""
    p = o.sub(
        subparsers,
        "table",
        "lookup tables (ratio x input speed x torque) for system "
        "simulation: CSV, MATLAB .mat, Modelica",
        "Efficiency, input torque and losses over ideal ratio x input speed x output "
        "torque under a clamping law, as table.csv, table.mat (Simscape table-based "
        "blocks), table_modelica.txt (Modelica CombiTable2Ds) and table.nc in --out "
        "(layout: docs/cycles.md). Beyond the traction capacity the .mat and Modelica "
        "tables hold the value at the limit; status and limit_torque say where.",
        "ballcvt table --design hub --clamp-law cam --speed-range 100 3000 --n-speed 6 "
        "--out tables",
    )
    o.add(p, "arch", *o.CLAMP_OPTIONS, *o.FLUID_OPTIONS)
    o.grid_options(
        p,
        n_ratio=16,
        n_torque=20,
        most=200,
        torque_max="the largest limiting torque; torques start at 0",
    )
    p.add_argument(
        "--speed-range",
        type=o.quantity("speed", "rpm", most=o.MOST_RPM),
        nargs=2,
        default=(500.0, 4000.0),
        metavar=("MIN", "MAX"),
        help="input speed range [rpm] (default: 500 4000)",
    )
    p.add_argument(
        "--n-speed",
        type=o.count(2, 100),
        default=5,
        help="input speeds, 2-100 (default: %(default)s)",
    )
    o.out(p, "ballcvt-table")
    o.run_options(p)
    add_oil_option(p, "balance")


def run(args) -> int:
    """Compute the table; write table.nc and the tables; print a summary."""
    grid = TableGrid(
        tuple(args.ratio_range),
        args.n_ratio,
        args.torque_max,
        args.n_torque,
        tuple(args.speed_range),
        args.n_speed,
    )
    out = check_output_dir(args.out)
    v = o.variator(args)
    ds = v.lookup_table(grid, **o.law(args), workers=args.workers, progress=o.show(args))
    to_netcdf(ds, out / "table.nc")
    write_tables(ds, out)
    if not args.quiet:
        st = ds.status.values
        o.emit(
            f"wrote {out}/table.csv, table.mat, table_modelica.txt, table.nc "
            f"({grid.n_ratio} ratios x {grid.n_speed} speeds x {args.n_torque} torques, "
            f"{v.design.name}, {args.clamp_law} clamping): {int((st == 0).sum())} points "
            f"within the capacity, {int((st == 1).sum())} beyond, {int((st == 2).sum())} "
            f"not converged; {ds.attrs['run_time_s']:.1f} s on {args.workers} worker(s)"
        )
    return 0
