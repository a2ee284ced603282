"""``ballcvt shift``: the shift transient from one ratio to another (docs/shifting.md)."""

from __future__ import annotations

from ...files import check_output_dir
from . import options as o
from .oil_option import add_oil_option


def add_parser(subparsers) -> None:
    """Add ``shift`` and its options."""
    p = o.sub(
        subparsers,
        "shift",
        "the shift transient: ratio, tilt, moments and losses over time",
        "Shift from one ideal ratio to another at an operating point (the options of "
        "'ballcvt point'; the input speed is held): skew-steered (--skew: the axles are "
        "skewed and the balls tilt at the rate that rolls without side slip) or "
        "tilt-direct at a tilt rate (--tilt-rate) or under an actuator moment "
        "(--actuator-moment, which needs the contact model's shift moments), with an "
        "optional first-order actuator lag. Writes shift.csv, summary.json and "
        "shift.png/.svg in --out (docs/shifting.md).",
        "ballcvt shift --design hub --from 0.5 --to 1.8 --skew 1 --speed 114 --torque 20",
    )
    p.add_argument(
        "--from",
        dest="from_ratio",
        type=o.number,
        required=True,
        metavar="R1",
        help="start ideal ratio tau_ID [-]",
    )
    p.add_argument(
        "--to",
        dest="to_ratio",
        type=o.number,
        required=True,
        metavar="R2",
        help="target ideal ratio tau_ID [-]",
    )
    how = p.add_mutually_exclusive_group(required=True)
    how.add_argument(
        "--skew",
        type=o.number,
        metavar="DEG",
        help="skew-steered: the axles' skew angle [deg], 0 < DEG < 10",
    )
    how.add_argument(
        "--tilt-rate",
        type=o.number,
        metavar="DEG_PER_S",
        help="tilt-direct at this tilt rate [deg/s], > 0",
    )
    how.add_argument(
        "--actuator-moment",
        type=o.number,
        metavar="N_M",
        help="tilt-direct under this moment about the tilt axes of all balls [N m], > 0",
    )
    p.add_argument(
        "--actuator-lag",
        type=o.quantity("actuator_lag", "s", most=60.0),
        default=0.0,
        metavar="S",
        help="first-order time constant of the actuator [s] (default: 0)",
    )
    p.add_argument(
        "--max-time",
        type=o.quantity("max_time", "s", above=0.0, most=3600.0),
        default=60.0,
        metavar="S",
        help="longest shift integrated before it is refused [s] (default: 60)",
    )
    p.add_argument(
        "--samples",
        type=o.count(3, 10_000),
        default=51,
        help="output samples over the shift, 3-10000 (default: 51)",
    )
    o.add(p, "arch", "torque", *o.CLAMP_OPTIONS, "speed", *o.FLUID_OPTIONS, "json")
    add_oil_option(p, "balance")
    o.out(p, "ballcvt-shift")
    p.add_argument("--quiet", action="store_true", help="no summary line")


def run(args) -> int:
    """Run the shift; write shift.csv, summary.json and the figure; print a summary."""
    out = check_output_dir(args.out)
    v = o.variator(args)
    r = v.shift(
        args.from_ratio,
        args.to_ratio,
        args.torque,
        skew_deg=args.skew,
        tilt_rate_deg_s=args.tilt_rate,
        actuator_moment=args.actuator_moment,
        **o.law(args),
        input_speed_rpm=o.rpm(args.speed),
        actuator_lag=args.actuator_lag,
        samples=args.samples,
        max_time=args.max_time,
    )
    r.save(out)
    import matplotlib

    matplotlib.use("Agg")  # the CLI writes files only
    from ...plotting import save, shift_figure

    title = (
        f"{v.design.name}\n{r.mechanism} shift {r.from_ratio:g} -> {r.to_ratio:g}, "
        f"{args.speed:g} rpm, {args.torque:g} N m, {o.clamp_label(args)}"
    )
    save(shift_figure(r.samples, title), out, "shift")
    if args.json:
        o.emit_json(r.to_dict())
    elif not args.quiet:
        peak = r.peak_shift_moment_Nm
        o.emit(
            f"wrote {out}/shift.csv, summary.json, shift.png, shift.svg: {r.mechanism} "
            f"{r.from_ratio:g} -> {r.to_ratio:g} in {r.shift_time_s:.4g} s, peak shift "
            f"moment {'unknown' if peak != peak else f'{peak:.4g} N m'}, energy lost "
            f"{r.energy_lost_J:.4g} J"
        )
    return 0
