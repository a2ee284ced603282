"""Names, units and long names of every variable a sweep writes (CF-style attributes).

The ``loss`` axis of ``losses`` is `SWEEP_LOSSES`: the components (`LOSS_COMPONENTS`, each
loss counted once, ``user_terms`` what user-registered loss terms dissipate) and one
``total``, their sum; the subtotals ``bearing`` and ``parasitic`` are the variable
``loss_subtotals`` on its own ``subtotal`` axis (a sweep's CSV keeps their ``loss_bearing``
and ``loss_parasitic`` columns).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...performance.efficiency import LOSS_KINDS  # the ``loss`` axis of a sweep
from ...performance.validity import WARNINGS
from ...status import Status

__all__ = [
    "VARIABLES",
    "POINT_VARIABLES",
    "CONTACT_VARIABLES",
    "LOSS_KINDS",
    "LOSS_COMPONENTS",
    "LOSS_SUBTOTALS",
    "SWEEP_LOSSES",
    "component_losses",
    "subtotal_losses",
    "contact_columns",
    "attrs_for",
    "SWEEP_CODES",
]

#: The subtotals of `LOSS_KINDS`, kept apart from the ``loss`` axis (``loss_subtotals``).
LOSS_SUBTOTALS = ("bearing", "parasitic")
#: The components of a sweep's ``loss`` axis (each loss counted once; ``user_terms`` is
#: what user-registered loss terms dissipate); they sum to ``total`` to round-off.
LOSS_COMPONENTS = (
    *(k for k in LOSS_KINDS if k not in (*LOSS_SUBTOTALS, "total")),
    "user_terms",
)
#: The ``loss`` axis of a sweep: the components, then one ``total``.
SWEEP_LOSSES = (*LOSS_COMPONENTS, "total")


def component_losses(kinds: np.ndarray) -> np.ndarray:
    """The `SWEEP_LOSSES` [W] from losses by every kind of `LOSS_KINDS` (last axis).

    ``user_terms`` is the parasitic subtotal less the built-in parasitic components (zero,
    not round-off, where no user term dissipates).
    """
    k = {name: kinds[..., i] for i, name in enumerate(LOSS_KINDS)}
    user = k["parasitic"] - (k["churning"] + k["seals"] + k["disc_bearings"] + k["hub_bearings"])
    user = np.where(np.abs(user) <= 1e-12 * np.maximum(1.0, np.abs(k["parasitic"])), 0.0, user)
    parts = [k[name] for name in LOSS_COMPONENTS[:-1]]
    return np.stack([*parts, user, k["total"]], axis=-1)


def subtotal_losses(kinds: np.ndarray) -> np.ndarray:
    """The `LOSS_SUBTOTALS` [W] (``loss_subtotals``) from losses by every kind of
    `LOSS_KINDS` (last axis)."""
    return kinds[..., [LOSS_KINDS.index(k) for k in LOSS_SUBTOTALS]]


def contact_columns(contacts: list, names) -> list[int]:
    """The columns of a sweep's ``contact`` axis ``contacts`` that an architecture's
    contacts ``names`` (`ballcvt.model.architectures.CONTACT_NAMES`) take, in their order."""
    return [contacts.index(c) for c in names]


#: The ``status`` codes a sweep writes (`ballcvt.status.Status`).
SWEEP_CODES = (Status.CONVERGED, Status.BEYOND_LIMIT, Status.NOT_CONVERGED)


#: name -> (units, long name). Dimensionless quantities have units "1" (CF conventions).
VARIABLES = {
    "ratio": ("1", "ideal speed ratio tau_ID"),
    "output_torque": ("N m", "output torque T_2"),
    "clamp_force": ("N", "clamping force at the input contact F_N0"),
    "axial_force": ("N", "axial thrust on each disc n F_N0 sin(theta_0)"),
    "input_speed": ("rad/s", "input speed omega_0"),
    "input_speed_rpm": ("rpm", "input speed omega_0"),
    "limit_torque": (
        "N m",
        "largest admissible output torque (all |creep| <= creep_limit; status 1 marks "
        "the torques beyond the capacity, also below it under a cam with a small preload)",
    ),
    "eta_at_limit": ("1", "overall efficiency (Eq. 38) at the limiting output torque"),
    "status": ("1", "point status: 0 converged, 1 beyond the traction capacity, 2 not converged"),
    "iterations": ("1", "solver iterations (residual-and-Jacobian evaluations)"),
    "residual_norm": ("1", "max |residual| of the equilibrium at the solution"),
    "eta": ("1", "overall efficiency (Eq. 38)"),
    "eta_loss": ("1", "overall efficiency from the power losses (Eq. 39)"),
    "eta_speed": ("1", "speed efficiency (Eq. 9)"),
    "eta_torque": ("1", "torque efficiency (Eq. 37)"),
    "input_torque": ("N m", "input torque T_0"),
    "actual_ratio": ("1", "actual speed ratio omega_2 / omega_0"),
    "tilt_deg": ("degree", "ball tilt angle gamma"),
    "losses": (
        "W",
        "power loss by kind (Eq. 40): the components creep, spin, roller_bearings, "
        "idler_bearings, churning, seals, disc_bearings, hub_bearings, user_terms, which "
        "sum to total",
    ),
    "loss_subtotals": (
        "W",
        "bearing (roller + idler bearings) and parasitic (churning + seals + disc "
        "bearings + user terms) power loss",
    ),
    "subtotal": ("1", "loss subtotal"),
    "warnings": ("1", "validity warnings (bit flags, docs/model.md section 10)"),
    "creep": ("1", "creep coefficient C (Eq. 7)"),
    "spin": ("1", "spin coefficient sigma (Eqs. 11-14)"),
    "mu": ("1", "traction coefficient mu (Eq. 30)"),
    "chi": ("1", "spin-moment coefficient chi (Eq. 31)"),
    "p_max": ("Pa", "Hertz peak pressure"),
    "film_thickness": ("m", "central film thickness (Hamrock-Dowson)"),
    "normal_load": ("N", "contact normal load F_N"),
    "creep_loss": ("W", "creep power loss of the contact, all balls"),
    "spin_loss": ("W", "spin power loss of the contact, all balls"),
    "lambda_ratio": ("1", "film thickness ratio h_min / surface roughness"),
    "loss": ("1", "kind of power loss"),
    "l10_hours": ("h", "system L10 rolling-contact fatigue life (docs/life.md)"),
    "damage": ("1", "Miner damage of the step, per pass over the cycle (docs/life.md)"),
}

POINT_VARIABLES = (
    "eta",
    "eta_loss",
    "eta_speed",
    "eta_torque",
    "input_torque",
    "actual_ratio",
    "tilt_deg",
    "axial_force",
)
CONTACT_VARIABLES = (
    "creep",
    "spin",
    "mu",
    "chi",
    "p_max",
    "film_thickness",
    "normal_load",
    "creep_loss",
    "spin_loss",
    "lambda_ratio",
)


def attrs_for(name: str) -> dict:
    """CF attributes of a variable: ``units``, ``long_name`` and the flags of ``status`` and
    ``warnings`` (``flag_values`` / ``flag_masks`` with ``flag_meanings``)."""
    units, long_name = VARIABLES[name]
    attrs: dict[str, Any] = {"long_name": long_name}
    if name not in ("status", "warnings"):  # CF: flag variables carry no units
        attrs["units"] = units
    if name == "status":
        attrs.update(
            flag_values=np.array([int(s) for s in SWEEP_CODES], dtype=np.int8),
            flag_meanings=" ".join(s.label for s in SWEEP_CODES),
        )
    elif name == "warnings":
        attrs.update(
            flag_masks=np.array(list(WARNINGS.values()), dtype=np.int8),
            flag_meanings=" ".join(WARNINGS),
        )
    return attrs
