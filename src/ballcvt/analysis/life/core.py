"""The fatigue lives of solved points: every element, the system in series (docs/life.md).

Each element's L10 comes from the physics of `ballcvt.model.life`: a track's in stress
cycles from `contact_l10`, a bearing's in revolutions from its catalogue rating
(`bearing_l10`, the ISO 281 basic rating life, times ``a_ISO`` where the design gives the
contamination factor and the bearing's fatigue load limit).
Dividing by the element's cycle rate gives hours; ``count`` identical parts in series
live ``count^(-1/e)`` times as long as one; the system is every element in series
(`system_l10`, the strict-series Weibull sum with the material's slope ``e``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ...model.life import a_iso, bearing_l10, contact_l10, system_l10
from ...params.material import FatigueMaterial
from ...registry import LIFE_MODELS
from .elements import BearingElement, LifeInputs, bearing_elements, rated_viscosity, track_elements

__all__ = ["LifeSettings", "ElementArrays", "LifeArrays", "life_arrays", "LIFE_MODELS"]

#: Seconds per hour.
HOUR = 3600.0


@dataclass(frozen=True)
class LifeSettings:
    """How lives are computed.

    Attributes
    ----------
    model : str
        Contact life model, a name in ``ballcvt.registry.LIFE_MODELS``.
    material : FatigueMaterial, optional
        Fatigue constants of the tracks; AISI 52100 steel (`FatigueMaterial.builtin`) by
        default.
    """

    model: str = "lundberg-palmgren"
    material: FatigueMaterial | None = field(default=None)

    def check(self) -> LifeSettings:
        """These settings with the material resolved; `InputError` for an unknown model."""
        LIFE_MODELS.get(self.model)
        if self.material is None:
            return LifeSettings(self.model, FatigueMaterial.builtin())
        return self


@dataclass(frozen=True)
class ElementArrays:
    """One element's lives over a batch of ``m`` points (see `ElementLife`)."""

    kind: str
    body: str
    count: int
    l10_cycles: np.ndarray
    cycle_rate: np.ndarray
    l10_hours: np.ndarray
    load: np.ndarray


@dataclass(frozen=True)
class LifeArrays:
    """Lives over a batch of ``m`` points.

    Attributes
    ----------
    elements : dict of ElementArrays
    l10_hours : ndarray
        System L10 of each point [h], ``(m,)``.
    notes : tuple of str
        Elements left out and why.
    weibull_slope : float
    """

    elements: dict[str, ElementArrays]
    l10_hours: np.ndarray
    notes: tuple[str, ...]
    weibull_slope: float

    def limiting(self) -> np.ndarray:
        """Name of the element of the shortest life at each point (``""`` where every life
        is infinite or unknown)."""
        names = list(self.elements)
        hours = np.stack([self.elements[k].l10_hours for k in names], axis=-1)
        hours = np.where(np.isnan(hours), np.inf, hours)
        best = np.argmin(hours, axis=-1)
        out = np.array(names, dtype=object)[best]
        return np.where(np.isfinite(np.min(hours, axis=-1)), out, "")


def _hours(cycles, rate, count, slope):
    """Hours of ``count`` parts in series, each of ``cycles`` at ``rate`` per second."""
    with np.errstate(divide="ignore", invalid="ignore"):
        one = np.where(rate > 0, cycles / (rate * HOUR), np.inf)
    return one * float(count) ** (-1.0 / slope)


def life_arrays(x: LifeInputs, settings: LifeSettings) -> LifeArrays:
    """Every element's life and the system life of a batch of solved points.

    Parameters
    ----------
    x : LifeInputs
        Loads, contact semi-axes and speeds of ``m`` points.
    settings : LifeSettings

    Returns
    -------
    LifeArrays
    """
    s = settings.check()
    assert s.material is not None
    e = s.material.weibull_slope
    out: dict[str, ElementArrays] = {}
    for t in track_elements(x):
        cycles = contact_l10(
            t.load, t.semi_major, t.semi_minor, t.track_length, s.material, s.model
        )
        hours = _hours(cycles, t.cycle_rate, t.count, e)
        out[t.name] = ElementArrays("track", t.body, t.count, cycles, t.cycle_rate, hours, t.load)
    bearings, notes = bearing_elements(x)
    for b in bearings:
        with np.errstate(divide="ignore"):
            revs = 1e6 * np.asarray(bearing_l10(b.rating, b.load), dtype=float)
        revs = revs * _life_factor(x, b, notes)
        hours = _hours(revs, b.speed, b.count, e)
        out[b.name] = ElementArrays("bearing", "bearing", b.count, revs, b.speed, hours, b.load)
    system = np.asarray(system_l10(np.stack([v.l10_hours for v in out.values()], -1), e))
    return LifeArrays(out, system, tuple(notes), e)


def _life_factor(x: LifeInputs, b: BearingElement, notes: list[str]):
    """``a_ISO`` of a bearing (ISO 281:2007 §9.3; 1 without ``e_C`` or its ``C_u``), with
    ``kappa = nu / nu_1`` from the design's ``viscosity_ratio`` or the fluid; a ``kappa``
    below the standard's 0.1 counts as 0.1, with a note."""
    ratings = x.design.bearings
    e_c = ratings.contamination_factor
    if e_c is None or b.fatigue_limit is None:
        return 1.0
    given = ratings.viscosity_ratio
    if given is None and b.diameter is None:
        notes.append(f"{b.name}: no a_ISO (no diameter for its rated viscosity)")
        return 1.0
    with np.errstate(divide="ignore", invalid="ignore"):
        kappa = np.asarray(
            x.kinematic_viscosity / rated_viscosity(b.speed, b.diameter)
            if given is None
            else given,
            dtype=float,
        )
    if np.any(kappa < 0.1):
        notes.append(f"{b.name}: viscosity ratio below 0.1 counted as 0.1 (ISO 281 range)")
    with np.errstate(divide="ignore"):
        return a_iso(e_c * b.fatigue_limit / b.load, np.maximum(np.nan_to_num(kappa), 0.1))
