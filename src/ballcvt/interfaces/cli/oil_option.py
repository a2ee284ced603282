"""``--oil-temperature``: the oil's bulk temperature of ``point``, ``cycle``, ``map``,
``table``, ``limit``, ``capacity``, ``shift`` and ``life`` (docs/model.md §15, docs/cli.md)."""

from __future__ import annotations

import argparse

from ...units import celsius_to_kelvin
from .options import number

__all__ = ["add_oil_option", "oil_setting"]


def add_oil_option(p, model: str) -> None:
    """Add ``--oil-temperature {fixed, MODEL} or C`` (``model``: ``balance`` for a point,
    ``transient`` for a cycle)."""
    what = (
        "the housing's steady heat balance"
        if model == "balance"
        else "the housing's lumped transient over the cycle (--initial-oil-temperature C "
        "at its start, the ambient by default)"
    )

    def parse(text: str):
        if text in ("fixed", model):
            return text
        try:
            return number(text)
        except argparse.ArgumentTypeError:
            raise argparse.ArgumentTypeError(
                f"{text!r} is not fixed, {model} or a temperature [C]"
            ) from None

    p.add_argument(
        "--oil-temperature",
        type=parse,
        default=None,
        metavar=f"{{fixed,{model},C}}",
        help=f"the oil's bulk temperature: fixed (the fluid as given), {model} "
        f"({what}, [design.thermal] of the drive file) or a temperature [C]; default: the "
        "drive file's [models] oil_temperature, else fixed",
    )
    if model == "transient":
        p.add_argument(
            "--initial-oil-temperature",
            type=number,
            default=None,
            metavar="C",
            help="oil temperature at the cycle's start with --oil-temperature transient [C]",
        )


def oil_setting(args) -> dict:
    """The API's ``oil_temperature`` (and ``initial_oil_temperature``) of the options, in K."""
    value = args.oil_temperature
    out: dict = {
        "oil_temperature": value
        if value is None or isinstance(value, str)
        else celsius_to_kelvin(value)
    }
    start = getattr(args, "initial_oil_temperature", None)
    if start is not None:
        out["initial_oil_temperature"] = celsius_to_kelvin(start)
    return out
