"""The ``ballcvt`` command line.

Every subcommand has only the options it uses, a description and an example
(``ballcvt SUBCOMMAND --help``). Output locations are checked before any computing starts.

Exit status: 0 success; 2 bad input, a torque beyond the traction capacity, no equilibrium,
or an output location that cannot be written (one line on stderr naming the quantity, its
value and the allowed range or the cause); 1 a bug (one line; set ``BALLCVT_DEBUG=1`` for a
traceback).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import textwrap
from pathlib import Path

from ..._version import __version__
from ...analysis.cycle_files import STRATEGIES
from ...api import Variator
from ...errors import BallCVTError, InputError
from ...files import atomic_write_text, check_output_dir, check_output_file
from ...model.clamping import CLAMP_LAWS
from ...model.modes import MEMBERS
from ...params.io import (
    BUILTIN_DRIVES,
    BUILTIN_FLUIDS,
    builtin_text,
    drive_to_toml,
    resolve_drive,
    resolve_fluid,
)
from ...params.models import ARCHITECTURES, TRACTION_LAWS, Fluid
from .format import clamp_table, limit_table, planetary_table, point_table

__all__ = ["main", "build_parser"]

PAPER_POINT = {"ratio": 1.0, "torque": 40.0, "clamp": 2000.0, "speed": 2000.0}


class _Parser(argparse.ArgumentParser):
    """argparse that reports usage errors in one line with exit status 2."""

    def error(self, message: str):  # noqa: D102
        self.exit(2, f"{self.prog}: error: {message}\n")


def _number(text: str) -> float:
    """A finite decimal number (``nan``, ``inf`` and overflowing literals are refused)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"{text!r} is not a finite number")
    return value


def _count(lo: int, hi: int):
    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
        if not lo <= value <= hi:
            raise argparse.ArgumentTypeError(f"{value} is out of range: allowed {lo}-{hi}")
        return value

    return parse


def _sub(sub, name: str, summary: str, description: str, example: str):
    return sub.add_parser(
        name,
        help=summary,
        description=textwrap.fill(description, 88),
        epilog="example:\n  " + example + "\n",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )


#: The options several subcommands share: name -> (add_argument keywords).
OPTIONS = {
    "arch": {
        "default": "double",
        "choices": ARCHITECTURES,
        "help": "idler architecture (default: double)",
    },
    "ratio": {
        "type": _number,
        "default": PAPER_POINT["ratio"],
        "help": "ideal speed ratio tau_ID [-] (default: %(default)s)",
    },
    "torque": {
        "type": _number,
        "default": PAPER_POINT["torque"],
        "help": "output torque T2 [N m] (default: %(default)s)",
    },
    "clamp": {
        "type": _number,
        "default": None,
        "help": f"input-contact normal load F_N0 [N] of the constant clamping law "
        f"(default: {PAPER_POINT['clamp']:g})",
    },
    "clamp-law": {
        "default": "constant",
        "choices": CLAMP_LAWS,
        "help": "clamping law (docs/model.md section 11): constant F_N0 (--clamp), "
        "the design's loading cam, or the efficiency-optimal force "
        "(default: constant)",
    },
    "cam-disc": {
        "choices": ("input", "output"),
        "default": None,
        "help": "disc whose torque the cam senses (default: the design's)",
    },
    "cam-preload": {
        "type": _number,
        "default": None,
        "help": "cam spring preload [N] (default: the design's)",
    },
    "cam-angle": {
        "type": _number,
        "default": None,
        "help": "cam ramp angle [deg] (default: the design's)",
    },
    "cam-radius": {
        "type": _number,
        "default": None,
        "help": "cam mean radius [m] (default: the design's)",
    },
    "cam-friction": {
        "type": _number,
        "default": None,
        "help": "cam ramp friction coefficient [-] (default: the design's)",
    },
    "speed": {
        "type": _number,
        "default": PAPER_POINT["speed"],
        "help": "input speed [rpm] (default: %(default)s)",
    },
    "creep-limit": {
        "type": _number,
        "default": None,
        "help": "largest admissible abs(creep) (default: the design's, 0.10)",
    },
    "design": {
        "metavar": "FILE.toml",
        "help": "drive definition: a TOML file, or a built-in drive's name (table1, "
        "hub) (default: table1, the paper's Table I drive)",
    },
    "json": {"action": "store_true", "help": "print one JSON object"},
    "traction-law": {
        "choices": TRACTION_LAWS,
        "default": None,
        "help": "shear law of the film (docs/model.md section 14): the paper's "
        "isothermal law, thermal or viscoelastic (default: the fluid's "
        "own, isothermal for the built-in drives)",
    },
    "fluid": {
        "metavar": "FILE.toml",
        "help": "fluid replacing the drive's: a TOML file with a [fluid] table (a "
        "drive file or one written by fit-fluid), or a built-in fluid's name "
        f"({', '.join(BUILTIN_FLUIDS)}) (default: the drive's fluid)",
    },
}


