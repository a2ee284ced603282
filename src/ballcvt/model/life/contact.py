"""`contact_l10`: the fatigue life of one rolling track under one contact, by any
registered life model (docs/life.md §3)."""

from __future__ import annotations

import numpy as np

from ...params.material import FatigueMaterial
from ...registry import LIFE_MODELS
from .base import LifeModel, track_contact

__all__ = ["contact_l10", "life_model"]


def life_model(name: str) -> LifeModel:
    """The registered `LifeModel` called ``name`` (`InputError` listing the names)."""
    return LIFE_MODELS.get(name)


def contact_l10(
    load,
    semi_major,
    semi_minor,
    track_length,
    material: FatigueMaterial,
    model: str = "lundberg-palmgren",
):
    """Fatigue life ``L10`` (90 % survival) of a rolling track under a Hertz contact.

    Parameters
    ----------
    load : array_like
        Normal load ``Q`` [N] (``<= 0``: unloaded, infinite life).
    semi_major : array_like
        Contact semi-axis ``a`` transverse to the rolling direction [m] (Lundberg and
        Palmgren's ``a``; the major one in the usual case, any ratio accepted).
    semi_minor : array_like
        Contact semi-axis ``b`` along the rolling direction [m].
    track_length : array_like
        Length ``l`` of the rolling track, the circumference the contact traces on the
        body [m].
    material : FatigueMaterial
        Fatigue constants (`ballcvt.params.material.FatigueMaterial.builtin`).
    model : str
        A name in ``ballcvt.registry.LIFE_MODELS``: ``"lundberg-palmgren"`` (default),
        ``"zaretsky"`` or ``"iso-fatigue-limit"``.

    Returns
    -------
    ndarray
        ``L10`` in stress cycles [-]: passages of the contact over a point of the track
        (``inf`` where the load is zero, or below the fatigue limit).
    """
    entry = life_model(model)
    return np.asarray(
        entry.l10(track_contact(load, semi_major, semi_minor, track_length), material)
    )
