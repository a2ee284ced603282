"""``ballcvt design``: show or export the drive definition as TOML, or size its cam.

``show``, ``export PATH`` and ``size-cam`` are subcommands of their own, so that the drive
options may stand before or after them and before or after ``PATH`` (``design export
--design hub FILE`` and ``design --design hub export FILE`` alike). What fits the geometry
but looks meant for another design is said on stderr, one ``warning:`` line each.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from ...api import drive_text, drive_to_toml, drive_warnings, size_cam
from ...errors import InputError
from ...files import atomic_write_text, check_output_file
from . import options as o

_EPILOG = "ballcvt design export --design hub my_drive.toml"


def add_parser(subparsers) -> None:
    """Add ``design`` with its subcommands ``show``, ``export`` and ``size-cam``."""
    p = o.sub(
        subparsers,
        "design",
        "show or export the drive definition as TOML, or size its cam",
        "Print the drive definition (the built-in Table I drive, with its sources, or "
        "--design FILE after validation), write it to PATH, or size its loading cam.",
        _EPILOG,
    )
    o.add(p, *o.FLUID_OPTIONS)
    sub = p.add_subparsers(dest="action", required=True, parser_class=type(p))
    show = sub.add_parser("show", help="print the drive's TOML", allow_abbrev=False)
    export = sub.add_parser("export", help="write the drive's TOML to PATH", allow_abbrev=False)
    export.add_argument("path", nargs="?", type=Path, help="output file (required)")
    cam = sub.add_parser(
        "size-cam",
        help="size the cam's preload and ramp angle for the rated torque",
        description="Size [design.cam] preload and ramp_angle_deg so that, over the "
        "drive's ratio range ([operating] ratio_range, else the usable range) at its input "
        "speed, every torque from 0 to the rated torque ([operating] rated_torque, else "
        "the constant-clamp capacity at [operating] clamp_force or 2000 N) keeps every "
        "creep within creep_limit / margin and every pressure within max_pressure. "
        "Prints the drive's TOML with the sized cam, or writes it to --out.",
        allow_abbrev=False,
    )
    cam.add_argument(
        "--margin",
        type=o.quantity("margin", "-", above=0.0, most=10.0),
        default=1.2,
        help="safety factor on the creep limit (default: %(default)s)",
    )
    cam.add_argument("--out", type=Path, default=None, help="output file (default: stdout)")
    for child in (show, export, cam):  # the drive options, also after the subcommand
        for name, keywords in o.options().items():
            if name in o.FLUID_OPTIONS:
                child.add_argument(f"--{name}", **{**keywords, "default": argparse.SUPPRESS})


def run(args) -> int:
    """Print the drive's TOML, write it to PATH, or size its cam."""
    out = getattr(args, "path", None) if args.action == "export" else getattr(args, "out", None)
    if args.action == "export" and out is None:
        raise InputError(
            "path",
            None,
            "an output file",
            message="design export needs PATH (use 'design show' to print)",
        )
    if out is not None:
        check_output_file(out, "PATH" if args.action == "export" else "--out")
    text = drive_text(args.design, args.fluid, args.traction_law, args.lubrication)
    v = o.variator(argparse.Namespace(**{**vars(args), "arch": "double"}))
    if args.action == "size-cam":
        sized = size_cam(v, margin=args.margin)
        text = drive_to_toml(sized.design, v.fluid, template=text)
        lo, hi = sized.ratios[0], sized.ratios[-1]
        print(
            f"ballcvt: sized [design.cam] preload = {sized.cam.preload:g} N, ramp_angle_deg = "
            f"{sized.cam.ramp_angle_deg:g} deg: 0 to {sized.rated_torque:.4g} N m within "
            f"creep {sized.creep_limit:.3g} over ratios {lo:.3g}-{hi:.3g}",
            file=sys.stderr,
        )
    else:
        for line in drive_warnings(v):
            print(f"ballcvt: warning: {line}", file=sys.stderr)
    if out is not None:
        atomic_write_text(out, text)
        print(f"wrote {out}", file=sys.stderr)
    else:
        o.emit(text.removesuffix("\n"))
    return 0