#: The drive and fluid options of every command that solves the drive.
FLUID_OPTIONS = ("design", "fluid", "traction-law")
#: The clamping-law options, and the [design.cam] key each overrides.
CLAMP_OPTIONS = (
    "clamp",
    "clamp-law",
    "cam-disc",
    "cam-preload",
    "cam-angle",
    "cam-radius",
    "cam-friction",
)
CAM_KEYS = {
    "cam_disc": "disc",
    "cam_preload": "preload",
    "cam_angle": "ramp_angle_deg",
    "cam_radius": "mean_radius",
    "cam_friction": "friction",
}


def _add(p, *names):
    for name in names:
        p.add_argument(f"--{name}", **OPTIONS[name])


def _out(p, default: str):
    p.add_argument(
        "--out", type=Path, default=Path(default), help="output folder (default: %(default)s)"
    )


def _grid_options(p, *, n_ratio: int, n_torque: int, most: int, torque_max: str):
    """The ratio x torque grid of ``map`` and ``table``."""
    p.add_argument(
        "--ratio-range",
        type=_number,
        nargs=2,
        default=(0.5, 2.0),
        metavar=("MIN", "MAX"),
        help="ratio range (default: 0.5 2)",
    )
    p.add_argument(
        "--n-ratio",
        type=_count(2, most),
        default=n_ratio,
        help=f"ratios, 2-{most} (default: %(default)s)",
    )
    p.add_argument(
        "--torque-max",
        type=_number,
        default=None,
        help=f"largest torque [N m] (default: {torque_max})",
    )
    p.add_argument(
        "--n-torque",
        type=_count(2, most),
        default=n_torque,
        help=f"torques, 2-{most} (default: %(default)s)",
    )


