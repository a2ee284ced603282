"""Options and helpers the subcommands share: argument types, the drive, clamping, fluid,
grid and run options, and their translation into the Python API's arguments.

The choices of ``--arch``, ``--clamp-law`` and ``--traction-law`` are read from
`ballcvt.registry` when the parser is built, so a law a user registers before calling
`ballcvt.interfaces.cli.main.main` is offered.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import textwrap
from pathlib import Path
from typing import Any

from ...api import (
    BUILTIN_FLUIDS,
    CAM_KEYS,
    LIFE_MODELS,
    PAPER_POINT,
    Variator,
    drive_clamp,
    effective_models,
    open_drive,
    with_oil_temperature,
)
from ...errors import InputError
from ...registry import ARCHITECTURES, CLAMP_LAWS, LUBRICATION_MODELS, TRACTION_LAWS
from ...units import celsius_to_kelvin

#: The paper's operating point: the defaults of ``point``, ``limit`` and ``clamp``.
#: The drive and fluid options of every command that solves the drive.
FLUID_OPTIONS = ("design", "fluid", "traction-law", "lubrication")
#: The clamping-law options.
CLAMP_OPTIONS = (
    "clamp",
    "clamp-law",
    "cam-disc",
    "cam-preload",
    "cam-angle",
    "cam-radius",
    "cam-friction",
)
#: The cam options, in the order of the ``[design.cam]`` keys they override.
CAM_OPTIONS = CLAMP_OPTIONS[2:]


def number(text: str) -> float:
    """A finite decimal number (``nan``, ``inf`` and overflowing literals are refused)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"{text!r} is not a finite number")
    return value


def quantity(name: str, unit: str, *, above: float | None = None, most: float | None = None):
    """A finite number ``above < value <= most`` [``unit``]: an absurd value (``1e308`` N)
    is refused by argparse with the flag, the value, its unit and the allowed range, before
    it can overflow a computation. A bound left None is checked by the API (with its
    message naming the quantity)."""

    def parse(text: str) -> float:
        value = number(text)
        if (above is not None and not value > above) or (most is not None and value > most):
            lo = f"{above:g} < " if above is not None else ""
            hi = f" <= {most:g}" if most is not None else ""
            raise argparse.ArgumentTypeError(
                f"{name} = {value:g} {unit} is out of range: allowed {lo}{name}{hi} {unit}"
            )
        return value

    return parse


#: The largest force, torque, speed and pressure the command line accepts: far beyond any
#: ball CVT, and well inside the range where the contact mechanics stays finite.
MOST_FORCE = 1e6  # [N]
MOST_TORQUE = 1e6  # [N m]
MOST_RPM = 1e5  # [rpm]
MOST_PRESSURE = 1e10  # [Pa]


def input_file(path: Path, what: str) -> Path:
    """``path``, an input file that exists and is not a folder (`InputError` otherwise);
    checked first, before any output is made."""
    if path.is_dir():
        raise InputError(
            what, str(path), "a file", message=f"{what} {path} is a folder: allowed a file"
        )
    if not path.exists():
        raise InputError(what, str(path), "a file", message=f"{what} {path}: not found")
    return path


class OutputStreamError(OSError):
    """Standard output cannot be written (a full disk, a failing device): exit status 1."""


def emit(text: str) -> None:
    """Print ``text`` on standard output; a failure to write it is an `OutputStreamError`
    (a broken pipe stays a `BrokenPipeError`: `ballcvt.interfaces.cli.main` exits quietly)."""
    try:
        print(text)
    except BrokenPipeError:
        raise
    except OSError as exc:
        raise OutputStreamError(
            exc.errno, f"cannot write to standard output: {exc.strerror or exc}"
        ) from None


def emit_json(data: Any) -> None:
    """Print ``data`` as strict JSON (RFC 8259): a non-finite number is written ``null``,
    never ``NaN`` or ``Infinity``."""
    emit(json.dumps(_finite(data), indent=2, allow_nan=False))


def emit_json_text(text: str) -> None:
    """Print JSON text (a result's ``to_json``, a saved summary) as strict JSON."""
    emit_json(json.loads(text))


def _finite(value: Any) -> Any:
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_finite(v) for v in value]
    return value


