"""``ballcvt point``: solve one operating point (default: the paper's)."""

from __future__ import annotations

import json

from ...api import PlanetaryResult, SolveSettings
from ...units import deg_to_rad
from . import options as o
from .format import planetary_table, point_table
from .modes import add_mode_options, mode_of
from .oil_option import add_oil_option, oil_setting


def add_tilt_rate(p) -> None:
    """``--tilt-rate DEG_PER_S``: the balls' tilt rate of a tilt-direct shift."""
    p.add_argument(
        "--tilt-rate",
        type=o.quantity("tilt_rate", "deg/s", above=0.0, most=1e5),
        default=None,
        metavar="DEG_PER_S",
        help="tilt rate of a tilt-direct shift [deg/s] (> 0, towards a higher ratio; "
        "the Python API takes either sign): adds the moment per ball to tilt the balls at "
        "that rate, shift_moment_Nm (docs/model.md section 17)",
    )


def add_parser(subparsers) -> None:
    """Add ``point`` and its options."""
    p = o.sub(
        subparsers,
        "point",
        "solve one operating point (default: the paper's)",
        "Solve the steady operating point: ratio and tilt, creep, spin, traction, "
        "pressure and film at every contact, the losses and the efficiency (Eq. 38 and "
        "Eq. 39), with validity warnings. A torque beyond the traction capacity is "
        "refused with the limiting torque. The JSON has the moment per ball that holds "
        "the tilt (holding_moment [N m]), the moment about its skew axis (skew_moment_Nm) "
        "and, with --tilt-rate, the moment to shift.",
        "ballcvt point --arch double --ratio 1.76 --torque 40 --clamp 2000 --speed 2000\n"
        "  ballcvt point --design hub --ratio 1.8 --torque 60 --tilt-rate 30 --json\n"
        "  ballcvt point --held disc0 --driver carrier --ratio 0.8 --torque 20 --speed 600",
    )
    o.add(p, "arch", "ratio", "torque", *o.CLAMP_OPTIONS, "speed", *o.FLUID_OPTIONS, "json")
    add_tilt_rate(p)
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
    shift = None
    if not isinstance(r, PlanetaryResult) and args.tilt_rate is not None:
        shift = v.shift_moments_at(r, tilt_rate=deg_to_rad(args.tilt_rate))
    if args.json:
        data = {**json.loads(r.to_json()), "models": models}
        if shift is not None:
            data.update(_shift_json(shift, args.tilt_rate))
        o.emit_json(data)
    else:
        table = planetary_table(r) if isinstance(r, PlanetaryResult) else point_table(r)
        o.emit(table + "\nmodels      " + ", ".join(f"{k} {m}" for k, m in models.items()))
        if shift is not None:
            o.emit(_shift_line(shift, args.tilt_rate))
    return 0


def _shift_json(shift, tilt_rate_deg) -> dict:
    """The moments of a tilt at ``tilt_rate_deg`` in the point's JSON [N m] (the steady
    ``holding_moment`` and ``skew_moment_Nm`` are the result's own)."""
    return {
        "tilt_rate_deg_s": tilt_rate_deg,
        "shift_moment_Nm": shift.shift_moment,
        "shifter_moment_Nm": shift.shifter_moment,
        "shift_saturated": shift.saturated,
        "side_slip": dict(zip(shift.contacts, shift.side_slip, strict=True)),
    }


def _shift_line(shift, tilt_rate_deg) -> str:
    """One line under the point's table: the moments of a tilt at ``tilt_rate_deg``."""
    return (
        f"tilt at {tilt_rate_deg:g} deg/s: {shift.shift_moment:.4g} N m per ball "
        f"(holding {shift.holding_moment:.3g}), {shift.shifter_moment:.4g} N m at the "
        f"shifter ({shift.n_balls} balls)"
        + (", lateral traction saturated" if shift.saturated else "")
    )
