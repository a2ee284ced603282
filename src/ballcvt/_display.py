"""Short summaries of ballcvt objects for the console and notebooks (``__repr__`` and
``_repr_html_``): a title and rows of (label, value, unit)."""

from __future__ import annotations

import html
import math
from collections.abc import Iterable

__all__ = ["text_summary", "html_summary", "fmt"]

Row = tuple[str, object, str]


def fmt(value: object) -> str:
    """A number to 4 significant figures (integers and text as they are)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return str(value)
    if isinstance(value, int):
        return f"{value:d}"
    if not math.isfinite(value):
        return str(value)
    return f"{value:.4g}"


def text_summary(title: str, rows: Iterable[Row]) -> str:
    """``title`` and aligned ``label  value unit`` lines."""
    rows = list(rows)
    width = max((len(r[0]) for r in rows), default=0)
    lines = [title] + [
        f"  {label:<{width}}  {fmt(value)}{' ' + unit if unit and unit != '-' else ''}"
        for label, value, unit in rows
    ]
    return "\n".join(lines)


def html_summary(title: str, rows: Iterable[Row]) -> str:
    """A small HTML table with ``title`` as its caption."""
    body = "".join(
        f"<tr><th style='text-align:left'>{html.escape(label)}</th>"
        f"<td style='text-align:right'>{html.escape(fmt(value))}</td>"
        f"<td style='text-align:left'>{html.escape('' if unit == '-' else unit)}</td></tr>"
        for label, value, unit in rows
    )
    return (
        f"<table><caption style='text-align:left'><b>{html.escape(title)}</b></caption>"
        f"{body}</table>"
    )
