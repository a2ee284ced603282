"""``ballcvt point``: solve one operating point (default: the paper's)."""

from __future__ import annotations

import math

from ...api import MEMBERS, OperatingMode, PlanetaryResult, SolveSettings
from ...errors import InputError
from ...units import rpm_to_rad_s
from . import options as o
from .format import planetary_table, point_table


def add_parser(subparsers) -> None:
    """Add ``point`` and its options."""
    p = o.sub(
        subparsers,
        "point",
        "solve one operating point (default: the paper's)",
        "Solve the steady operating point: ratio and tilt, creep, spin, traction, "
        "pressure and film at every contact, the losses and the efficiency (Eq. 38 and "
        "Eq. 39), with validity warnings. A torque beyond the traction capacity is "
        "refused with the limiting torque.",
        "ballcvt point --arch double --ratio 1.76 --torque 40 --clamp 2000 --speed 2000\n"
        "  ballcvt point --held disc0 --driver carrier --ratio 0.8 --torque 20 --speed 600",
    )
    o.add(p, "arch", "ratio", "torque", *o.CLAMP_OPTIONS, "speed", *o.FLUID_OPTIONS, "json")
    p.add_argument(
        "--held",
        choices=MEMBERS,
        default="carrier",
        help="member held at zero speed (default: carrier, the paper's drive); "
        "with another, --torque is the driven member's load torque and "
        "--speed the driver's speed (docs/model.md section 13)",
    )
    p.add_argument(
        "--driver",
        choices=MEMBERS,
        default="disc0",
        help="member whose speed --speed gives (default: disc0); the third member is driven",
    )
    p.add_argument(
        "--held-speed",
        type=o.quantity("held_speed", "rpm", above=-o.MOST_RPM, most=o.MOST_RPM),
        default=0.0,
        metavar="RPM",
        help="speed of the --held member [rpm] (default 0: held); another value "
        "makes the drive a free differential",
    )
    p.add_argument(
        "--no-centrifugal",
        action="store_true",
        help="leave out the balls' centrifugal force with the carrier turning",
    )
    p.add_argument(
        "--no-gyroscopic",
        action="store_true",
        help="leave out the balls' gyroscopic moment with the carrier turning",
    )


def run(args) -> int:
    """Solve the point; print it as a table or JSON."""
    v = o.variator(args)
    if not math.isfinite(args.held_speed):
        raise InputError("held_speed", args.held_speed, "finite (rpm)")
    mode = OperatingMode(
        args.held,
        args.driver,
        not args.no_centrifugal,
        not args.no_gyroscopic,
        rpm_to_rad_s(args.held_speed),
    )
    r = v.solve(
        ratio=args.ratio,
        output_torque=args.torque,
        **o.law(args),
        input_speed_rpm=o.rpm(args.speed),
        settings=SolveSettings(mode=mode),
    )
    if args.json:
        o.emit_json_text(r.to_json())
    else:
        o.emit(planetary_table(r) if isinstance(r, PlanetaryResult) else point_table(r))
    return 0
