"""Power losses (Eqs. 39-40) and efficiency two ways (Eq. 38 and Eq. 39).

Both are computed from a solved `EquilibriumState`; at an equilibrium they agree to
round-off, an identity of the balances that tests the signs (docs/model.md §7).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..equilibrium.problem import EquilibriumProblem
from ..equilibrium.residual import EquilibriumState
from ..model.kinematics import creep_term
from ..model.losses import DragMagnitudes, drag_power

__all__ = [
    "PowerLosses",
    "Efficiency",
    "power_losses",
    "efficiency",
    "loss_breakdown",
    "LOSS_KINDS",
]

#: Kinds of power loss, the keys of `loss_breakdown` (``bearing`` = roller + idler
#: bearings, ``parasitic`` = churning + seals + disc bearings, ``total`` = all).
LOSS_KINDS = (
    "creep",
    "spin",
    "roller_bearings",
    "idler_bearings",
    "bearing",
    "churning",
    "seals",
    "disc_bearings",
    "hub_bearings",
    "parasitic",
    "total",
)


@dataclass(frozen=True)
class PowerLosses:
    """Dissipated power [W] (Eq. 40, idler bearings counted once per idler, docs/model.md §7).

    Attributes
    ----------
    creep, spin : ndarray
        Per contact, summed over the ``n`` balls, shape ``(..., n_c)``.
    roller_bearings : ndarray
        ``n T_BLS |omega_S|``, shape ``(...)``.
    idler_bearings : ndarray
        ``T_BL,c |Omega_c|`` per contact (0 at the discs), shape ``(..., n_c)``.
    by_kind : dict of ndarray
        Parasitic losses by kind of loss term (docs/model.md §12; zero without
        ``design.parasitic`` and user loss terms), shape ``(...)`` each: ``churning`` of
        the balls and discs, the two shaft ``seals``, the discs' thrust bearings
        (``disc_bearings``), then each user term's kind (`ballcvt.registry.LOSS_TERMS`).
    """

    creep: np.ndarray
    spin: np.ndarray
    roller_bearings: np.ndarray
    idler_bearings: np.ndarray
    by_kind: dict

    @property
    def churning(self) -> np.ndarray:
        """Churning of the balls and discs [W]."""
        return self.by_kind["churning"]

    @property
    def seals(self) -> np.ndarray:
        """The two shaft seals [W]."""
        return self.by_kind["seals"]

    @property
    def disc_bearings(self) -> np.ndarray:
        """The discs' thrust bearing [W]."""
        return self.by_kind["disc_bearings"]

    @property
    def bearing(self) -> np.ndarray:
        """All bearing losses [W]."""
        return self.roller_bearings + np.sum(self.idler_bearings, axis=-1)

    @property
    def parasitic(self) -> np.ndarray:
        """Churning, seal and disc-bearing losses and those of user terms [W]."""
        kinds = iter(self.by_kind.values())
        total = next(kinds)
        for value in kinds:
            total = total + value
        return total

    @property
    def total(self) -> np.ndarray:
        """``P_loss = P_CR + P_SP + P_BL`` (Eq. 40) plus the parasitic losses [W]."""
        return np.sum(self.creep + self.spin, axis=-1) + self.bearing + self.parasitic


def loss_breakdown(losses: PowerLosses) -> dict:
    """Every kind of `LOSS_KINDS` summed over the contacts [W], shape ``(...)`` each,
    with the kind of each user loss term after ``disc_bearings`` (its power is also in
    ``parasitic`` and ``total``)."""
    return {
        "creep": losses.creep.sum(axis=-1),
        "spin": losses.spin.sum(axis=-1),
        "roller_bearings": losses.roller_bearings,
        "idler_bearings": losses.idler_bearings.sum(axis=-1),
        "bearing": losses.bearing,
        **losses.by_kind,
        "parasitic": losses.parasitic,
        "total": losses.total,
    }


@dataclass(frozen=True)
class Efficiency:
    """Efficiencies [-]: speed (Eq. 9), torque (Eq. 37), overall by Eq. 38 and Eq. 39."""

    speed: np.ndarray
    torque: np.ndarray
    overall: np.ndarray
    from_losses: np.ndarray


def power_losses(problem: EquilibriumProblem, state: EquilibriumState) -> PowerLosses:
    """Creep, spin and bearing losses of a solved state (Eq. 40).

    Creep loss per contact ``n |F_c| u_ref |c|`` (``u_ref c`` is the gross sliding speed:
    ``|omega_0| r_0 C_0`` at the input, ``|omega_S| r_Sc C_c`` elsewhere); spin loss
    ``n |T_c sigma_c Omega_c|``.

    Parameters
    ----------
    problem : EquilibriumProblem
    state : EquilibriumState

    Returns
    -------
    PowerLosses
    """
    n = problem.design.n_rollers
    creep = n * np.abs(state.force * state.u_ref * creep_term(state.creep))
    spin = n * np.abs(state.moment * state.spin * state.omega)
    roller = n * state.roller_bearing_torque * np.abs(state.omega_s)
    idler = state.idler_bearing_torque * np.abs(state.omega)
    # parasitic drags times the solved speeds they oppose, by kind (docs/model.md §12)
    drags = DragMagnitudes(
        problem.drag_kinds,
        problem.roller_drag,
        problem.input_drag,
        problem.output_drag,
        problem.disc_drag,
    )
    shafts = drag_power(drags, state.omega[..., 0], state.omega[..., -1])
    parasitic = shafts + n * problem.roller_drag * np.abs(state.omega_s)[..., None]
    return PowerLosses(
        creep=creep,
        spin=spin,
        roller_bearings=roller,
        idler_bearings=idler,
        by_kind={kind: parasitic[..., i] for i, kind in enumerate(problem.drag_kinds)},
    )


def efficiency(
    problem: EquilibriumProblem, state: EquilibriumState, losses: PowerLosses | None = None
) -> Efficiency:
    """Speed, torque and overall efficiency, the last by Eq. 38 and by Eq. 39.

    Parameters
    ----------
    problem : EquilibriumProblem
    state : EquilibriumState
    losses : PowerLosses, optional
        Computed if not given.

    Returns
    -------
    Efficiency
    """
    losses = power_losses(problem, state) if losses is None else losses
    c = state.creep
    speed = (1.0 - c[..., 0]) * (1.0 - c[..., -1])  # Eq. 9
    t0 = state.input_torque
    torque = problem.ratio * problem.output_torque / t0  # Eq. 37
    p0 = t0 * problem.input_speed
    return Efficiency(
        speed=speed,
        torque=torque,
        overall=speed * torque,  # Eq. 38
        from_losses=1.0 - losses.total / p0,
    )  # Eq. 39