def _run_options(p):
    p.add_argument(
        "--workers", type=_count(1, 64), default=1, help="worker processes, 1-64 (default: 1)"
    )
    p.add_argument("--quiet", action="store_true", help="no progress bars and no summary line")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``ballcvt`` command."""
    parser = _Parser(
        prog="ballcvt",
        description="Steady-state model of ball-type traction "
        "CVTs (Tomaselli et al., Mech. Mach. Theory 150 (2020) 103877).",
    )
    parser.add_argument("--version", action="version", version=f"ballcvt {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)

    p = _sub(
        sub,
        "point",
        "solve one operating point (default: the paper's)",
        "Solve the steady operating point: ratio and tilt, creep, spin, traction, "
        "pressure and film at every contact, the losses and the efficiency (Eq. 38 and "
        "Eq. 39), with validity warnings. A torque beyond the traction capacity is "
        "refused with the limiting torque.",
        "ballcvt point --arch double --ratio 1.76 --torque 40 --clamp 2000 --speed 2000\n"
        "  ballcvt point --held disc0 --driver carrier --ratio 0.8 --torque 20 --speed 600",
    )
    _add(p, "arch", "ratio", "torque", *CLAMP_OPTIONS, "speed", *FLUID_OPTIONS, "json")
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
        type=_number,
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

    p = _sub(
        sub,
        "limit",
        "limiting output torque at a ratio, clamp and speed",
        "The largest output torque with a converged equilibrium and every abs(creep) <= "
        "the creep limit (docs/model.md section 8); under the cam law also every peak "
        "pressure <= the design's max_pressure (section 11).",
        "ballcvt limit --arch single --ratio 2 --clamp 2000 --speed 2000",
    )
    _add(p, "arch", "ratio", *CLAMP_OPTIONS, "speed", "creep-limit", *FLUID_OPTIONS, "json")

    p = _sub(
        sub,
        "clamp",
        "clamping force of maximum efficiency under the creep and pressure limits",
        "The input-contact normal load F_N0 that maximises the overall efficiency at "
        "this ratio, torque and speed, keeping every abs(creep) <= the creep limit and "
        "every Hertz peak pressure <= the pressure limit.",
        "ballcvt clamp --ratio 1 --torque 60 --speed 2000 --max-pressure 3e9",
    )
    _add(p, "arch", "ratio", "torque", "speed", "creep-limit", *FLUID_OPTIONS, "json")
    p.add_argument(
        "--max-pressure",
        type=_number,
        default=None,
        help="largest admissible Hertz peak pressure [Pa] (default: the design's)",
    )

    p = _sub(
        sub,
        "map",
        "efficiency map (ratio x output torque) as data and figure",
        "Efficiency over ideal ratio x output torque at one clamping force and speed, "
        "with the limiting-torque curve: map.png, map.svg, map.nc (NetCDF-4, CF) and "
        "map.csv in --out. Points beyond the limit have status 1.",
        "ballcvt map --out map_dir --clamp 2000 --speed 2000 --n-ratio 31 --n-torque 35",
    )
    _add(p, "arch", *CLAMP_OPTIONS, "speed", *FLUID_OPTIONS)
    _out(p, "ballcvt-map")
    _grid_options(
        p, n_ratio=31, n_torque=35, most=1000, torque_max="1.02 x the largest limiting torque"
    )
    _run_options(p)

    p = _sub(
        sub,
        "cycle",
        "a duty cycle: energy, efficiency and losses over a time series",
        "Run the drive over a duty cycle (a CSV time series with the units in the "
        "header: time and output speed and torque, or time and input speed and power "
        "with an optional ratio; docs/cycles.md). A strategy picks the ratio at each "
        "step; all steps are solved batched. Writes steps.csv, summary.json and "
        "cycle.png/.svg in --out; steps beyond the capacity or outside the ratio range "
        "are flagged, never hidden.",
        "ballcvt cycle examples/cycles/ebike_commute.csv --design hub --clamp-law cam "
        "--strategy target-input-speed --target-speed 180 --out commute",
    )
    p.add_argument("cycle_file", type=Path, metavar="CYCLE.csv", help="the duty cycle")
    _add(p, "arch", *CLAMP_OPTIONS, *FLUID_OPTIONS)
    p.add_argument(
        "--strategy",
        choices=STRATEGIES,
        default="target-input-speed",
        help="how the ratio is chosen (default: %(default)s)",
    )
    p.add_argument(
        "--target-speed",
        type=_number,
        default=None,
        help="input speed held by target-input-speed [rpm] (required by it)",
    )
    p.add_argument(
        "--candidates",
        type=_count(3, 101),
        default=9,
        help="ratios tried per step by max-efficiency, 3-101 (default: 9)",
    )
    p.add_argument(
        "--ratio-range",
        type=_number,
        nargs=2,
        default=None,
        metavar=("MIN", "MAX"),
        help="ratios max-efficiency may use (default: the usable range)",
    )
    _out(p, "ballcvt-cycle")
    _add(p, "json")
    _run_options(p)

    p = _sub(
        sub,
        "table",
        "lookup tables (ratio x input speed x torque) for system "
        "simulation: CSV, MATLAB .mat, Modelica",
        "Efficiency, input torque and losses over ideal ratio x input speed x output "
        "torque under a clamping law, as table.csv, table.mat (Simscape table-based "
        "blocks), table_modelica.txt (Modelica CombiTable2Ds) and table.nc in --out "
        "(layout: docs/cycles.md). Beyond the traction capacity the .mat and Modelica "
        "tables hold the value at the limit; status and limit_torque say where.",
        "ballcvt table --design hub --clamp-law cam --speed-range 100 3000 --n-speed 6 "
        "--out tables",
    )
    _add(p, "arch", *CLAMP_OPTIONS, *FLUID_OPTIONS)
    _grid_options(
        p,
        n_ratio=16,
        n_torque=20,
        most=200,
        torque_max="the largest limiting torque; torques start at 0",
    )
    p.add_argument(
        "--speed-range",
        type=_number,
        nargs=2,
        default=(500.0, 4000.0),
        metavar=("MIN", "MAX"),
        help="input speed range [rpm] (default: 500 4000)",
    )
    p.add_argument(
        "--n-speed",
        type=_count(2, 100),
        default=5,
        help="input speeds, 2-100 (default: %(default)s)",
    )
    _out(p, "ballcvt-table")
    _run_options(p)

    p = _sub(
        sub,
        "reproduce",
        "recompute every result of the paper: figures, data and report",
        "Recompute every result figure and stated number of the paper on the Table I "
        "drive: figNN.png/.svg/.csv, data/NAME.nc, claims.csv, report.md and report.html "
        "in --out.",
        "ballcvt reproduce --out reproduction --quick --workers 2",
    )
    _out(p, "ballcvt-reproduction")
    p.add_argument("--quick", action="store_true", help="coarse grids (seconds)")
    _add(p, "traction-law")
    _run_options(p)

    p = _sub(
        sub,
        "traction-curve",
        "traction coefficient vs slide-to-roll ratio of one contact (twin-disc or ball-on-disc)",
        "Traction coefficient mu and spin-moment coefficient chi of one elliptical "
        "contact against the slide-to-roll ratio, under any traction law (docs/model.md "
        "section 14): traction_curve.csv, .png and .svg in --out, or --json.",
        "ballcvt traction-curve --law thermal --rx 0.02 --ry 0.05 --load 1400 "
        "--speed 10 --spin 0 --creep-max 0.08",
    )
    p.add_argument(
        "--law",
        "--traction-law",
        dest="traction_law",
        choices=TRACTION_LAWS,
        default=None,
        help="traction law (default: the fluid's own)",
    )
    p.add_argument(
        "--rx",
        type=_number,
        required=True,
        metavar="M",
        help="equivalent radius along the rolling direction [m]",
    )
    p.add_argument(
        "--ry",
        type=_number,
        required=True,
        metavar="M",
        help="equivalent radius across the rolling direction [m]",
    )
    group = p.add_mutually_exclusive_group(required=True)
    group.add_argument("--load", type=_number, metavar="N", help="normal load [N]")
    group.add_argument("--pmax", type=_number, metavar="PA", help="Hertz peak pressure [Pa]")
    p.add_argument(
        "--speed",
        type=_number,
        required=True,
        metavar="M_PER_S",
        help="rolling (entrainment) speed [m/s]",
    )
    p.add_argument(
        "--spin",
        type=_number,
        default=0.0,
        metavar="S",
        help="spin-to-roll ratio omega_spin R_x / U [-] (default: 0)",
    )
    p.add_argument(
        "--creep-max",
        type=_number,
        default=0.1,
        metavar="C",
        help="largest slide-to-roll ratio, 0 < C < 2 (default: 0.1)",
    )
    p.add_argument(
        "--n-creep",
        type=_count(2, 2001),
        default=101,
        help="points on the curve, 2-2001 (default: 101)",
    )
    _add(p, "fluid", "design")
    _out(p, "ballcvt-traction-curve")
    _add(p, "json")

    p = _sub(
        sub,
        "fit-fluid",
        "fit a fluid's traction parameters to measured traction curves",
        "Least-squares fit of the fluid's traction parameters to measured curves "
        "(CSV columns condition, rx [m], ry [m], load [N], speed [m/s], spin, creep, mu; "
        "docs/model.md section 14): estimates with standard errors and correlations, "
        "warnings for parameters the data do not determine, residual plots, and the "
        "fitted fluid as fluid.toml, which every command loads with --fluid.",
        "ballcvt fit-fluid examples/traction/curves.csv --law thermal --out fit",
    )
    p.add_argument("curves_file", type=Path, metavar="CURVES.csv", help="measured traction curves")
    p.add_argument(
        "--law",
        "--traction-law",
        dest="traction_law",
        choices=TRACTION_LAWS,
        default=None,
        help="traction law to fit (default: the start fluid's own)",
    )
    p.add_argument(
        "--params",
        default=None,
        metavar="NAME,NAME",
        help="fluid fields to fit, comma-separated (default: the law's: "
        "limiting shear stress and slope, and the temperature-viscosity "
        "coefficient (thermal) or the shear modulus (viscoelastic))",
    )
    _add(p, "fluid", "design")
    _out(p, "ballcvt-fit")
    _add(p, "json")

    p = _sub(
        sub,
        "explore",
        "design study: sample or optimise designs on Dask, Pareto front and the chosen design",
        "Evaluate the designs of a study file (docs/studies.md) on a local Dask cluster "
        "or a running one: every design with its objectives and status in designs.zarr "
        "(written as designs finish; --resume continues an interrupted study), "
        "designs.csv, pareto.csv, chosen_design.toml, summary.json, figures and a "
        "report in --out.",
        "ballcvt explore examples/studies/study_quick.toml --out study --workers 2",
    )
    p.add_argument("study_file", type=Path, metavar="STUDY.toml", help="the study")
    _out(p, "ballcvt-study")
    p.add_argument(
        "--workers",
        type=_count(1, 256),
        default=2,
        help="processes of the local Dask cluster, 1-256 (default: 2)",
    )
    p.add_argument(
        "--scheduler",
        default=None,
        metavar="ADDRESS",
        help="address of a running Dask scheduler, e.g. tcp://10.0.0.1:8786 "
        "(default: a local cluster of --workers processes)",
    )
    p.add_argument(
        "--in-process", action="store_true", help="evaluate in this process, without Dask"
    )
    p.add_argument(
        "--traction-law",
        choices=TRACTION_LAWS,
        default=None,
        help="traction law of every design (default: the study's traction_law, else the "
        "fluid's own)",
    )
    p.add_argument(
        "--resume",
        action="store_true",
        help="continue the study in --out: evaluated designs are kept",
    )
    p.add_argument("--quiet", action="store_true", help="no progress bar and no summary")
    _add(p, "json")

    p = _sub(
        sub,
        "explore-ui",
        "interactive explorer in the browser: sliders, operating point, efficiency map",
        "Start a local web app (Bokeh server) with sliders for the ratio, output torque, "
        "clamping force, input speed and the main design parameters, showing the operating "
        "point (efficiency, losses, creeps, pressures, films), the efficiency map with the "
        "point on it and the limiting-torque curve. It binds to 127.0.0.1 (this machine "
        "only) unless --address says otherwise; Ctrl-C stops it.",
        "ballcvt explore-ui --design hub --port 5006",
    )
    _add(p, "arch", *FLUID_OPTIONS)
    p.add_argument(
        "--port",
        type=_count(0, 65535),
        default=5006,
        help="TCP port, 0 for any free one (default: 5006)",
    )
    p.add_argument(
        "--address",
        default="127.0.0.1",
        help="address to bind (default: 127.0.0.1, this machine only)",
    )
    p.add_argument("--show", action="store_true", help="open the page in the browser")

    p = _sub(
        sub,
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
    _add(p, *FLUID_OPTIONS)
    return parser


def _drive(design):
    """A ``--design`` value: a built-in drive's name or a TOML file."""
    return resolve_drive(design)


