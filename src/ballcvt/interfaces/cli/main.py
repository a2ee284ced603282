"""The ``ballcvt`` command line: parse, dispatch, exit status.

Every subcommand has only the options it uses, a description and an example
(``ballcvt SUBCOMMAND --help``); each lives in its own module of this package (its
``add_parser`` and ``run``), on the public API (`ballcvt.api`). Output locations are checked
before any computing starts.

Exit status: 0 success; 2 bad input, a torque beyond the traction capacity, no equilibrium,
or an output location that cannot be written (one line on stderr naming the quantity, its
value and the allowed range or the cause); 1 a bug (one line; set ``BALLCVT_DEBUG=1`` for a
traceback).
"""

from __future__ import annotations

import argparse
import os
import sys

from ..._version import __version__
from ...errors import BallCVTError
from . import (
    clamp,
    cycle,
    design,
    explore,
    explore_ui,
    fit_fluid,
    limit,
    point,
    reproduce,
    table,
    traction_curve,
)
from . import map as efficiency_map

__all__ = ["main", "build_parser", "COMMANDS"]

#: Command name -> its module (``add_parser(subparsers)``, ``run(args) -> exit status``),
#: in the order of ``ballcvt --help``.
COMMANDS = {
    "point": point,
    "limit": limit,
    "clamp": clamp,
    "map": efficiency_map,
    "cycle": cycle,
    "table": table,
    "reproduce": reproduce,
    "traction-curve": traction_curve,
    "fit-fluid": fit_fluid,
    "explore": explore,
    "explore-ui": explore_ui,
    "design": design,
}


class _Parser(argparse.ArgumentParser):
    """argparse that reports usage errors in one line with exit status 2."""

    def error(self, message: str):  # noqa: D102
        self.exit(2, f"{self.prog}: error: {message}\n")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``ballcvt`` command (choices read from the registries)."""
    parser = _Parser(
        prog="ballcvt",
        description="Steady-state model of ball-type traction "
        "CVTs (Tomaselli et al., Mech. Mach. Theory 150 (2020) 103877).",
    )
    parser.add_argument("--version", action="version", version=f"ballcvt {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    for module in COMMANDS.values():
        module.add_parser(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    args = build_parser().parse_args(argv)
    try:
        return COMMANDS[args.command].run(args)
    except BallCVTError as exc:  # bad input, beyond capacity, no equilibrium: exit 2
        print(f"ballcvt: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("ballcvt: interrupted", file=sys.stderr)
        return 130
    except Exception as exc:  # a bug: say so in one line unless debugging
        if os.environ.get("BALLCVT_DEBUG"):
            raise
        print(
            f"ballcvt: internal error: {type(exc).__name__}: {exc} "
            "(set BALLCVT_DEBUG=1 for a traceback)",
            file=sys.stderr,
        )
        return 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
