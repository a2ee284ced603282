"""What a life model is: a `LifeModel` in the `LIFE_MODELS` registry, evaluated on a
`TrackContact` (docs/life.md §3).

A new life model is one module: define its ``l10(contact, material)`` function and
register a `LifeModel` (see `ballcvt.model.life.lundberg_palmgren`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from ...errors import InputError
from ...params.material import FatigueMaterial
from ...registry import LIFE_MODELS
from .stress import orthogonal_shear, peak_pressure

__all__ = ["LIFE_MODELS", "LifeModel", "TrackContact", "track_contact"]


@dataclass(frozen=True)
class TrackContact:
    """A Hertz contact rolling along a closed track, with its subsurface stress (arrays
    of one shape).

    Attributes
    ----------
    load : ndarray
        Normal load ``Q`` [N].
    semi_major, semi_minor : ndarray
        Semi-axes transverse to (``a``) and along (``b``) the rolling direction [m].
    track_length : ndarray
        Length ``l`` of the rolling track (its circumference) [m].
    p_max : ndarray
        Peak Hertz pressure ``p0`` [Pa].
    tau0, z0 : ndarray
        Orthogonal shear stress amplitude [Pa] and its depth [m].
    """

    load: np.ndarray
    semi_major: np.ndarray
    semi_minor: np.ndarray
    track_length: np.ndarray
    p_max: np.ndarray
    tau0: np.ndarray
    z0: np.ndarray

    @property
    def stressed_volume(self) -> np.ndarray:
        """Lundberg and Palmgren's stressed volume ``V = a z0 l`` [m^3]."""
        return self.semi_major * self.z0 * self.track_length


def track_contact(load, semi_major, semi_minor, track_length) -> TrackContact:
    """The `TrackContact` of a load, its Hertz semi-axes and its track length.

    Parameters
    ----------
    load : array_like
        Normal load ``Q`` [N] (``<= 0``: unloaded, infinite life).
    semi_major, semi_minor : array_like
        Semi-axes transverse to (``a``) and along (``b``) the rolling direction [m]
        (any value where unloaded).
    track_length : array_like
        Circumference of the rolling track ``l`` [m].

    Raises
    ------
    InputError
        If a loaded contact has a semi-axis or track length that is not positive.
    """
    arrays = np.broadcast_arrays(
        *(np.asarray(x, dtype=float) for x in (load, semi_major, semi_minor, track_length))
    )
    load, a, b, length = (np.array(x) for x in arrays)
    loaded = load > 0.0
    for name, value in (("semi_major", a), ("semi_minor", b), ("track_length", length)):
        bad = loaded & ~(value > 0.0)
        if np.any(bad):
            raise InputError(name, float(value[bad].flat[0]), "> 0 [m] where the load is > 0")
    # An unloaded contact (its semi-axes may be zero) gets a unit ellipse and no stress.
    a, b, length = (np.where(loaded, x, 1.0) for x in (a, b, length))
    p0 = np.where(loaded, peak_pressure(np.where(loaded, load, 0.0), a, b), 0.0)
    tau0, z0 = orthogonal_shear(a, b, p0)
    return TrackContact(load, a, b, length, p0, tau0, z0)


@dataclass(frozen=True)
class LifeModel:
    """A named rolling-contact fatigue life model.

    Attributes
    ----------
    name : str
        Its registered name (``ballcvt.registry.LIFE_MODELS``).
    l10 : callable
        ``l10(contact: TrackContact, material: FatigueMaterial) -> ndarray``: the life
        with 90 % survival of every point of the track, in stress cycles [-] (one cycle:
        one passage of the contact over a point of the track); ``inf`` where unloaded.
    summary : str
        One line for listings and the documentation.
    """

    name: str
    l10: Callable[[TrackContact, FatigueMaterial], np.ndarray]
    summary: str
