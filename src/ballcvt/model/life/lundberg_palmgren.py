"""Lundberg and Palmgren's life of a rolling track (docs/life.md §3.1), and its variant
with the ISO 281 fatigue limit (§3.3)."""

from __future__ import annotations

import numpy as np

from ...params.material import FatigueMaterial
from ...registry import LIFE_MODELS
from .base import LifeModel, TrackContact

__all__ = ["lundberg_palmgren_l10", "fatigue_limit_l10", "lp_life"]


def lp_life(tau, z0, semi_major, track_length, material: FatigueMaterial):
    """Lundberg-Palmgren life for a given shear stress amplitude.

    ``ln(1/S) = tau^c N^e a z0 l / (A' z0^h)`` with ``S = 0.9`` gives
    ``L10^e = A z0^(h-1) / (tau^c a l)`` (Lundberg and Palmgren 1947, Eq. 19; Harris
    and Kotzalas, Rolling Bearing Analysis, 5th ed., Eq. 23.19), with ``A`` the
    material's ``lp_constant`` (the factor ``ln(1/0.9)`` included).

    Parameters
    ----------
    tau : array_like
        Amplitude of the orthogonal shear stress [Pa] (``<= 0``: infinite life).
    z0 : array_like
        Its depth [m].
    semi_major : array_like
        Contact semi-axis transverse to rolling ``a`` [m].
    track_length : array_like
        Track circumference ``l`` [m].
    material : FatigueMaterial
        ``c``, ``h``, ``e`` and ``A``.

    Returns
    -------
    ndarray
        ``L10`` [stress cycles].
    """
    m = material
    with np.errstate(divide="ignore"):
        log_tau = np.log(np.maximum(np.asarray(tau, dtype=float), 0.0))
        log_life = (
            np.log(m.lp_constant)
            + (m.depth_exponent - 1.0) * np.log(z0)
            - m.stress_exponent * log_tau
            - np.log(semi_major)
            - np.log(track_length)
        ) / m.weibull_slope
    with np.errstate(over="ignore"):
        return np.exp(log_life)


def lundberg_palmgren_l10(contact: TrackContact, material: FatigueMaterial) -> np.ndarray:
    """Lundberg-Palmgren ``L10`` of a track [stress cycles] (`lp_life` at ``tau0``).

    At fixed contact curvatures ``tau0``, ``z0`` and ``a`` grow as ``Q^(1/3)``, so
    ``L10 ~ Q^-((c - h + 2) / (3 e)) = Q^-3``, i.e. ``p0^-9``.
    """
    return lp_life(contact.tau0, contact.z0, contact.semi_major, contact.track_length, material)


def fatigue_limit_l10(contact: TrackContact, material: FatigueMaterial) -> np.ndarray:
    """Lundberg-Palmgren ``L10`` with the ISO 281 fatigue limit subtracted [stress cycles].

    ``tau0`` is replaced by ``tau0 - tau_u``, with ``tau_u = tau0 p_u / p0`` the
    orthogonal shear stress of the same ellipse at the fatigue-limit pressure ``p_u``
    (ISO 281:2007 §9.3 and Annex; Ioannides and Harris, J. Tribol. 107 (1985) 367):
    ``L10 = L10_LP (1 - p_u / p0)^(-c/e)``, infinite for ``p0 <= p_u``. The material
    constant is Lundberg-Palmgren's, not recalibrated, so this life is always the longer.
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        margin = np.where(
            contact.p_max > 0.0, 1.0 - material.fatigue_limit_pressure / contact.p_max, 0.0
        )
    tau = contact.tau0 * np.maximum(margin, 0.0)
    return lp_life(tau, contact.z0, contact.semi_major, contact.track_length, material)


LIFE_MODELS.register(
    LifeModel(
        "lundberg-palmgren",
        lundberg_palmgren_l10,
        "Lundberg-Palmgren (1947): orthogonal shear stress, depth and stressed volume",
    )
)
LIFE_MODELS.register(
    LifeModel(
        "iso-fatigue-limit",
        fatigue_limit_l10,
        "Lundberg-Palmgren with the ISO 281 fatigue-limit stress subtracted",
    )
)