def count(lo: int, hi: int):
    """A whole number in ``lo``-``hi``."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
        if not lo <= value <= hi:
            raise argparse.ArgumentTypeError(f"{value} is out of range: allowed {lo}-{hi}")
        return value

    return parse


def sub(subparsers, name: str, summary: str, description: str, example: str):
    """A subcommand's parser with its summary, description and example."""
    return subparsers.add_parser(
        name,
        allow_abbrev=False,
        help=summary,
        description=textwrap.fill(description, 88),
        epilog="example:\n  " + example + "\n",
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )


def _cam_option(unit: str, what: str) -> dict:
    return {
        "type": number,
        "default": None,
        "help": f"cam {what} [{unit}] (default: the design's)",
    }


def options() -> dict[str, dict]:
    """The options several subcommands share: name -> add_argument keywords (the choices
    read from the registries now)."""
    return {
        "arch": {
            "default": "double",
            "choices": ARCHITECTURES.names(),
            "help": "idler architecture (default: double)",
        },
        "ratio": {
            "type": number,
            "default": PAPER_POINT.ratio,
            "help": "ideal speed ratio tau_ID [-] (default: %(default)s)",
        },
        "torque": {
            "type": quantity("output_torque", "N m", most=MOST_TORQUE),
            "default": PAPER_POINT.output_torque,
            "help": "output torque T2 [N m] (default: %(default)s)",
        },
        "clamp": {
            "type": quantity("clamp_force", "N", most=MOST_FORCE),
            "default": None,
            "help": f"input-contact normal load F_N0 [N] of the constant clamping law "
            f"(default: the drive's [operating] clamp_force, else "
            f"{PAPER_POINT.clamp_force:g})",
        },
        "clamp-law": {
            "default": "constant",
            "choices": CLAMP_LAWS.names(),
            "help": "clamping law (docs/model.md section 11): constant F_N0 (--clamp), "
            "the design's loading cam, or the efficiency-optimal force "
            "(default: the drive's [operating] clamp_law, else constant)",
        },
        "cam-disc": {
            "choices": ("input", "output"),
            "default": None,
            "help": "disc whose torque the cam senses (default: the design's)",
        },
        "cam-preload": {
            **_cam_option("N", "spring preload"),
            "type": quantity("cam preload", "N", most=MOST_FORCE),
        },
        "cam-angle": _cam_option("deg", "ramp angle"),
        "cam-radius": _cam_option("m", "mean radius"),
        "cam-friction": _cam_option("-", "ramp friction coefficient"),
        "speed": {
            "type": quantity("speed", "rpm", most=MOST_RPM),
            "default": PAPER_POINT.input_speed_rpm,
            "help": "input speed [rpm] (default: the drive's [operating] input_speed_rpm, "
            "else %(default)s)",
        },
        "creep-limit": {
            "type": number,
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
            "choices": TRACTION_LAWS.names(),
            "default": None,
            "help": "shear law of the film (docs/model.md section 14): the paper's "
            "isothermal law, thermal or viscoelastic (default: the fluid's "
            "own, isothermal for the built-in drives)",
        },
        "lubrication": {
            "choices": LUBRICATION_MODELS.names(),
            "default": None,
            "help": "lubrication model, docs/model.md section 15 (default: the drive's)",
        },
        "fluid": {
            "metavar": "FILE.toml",
            "help": "fluid replacing the drive's: a TOML file with a [fluid] table (a "
            "drive file or one written by fit-fluid), or a built-in fluid's name "
            f"({', '.join(BUILTIN_FLUIDS)}) (default: the drive's fluid)",
        },
        **_life_options(),
    }


def _life_options() -> dict[str, dict]:
    """The fatigue-life options (``life``, ``map --life``, ``cycle --life``)."""
    return {
        "life": {
            "action": "store_true",
            "help": "add the rolling-contact fatigue life (system L10 [h], docs/life.md)",
        },
        "material": {
            "metavar": "NAME|FILE.toml",
            "default": None,
            "help": "fatigue material of the tracks: a built-in name or a TOML file with a "
            "[material] table (default: steel_52100, AISI 52100 bearing steel)",
        },
        "life-model": {
            "choices": LIFE_MODELS.names(),
            "default": "lundberg-palmgren",
            "help": "contact fatigue life model (docs/life.md) (default: %(default)s)",
        },
    }


