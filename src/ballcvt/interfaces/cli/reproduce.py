"""``ballcvt reproduce``: recompute every result of the paper (figures, data, report)."""

from __future__ import annotations

from . import options as o


def add_parser(subparsers) -> None:
    """Add ``reproduce`` and its options."""
    p = o.sub(
        subparsers,
        "reproduce",
        "recompute every result of the paper: figures, data and report",
        "Recompute every result figure and stated number of the paper on the Table I "
        "drive: figNN.png/.svg/.csv, data/NAME.nc, claims.csv, report.md and report.html "
        "in --out.",
        "ballcvt reproduce --out reproduction --quick --workers 2",
    )
    o.out(p, "ballcvt-reproduction")
    p.add_argument("--quick", action="store_true", help="coarse grids (seconds)")
    o.add(p, "traction-law")
    o.run_options(p)


def run(args) -> int:
    """Run the reproduction; print where the report is and how many claims agree."""
    import matplotlib

    matplotlib.use("Agg")  # the CLI writes files only
    from ...reports import reproduce

    r = reproduce(
        args.out,
        quick=args.quick,
        workers=args.workers,
        progress=o.show(args),
        traction_law=args.traction_law,
    )
    n_agree = sum(c.verdict == "agrees" for c in r.claims)
    if not args.quiet:
        o.emit(
            f"wrote {len(r.files)} files to {r.out} (report: {r.out / 'report.html'}); "
            f"{n_agree} of {len(r.claims)} claims agree; run time {r.run_time:.1f} s on "
            f"{args.workers} worker(s)"
        )
    return 0
