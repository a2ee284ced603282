"""A parasitic-loss term, and the sum of the registered ones (docs/model.md §12).

A `LossTerm` names a drag torque, the member it acts on and a pure function giving its
magnitude from a `DragInputs`. The terms are kept in `ballcvt.registry.LOSS_TERMS`;
`parasitic_drags` sums every registered term that applies to a design, grouped by the
term's ``kind`` (the key of the loss breakdown), so a term registered from a user's code
enters every solve, sweep and limit search, and shows in a result's losses under its kind.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...errors import InputError
from ...params.models import Design, Fluid
from ...registry import LOSS_TERMS

__all__ = [
    "ACTS_ON",
    "DragInputs",
    "LossTerm",
    "ParasiticDrags",
    "drag_kinds",
    "active_terms",
    "has_parasitic",
    "parasitic_drags",
    "parasitic_torques",
]

#: Where a term acts: each ball about its spin axis, both disc shafts (each at its own
#: speed), one shaft, or between the two discs (a term of their relative speed that brakes
#: the faster disc and drives the slower one, like the thrust bearing closing the clamping
#: loop).
ACTS_ON = ("rollers", "shafts", "input", "output", "between_discs")


@dataclass(frozen=True)
class DragInputs:
    """What a loss term's torque function is given (SI units).

    Attributes
    ----------
    design, fluid : Design, Fluid
        The drive (a term may read ``design.parasitic`` or carry its own numbers).
    speed : ndarray
        Speed of the member the term acts on [rad/s]: the ball's spin ``omega_S``, a
        shaft's ``omega_0`` or ``omega_2`` (positive in the carrier frame), or
        ``omega_0 - omega_2`` between the discs.
    thrust : ndarray
        Axial thrust between the discs ``F_ax = n F_N0 sin(theta_0)`` [N].
    """

    design: Design
    fluid: Fluid
    speed: np.ndarray
    thrust: np.ndarray


def _always(design: Design) -> bool:
    return True


def has_parasitic(design: Design) -> bool:
    """Whether ``design`` has a ``[design.parasitic]`` table (the built-in terms need it)."""
    return design.parasitic is not None


@dataclass(frozen=True)
class LossTerm:
    """One parasitic drag torque: a registry entry of `ballcvt.registry.LOSS_TERMS`.

    Attributes
    ----------
    name : str
        Registry name.
    acts_on : str
        One of `ACTS_ON`.
    torque : callable
        ``torque(inputs: DragInputs) -> array_like``: the torque magnitude [N m] opposing
        the member's motion (per ball for ``"rollers"``); a pure function, broadcasting over
        ``inputs.speed``.
    kind : str
        Key of the loss breakdown the term's power adds to (default: ``name``); built-in
        terms share ``churning``, ``seals`` and ``disc_bearings``.
    parameters : str
        Where the term's numbers come from (for documentation and messages).
    applies : callable
        ``applies(design) -> bool``: whether the term acts on this design (the built-in
        terms need ``design.parasitic``); by default always.
    """

    name: str
    acts_on: str
    torque: Callable[[DragInputs], Any]
    kind: str = ""
    parameters: str = ""
    applies: Callable[[Design], bool] = _always

    def __post_init__(self):
        if self.acts_on not in ACTS_ON:
            raise InputError("acts_on", self.acts_on, "one of: " + ", ".join(ACTS_ON))
        if not self.kind:
            object.__setattr__(self, "kind", self.name)


@dataclass(frozen=True)
class ParasiticDrags:
    """Drag torques of the registered loss terms, by kind (the last axis, `kinds`).

    Attributes
    ----------
    kinds : tuple of str
        Loss kinds, in order of first registration (`drag_kinds`).
    roller : ndarray
        On each roller (ball) about its spin axis [N m], ``(..., n_kinds)``.
    input, output : ndarray
        On the input and output shafts [N m], ``(..., n_kinds)``: signed to oppose
        the shaft's rotation (positive for a positive speed).
    """

    kinds: tuple[str, ...]
    roller: np.ndarray
    input: np.ndarray
    output: np.ndarray


def drag_kinds() -> tuple[str, ...]:
    """The loss kinds of the registered terms, in order of first registration."""
    return tuple(dict.fromkeys(term.kind for _, term in LOSS_TERMS.items()))


def active_terms(design: Design) -> tuple[LossTerm, ...]:
    """The registered terms that act on ``design``."""
    return tuple(term for _, term in LOSS_TERMS.items() if term.applies(design))


def parasitic_drags(
    design: Design, fluid: Fluid, input_speed, output_speed, roller_speed, thrust
) -> ParasiticDrags:
    """Sum the registered loss terms at given speeds, by kind (docs/model.md §12).

    Parameters
    ----------
    design, fluid : Design, Fluid
        The drive; a term that does not apply to it contributes zeros.
    input_speed, output_speed : array_like
        Disc speeds ``omega_0``, ``omega_2`` [rad/s].
    roller_speed : array_like
        Ball spin speed ``omega_S`` [rad/s].
    thrust : array_like
        Disc axial thrust ``F_ax`` [N].

    Returns
    -------
    ParasiticDrags
    """
    w0, w2, ws, fax = (
        np.asarray(v, dtype=float) for v in (input_speed, output_speed, roller_speed, thrust)
    )
    shape = np.broadcast_shapes(w0.shape, w2.shape, ws.shape, fax.shape)
    kinds = drag_kinds()
    out = {m: np.zeros(shape + (len(kinds),)) for m in ("roller", "input", "output")}
    for term in active_terms(design):
        col = kinds.index(term.kind)
        for member, value in _acting(term, DragInputs(design, fluid, w0, fax), w2, ws):
            out[member][..., col] += value
    return ParasiticDrags(kinds, out["roller"], out["input"], out["output"])


def _acting(term: LossTerm, at: DragInputs, output_speed, roller_speed):
    """``(member, signed torque)`` pairs of ``term`` (``at.speed`` is the input speed)."""

    def torque(speed):  # a magnitude, whatever sign a user's function returns
        return np.abs(np.asarray(term.torque(DragInputs(at.design, at.fluid, speed, at.thrust))))

    if term.acts_on == "rollers":
        return [("roller", torque(roller_speed))]
    if term.acts_on == "between_discs":
        relative = at.speed - output_speed
        m = np.sign(relative) * torque(relative)
        return [("input", m), ("output", -1.0 * m)]
    shafts = {"input": at.speed, "output": output_speed}
    members = ("input", "output") if term.acts_on == "shafts" else (term.acts_on,)
    # opposing the shaft's rotation either way (a positive speed: the magnitude itself)
    return [(m, np.where(shafts[m] < 0, -1.0, 1.0) * torque(shafts[m])) for m in members]


def parasitic_torques(
    design: Design, fluid: Fluid, input_speed, output_speed, roller_speed, thrust
):
    """Drag torques of the parasitic losses at given speeds (docs/model.md §12).

    Parameters
    ----------
    design, fluid : Design, Fluid
        The drive; ``design.parasitic`` None and no user term gives zeros (the paper's
        model).
    input_speed, output_speed : array_like
        Disc speeds ``omega_0``, ``omega_2`` [rad/s].
    roller_speed : array_like
        Ball spin speed ``omega_S`` [rad/s].
    thrust : array_like
        Disc axial thrust ``F_ax`` [N].

    Returns
    -------
    ball : ndarray
        Drag torque on each ball about its spin axis [N m], shape ``(...)``.
    input, output : ndarray
        Drag torques on the input and output shafts by kind (`drag_kinds`; the built-in
        ``churning, seals, disc_bearings`` first) [N m], shape ``(..., n_kinds)``:
        positive where they oppose the shaft's rotation. The disc thrust bearing's torque
        has opposite signs on the two shafts; its power is ``M |omega_0 - omega_2|``.
    """
    drags = parasitic_drags(design, fluid, input_speed, output_speed, roller_speed, thrust)
    return np.sum(drags.roller, axis=-1), drags.input, drags.output
