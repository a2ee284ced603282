"""The ``ballcvt`` command line.

Exit status: 0 success, 2 bad input (one line on stderr naming the quantity, its value and
the allowed range), 1 any other failure (one line; set ``BALLCVT_DEBUG=1`` for a traceback).
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path

from .._version import __version__
from ..errors import BallCVTError, InputError
from ..params.io import builtin_text, drive_to_toml, load_builtin, load_drive
from ..params.models import ARCHITECTURES
from ..variator import Variator
from .format import clamp_table, limit_table, point_table

__all__ = ["main", "build_parser"]

PAPER_POINT = {"ratio": 1.0, "torque": 40.0, "clamp": 2000.0, "speed": 2000.0}


class _Parser(argparse.ArgumentParser):
    """argparse that reports usage errors in one line with exit status 2."""

    def error(self, message: str):  # noqa: D102
        self.exit(2, f"{self.prog}: error: {message}\n")


def _common(p: argparse.ArgumentParser, torque: bool) -> None:
    p.add_argument("--arch", default="double", choices=ARCHITECTURES,
                   help="idler architecture (default: double)")
    p.add_argument("--ratio", type=float, default=PAPER_POINT["ratio"],
                   help="ideal speed ratio tau_ID (default: %(default)s)")
    if torque:
        p.add_argument("--torque", type=float, default=PAPER_POINT["torque"],
                       help="output torque T2 [N m] (default: %(default)s)")
    p.add_argument("--clamp", type=float, default=PAPER_POINT["clamp"],
                   help="input-contact normal load F_N0 [N] (default: %(default)s)")
    p.add_argument("--speed", type=float, default=PAPER_POINT["speed"],
                   help="input speed [rpm] (default: %(default)s)")
    p.add_argument("--design", type=Path, help="drive definition TOML (default: Table I)")
    p.add_argument("--json", action="store_true", help="print one JSON object")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``ballcvt`` command."""
    parser = _Parser(prog="ballcvt", description="Steady-state model of ball-type traction "
                     "CVTs (Tomaselli et al., Mech. Mach. Theory 150 (2020) 103877).")
    parser.add_argument("--version", action="version", version=f"ballcvt {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    p = sub.add_parser("point", help="solve one operating point (default: the paper's)")
    _common(p, torque=True)
    p = sub.add_parser("limit", help="limiting output torque at a ratio, clamp and speed")
    _common(p, torque=False)
    p.add_argument("--creep-limit", type=float, default=None,
                   help="largest admissible |creep| (default: the design's, 0.10)")

    p = sub.add_parser("clamp", help="clamping force of maximum efficiency under the creep "
                       "and pressure limits")
    _common(p, torque=True)
    p.set_defaults(clamp=None)
    p.add_argument("--creep-limit", type=float, default=None,
                   help="largest admissible |creep| (default: the design's, 0.10)")
    p.add_argument("--max-pressure", type=float, default=None,
                   help="largest admissible Hertz peak pressure [Pa] (default: the design's)")

    p = sub.add_parser("map", help="efficiency map (ratio x output torque) as data and PNG")
    _common(p, torque=False)
    p.set_defaults(ratio=None)
    p.add_argument("--out", type=Path, default=Path("ballcvt-map"),
                   help="output directory (default: %(default)s)")
    p.add_argument("--ratio-range", type=float, nargs=2, default=(0.5, 2.0),
                   metavar=("MIN", "MAX"), help="ratio range (default: 0.5 2)")
    p.add_argument("--n-ratio", type=int, default=31, help="ratios (default: %(default)s)")
    p.add_argument("--torque-max", type=float, default=None,
                   help="largest torque [N m] (default: the largest limiting torque)")
    p.add_argument("--n-torque", type=int, default=35, help="torques (default: %(default)s)")
    _run_options(p)

    p = sub.add_parser("reproduce", help="recompute every result of the paper: figures, "
                       "data and report")
    p.add_argument("--out", type=Path, default=Path("ballcvt-reproduction"),
                   help="output directory (default: %(default)s)")
    p.add_argument("--quick", action="store_true", help="coarse grids (seconds)")
    _run_options(p)

    p = sub.add_parser("design", help="show or export the drive definition as TOML")
    p.add_argument("action", choices=("show", "export"))
    p.add_argument("path", nargs="?", type=Path, help="output file of 'export' (default: stdout)")
    p.add_argument("--design", type=Path, help="drive definition to validate and show")
    return parser


def _run_options(p):
    p.add_argument("--workers", type=int, default=1, help="processes (default: 1)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")


def _progress(args):
    return False if args.quiet else None          # None: only when stderr is a terminal


def _variator(args) -> Variator:
    design, fluid = load_drive(args.design) if args.design else load_builtin()
    return Variator(design, fluid, args.arch)


def _cmd_point(args) -> int:
    v = _variator(args)
    r = v.solve(ratio=args.ratio, output_torque=args.torque, clamp_force=args.clamp,
                input_speed_rpm=_rpm(args.speed))
    print(r.to_json(indent=2) if args.json else point_table(r))
    return 0


def _cmd_limit(args) -> int:
    v = _variator(args)
    c_lim = v.design.creep_limit if args.creep_limit is None else args.creep_limit
    t = v.limit_torque(ratio=args.ratio, clamp_force=args.clamp,
                       input_speed_rpm=_rpm(args.speed), creep_limit=c_lim)
    data = {"limit_torque": t, "architecture": args.arch, "ratio": args.ratio,
            "clamp_force": args.clamp, "input_speed_rpm": args.speed, "creep_limit": c_lim,
            "version": __version__}
    print(json.dumps(data, indent=2) if args.json else limit_table(data))
    return 0


def _cmd_clamp(args) -> int:
    v = _variator(args)
    o = v.optimal_clamp_force(ratio=args.ratio, output_torque=args.torque,
                              input_speed_rpm=_rpm(args.speed), creep_limit=args.creep_limit,
                              max_pressure=args.max_pressure)
    data = {"clamp_force": o.clamp_force, "eta": o.eta, "max_creep": o.max_creep,
            "max_pressure": o.max_pressure, "feasible_clamp_range": list(o.bounds),
            "active_constraint": o.active, "architecture": args.arch, "ratio": args.ratio,
            "output_torque": args.torque, "input_speed_rpm": args.speed,
            "version": __version__}
    print(json.dumps(data, indent=2) if args.json else clamp_table(data))
    return 0


def _cmd_map(args) -> int:
    import numpy as np

    from ..equilibrium.problem import build_problem
    from ..plotting import efficiency_map, save
    from ..solver.limit import limit_torque_batch
    from ..sweeps import to_csv, to_netcdf
    v = _variator(args)
    lo, hi = args.ratio_range
    for name, n in (("n_ratio", args.n_ratio), ("n_torque", args.n_torque)):
        if n < 2:
            raise InputError(name, n, ">= 2")
    if not 0 < lo < hi:
        raise InputError("ratio_range", f"{lo:g} {hi:g}", "0 < MIN < MAX")
    ratios = np.linspace(lo, hi, args.n_ratio)
    # the limiting torque of every ratio, found once: it sets the default torque range
    # and is handed to the sweep
    base = build_problem(v.design, v.fluid, v.architecture, ratios, 0.0, args.clamp,
                         _rpm(args.speed) * np.pi / 30.0)
    limits = limit_torque_batch(base, v.design.creep_limit, v.options)
    top = 1.02 * float(np.nanmax(limits)) if args.torque_max is None else args.torque_max
    if not top > 0:
        raise InputError("torque_max", top, "> 0 N m")
    ds = v.sweep(ratio=ratios, output_torque=np.linspace(top / args.n_torque, top,
                                                         args.n_torque),
                 clamp_force=args.clamp, input_speed_rpm=_rpm(args.speed), limit_torque=limits,
                 workers=args.workers, progress=_progress(args))
    args.out.mkdir(parents=True, exist_ok=True)
    to_netcdf(ds, args.out / "map.nc")
    to_csv(ds, args.out / "map.csv")
    one = ds.squeeze(drop=True)
    save(efficiency_map(one.ratio.values, one.output_torque.values, one.eta.values,
                        one.limit_torque.values, f"Efficiency map, {args.arch} idler, "
                        f"F_N0 = {args.clamp:g} N, {args.speed:g} rpm"), args.out, "map")
    n_ok = int((ds.status == 0).sum())
    print(f"wrote {args.out}/map.png, map.svg, map.nc, map.csv: {n_ok} of {ds.status.size} "
          f"points converged within the limit, max eta {float(ds.eta.max()):.4f}, "
          f"{ds.attrs['run_time_s']:.1f} s")
    return 0


def _cmd_reproduce(args) -> int:
    from ..reports import reproduce
    r = reproduce(args.out, quick=args.quick, workers=args.workers, progress=_progress(args))
    n_agree = sum(c.verdict == "agrees" for c in r.claims)
    print(f"wrote {len(r.files)} files to {r.out} (report: {r.out / 'report.html'}); "
          f"{n_agree} of {len(r.claims)} claims agree; run time {r.run_time:.1f} s")
    return 0


def _cmd_design(args) -> int:
    if args.design:
        text = drive_to_toml(*load_drive(args.design))
    else:
        text = builtin_text()
    if args.action == "export" and args.path:
        args.path.write_text(text)
        print(f"wrote {args.path}", file=sys.stderr)
    else:
        sys.stdout.write(text)
    return 0


def _rpm(speed: float) -> float:
    if not speed > 0 or speed == float("inf"):
        raise InputError("speed", speed, "> 0 rpm and finite")
    return speed


COMMANDS = {"point": _cmd_point, "limit": _cmd_limit, "clamp": _cmd_clamp, "map": _cmd_map,
            "reproduce": _cmd_reproduce, "design": _cmd_design}


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    args = build_parser().parse_args(argv)
    try:
        return COMMANDS[args.command](args)
    except InputError as exc:
        print(f"ballcvt: error: {exc}", file=sys.stderr)
        return 2
    except BallCVTError as exc:
        print(f"ballcvt: error: {exc}", file=sys.stderr)
        return 1
    except Exception as exc:  # a bug: say so in one line unless debugging
        if os.environ.get("BALLCVT_DEBUG"):
            raise
        print(f"ballcvt: internal error: {type(exc).__name__}: {exc} "
              "(set BALLCVT_DEBUG=1 for a traceback)", file=sys.stderr)
        return 1


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
