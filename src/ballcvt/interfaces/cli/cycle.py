"""``ballcvt cycle``: a duty cycle's energy, efficiency and losses over a time series."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

from ...api import read_cycle
from ...errors import InputError
from ...files import check_output_dir
from . import options as o
from .cycle_options import cycle_options, cycle_settings
from .modes import add_mode_options, mode_of
from .oil_option import add_oil_option, oil_setting


def add_parser(subparsers) -> None:
    """Add ``cycle`` and its options."""
    p = o.sub(
        subparsers,
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
    o.add(p, "arch", *o.CLAMP_OPTIONS, *o.FLUID_OPTIONS)
    cycle_options(p)
    add_oil_option(p, "transient")
    o.out(p, "ballcvt-cycle")
    o.add(p, "json", "life", "life-model", "material")
    o.run_options(p)
    add_mode_options(
        p, "the cycle's output is the driven member's speed and load torque", "--target-speed"
    )


def run(args) -> int:
    """Run the cycle; write steps.csv, summary.json and the figure; print a summary."""
    o.input_file(args.cycle_file, "cycle file")
    out = check_output_dir(args.out)
    cycle = read_cycle(args.cycle_file)
    v = o.variator(args)
    settings = replace(cycle_settings(args, cycle.kind), **oil_setting(args))
    mode = mode_of(args)
    if args.life and not mode.is_default:
        raise InputError(
            "--life",
            "with --held/--driver",
            "the carrier-held drive only (fatigue life over a cycle in a planetary mode is "
            "not modelled)",
        )
    result = (
        v.cycle_life(cycle, **o.law(args), settings=settings, **o.life(args))
        if args.life
        else v.run_cycle(cycle, **o.law(args), settings=settings, mode=mode)
    )
    result.save(out)
    import matplotlib

    matplotlib.use("Agg")  # the CLI writes files only
    from ...plotting import cycle_figure, save

    s = result.summary
    title = f"{cycle.name}: {v.design.name}, {s['strategy']}, {o.clamp_label(args)}"
    save(cycle_figure(result.steps, title), out, "cycle")
    if args.json:
        o.emit_json(s)
    elif not args.quiet:
        eff = "n/a" if s["efficiency"] is None else f"{s['efficiency']:.4f}"
        o.emit(
            f"wrote {out}/steps.csv, summary.json, cycle.png, cycle.svg: {s['steps']} steps "
            f"({s['duration_s']:.0f} s), energy in {s['energy_in_J'] / 3.6e3:.2f} Wh, out "
            f"{s['energy_out_J'] / 3.6e3:.2f} Wh, efficiency {eff}; {s['steps_flagged']} "
            f"steps flagged; {s['run_time_s']:.1f} s on {args.workers} worker(s)"
            + (f"; {o.life_line(s['life'])}" if args.life else "")
            + _oil_line(s.get("oil_temperature"))
        )
    return 0


def _oil_line(oil) -> str:
    """The oil's temperatures of the summary, when modelled (``--oil-temperature``)."""
    if oil is None:
        return ""
    return f"; oil {oil['max_C']:.1f} C max, {oil['final_C']:.1f} C at the end ({oil['model']})"
