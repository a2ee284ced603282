"""``ballcvt life``: rolling-contact fatigue life at a point or over a duty cycle."""

from __future__ import annotations

from pathlib import Path

from ...api import read_cycle
from ...errors import InputError
from . import options as o
from .cycle_options import cycle_options, cycle_settings
from .oil_option import add_oil_option


def add_parser(subparsers) -> None:
    """Add ``life`` and its options."""
    p = o.sub(
        subparsers,
        "life",
        "rolling-contact fatigue life (L10) at a point or over a duty cycle",
        "The L10 fatigue life of every disc, idler and ball track (a contact life model "
        "on the solved loads, pressures and speeds) and of the support bearings rated in "
        "the design ([design.bearings]: catalogue C), and of the drive as all of them in "
        "series, with the element that limits it (docs/life.md). At an operating point "
        "(the options of 'ballcvt point'), or over a duty cycle by Miner's rule with "
        "--cycle (the options of 'ballcvt cycle'; a vehicle_speed column gives the life "
        "in km).",
        "ballcvt life --design hub --clamp-law cam --ratio 1.5 --torque 30 --speed 180\n"
        "  ballcvt life --design hub --clamp-law cam --cycle "
        "examples/cycles/ebike_commute.csv --target-speed 180 --json",
    )
    o.add(p, "arch", "ratio", "torque", *o.CLAMP_OPTIONS, "speed", *o.FLUID_OPTIONS)
    o.add(p, "life-model", "material", "json")
    add_oil_option(p, "balance")
    p.add_argument(
        "--cycle",
        type=Path,
        default=None,
        metavar="CYCLE.csv",
        help="a duty cycle (docs/cycles.md): its life by Miner's rule instead of a point's",
    )
    cycle_options(p)
    o.run_options(p)


def run(args) -> int:
    """Compute the life; print it as a table or JSON."""
    v = o.variator(args)
    if args.cycle is not None:
        return _cycle(args, v)
    _point_only(args)
    r = v.life(
        args.ratio,
        args.torque,
        life_model=args.life_model,
        material=args.material,
        **o.law(args),
        input_speed_rpm=o.rpm(args.speed),
    )
    if args.json:
        o.emit_json(r.to_dict())
        return 0
    rows = [f"{'element':<18} {'parts':>5} {'L10 [h]':>11} {'L10 [cycles]':>13}"]
    for name, e in r.elements.items():
        rows.append(f"{name:<18} {e.count:>5} {e.l10_hours:>11.4g} {e.l10_cycles:>13.4g}")
    rows += [f"note: {n}" for n in r.notes]
    o.emit("\n".join(rows + ([] if args.quiet else [o.life_line(r.to_dict())])))
    return 0


def _point_only(args) -> None:
    """Refuse the duty-cycle options without ``--cycle`` (they would do nothing)."""
    given = {
        "--strategy": args.strategy is not None,
        "--target-speed": args.target_speed is not None,
        "--candidates": args.candidates is not None,
        "--ratio-range": args.ratio_range is not None,
        "--workers": args.workers != 1,
    }
    for flag, used in given.items():
        if used and flag not in getattr(args, "from_operating", ()):
            raise InputError(flag, None, "--cycle", message=f"{flag} needs --cycle")


def _cycle(args, v) -> int:
    """The life over ``--cycle`` by Miner's rule."""
    o.input_file(args.cycle, "cycle file")
    cycle = read_cycle(args.cycle)
    result = v.cycle_life(
        cycle,
        **o.law(args),
        settings=cycle_settings(args, cycle.kind),
        life_model=args.life_model,
        material=args.material,
    )
    life = result.summary["life"]
    if args.json:
        rest = {k: v for k, v in result.summary.items() if k != "life"}
        o.emit_json({**life, "cycle": rest})
        return 0
    rows = [f"{'element':<18} {'Miner L10 [h]':>13}"]
    rows += [f"{k:<18} {e['l10_hours']:>13.4g}" for k, e in life["elements"].items()]
    km = "" if life["l10_km"] is None else f", {life['l10_km']:.4g} km"
    rows.append(
        f"{cycle.name}: damage {life['damage_per_pass']:.4g} per pass, "
        f"{life['l10_passes']:.4g} passes{km}; "
        f"{life['steps_not_counted']} steps without a solution not counted"
    )
    o.emit("\n".join(rows + ([] if args.quiet else [o.life_line(life)])))
    return 0