def _fluid(args, fluid):
    """The drive's fluid, or the ``--fluid`` one, under ``--traction-law`` if given."""
    if getattr(args, "fluid", None) is not None:
        fluid = resolve_fluid(args.fluid)
    return fluid.with_traction_law(getattr(args, "traction_law", None))


def _variator(args) -> Variator:
    design, fluid = _drive(args.design)
    fluid = _fluid(args, fluid)
    cam = {
        key: getattr(args, opt)
        for opt, key in CAM_KEYS.items()
        if getattr(args, opt, None) is not None
    }
    if cam:
        if getattr(args, "clamp_law", "constant") != "cam":
            opt = "--" + next(o for o, k in CAM_KEYS.items() if k in cam).replace("_", "-")
            raise InputError(opt, None, "--clamp-law cam", message=f"{opt} needs --clamp-law cam")
        base = design.cam.model_dump() if design.cam is not None else {}
        missing = [k for k in CAM_KEYS.values() if k not in {**base, **cam}]
        if missing:
            raise InputError(
                "design.cam",
                None,
                "every cam key",
                message=(
                    "the design has no [design.cam] table: give every cam option (missing: "
                    + ", ".join(
                        "--" + o.replace("_", "-") for o, k in CAM_KEYS.items() if k in missing
                    )
                    + ")"
                ),
            )
        design = design.replace(cam={**base, **cam})
    return Variator(design, fluid, args.arch)


