"""`LifeResult`: the fatigue life of one operating point, element by element."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field
from typing import Any

from ..._display import html_summary, text_summary
from ..._version import __version__

__all__ = ["ElementLife", "LifeResult"]


@dataclass(frozen=True)
class ElementLife:
    """The L10 life of one element (a track or a support bearing; docs/life.md).

    Attributes
    ----------
    kind : {"track", "bearing"}
    body : str
        ``disc``, ``idler``, ``ball`` or ``bearing``.
    count : int
        Identical parts the element stands for (``n`` ball tracks, ``n`` axle bearings).
    l10_cycles : float
        L10 of one part: stress cycles of a track, revolutions of a bearing [-].
    cycle_rate : float
        Stress cycles (tracks) or revolutions (bearings) per second of one part [1/s].
    l10_hours : float
        L10 of all ``count`` parts in series (one part's life times
        ``count^(-1/e)``, ``e`` the Weibull slope) [h]; infinite for a part at rest.
    load : float
        Contact load or bearing equivalent load [N].
    """

    kind: str
    body: str
    count: int
    l10_cycles: float
    cycle_rate: float
    l10_hours: float
    load: float


@dataclass(frozen=True)
class LifeResult:
    """Rolling-contact fatigue life of a solved operating point (docs/life.md).

    Attributes
    ----------
    elements : Mapping[str, ElementLife]
        Per element: disc, idler and ball tracks, and the rated support bearings.
    l10_hours : float
        System L10: every element in series, ``(sum L_i^-e)^(-1/e)`` [h].
    limiting_element : str
        The element of the shortest life.
    model : str
        Contact life model (``lundberg-palmgren``, ``zaretsky``, ``iso-fatigue-limit``).
    material : str
        Name of the fatigue material.
    weibull_slope : float
        ``e`` of the system sum [-].
    notes : tuple of str
        Elements left out and why (a bearing without a rating in the design).
    point : Mapping[str, float]
        The operating point: ratio [-], output torque [N m], clamp force [N], input speed
        [rpm].
    """

    elements: Mapping[str, ElementLife]
    l10_hours: float
    limiting_element: str
    model: str
    material: str
    weibull_slope: float
    notes: tuple[str, ...] = ()
    point: Mapping[str, float] = field(default_factory=dict)
    version: str = __version__

    def _summary(self) -> tuple[str, list]:
        rows: list = [
            ("system L10", self.l10_hours, "h"),
            ("limiting element", self.limiting_element, ""),
            ("life model", self.model, ""),
        ]
        for name, e in self.elements.items():
            rows.append((f"  {name}", e.l10_hours, f"h ({e.count} x)"))
        return "LifeResult", rows

    def __repr__(self) -> str:
        return text_summary(*self._summary())

    def _repr_html_(self) -> str:
        return html_summary(*self._summary())

    def to_dict(self) -> dict[str, Any]:
        """Plain JSON-able data: ``l10_hours`` (system), ``limiting_element``, ``model``,
        ``elements`` (each with ``l10_cycles`` and ``l10_hours``), ``notes``, ``point``;
        an infinite life (a part at rest) is ``None``."""
        return {
            "l10_hours": _finite(self.l10_hours),
            "limiting_element": self.limiting_element,
            "model": self.model,
            "material": self.material,
            "weibull_slope": self.weibull_slope,
            "elements": {
                k: {n: _finite(v) for n, v in asdict(e).items()} for k, e in self.elements.items()
            },
            "notes": list(self.notes),
            "point": dict(self.point),
            "version": self.version,
        }


def _finite(value):
    """A float as is, an infinite or NaN one as None (strict JSON)."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value
