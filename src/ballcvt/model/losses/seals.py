"""Shaft seals: one contact lip seal on each disc shaft (docs/model.md §12).

The built-in loss term ``seals``, read from ``design.parasitic``.
"""

from __future__ import annotations

from ...registry import LOSS_TERMS
from .base import DragInputs, LossTerm, has_parasitic

__all__ = ["seal_torque", "SEALS"]


def seal_torque(diameter, k1, beta, k2):
    """Friction torque of one contact lip seal ``M = K_S1 d_s^beta + K_S2`` [N m].

    The form of the SKF model of the seals' frictional moment (SKF, Rolling bearings,
    catalogue 17000 EN, 2018, "The SKF model for calculating the frictional moment"), with
    ``d_s`` in mm and ``M`` in N mm; the constants depend on the seal type and size and
    come from its maker.

    Parameters
    ----------
    diameter : float
        Seal counterface diameter ``d_s`` [m].
    k1, beta, k2 : float
        ``K_S1`` [N mm / mm^beta], ``beta`` [-], ``K_S2`` [N mm].

    Returns
    -------
    float
        Torque [N m].
    """
    return 1e-3 * (k1 * (diameter * 1e3) ** beta + k2)


def _seals(at: DragInputs):
    """Torque of the seal on one shaft (`seal_torque`; zero without a seal) [N m]."""
    par = at.design.parasitic
    assert par is not None
    if par.seal_diameter > 0:
        return seal_torque(par.seal_diameter, par.seal_k1, par.seal_beta, par.seal_k2)
    return 0.0


SEALS = LOSS_TERMS.register(
    LossTerm(
        "seals",
        "shafts",
        _seals,
        "seals",
        "design.parasitic: seal_diameter, seal_k1, seal_beta, seal_k2",
        has_parasitic,
    )
)
