"""``ballcvt traction-curve``: traction coefficient vs slide-to-roll ratio of one contact."""

from __future__ import annotations

import numpy as np

from ...api import contact_fluid, traction_curve
from ...errors import InputError
from ...files import atomic_write_text, check_output_dir
from . import options as o


def add_parser(subparsers) -> None:
    """Add ``traction-curve`` and its options."""
    p = o.sub(
        subparsers,
        "traction-curve",
        "traction coefficient vs slide-to-roll ratio of one contact (twin-disc or ball-on-disc)",
        "Traction coefficient mu and spin-moment coefficient chi of one elliptical "
        "contact against the slide-to-roll ratio, under any traction law (docs/model.md "
        "section 14): traction_curve.csv, .png and .svg in --out, or --json.",
        "ballcvt traction-curve --law thermal --rx 0.02 --ry 0.05 --load 1400 "
        "--speed 10 --spin 0 --creep-max 0.08",
    )
    o.law_option(p, "traction law (default: the fluid's own)")
    for flag, what in (("--rx", "along"), ("--ry", "across")):
        p.add_argument(
            flag,
            type=o.quantity(flag[2:], "m", above=1e-6, most=1e3),
            required=True,
            metavar="M",
            help=f"equivalent radius {what} the rolling direction [m]",
        )
    group = p.add_mutually_exclusive_group(required=True)
    group.add_argument(
        "--load",
        type=o.quantity("load", "N", most=o.MOST_FORCE),
        metavar="N",
        help="normal load [N]",
    )
    group.add_argument(
        "--pmax",
        type=o.quantity("p_max", "Pa", most=o.MOST_PRESSURE),
        metavar="PA",
        help="Hertz peak pressure [Pa]",
    )
    p.add_argument(
        "--speed",
        type=o.quantity("speed", "m/s", most=1e3),
        required=True,
        metavar="M_PER_S",
        help="rolling (entrainment) speed [m/s]",
    )
    p.add_argument(
        "--spin",
        type=o.number,
        default=0.0,
        metavar="S",
        help="spin-to-roll ratio omega_spin R_x / U [-] (default: 0)",
    )
    p.add_argument(
        "--creep-max",
        type=o.number,
        default=0.1,
        metavar="C",
        help="largest slide-to-roll ratio, 0 < C < 2 (default: 0.1)",
    )
    p.add_argument(
        "--n-creep",
        type=o.count(2, 2001),
        default=101,
        help="points on the curve, 2-2001 (default: 101)",
    )
    o.add(p, "fluid", "design")
    o.out(p, "ballcvt-traction-curve")
    o.add(p, "json")


def run(args) -> int:
    """Compute the curve; print JSON, or write the CSV and figure and print a summary."""
    if not 0 < args.creep_max < 2:
        raise InputError("creep_max", args.creep_max, "0 < C < 2")
    fluid, modulus = contact_fluid(args.design, args.fluid, args.traction_law)
    curve = traction_curve(
        fluid,
        rx=args.rx,
        ry=args.ry,
        speed=args.speed,
        creep=np.linspace(0.0, args.creep_max, args.n_creep),
        load=args.load,
        p_max=args.pmax,
        spin=args.spin,
        reduced_modulus=modulus,
    )
    if args.json:
        o.emit_json(curve.as_dict())
        return 0
    out = check_output_dir(args.out)
    import pandas as pd

    columns = {"creep": curve.creep, "mu": curve.mu, "chi": curve.chi}
    frame = pd.DataFrame({**columns, "temperature_rise_K": curve.temperature_rise})
    atomic_write_text(out / "traction_curve.csv", frame.to_csv(index=False))
    c = curve.conditions
    _figure(curve, out, f"{fluid.name}: {curve.law} law, p_max {c['p_max'] / 1e9:.2f} GPa, ")
    peak = int(np.argmax(curve.mu))
    o.emit(
        f"wrote {out}/traction_curve.csv, .png, .svg: {curve.law} law, p_max "
        f"{c['p_max'] / 1e9:.3f} GPa, film {c['film'] * 1e6:.3f} um; mu peaks at "
        f"{curve.mu[peak]:.4f} at slide-to-roll {curve.creep[peak]:.4f}"
    )
    return 0


def _figure(curve, out, title: str) -> None:
    """traction_curve.png and .svg in ``out``."""
    import matplotlib

    matplotlib.use("Agg")
    from ...plotting import save, traction_curve_figure

    c = curve.conditions
    title += f"U {c['speed']:g} m/s, spin {c['spin']:g}"
    save(traction_curve_figure([curve], title), out, "traction_curve")
