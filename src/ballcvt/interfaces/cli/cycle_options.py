"""The duty-cycle options shared by ``ballcvt cycle`` and ``ballcvt life --cycle``
(docs/cli.md, docs/cycles.md)."""

from __future__ import annotations

from ...api import STRATEGIES, CycleSettings
from .options import MOST_RPM, count, number, quantity, rpm, show

__all__ = ["cycle_options", "cycle_settings"]


def cycle_options(p) -> None:
    """The ratio strategy of a duty cycle (``cycle`` and ``life --cycle``)."""
    p.add_argument(
        "--strategy",
        choices=STRATEGIES,
        default=None,
        help="how the ratio is chosen (default: target-input-speed with --target-speed, "
        "else max-efficiency; an input-side cycle with a ratio column takes none)",
    )
    p.add_argument(
        "--target-speed",
        type=quantity("target_speed", "rpm", most=MOST_RPM),
        default=None,
        help="input speed held by target-input-speed [rpm] (required by it, refused by "
        "the others)",
    )
    p.add_argument(
        "--candidates",
        type=count(3, 101),
        default=None,
        help="ratios tried per step by max-efficiency, 3-101 (default: 9; refused by the others)",
    )
    p.add_argument(
        "--ratio-range",
        type=number,
        nargs=2,
        default=None,
        metavar=("MIN", "MAX"),
        help="ratios any strategy may use (default: the usable range); a held or "
        "commanded ratio outside runs at its end, flagged ratio_limited",
    )


def cycle_settings(args, kind: str = "output") -> CycleSettings:
    """The `CycleSettings` of `cycle_options` (and ``--workers``, ``--quiet``) for a cycle
    of ``kind`` (``"output"`` or ``"input"``).

    Without ``--target-speed``, the drive file's ``[operating]`` input speed is held where
    the target-input-speed strategy would run: an output-side cycle, no ``--strategy``
    other than it and no ``--candidates`` (which ask for max-efficiency).
    """
    target = args.target_speed
    fallback = getattr(args, "operating_target_speed", None)
    if (
        target is None
        and fallback is not None
        and kind == "output"
        and args.strategy in (None, "target-input-speed")
        and args.candidates is None
    ):
        target = fallback
    return CycleSettings(
        strategy=args.strategy,
        target_input_speed_rpm=None if target is None else rpm(target),
        candidates=args.candidates,
        ratio_range=args.ratio_range,
        progress=show(args),
        workers=args.workers,
    )
