"""The ``ballcvt`` command line: parse, dispatch, exit status.

Every subcommand has only the options it uses, a description and an example
(``ballcvt SUBCOMMAND --help``); each lives in its own module of this package (its
``add_parser`` and ``run``), on the public API (`ballcvt.api`). Output locations are checked
before any computing starts. Options are never abbreviated (``--rat`` is not ``--ratio``).

Exit status (docs/cli.md, "Exit codes"), always with one line on stderr:

- 0 success;
- 1 a failure of the environment: an output stream that cannot be written (a full disk), a
  Dask scheduler that cannot be reached, an address that cannot be bound, any other
  operating-system error; also a bug ("internal error"; ``BALLCVT_DEBUG=1`` gives the
  traceback);
- 2 bad input, a torque beyond the traction capacity, no equilibrium, or an output
  location that cannot be written (naming the quantity, its value and the allowed range or
  the cause);
- 141 (quietly, 128 + SIGPIPE) when the reader of standard output went away (``| head``).

Numerical RuntimeWarnings never reach the user: a result that went non-finite is reported
by its status or refused with exit 2.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
import warnings

from ..._version import __version__
from ...errors import BallCVTError, UnitHintWarning
from . import (
    capacity,
    clamp,
    cycle,
    design,
    explore,
    explore_ui,
    fit_fluid,
    life,
    limit,
    options,
    point,
    reproduce,
    shift,
    table,
    traction_curve,
    uncertainty,
)
from . import map as efficiency_map

__all__ = ["main", "build_parser", "COMMANDS"]

#: Command name -> its module (``add_parser(subparsers)``, ``run(args) -> exit status``),
#: in the order of ``ballcvt --help``.
COMMANDS = {
    "point": point,
    "limit": limit,
    "capacity": capacity,
    "clamp": clamp,
    "map": efficiency_map,
    "cycle": cycle,
    "shift": shift,
    "life": life,
    "table": table,
    "reproduce": reproduce,
    "traction-curve": traction_curve,
    "fit-fluid": fit_fluid,
    "explore": explore,
    "explore-ui": explore_ui,
    "design": design,
    "uncertainty": uncertainty,
}


class _Parser(argparse.ArgumentParser):
    """argparse that reports usage errors in one line with exit status 2."""

    def __init__(self, *args, **kwargs) -> None:
        super().__init__(*args, **{"allow_abbrev": False, **kwargs})

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
    argv = sys.argv[1:] if argv is None else list(argv)
    args = build_parser().parse_args(argv)
    with _open_stdout():
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", RuntimeWarning)
                warnings.showwarning = _show_warning
                options.apply_operating(args, argv)  # where the drive runs (typed flags win)
                code = COMMANDS[args.command].run(args)
            return _flushed(code)
        except BrokenPipeError:  # the reader went away (| head): quiet, as Unix tools are
            _discard_stdout()
            return 141
        except BallCVTError as exc:  # bad input, beyond capacity, no equilibrium: exit 2
            return _say(f"error: {exc.restated(_typed(args))}", 2)
        except KeyboardInterrupt:
            return _say("interrupted", 130)
        except OSError as exc:  # the environment: a full disk, a network, a device
            if exc.filename is None:  # a stream (standard output): drop what it holds
                _discard_stdout()
            return _say(f"error: {_environment(exc)}", 1)
        except Exception as exc:  # a bug: say so in one line unless debugging
            if os.environ.get("BALLCVT_DEBUG"):
                raise
            return _say(
                f"internal error: {type(exc).__name__}: {exc} "
                "(set BALLCVT_DEBUG=1 for a traceback)",
                1,
            )


_SHOW_WARNING = warnings.showwarning


def _show_warning(message, category, filename, lineno, file=None, line=None) -> None:
    """A unit hint as one line ``ballcvt: warning: ...``; other warnings as Python shows
    them."""
    if issubclass(category, UnitHintWarning):
        _say(f"warning: {message}", 0)
    else:
        _SHOW_WARNING(message, category, filename, lineno, file, line)


def _typed(args) -> dict[str, str]:
    """The quantities of an error message as the user typed them: the flag and its unit
    (``input speed 209.44 rad/s`` becomes ``--speed 2000 rpm``; `BallCVTError.restated`)."""
    terms = {}
    if getattr(args, "speed", None) is not None:
        terms["input_speed"] = f"--speed {args.speed:g} rpm"
    if getattr(args, "clamp", None) is not None:
        terms["clamp_force"] = f"--clamp {args.clamp:g} N"
    return terms


def _say(message: str, code: int) -> int:
    """One line ``ballcvt: MESSAGE`` on stderr (if there is a stderr); returns ``code``."""
    print(f"ballcvt: {message}", file=sys.stderr)
    return code


def _flushed(code: int) -> int:
    """Flush standard output now, so that a broken pipe or a full disk shows here (one line,
    or quiet for a pipe) rather than as a traceback at the interpreter's exit."""
    try:
        sys.stdout.flush()
    except BrokenPipeError:
        raise
    except OSError as exc:
        _discard_stdout()
        return _say(f"error: cannot write to standard output: {_environment(exc)}", 1)
    return code


def _environment(exc: OSError) -> str:
    """One line naming an operating-system failure and the file it concerns."""
    cause = exc.strerror or str(exc) or type(exc).__name__
    where = f": {exc.filename}" if exc.filename else ""
    return f"{cause}{where}"


def _discard_stdout() -> None:
    """Point standard output at the null device, so that nothing more (not even the
    interpreter's flush at exit) writes to a stream that failed."""
    try:
        fd = sys.stdout.fileno()
    except (AttributeError, OSError, ValueError):  # not a real file (a test's capture)
        return
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, fd)
    os.close(devnull)


@contextlib.contextmanager
def _open_stdout():
    """A closed standard output (``>&-``) writes to the null device: the command still
    runs and writes its files, and prints nothing."""
    if sys.stdout is not None:
        yield
        return
    with open(os.devnull, "w") as sink:
        sys.stdout = sink
        try:
            yield
        finally:
            sys.stdout = None  # type: ignore[assignment]


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
