"""``ballcvt design``: show or export the drive definition as TOML."""

from __future__ import annotations

import sys
from pathlib import Path

from ...api import drive_text
from ...errors import InputError
from ...files import atomic_write_text, check_output_file
from . import options as o


def add_parser(subparsers) -> None:
    """Add ``design`` and its options."""
    p = o.sub(
        subparsers,
        "design",
        "show or export the drive definition as TOML",
        "Print the drive definition (the built-in Table I drive, with its sources, or "
        "--design FILE after validation), or write it to PATH.",
        "ballcvt design export my_drive.toml",
    )
    p.add_argument("action", choices=("show", "export"))
    p.add_argument(
        "path", nargs="?", type=Path, help="output file of 'export' (required for export)"
    )
    o.add(p, *o.FLUID_OPTIONS)


def run(args) -> int:
    """Print the drive's TOML, or write it to PATH."""
    if args.action == "export" and args.path is None:
        raise InputError(
            "path",
            None,
            "an output file",
            message="design export needs PATH (use 'design show' to print)",
        )
    if args.action == "show" and args.path is not None:
        raise InputError(
            "path",
            str(args.path),
            "no PATH with 'show'",
            message="design show takes no PATH (use 'design export PATH')",
        )
    if args.path is not None:
        check_output_file(args.path, "PATH")
    text = drive_text(args.design, args.fluid, args.traction_law)
    if args.action == "export":
        atomic_write_text(args.path, text)
        print(f"wrote {args.path}", file=sys.stderr)
    else:
        o.emit(text.removesuffix("\n"))
    return 0
