"""Zaretsky's life of a rolling track: stress-life exponent 12, no depth weighting
(docs/life.md §3.2)."""

from __future__ import annotations

import numpy as np

from ...params.material import FatigueMaterial
from ...registry import LIFE_MODELS
from .base import LifeModel, TrackContact

__all__ = ["zaretsky_l10"]


def zaretsky_l10(contact: TrackContact, material: FatigueMaterial) -> np.ndarray:
    """Zaretsky's ``L10`` of a track [stress cycles].

    ``ln(1/S) ~ tau0^(c e) N^e V`` with ``V = a z0 l`` and no depth term (Zaretsky,
    "Rolling bearing life prediction, theory, and application", NASA/TP-2013-215305;
    Zaretsky, Poplawski and Peters, STLE Tribol. Trans. 39 (1996) 237): ``L10 = (B /
    (tau0^(c e) V))^(1/e)``. ``c = n - 2/e`` is set from the stress-life exponent
    ``n = 12`` of the material (Parker and Zaretsky, "Reevaluation of the stress-life
    relation in rolling-element bearings", NASA, 1972: five-ball tests of
    vacuum-degassed 52100; Zaretsky, Poplawski and Root, NASA/TM-2008-214265), so
    that, ``V`` growing as ``p0^2`` at a fixed contact shape, ``L10 ~ p0^-n``, i.e.
    ``Q^-(n/3) = Q^-4`` for a point contact.
    """
    m = material
    exponent = m.zaretsky_stress_exponent * m.weibull_slope - 2.0  # c e
    with np.errstate(divide="ignore"):
        log_life = (
            np.log(m.zaretsky_constant)
            - exponent * np.log(contact.tau0)
            - np.log(contact.stressed_volume)
        ) / m.weibull_slope
    with np.errstate(over="ignore"):
        return np.exp(log_life)


LIFE_MODELS.register(
    LifeModel(
        "zaretsky",
        zaretsky_l10,
        "Zaretsky: stress-life exponent 12, stressed volume without depth weighting",
    )
)