def _law(args):
    """(clamp_force, clamp_law) keywords of the Python API from the options."""
    if args.clamp_law == "constant":
        return {"clamp_force": PAPER_POINT["clamp"] if args.clamp is None else args.clamp}
    if args.clamp is not None:
        raise InputError(
            "clamp",
            args.clamp,
            f"not given with --clamp-law {args.clamp_law}",
            message=f"--clamp is the constant law's force: not given with "
            f"--clamp-law {args.clamp_law} (the law sets the force)",
        )
    return {"clamp_law": args.clamp_law}


def _cmd_point(args) -> int:
    from ...model.modes import OperatingMode

    v = _variator(args)
    if not math.isfinite(args.held_speed):
        raise InputError("held_speed", args.held_speed, "finite (rpm)")
    mode = OperatingMode(
        args.held,
        args.driver,
        not args.no_centrifugal,
        not args.no_gyroscopic,
        args.held_speed * math.pi / 30,
    )
    r = v.solve(
        ratio=args.ratio,
        output_torque=args.torque,
        **_law(args),
        input_speed_rpm=_rpm(args.speed),
        mode=mode,
    )
    from ...results.planetary import PlanetaryResult

    if args.json:
        print(r.to_json(indent=2))
    else:
        print(planetary_table(r) if isinstance(r, PlanetaryResult) else point_table(r))
    return 0


def _cmd_limit(args) -> int:
    v = _variator(args)
    c_lim = v.design.creep_limit if args.creep_limit is None else args.creep_limit
    law = _law(args)
    t = v.limit_torque(
        ratio=args.ratio, **law, input_speed_rpm=_rpm(args.speed), creep_limit=c_lim
    )
    data = {
        "limit_torque": t,
        "architecture": args.arch,
        "ratio": args.ratio,
        "clamp_law": args.clamp_law,
        "clamp_force": law.get("clamp_force"),
        "input_speed_rpm": args.speed,
        "creep_limit": c_lim,
        "design": v.design.name,
        "version": __version__,
    }
    print(json.dumps(data, indent=2) if args.json else limit_table(data))
    return 0


def _cmd_clamp(args) -> int:
    v = _variator(args)
    o = v.optimal_clamp_force(
        ratio=args.ratio,
        output_torque=args.torque,
        input_speed_rpm=_rpm(args.speed),
        creep_limit=args.creep_limit,
        max_pressure=args.max_pressure,
    )
    data = {
        "clamp_force": o.clamp_force,
        "eta": o.eta,
        "max_creep": o.max_creep,
        "max_pressure": o.max_pressure,
        "feasible_clamp_range": list(o.bounds),
        "active_constraint": o.active,
        "architecture": args.arch,
        "ratio": args.ratio,
        "output_torque": args.torque,
        "input_speed_rpm": args.speed,
        "design": v.design.name,
        "version": __version__,
    }
    print(json.dumps(data, indent=2) if args.json else clamp_table(data))
    return 0


def _grid(args):
    """Validated grid options of ``map`` and ``table``: (out, variator, law, ratios)."""
    import numpy as np

    lo, hi = args.ratio_range
    if not 0 < lo < hi:
        raise InputError("ratio_range", f"{lo:g} {hi:g}", "0 < MIN < MAX")
    if args.torque_max is not None and not args.torque_max > 0:
        raise InputError("torque_max", args.torque_max, "> 0 N m")
    return (
        check_output_dir(args.out),
        _variator(args),
        _law(args),
        np.linspace(lo, hi, args.n_ratio),
    )