def add(p, *names: str) -> None:
    """Add the shared options ``names`` to the parser ``p``."""
    table = options()
    for name in names:
        p.add_argument(f"--{name}", **table[name])


def law_option(p, help: str) -> None:
    """``--law`` (or ``--traction-law``): a traction law of the registry, for the
    single-contact commands."""
    p.add_argument(
        "--law",
        "--traction-law",
        dest="traction_law",
        choices=TRACTION_LAWS.names(),
        default=None,
        help=help,
    )


def out(p, default: str) -> None:
    """The ``--out`` folder option."""
    p.add_argument(
        "--out", type=Path, default=Path(default), help="output folder (default: %(default)s)"
    )


def run_options(p) -> None:
    """``--workers`` and ``--quiet``."""
    p.add_argument(
        "--workers", type=count(1, 64), default=1, help="worker processes, 1-64 (default: 1)"
    )
    p.add_argument("--quiet", action="store_true", help="no progress bars and no summary line")


def variator(args) -> Variator:
    """The drive of ``--design``, ``--fluid``, ``--traction-law``, ``--arch`` and the cam
    options (which need ``--clamp-law cam``)."""
    design, fluid = open_drive(args.design, args.fluid, getattr(args, "traction_law", None))
    design = design.with_lubrication(getattr(args, "lubrication", None))
    flags = {key: "--" + opt for opt, key in zip(CAM_OPTIONS, CAM_KEYS)}
    cam = {
        key: getattr(args, opt.replace("-", "_"))
        for opt, key in zip(CAM_OPTIONS, CAM_KEYS)
        if getattr(args, opt.replace("-", "_"), None) is not None
    }
    if cam and getattr(args, "clamp_law", "constant") != "cam":
        opt = flags[next(iter(cam))]
        raise InputError(opt, None, "--clamp-law cam", message=f"{opt} needs --clamp-law cam")
    v = Variator(design, fluid, args.arch, traction_law=fluid.traction_law)
    oil = getattr(args, "oil_temperature", None)  # --oil-temperature on every path (§15)
    if oil is not None and oil != "transient":
        v = with_oil_temperature(v, oil if isinstance(oil, str) else celsius_to_kelvin(oil))
    return v.with_cam(cam, flags) if cam else v


def models_used(args, v: Variator) -> dict[str, str]:
    """The models a command ran with (`ballcvt.api.effective_models`): the drive's, with
    the clamping law the options chose (``--clamp-law``, else the drive file's)."""
    law = getattr(args, "clamp_law", None)
    force = getattr(args, "clamp", None)
    return effective_models(
        v.design, v.fluid, clamp_law=law, clamp_force=force, traction_law=v.fluid.traction_law
    )


#: The commands that run the drive (``traction-curve --speed`` is a rolling speed in m/s).
DRIVEN = ("point", "limit", "clamp", "map", "table", "cycle", "life", "shift", "explore-ui")
#: Option -> (``[operating]`` key, the ``args`` attribute it sets).
_OPERATING = {
    "--speed": ("input_speed_rpm", "speed"),
    "--target-speed": ("input_speed_rpm", "operating_target_speed"),
    "--ratio-range": ("ratio_range", "ratio_range"),
    "--speed-range": ("speed_range_rpm", "speed_range"),
}


def apply_operating(args, argv: list[str]) -> None:
    """Start where the drive runs: the ``[operating]`` table of ``--design`` (docs/cli.md)
    gives the options a command has and ``argv`` does not type (typed flags always win).

    The clamping law is the drive file's (``[models]``, else ``[operating]``
    ``clamp_law``) unless ``--clamp-law`` or ``--clamp`` is typed; the constant law's
    force is ``[operating] clamp_force`` unless ``--clamp`` is typed. The traction law of
    ``[models]`` is the fluid's unless ``--traction-law`` is typed (`variator`).
    """
    if getattr(args, "design", None) is None or getattr(args, "command", None) not in DRIVEN:
        return
    design, _ = open_drive(args.design, None, None)
    op = design.operating
    typed = {word.split("=", 1)[0] for word in argv if word.startswith("--")}
    for flag, (key, attr) in _OPERATING.items():
        value = getattr(op, key) if op is not None else None
        settable = hasattr(args, attr) or (
            attr == "operating_target_speed" and hasattr(args, "target_speed")
        )
        if settable and flag not in typed and value is not None:
            setattr(args, attr, tuple(value) if isinstance(value, tuple) else value)
            args.from_operating = (*getattr(args, "from_operating", ()), flag)
    law = drive_clamp(design)[0]  # [models], else [operating] clamp_law
    if hasattr(args, "clamp_law") and not typed & {"--clamp-law", "--clamp"} and law:
        if law not in CLAMP_LAWS.names():
            raise InputError("models.clamp_law", law, "one of " + ", ".join(CLAMP_LAWS.names()))
        args.clamp_law = law
    if getattr(args, "clamp_law", None) == "constant" and "--clamp" not in typed:
        if op is not None and op.clamp_force is not None:
            args.clamp = op.clamp_force


