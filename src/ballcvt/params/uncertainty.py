"""Uncertain parameters of a drive file: the optional ``[uncertainty]`` table.

Any numeric value of a drive file (``[design]`` and its sub-tables, ``[fluid]``,
``[operating]``) may carry an uncertainty, keyed by its dotted path (docs/uncertainty.md)::

    [uncertainty]
    "design.cam.preload" = { range = [500.0, 1500.0], source = "spring tolerance" }
    "design.cam.ramp_angle_deg" = { relative = 0.2 }          # +-20 %, uniform
    "fluid.limiting_shear_stress" = { distribution = "normal", mean = 2.0e7, std = 2.0e6 }

Every entry is checked when the file is read (`parse_uncertainty`): the path must name a
numeric value the drive has, the distribution its own keys. Whether every value drawn
gives a drive that can be built is known only when the designs are built: those that
cannot are counted and reported by the propagation (`ballcvt.analysis.uncertainty`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any, Literal

from pydantic import model_validator

from ..errors import InputError
from .base import ParameterModel
from .models import Design, Fluid

__all__ = [
    "DISTRIBUTIONS",
    "UncertainParameter",
    "UncertainValue",
    "UncertaintyTable",
    "parse_uncertainty",
    "with_values",
]

#: Distributions an uncertain parameter may follow, with the keys each needs.
DISTRIBUTIONS = {
    "uniform": "range = [lo, hi], or relative = r (nominal x (1 -+ r))",
    "normal": "mean (default: the nominal value) and std, or relative = r (std = r x nominal);"
    " optional range = [lo, hi] truncates it",
    "triangular": "range = [lo, hi] and mode (default: the nominal value)",
    "loguniform": "range = [lo, hi], 0 < lo < hi (a value known to its order of magnitude)",
}
#: Roots of a dotted path: the file's tables (``operating`` lives in the design).
ROOTS = ("design", "fluid", "operating")


class UncertainParameter(ParameterModel):
    """One entry of ``[uncertainty]``: how a value is distributed (`DISTRIBUTIONS`)."""

    distribution: Literal["uniform", "normal", "triangular", "loguniform"] = "uniform"
    range: tuple[float, float] | None = None
    relative: float | None = None
    mean: float | None = None
    std: float | None = None
    mode: float | None = None
    source: str | None = None

    @model_validator(mode="after")
    def _complete(self) -> UncertainParameter:
        d = self.distribution
        if self.range is not None:
            lo, hi = self.range
            if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi):
                raise InputError("range", list(self.range), "[lo, hi], finite, lo < hi")
        if self.relative is not None and not 0 < self.relative < 10:
            raise InputError("relative", self.relative, "0 < relative < 10")
        if self.std is not None and not (math.isfinite(self.std) and self.std > 0):
            raise InputError("std", self.std, "a finite number > 0")
        unused = {
            "uniform": ("mean", "std", "mode"),
            "normal": ("mode",),
            "triangular": ("mean", "std", "relative"),
            "loguniform": ("mean", "std", "mode", "relative"),
        }[d]
        for key in unused:
            if getattr(self, key) is not None:
                raise InputError(key, getattr(self, key), f"not with distribution {d!r}")
        if d == "uniform" and (self.range is None) == (self.relative is None):
            raise InputError("range", self.range, "range = [lo, hi] or relative = r (one of)")
        if d == "normal" and (self.std is None) == (self.relative is None):
            raise InputError("std", self.std, "std or relative (one of), for 'normal'")
        if d in ("triangular", "loguniform") and self.range is None:
            raise InputError("range", None, f"range = [lo, hi] for {d!r}")
        if d == "loguniform" and self.range is not None and self.range[0] <= 0:
            raise InputError("range", list(self.range), "0 < lo < hi for 'loguniform'")
        if d == "triangular" and self.range is not None and self.mode is not None:
            if not self.range[0] <= self.mode <= self.range[1]:
                raise InputError("mode", self.mode, f"within range {list(self.range)}")
        return self


@dataclass(frozen=True)
class UncertainValue:
    """An uncertain value bound to its drive: path, nominal value and the resolved
    distribution parameters (SI, as the drive file's units).

    Parameters
    ----------
    path : str
        Dotted path, e.g. ``"design.cam.preload"``.
    nominal : float
        The drive file's value.
    distribution : str
        A name in `DISTRIBUTIONS`.
    lo, hi : float
        The range (uniform, triangular, loguniform; truncation of a normal; else -inf, inf).
    mean, std, mode : float
        The normal's mean and standard deviation, the triangular's mode (else NaN).
    integer : bool
        The value is a whole number (rounded when drawn).
    source : str
        Where the uncertainty comes from ("" if not said).
    """

    path: str
    nominal: float
    distribution: str
    lo: float
    hi: float
    mean: float = math.nan
    std: float = math.nan
    mode: float = math.nan
    integer: bool = False
    source: str = ""

    def describe(self) -> str:
        """The distribution in words, e.g. ``uniform 500 to 1500``."""
        if self.distribution == "normal":
            cut = f", within {self.lo:.4g} to {self.hi:.4g}" if math.isfinite(self.lo) else ""
            return f"normal, mean {self.mean:.4g}, std {self.std:.4g}{cut}"
        mode = f", mode {self.mode:.4g}" if self.distribution == "triangular" else ""
        return f"{self.distribution} {self.lo:.4g} to {self.hi:.4g}{mode}"


@dataclass(frozen=True)
class UncertaintyTable:
    """The uncertain values of a drive, in the file's order."""

    values: tuple[UncertainValue, ...] = ()

    @property
    def paths(self) -> tuple[str, ...]:
        return tuple(v.path for v in self.values)

    def __len__(self) -> int:
        return len(self.values)


def _lookup(data: dict, path: str) -> Any:
    """The value at ``path`` in the drive's data (``{"design": ..., "fluid": ...}``)."""
    keys = path.split(".")
    if keys[0] == "operating":
        keys = ["design", *keys]
    node: Any = data
    for key in keys:
        if not isinstance(node, dict) or key not in node:
            return None
        node = node[key]
    return node


def _drive_data(design: Design, fluid: Fluid) -> dict:
    return {"design": design.model_dump(), "fluid": fluid.model_dump()}


def _bind(path: str, entry: UncertainParameter, nominal: float) -> UncertainValue:
    """The entry's distribution with the nominal value filled in where it is implied."""
    d, rng, rel = entry.distribution, entry.range, entry.relative
    lo, hi = rng if rng is not None else (-math.inf, math.inf)
    kw: dict[str, Any] = {}
    if d == "uniform" and rel is not None:
        lo, hi = sorted((nominal * (1 - rel), nominal * (1 + rel)))
    if d == "normal":
        kw["mean"] = nominal if entry.mean is None else entry.mean
        kw["std"] = entry.std if entry.std is not None else abs(nominal) * (rel or 0.0)
        if not kw["std"] > 0:
            raise InputError(path, nominal, "a nonzero nominal value for a relative std")
        if rng is not None and not lo <= kw["mean"] <= hi:
            raise InputError(f"{path}.mean", kw["mean"], f"within range [{lo:g}, {hi:g}]")
    if d == "triangular":
        kw["mode"] = nominal if entry.mode is None else entry.mode
        if not lo <= kw["mode"] <= hi:
            raise InputError(f"{path}.mode", kw["mode"], f"within range [{lo:g}, {hi:g}]")
    if d == "uniform" and not hi > lo:
        raise InputError(path, nominal, "a nonzero nominal value for a relative range")
    return UncertainValue(
        path, float(nominal), d, float(lo), float(hi), source=entry.source or "", **kw
    )


def parse_uncertainty(
    table: dict | None, design: Design, fluid: Fluid, source: str = "design file"
) -> UncertaintyTable:
    """Validate the ``[uncertainty]`` table of a drive file against its drive.

    Parameters
    ----------
    table : dict or None
        The table as TOML reads it: dotted path -> inline table (`UncertainParameter`).
    design, fluid : Design, Fluid
        The drive the paths name values of.
    source : str
        The file, for the messages.

    Returns
    -------
    UncertaintyTable
        Empty when ``table`` is None or empty.

    Raises
    ------
    InputError
        A path that names no numeric value of the drive, or an entry whose keys do not make
        a distribution (one line naming the path).
    """
    if not table:
        return UncertaintyTable()
    if not isinstance(table, dict):
        raise InputError("uncertainty", table, "a table of dotted paths")
    data = _drive_data(design, fluid)
    out = []
    for path, entry in table.items():
        value = _lookup(data, path)
        if path.split(".")[0] not in ROOTS or isinstance(value, bool):
            value = None
        if not isinstance(value, (int, float)) or not math.isfinite(value):
            raise InputError(
                "uncertainty",
                path,
                "the dotted path of a finite number of the drive (e.g. 'design.cam.preload')",
                message=f"{source}: [uncertainty] {path!r} names no finite number of the drive",
            )
        try:
            if not isinstance(entry, dict):
                raise InputError(path, entry, "an inline table, e.g. { relative = 0.2 }")
            bound = _bind(path, UncertainParameter(**entry), float(value))
        except InputError as exc:
            raise InputError(
                exc.quantity,
                exc.value,
                exc.allowed,
                message=f"{source}: [uncertainty] {path!r}: {exc}",
            ) from None
        out.append(replace(bound, integer=isinstance(value, int)))
    return UncertaintyTable(tuple(out))


def with_values(design: Design, fluid: Fluid, values: dict[str, float]) -> tuple[Design, Fluid]:
    """The drive with the values at the dotted paths replaced, through the normal
    validators (`InputError` when the drive cannot be built with them)."""
    data = _drive_data(design, fluid)
    for path, value in values.items():
        keys = path.split(".")
        if keys[0] == "operating":
            keys = ["design", *keys]
        node = data
        for key in keys[:-1]:
            node = node[key]
        node[keys[-1]] = int(round(value)) if isinstance(node[keys[-1]], int) else float(value)
    return Design(**data["design"]), Fluid(**data["fluid"])