def _limits(args, v, law, ratios, speeds):
    """The limit search of every (ratio, speed), run once (with a progress bar): its
    torques set the default torque range, and the search (torques and the creeps there)
    is handed to the sweep."""
    from tqdm.auto import tqdm

    from ...analysis.sweeps.curves import Curves, limit_search_curves
    from ...equilibrium.problem import build_problem
    from ...params.drive import Drive
    from ...solvers.limit import bisection_steps

    force = law.get("clamp_force")
    build_problem(
        v.design, v.fluid, v.architecture, ratios, 0.0, 1.0 if force is None else force, speeds
    )  # validates every input
    with tqdm(
        total=bisection_steps(),
        desc=f"limiting torque at {ratios.size} points",
        unit="step",
        disable=not _show(args),
    ) as bar:
        rows = Curves.of(
            Drive(v.design, v.fluid, v.architecture),
            ratios,
            speeds,
            force,
            None if force is not None else v.clamp_law(args.clamp_law),
            v.options,
        )
        return limit_search_curves(rows, bar.update)[1]


def _cmd_map(args) -> int:
    import numpy as np

    out, v, law, ratios = _grid(args)
    show = _show(args)
    limits = _limits(args, v, law, ratios, np.full(ratios.size, _rpm(args.speed) * np.pi / 30))
    top = 1.02 * float(np.nanmax(limits.torque)) if args.torque_max is None else args.torque_max
    ds = v.sweep(
        ratio=ratios,
        output_torque=np.linspace(top / args.n_torque, top, args.n_torque),
        **law,
        input_speed_rpm=_rpm(args.speed),
        limit_torque=limits,
        workers=args.workers,
        progress=show,
        label="efficiency map",
    )
    _write_map(ds, out, args)
    if not args.quiet:
        st = ds.status.values
        n_warn = int((ds.warnings.values != 0).sum())
        print(
            f"wrote {out}/map.png, map.svg, map.nc, map.csv ({v.design.name}): "
            f"{int((st == 0).sum())} of {st.size} points converged within the limit, "
            f"{int((st == 1).sum())} beyond the limiting torque, {int((st == 2).sum())} not "
            f"converged; {n_warn} with validity warnings; max eta "
            f"{float(ds.eta.max()):.4f}; {ds.attrs['run_time_s']:.1f} s on "
            f"{args.workers} worker(s)"
        )
        if (st == 1).sum() > st.size / 2:
            print(
                f"note: most points lie beyond the limiting torque (max "
                f"{float(np.nanmax(limits.torque)):.1f} N m); lower --torque-max",
                file=sys.stderr,
            )
    return 0


def _write_map(ds, out, args):
    import matplotlib

    matplotlib.use("Agg")  # the CLI writes files only
    from ...analysis.sweeps.export import to_csv, to_netcdf
    from ...plotting import efficiency_map, save

    to_netcdf(ds, out / "map.nc")
    to_csv(ds, out / "map.csv")
    one = ds.squeeze(drop=True)
    save(
        efficiency_map(
            one.ratio.values,
            one.output_torque.values,
            one.eta.values,
            one.limit_torque.values,
            f"Efficiency map, {args.arch} idler, {_clamp_label(args)}, {args.speed:g} rpm",
            limit_eta=one.eta_at_limit.values,
        ),
        out,
        "map",
    )


def _cmd_cycle(args) -> int:
    from ...analysis.cycle_files import read_cycle
    from ...analysis.cycles import run_cycle

    out = check_output_dir(args.out)
    cycle = read_cycle(args.cycle_file)
    v = _variator(args)
    target = None if args.target_speed is None else _rpm(args.target_speed) * math.pi / 30
    law = _law(args)
    result = run_cycle(
        v,
        cycle,
        strategy=args.strategy,
        target_input_speed=target,
        clamp_force=law.get("clamp_force"),
        clamp_law=law.get("clamp_law"),
        candidates=args.candidates,
        ratio_range=args.ratio_range,
        progress=_show(args),
        workers=args.workers,
    )
    result.save(out)
    import matplotlib

    matplotlib.use("Agg")  # the CLI writes files only
    from ...plotting import cycle_figure, save

    save(
        cycle_figure(
            result.steps,
            f"{cycle.name}: {v.design.name}, {result.summary['strategy']}, {_clamp_label(args)}",
        ),
        out,
        "cycle",
    )
    s = result.summary
    if args.json:
        print(json.dumps(s, indent=2))
    elif not args.quiet:
        eff = "n/a" if s["efficiency"] is None else f"{s['efficiency']:.4f}"
        print(
            f"wrote {out}/steps.csv, summary.json, cycle.png, cycle.svg: {s['steps']} steps "
            f"({s['duration_s']:.0f} s), energy in {s['energy_in_J'] / 3.6e3:.2f} Wh, out "
            f"{s['energy_out_J'] / 3.6e3:.2f} Wh, efficiency {eff}; {s['steps_flagged']} "
            f"steps flagged; {s['run_time_s']:.1f} s on {args.workers} worker(s)"
        )
    return 0


