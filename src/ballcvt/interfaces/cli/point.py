"""``ballcvt point``: solve one operating point (default: the paper's)."""

from __future__ import annotations

import json

from ...api import PlanetaryResult, SolveSettings
from . import options as o
from .format import planetary_table, point_table
from .modes import add_mode_options, mode_of
from .oil_option import add_oil_option, oil_setting


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
    add_mode_options(p)
    add_oil_option(p, "balance")


def run(args) -> int:
    """Solve the point; print it as a table or JSON."""
    v = o.variator(args)
    mode = mode_of(args)
    r = v.solve(
        ratio=args.ratio,
        output_torque=args.torque,
        **o.law(args),
        input_speed_rpm=o.rpm(args.speed),
        settings=SolveSettings(mode=mode, **oil_setting(args)),
    )
    models = o.models_used(args, v)
    if args.json:
        o.emit_json({**json.loads(r.to_json()), "models": models})
    else:
        table = planetary_table(r) if isinstance(r, PlanetaryResult) else point_table(r)
        o.emit(table + "\nmodels      " + ", ".join(f"{k} {m}" for k, m in models.items()))
    return 0