def law(args) -> dict:
    """``clamp_force`` or ``clamp_law`` keyword of the Python API from the options."""
    if args.clamp_law == "constant":
        return {"clamp_force": PAPER_POINT.clamp_force if args.clamp is None else args.clamp}
    if args.clamp is not None:
        raise InputError(
            "clamp",
            args.clamp,
            f"not given with --clamp-law {args.clamp_law}",
            message=f"--clamp is the constant law's force: not given with "
            f"--clamp-law {args.clamp_law} (the law sets the force)",
        )
    return {"clamp_law": args.clamp_law}


def clamp_label(args) -> str:
    """The clamping of a figure's title, then each model that is not the paper's
    (traction law, lubrication, oil temperature: `models_used`)."""
    if args.clamp_law == "constant":
        force = PAPER_POINT.clamp_force if args.clamp is None else args.clamp
        label = f"$F_{{N0}}$ = {force:g} N"
    else:
        label = f"{args.clamp_law} clamping"
    design, fluid = open_drive(
        getattr(args, "design", None),
        getattr(args, "fluid", None),
        getattr(args, "traction_law", None),
    )
    models = effective_models(
        design, fluid, clamp_law=args.clamp_law, traction_law=fluid.traction_law
    )
    oil = getattr(args, "oil_temperature", None)  # --oil-temperature wins over the file
    if oil is not None:
        models["oil_temperature"] = oil if isinstance(oil, str) else f"{oil:g} C"
    paper = {"traction_law": "isothermal", "lubrication": "full-film", "oil_temperature": "fixed"}
    said = {
        "traction_law": "{} traction",
        "lubrication": "{} lubrication",
        "oil_temperature": "oil {}",
    }
    return ", ".join(
        [label] + [said[k].format(models[k]) for k, m in paper.items() if models[k] != m]
    )


def show(args) -> bool:
    """Progress bars: not with ``--quiet``, else when stderr is a terminal."""
    return False if args.quiet else sys.stderr.isatty()


def rpm(speed: float) -> float:
    """A ``--speed`` value [rpm], checked."""
    if not speed > 0 or speed == float("inf"):
        raise InputError("speed", speed, "> 0 rpm and finite")
    return speed


def grid_options(p, *, n_ratio: int, n_torque: int, most: int, torque_max: str) -> None:
    """The ratio x torque grid of ``map`` and ``table``."""
    p.add_argument(
        "--ratio-range",
        type=number,
        nargs=2,
        default=(0.5, 2.0),
        metavar=("MIN", "MAX"),
        help="ratio range (default: the drive's [operating] ratio_range, else 0.5 2)",
    )
    p.add_argument(
        "--n-ratio",
        type=count(2, most),
        default=n_ratio,
        help=f"ratios, 2-{most} (default: %(default)s)",
    )
    p.add_argument(
        "--torque-max",
        type=quantity("torque_max", "N m", most=MOST_TORQUE),
        default=None,
        help=f"largest torque [N m] (default: {torque_max})",
    )
    p.add_argument(
        "--n-torque",
        type=count(2, most),
        default=n_torque,
        help=f"torques, 2-{most} (default: %(default)s)",
    )


def life(args) -> dict:
    """``life_model`` and ``material`` keywords of the Python API from the options."""
    return {"life_model": args.life_model, "material": args.material}


def life_line(life: dict) -> str:
    """One line of a life's ``to_dict`` or a cycle's ``summary["life"]``."""
    hours = life["l10_hours"]
    text = "infinite" if hours is None else f"{hours:.4g} h"
    return f"system L10 {text} ({life['model']}), limited by {life['limiting_element'] or '-'}"