def _cmd_table(args) -> int:
    import numpy as np

    from ...analysis.sweeps.export import to_netcdf
    from ...analysis.tables import write_tables

    w_lo, w_hi = args.speed_range
    if not 0 < w_lo < w_hi or not math.isfinite(w_hi):
        raise InputError("speed_range", f"{w_lo:g} {w_hi:g}", "0 < MIN < MAX rpm")
    out, v, law, ratios = _grid(args)
    rpm = np.linspace(w_lo, w_hi, args.n_speed)
    r_grid, w_grid = (g.ravel() for g in np.meshgrid(ratios, rpm * math.pi / 30))
    limits = _limits(args, v, law, r_grid, w_grid)
    top = float(np.nanmax(limits.torque)) if args.torque_max is None else args.torque_max
    ds = v.sweep(
        ratio=ratios,
        output_torque=np.linspace(0.0, top, args.n_torque),
        **law,
        input_speed_rpm=rpm,
        limit_torque=limits,
        workers=args.workers,
        progress=_show(args),
        label="lookup table",
    )
    to_netcdf(ds, out / "table.nc")
    write_tables(ds, out)
    if not args.quiet:
        st = ds.status.values
        print(
            f"wrote {out}/table.csv, table.mat, table_modelica.txt, table.nc "
            f"({ratios.size} ratios x {rpm.size} speeds x {args.n_torque} torques, "
            f"{v.design.name}, {args.clamp_law} clamping): {int((st == 0).sum())} points "
            f"within the capacity, {int((st == 1).sum())} beyond, {int((st == 2).sum())} "
            f"not converged; {ds.attrs['run_time_s']:.1f} s on {args.workers} worker(s)"
        )
    return 0


def _clamp_label(args) -> str:
    if args.clamp_law == "constant":
        force = PAPER_POINT["clamp"] if args.clamp is None else args.clamp
        return f"$F_{{N0}}$ = {force:g} N"
    return f"{args.clamp_law} clamping"


def _cmd_reproduce(args) -> int:
    import matplotlib

    matplotlib.use("Agg")  # the CLI writes files only
    from ...reports import reproduce

    r = reproduce(
        args.out,
        quick=args.quick,
        workers=args.workers,
        progress=_show(args),
        traction_law=args.traction_law,
    )
    n_agree = sum(c.verdict == "agrees" for c in r.claims)
    if not args.quiet:
        print(
            f"wrote {len(r.files)} files to {r.out} (report: {r.out / 'report.html'}); "
            f"{n_agree} of {len(r.claims)} claims agree; run time {r.run_time:.1f} s on "
            f"{args.workers} worker(s)"
        )
    return 0


def _contact_fluid(args):
    """(fluid, E') of a single-contact command: --fluid (default the drive's) under --law."""
    design, fluid = _drive(args.design)
    return _fluid(args, fluid), design.material.reduced_modulus


def _cmd_traction_curve(args) -> int:
    import numpy as np

    from ...model.traction.curve import traction_curve

    if not 0 < args.creep_max < 2:
        raise InputError("creep_max", args.creep_max, "0 < C < 2")
    fluid, modulus = _contact_fluid(args)
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
        print(json.dumps(curve.as_dict(), indent=2))
        return 0
    import matplotlib

    matplotlib.use("Agg")
    import pandas as pd

    from ...plotting import save, traction_curve_figure

    out = check_output_dir(args.out)
    frame = pd.DataFrame(
        {
            "creep": curve.creep,
            "mu": curve.mu,
            "chi": curve.chi,
            "temperature_rise_K": curve.temperature_rise,
        }
    )
    atomic_write_text(out / "traction_curve.csv", frame.to_csv(index=False))
    c = curve.conditions
    save(
        traction_curve_figure(
            [curve],
            f"{fluid.name}: {curve.law} law, p_max "
            f"{c['p_max'] / 1e9:.2f} GPa, U {c['speed']:g} m/s, spin "
            f"{c['spin']:g}",
        ),
        out,
        "traction_curve",
    )
    peak = int(np.argmax(curve.mu))
    print(
        f"wrote {out}/traction_curve.csv, .png, .svg: {curve.law} law, p_max "
        f"{c['p_max'] / 1e9:.3f} GPa, film {c['film'] * 1e6:.3f} um; mu peaks at "
        f"{curve.mu[peak]:.4f} at slide-to-roll {curve.creep[peak]:.4f}"
    )
    return 0


