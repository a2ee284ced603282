"""The planetary-mode options shared by ``point``, ``limit``, ``map`` and ``cycle`` (docs/model.md §13):
``--held``, ``--driver``, ``--held-speed`` and the carrier effects."""

from __future__ import annotations

import math

from ...api import MEMBERS, OperatingMode
from ...errors import InputError
from ...units import rpm_to_rad_s
from . import options as o

__all__ = ["add_mode_options", "mode_of"]


def add_mode_options(
    p, what: str = "--torque is the driven member's load torque", speed: str = "--speed"
) -> None:
    """Add ``--held``, ``--driver``, ``--held-speed``, ``--no-centrifugal`` and
    ``--no-gyroscopic`` to the parser ``p``; ``what`` says what the torque means then, and
    ``speed`` names the option that gives the driver's speed."""
    p.add_argument(
        "--held",
        choices=MEMBERS,
        default="carrier",
        help="member held at zero speed (default: carrier, the paper's drive); "
        f"with another, {what} and "
        f"{speed} the driver's speed (docs/model.md section 13)",
    )
    p.add_argument(
        "--driver",
        choices=MEMBERS,
        default="disc0",
        help=f"member whose speed {speed} gives (default: disc0); the third member is driven",
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


def mode_of(args) -> OperatingMode:
    """The `OperatingMode` the options of `add_mode_options` name."""
    if not math.isfinite(args.held_speed):
        raise InputError("held_speed", args.held_speed, "finite (rpm)")
    return OperatingMode(
        args.held,
        args.driver,
        not args.no_centrifugal,
        not args.no_gyroscopic,
        rpm_to_rad_s(args.held_speed),
    )
