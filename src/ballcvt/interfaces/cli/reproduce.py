"""``ballcvt reproduce``: recompute every result of the paper (figures, data, report)."""

from __future__ import annotations

from ...api import Variator, open_drive
from . import options as o


def add_parser(subparsers) -> None:
    """Add ``reproduce`` and its options."""
    p = o.sub(
        subparsers,
        "reproduce",
        "recompute every result of the paper: figures, data and report",
        "Recompute every result figure and stated number of the paper on the Table I "
        "drive: figNN.png/.svg/.csv, data/NAME.nc, claims.csv, report.md and report.html "
        "in --out. --design, --fluid and --creep-limit recompute them on another drive "
        "(the claims still quote the paper's values; the report names the drive).",
        "ballcvt reproduce --out reproduction --quick --workers 2",
    )
    o.out(p, "ballcvt-reproduction")
    p.add_argument("--quick", action="store_true", help="coarse grids (seconds)")
    o.add(p, "traction-law", "design", "fluid", "creep-limit")
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
        **_drive(args),
    )
    n_agree = sum(c.verdict == "agrees" for c in r.claims)
    if not args.quiet:
        o.emit(
            f"wrote {len(r.files)} files to {r.out} (report: {r.out / 'report.html'}); "
            f"{n_agree} of {len(r.claims)} claims agree; run time {r.run_time:.1f} s on "
            f"{args.workers} worker(s)"
        )
    return 0


def _drive(args) -> dict:
    """``traction_law`` alone (the paper's drive), or ``drive``: the Variator of
    ``--design``, ``--fluid``, ``--traction-law`` and ``--creep-limit``."""
    if args.design is None and args.fluid is None and args.creep_limit is None:
        return {"traction_law": args.traction_law}
    design, fluid = open_drive(args.design, args.fluid, args.traction_law)
    if args.creep_limit is not None:
        design = design.replace(creep_limit=args.creep_limit)
    return {"drive": Variator(design, fluid)}
