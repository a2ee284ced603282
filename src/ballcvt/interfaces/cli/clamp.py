"""``ballcvt clamp``: the clamping force of maximum efficiency under the creep and
pressure limits."""

from __future__ import annotations

from ..._version import __version__
from . import options as o
from .format import clamp_table


def add_parser(subparsers) -> None:
    """Add ``clamp`` and its options."""
    p = o.sub(
        subparsers,
        "clamp",
        "clamping force of maximum efficiency under the creep and pressure limits",
        "The input-contact normal load F_N0 that maximises the overall efficiency at "
        "this ratio, torque and speed, keeping every abs(creep) <= the creep limit and "
        "every Hertz peak pressure <= the pressure limit.",
        "ballcvt clamp --ratio 1 --torque 60 --speed 2000 --max-pressure 3e9",
    )
    o.add(p, "arch", "ratio", "torque", "speed", "creep-limit", *o.FLUID_OPTIONS, "json")
    p.add_argument(
        "--max-pressure",
        type=o.quantity("max_pressure", "Pa", most=o.MOST_PRESSURE),
        default=None,
        help="largest admissible Hertz peak pressure [Pa] (default: the design's)",
    )


def run(args) -> int:
    """Find the optimal force; print it as a table or JSON."""
    v = o.variator(args)
    opt = v.optimal_clamp_force(
        ratio=args.ratio,
        output_torque=args.torque,
        input_speed_rpm=o.rpm(args.speed),
        creep_limit=args.creep_limit,
        max_pressure=args.max_pressure,
    )
    data = {
        "clamp_force": opt.clamp_force,
        "eta": opt.eta,
        "max_creep": opt.max_creep,
        "max_pressure": opt.max_pressure,
        "feasible_clamp_range": list(opt.bounds),
        "active_constraint": opt.active,
        "architecture": args.arch,
        "ratio": args.ratio,
        "output_torque": args.torque,
        "input_speed_rpm": args.speed,
        "design": v.design.name,
        "version": __version__,
    }
    o.emit_json(data) if args.json else o.emit(clamp_table(data))
    return 0