def _cmd_fit_fluid(args) -> int:
    from ...analysis.fitting import fit_fluid, read_curves
    from ...params.io import fluid_to_toml

    fluid, modulus = _contact_fluid(args)
    curves = read_curves(args.curves_file)
    params = (
        None if args.params is None else [p.strip() for p in args.params.split(",") if p.strip()]
    )
    out = check_output_dir(args.out)
    fit = fit_fluid(curves, fluid, params, reduced_modulus=modulus)
    header = (
        f"ballcvt {__version__} fit-fluid: {fit.fluid.traction_law} law fitted to "
        f"{args.curves_file} ({fit.model.size} points, rms residual {fit.rms:.3e})\n"
        + "\n".join(
            f"{n} = {fit.estimates[n]:.6g} +/- {fit.standard_errors[n]:.3g} "
            f"[{Fluid.unit(n)}] (one standard error)"
            for n in fit.parameters
        )
        + "".join(f"\nWARNING: {w}" for w in fit.warnings)
        + f"\nthe other values are those of the start fluid '{fluid.name}'"
    )
    named = Fluid(
        **{
            **fit.fluid.model_dump(),
            "name": f"{fluid.name} (fitted to {Path(args.curves_file).name})",
        }
    )
    atomic_write_text(out / "fluid.toml", fluid_to_toml(named, header))
    summary = fit.as_dict()
    atomic_write_text(out / "fit.json", json.dumps(summary, indent=2))
    import matplotlib

    matplotlib.use("Agg")
    import pandas as pd

    from ...plotting import fit_figure, save

    frame = pd.DataFrame(
        {
            "condition": curves.condition,
            "creep": curves.creep,
            "mu": curves.mu,
            "mu_model": fit.model,
            "residual": fit.residuals,
        }
    )
    atomic_write_text(out / "fit.csv", frame.to_csv(index=False))
    save(fit_figure(curves, fit, f"{fit.fluid.traction_law} law"), out, "fit_residuals")
    for w in fit.warnings:
        print(f"ballcvt: warning: {w}", file=sys.stderr)
    if args.json:
        print(json.dumps(summary, indent=2))
    else:
        print(
            f"wrote {out}/fluid.toml, fit.json, fit.csv, fit_residuals.png/.svg: rms "
            f"residual {fit.rms:.3e} over {fit.model.size} points"
        )
        for n in fit.parameters:
            print(
                f"  {n} = {fit.estimates[n]:.6g} +/- {fit.standard_errors[n]:.3g} "
                f"[{Fluid.unit(n)}]"
            )
    return 0


def _cmd_explore(args) -> int:
    import matplotlib

    matplotlib.use("Agg")
    from ...analysis.studies import read_study, run_study
    from ...reports.study import study_report

    spec = read_study(args.study_file)
    if args.traction_law is not None:
        spec = spec.model_copy(
            update={"study": spec.study.model_copy(update={"traction_law": args.traction_law})}
        )
    if args.scheduler is not None and args.in_process:
        raise InputError("scheduler", args.scheduler, "not with --in-process")
    result = run_study(
        spec,
        args.out,
        workers=args.workers,
        scheduler=args.scheduler,
        in_process=args.in_process,
        resume=args.resume,
        progress=_show(args),
    )
    files = result.files + study_report(result, spec, args.out)
    counts = result.counts()
    if args.json:
        print((Path(args.out) / "summary.json").read_text())
    elif not args.quiet:
        chosen = (
            "none feasible"
            if result.chosen < 0
            else f"chosen design {int(result.dataset['design'].values[result.chosen])} -> "
            f"{Path(args.out) / 'chosen_design.toml'}"
        )
        print(
            f"wrote {len(files)} files and {Path(args.out) / 'designs.zarr'} to {args.out}: "
            f"{result.dataset.sizes['design']} designs ({result.evaluated_now} evaluated "
            f"now), {counts['evaluated']} feasible, {counts['cannot be built']} cannot be "
            f"built, {counts['constraint violated']} violate a constraint; "
            f"{int(result.dataset['pareto'].sum())} on the Pareto front; {chosen}; "
            f"{result.run_time:.1f} s"
        )
    return 0


def _cmd_explore_ui(args) -> int:
    from ..ui import serve

    v = _variator(args)
    serve(
        v.design,
        v.fluid,
        architecture=v.architecture,
        port=args.port,
        address=args.address,
        show=args.show,
    )
    return 0


def _cmd_design(args) -> int:
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
    design, fluid = _drive(args.design)  # validated first
    if args.design is None or (args.design in BUILTIN_DRIVES and not Path(args.design).exists()):
        template = builtin_text(args.design or "table1")
    else:
        template = Path(args.design).read_text(encoding="utf-8")
    new_fluid = _fluid(args, fluid)
    text = (
        template
        if new_fluid == fluid and args.design in (None, *BUILTIN_DRIVES)
        else drive_to_toml(design, new_fluid, template=template)
    )
    if args.action == "export":
        atomic_write_text(args.path, text)
        print(f"wrote {args.path}", file=sys.stderr)
    else:
        sys.stdout.write(text)
    return 0


def _show(args):
    return False if args.quiet else sys.stderr.isatty()


def _rpm(speed: float) -> float:
    if not speed > 0 or speed == float("inf"):
        raise InputError("speed", speed, "> 0 rpm and finite")
    return speed


COMMANDS = {
    "point": _cmd_point,
    "limit": _cmd_limit,
    "clamp": _cmd_clamp,
    "map": _cmd_map,
    "cycle": _cmd_cycle,
    "table": _cmd_table,
    "reproduce": _cmd_reproduce,
    "design": _cmd_design,
    "traction-curve": _cmd_traction_curve,
    "fit-fluid": _cmd_fit_fluid,
    "explore": _cmd_explore,
    "explore-ui": _cmd_explore_ui,
}


def main(argv: list[str] | None = None) -> int:
    """Run the command line; returns the exit status."""
    args = build_parser().parse_args(argv)
    try:
        return COMMANDS[args.command](args)
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
