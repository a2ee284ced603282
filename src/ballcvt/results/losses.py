"""Power losses by component, and exactly one total (docs/model.md §7, §12).

The components are the keys of a `LossBreakdown` other than ``total``: ``creep``,
``spin``, ``roller_bearings``, ``idler_bearings``, ``churning``, ``seals``,
``disc_bearings``, ``hub_bearings`` and the kind of each user loss term (`ballcvt.registry.LOSS_TERMS`).
Each power is counted in exactly one component, and ``total`` is their sum (Eq. 40 plus
the parasitic losses, as the model adds them: ``sum(v for k, v in losses.items() if k !=
"total")`` equals ``losses["total"]`` to round-off, relative 1e-12), so summing the
components never counts a loss twice. ``total`` is the only key that is not a component.

The subtotals of earlier releases are no longer keys (summing the mapping counted their
losses twice): they are the properties ``bearing`` (``roller_bearings +
idler_bearings``) and ``parasitic`` (``churning + seals + disc_bearings`` and the user
terms). ``losses["bearing"]`` and ``losses["parasitic"]`` still answer, with one
`ballcvt.errors.BallCVTDeprecationWarning` naming the property.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping
from typing import Any

from .._compat import warn_renamed

__all__ = ["LossBreakdown", "LOSS_SUBTOTALS", "NOT_PARASITIC"]

#: The old subtotal keys, each now a property of `LossBreakdown`.
LOSS_SUBTOTALS = ("bearing", "parasitic")
#: Components that are not parasitic losses (with the key ``total``).
NOT_PARASITIC = ("creep", "spin", "roller_bearings", "idler_bearings", "total")


class LossBreakdown(Mapping):
    """Power loss by component [W] and their ``total`` (module docstring).

    Parameters
    ----------
    losses : Mapping[str, Any]
        Power by kind [W] (floats, or arrays of one shape): every component, and
        ``total`` (their sum as the model computed it; the sum of the components when
        missing). Subtotal keys (``bearing``, ``parasitic``) are dropped.
    """

    def __init__(self, losses: Mapping[str, Any]) -> None:
        parts = {k: v for k, v in losses.items() if k not in (*LOSS_SUBTOTALS, "total")}
        total: Any = 0.0
        for value in parts.values():
            total = total + value
        self._data = {**parts, "total": losses.get("total", total)}

    def __getitem__(self, key: str) -> Any:
        if key in LOSS_SUBTOTALS:
            warn_renamed(f"losses['{key}']", f"losses.{key} (a subtotal, not a component)")
            return getattr(self, key)
        return self._data[key]

    def __contains__(self, key: object) -> bool:
        return key in self._data

    def __iter__(self) -> Iterator[str]:
        return iter(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def __repr__(self) -> str:
        return f"LossBreakdown({self._data!r})"

    @property
    def components(self) -> dict[str, Any]:
        """Every component [W] (all keys but ``total``)."""
        return {k: v for k, v in self._data.items() if k != "total"}

    @property
    def bearing(self) -> Any:
        """Bearing losses [W]: ``roller_bearings + idler_bearings`` (a subtotal)."""
        return self._data["roller_bearings"] + self._data["idler_bearings"]

    @property
    def parasitic(self) -> Any:
        """Churning, seal, disc-bearing and user-term losses [W] (a subtotal)."""
        total: Any = 0.0
        for key, value in self._data.items():
            if key not in NOT_PARASITIC:
                total = total + value
        return total
