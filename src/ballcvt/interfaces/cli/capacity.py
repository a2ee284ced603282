"""``ballcvt capacity``: the traction capacity over a ratio range, with what sets it."""

from __future__ import annotations

import numpy as np

from ...api import capacity_curve
from ...files import atomic_path, check_output_dir
from . import options as o
from .oil_option import add_oil_option


def add_parser(subparsers) -> None:
    """Add ``capacity`` and its options."""
    p = o.sub(
        subparsers,
        "capacity",
        "traction capacity over a ratio range, with its active constraint",
        "The admissible output torques (as in `ballcvt limit`) at --points ratios from "
        "--ratio-range LO to HI, and at each the constraint that sets the largest: creep "
        "at a named contact, pressure (max_pressure, cam law), or no equilibrium. Writes "
        "capacity.csv (ratio, limit_torque [N m], lowest_torque [N m], active_constraint, "
        "lower_constraint, n_intervals, intervals; limit_torque empty where no torque is "
        "admissible) and capacity.png, capacity.svg in --out.",
        "ballcvt capacity --design hub --clamp-law cam --ratio-range 0.5 2 --points 7",
    )
    o.add(p, "arch", *o.CLAMP_OPTIONS, "speed", "creep-limit", *o.FLUID_OPTIONS)
    p.add_argument(
        "--ratio-range",
        type=o.number,
        nargs=2,
        default=(0.5, 2.0),
        metavar=("LO", "HI"),
        help="ratio range (default: 0.5 2)",
    )
    p.add_argument("--points", type=o.count(2, 200), default=7, help="ratios, 2-200 (default: 7)")
    o.out(p, "ballcvt-capacity")
    add_oil_option(p, "balance")
    p.add_argument("--quiet", action="store_true", help="no summary")


def run(args) -> int:
    """Find the capacity at each ratio; write capacity.csv and the figure."""
    out = check_output_dir(args.out)
    v = o.variator(args)
    lo, hi = args.ratio_range
    curve = capacity_curve(
        v,
        np.linspace(lo, hi, args.points),
        **o.law(args),
        input_speed_rpm=o.rpm(args.speed),
        creep_limit=args.creep_limit,
    )
    frame = curve.to_frame()
    with atomic_path(out / "capacity.csv") as tmp:
        frame.to_csv(tmp, index=False, float_format="%.6g")
    _figure(frame, out, args, v.design.name)
    if not args.quiet:
        o.emit(_summary(frame, out))
    return 0


def _figure(frame, out, args, design: str) -> None:
    """capacity.png and capacity.svg in ``out``."""
    import matplotlib

    matplotlib.use("Agg")  # the CLI writes files only
    from ...plotting import capacity_figure, save

    title = f"Traction capacity, {design}\n{args.arch} idler, {o.clamp_label(args)}, "
    save(capacity_figure(frame, title + f"{args.speed:g} rpm"), out, "capacity")


def _summary(frame, out) -> str:
    """One line per ratio: its largest admissible torque and what sets it."""
    rows = [
        f"  ratio {r:.4g}: {t:.2f} N m, set by {a}"
        if np.isfinite(t)
        else f"  ratio {r:.4g}: none admissible ({a})"
        for r, t, a in zip(frame["ratio"], frame["limit_torque"], frame["active_constraint"])
    ]
    return f"wrote {out}/capacity.csv, capacity.png, capacity.svg\n" + "\n".join(rows)
