"""``ballcvt limit``: the limiting output torque at a ratio, clamp and speed."""

from __future__ import annotations

from ..._version import __version__
from . import options as o
from .format import limit_table
from .modes import add_mode_options, mode_of
from .oil_option import add_oil_option


def add_parser(subparsers) -> None:
    """Add ``limit`` and its options."""
    p = o.sub(
        subparsers,
        "limit",
        "limiting output torque at a ratio, clamp and speed",
        "The largest output torque with a converged equilibrium and every abs(creep) <= "
        "the creep limit (docs/model.md section 8); under the cam law also every peak "
        "pressure <= the design's max_pressure (section 11). Where the admissible torques "
        "do not run from zero to it (a cam with a small preload) they are shown as "
        "intervals (JSON: capacity_intervals, [[lo, hi], ...] in N m). The constraint that sets "
        "the limit is named (JSON: active_constraint, e.g. 'creep (output contact)' or "
        "'pressure (max_pressure 3 GPa)'; interval_constraints: the constraint of each end).",
        "ballcvt limit --arch single --ratio 2 --clamp 2000 --speed 2000",
    )
    o.add(p, "arch", "ratio", *o.CLAMP_OPTIONS, "speed", "creep-limit", *o.FLUID_OPTIONS, "json")
    add_mode_options(p, "the limit is the driven member's largest load torque")
    add_oil_option(p, "balance")


def run(args) -> int:
    """Find the limit; print it as a table or JSON."""
    v = o.variator(args)
    c_lim = v.design.creep_limit if args.creep_limit is None else args.creep_limit
    law = o.law(args)
    where = {"input_speed_rpm": o.rpm(args.speed), "creep_limit": c_lim}
    mode = mode_of(args)
    if mode.is_default:
        cap = v.capacity(args.ratio, **law, **where)
        if not cap.intervals:  # none admissible: the limit search says why
            v.limit_torque(args.ratio, **law, **where)
        largest, spans = cap.largest, [list(span) for span in cap.intervals]
        active, ends = cap.active_constraint, [list(pair) for pair in cap.constraints]
    else:  # a planetary mode: the driven member's largest load, from zero
        largest = v.limit_torque(ratio=args.ratio, **law, **where, mode=mode)
        spans, active, ends = [[0.0, largest]], None, None
    data = {
        "limit_torque": largest,
        "capacity_intervals": spans,
        "active_constraint": active,
        "interval_constraints": ends,
        "architecture": args.arch,
        "ratio": args.ratio,
        "clamp_law": args.clamp_law,
        "clamp_force": law.get("clamp_force"),
        "input_speed_rpm": args.speed,
        "creep_limit": c_lim,
        "design": v.design.name,
        "version": __version__,
    }
    if not mode.is_default:  # the limit is the driven member's load torque
        data["mode"] = {
            "label": mode.label,
            "held": mode.held,
            "driver": mode.driver,
            "driven": mode.driven,
            "held_speed_rpm": args.held_speed,
            "centrifugal": mode.centrifugal,
            "gyroscopic": mode.gyroscopic,
        }
    o.emit_json(data) if args.json else o.emit(limit_table(data))
    return 0
