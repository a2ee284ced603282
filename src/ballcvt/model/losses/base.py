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
    "STICK_SPEED",
    "DragInputs",
    "DragMagnitudes",
    "coulomb_direction",
    "drag_magnitudes",
    "drag_power",
    "shaft_drags",
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

#: Regularisation speed ``omega_s`` of the friction torques' direction [rad/s]
#: (`coulomb_direction`): a shaft or disc-bearing torque reaches its full magnitude to
#: round-off above ``19 omega_s`` = 0.019 rad/s (0.18 rpm), far below any speed a drive
#: runs at; a thrust bearing of 60 mm bore slides at ``3e-5`` m/s at ``omega_s``, within
#: the pre-sliding range of rolling and boundary-lubricated contacts.
STICK_SPEED = 1e-3


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
    input_torque : ndarray or float
        Lossless estimate of the input torque ``T_2 omega_2 / omega_0`` [N m] (the
        output power at the creep-free speeds over the input speed; it is short of the
        solved ``T_0`` by the losses, a few per cent), for a term loaded by the drive's
        torque such as a hub's chain pull; 0 where no torque is given.
    """

    design: Design
    fluid: Fluid
    speed: np.ndarray
    thrust: np.ndarray
    input_torque: Any = 0.0


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
        the shaft's rotation (positive for a positive speed), the terms between the discs
        signed by the discs' relative speed (`shaft_drags`).
    """

    kinds: tuple[str, ...]
    roller: np.ndarray
    input: np.ndarray
    output: np.ndarray


@dataclass(frozen=True)
class DragMagnitudes:
    """Magnitudes of the registered loss terms' torques, by kind (the last axis, `kinds`).

    The directions follow the speeds the torques act at (`shaft_drags`), so an equilibrium
    can take them at its solved speeds while the magnitudes stay those of given speeds.

    Attributes
    ----------
    kinds : tuple of str
        Loss kinds, in order of first registration (`drag_kinds`).
    roller : ndarray
        On each roller (ball) about its spin axis [N m], ``(..., n_kinds)``, >= 0.
    input, output : ndarray
        Of the terms on the input and on the output shaft [N m], ``(..., n_kinds)``, >= 0.
    between : ndarray
        Of the terms between the two discs [N m], ``(..., n_kinds)``, >= 0.
    """

    kinds: tuple[str, ...]
    roller: np.ndarray
    input: np.ndarray
    output: np.ndarray
    between: np.ndarray


def drag_kinds() -> tuple[str, ...]:
    """The loss kinds of the registered terms, in order of first registration."""
    return tuple(dict.fromkeys(term.kind for _, term in LOSS_TERMS.items()))


def active_terms(design: Design) -> tuple[LossTerm, ...]:
    """The registered terms that act on ``design``."""
    return tuple(term for _, term in LOSS_TERMS.items() if term.applies(design))


def coulomb_direction(speed, stick_speed: float = STICK_SPEED):
    """Direction factor ``tanh(omega / omega_s)`` of a friction torque [-].

    Coulomb friction regularised by a hyperbolic tangent (Andersson, Soderberg and
    Bjorklund, "Friction models for sliding dry, boundary and mixed lubricated contacts",
    Tribology International 40 (2007) 580-587, the ``tanh`` model of Sec. 2): the torque
    ``M tanh(omega / omega_s)`` opposes the relative speed ``omega`` and dissipates
    ``M tanh(omega / omega_s) omega >= 0`` at any speed; it equals ``M sign(omega)`` to
    round-off once ``|omega| > 19 omega_s`` and passes smoothly through zero in the stick
    band ``|omega| <~ omega_s`` (where a rigid Coulomb contact would stick at any torque
    below ``M``).

    Parameters
    ----------
    speed : array_like
        Relative speed ``omega`` of the rubbing surfaces [rad/s].
    stick_speed : float
        Regularisation speed ``omega_s`` > 0 [rad/s] (`STICK_SPEED`).

    Returns
    -------
    ndarray
        ``tanh(omega / omega_s)`` in ``[-1, 1]`` [-], of the sign of ``speed``.
    """
    return np.tanh(np.asarray(speed, dtype=float) / stick_speed)


def shaft_drags(drags: DragMagnitudes, input_speed, output_speed):
    """The drag torques on the two shafts, by kind, at the shafts' actual speeds [N m].

    A shaft term opposes its shaft's rotation, a term between the discs their relative
    speed ``omega_0 - omega_2`` (it brakes the faster disc and drives the slower one), each
    through `coulomb_direction`. So the power ``M_0 omega_0 + M_2 omega_2`` of every kind is
    ``>= 0`` at any speeds (docs/model.md §12).

    Parameters
    ----------
    drags : DragMagnitudes
        Torque magnitudes by kind, ``(..., n_kinds)``.
    input_speed, output_speed : array_like
        Disc speeds ``omega_0``, ``omega_2`` [rad/s], broadcasting with ``drags``' batch.

    Returns
    -------
    input, output : ndarray
        Torques opposing the input and output shafts' rotation [N m], ``(..., n_kinds)``.
    """
    w0 = np.asarray(input_speed, dtype=float)[..., None]
    w2 = np.asarray(output_speed, dtype=float)[..., None]
    between = drags.between * coulomb_direction(w0 - w2)
    return (
        drags.input * coulomb_direction(w0) + between,
        drags.output * coulomb_direction(w2) - between,
    )


def drag_power(drags: DragMagnitudes, input_speed, output_speed):
    """Power dissipated by the shaft and between-disc terms, by kind [W].

    ``M_0 omega_0 + M_2 omega_2`` of `shaft_drags`, summed term by term so that each
    product is of two factors of one sign: ``>= 0`` exactly, also where the discs' speeds
    nearly agree.

    Parameters
    ----------
    drags : DragMagnitudes
        Torque magnitudes by kind, ``(..., n_kinds)``.
    input_speed, output_speed : array_like
        Disc speeds ``omega_0``, ``omega_2`` [rad/s].

    Returns
    -------
    ndarray
        ``(..., n_kinds)`` [W].
    """
    w0 = np.asarray(input_speed, dtype=float)[..., None]
    w2 = np.asarray(output_speed, dtype=float)[..., None]
    relative = w0 - w2
    return (
        drags.input * (coulomb_direction(w0) * w0)
        + drags.output * (coulomb_direction(w2) * w2)
        + drags.between * (coulomb_direction(relative) * relative)
    )


def drag_magnitudes(
    design: Design,
    fluid: Fluid,
    input_speed,
    output_speed,
    roller_speed,
    thrust,
    output_torque=0.0,
) -> DragMagnitudes:
    """The registered loss terms' torque magnitudes at given speeds, by kind (§12).

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
    output_torque : array_like
        Output torque ``T_2`` [N m] (default 0): gives the terms the lossless input torque
        ``T_2 |omega_2 / omega_0|`` (`DragInputs.input_torque`).

    Returns
    -------
    DragMagnitudes
    """
    w0, w2, ws, fax, t2 = (
        np.asarray(v, dtype=float)
        for v in (input_speed, output_speed, roller_speed, thrust, output_torque)
    )
    shape = np.broadcast(w0, w2, ws, fax, t2).shape
    kinds = drag_kinds()
    out = {m: np.zeros(shape + (len(kinds),)) for m in ("roller", "input", "output", "between")}
    terms = active_terms(design)
    if terms:  # (none: the paper's drive, every magnitude zero)
        speed_ratio = np.abs(np.divide(w2, w0, out=np.zeros(shape), where=w0 != 0.0))
        t0 = np.abs(t2) * speed_ratio
        speeds = {"roller": ws, "input": w0, "output": w2, "between": w0 - w2}
    for term in terms:
        col = kinds.index(term.kind)
        for member in _MEMBERS[term.acts_on]:
            at = DragInputs(design, fluid, speeds[member], fax, t0)
            # a magnitude, whatever sign a user's function returns
            out[member][..., col] += np.abs(np.asarray(term.torque(at)))
    return DragMagnitudes(kinds, out["roller"], out["input"], out["output"], out["between"])


#: The members of `DragMagnitudes` each place a term acts on loads.
_MEMBERS = {
    "rollers": ("roller",),
    "shafts": ("input", "output"),
    "input": ("input",),
    "output": ("output",),
    "between_discs": ("between",),
}


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
        The torques at these speeds, directed by `shaft_drags`.
    """
    mag = drag_magnitudes(design, fluid, input_speed, output_speed, roller_speed, thrust)
    shape = mag.roller.shape[:-1]
    w0, w2 = (np.broadcast_to(np.asarray(v, float), shape) for v in (input_speed, output_speed))
    m0, m2 = shaft_drags(mag, w0, w2)
    return ParasiticDrags(mag.kinds, mag.roller, m0, m2)


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
        ``churning, seals, disc_bearings, hub_bearings`` first) [N m], shape
        ``(..., n_kinds)``:
        positive where they oppose the shaft's rotation. The disc thrust bearing's torque
        has opposite signs on the two shafts; its power is
        ``M tanh((omega_0 - omega_2) / omega_s) (omega_0 - omega_2) >= 0``
        (`coulomb_direction`).
    """
    drags = parasitic_drags(design, fluid, input_speed, output_speed, roller_speed, thrust)
    return np.sum(drags.roller, axis=-1), drags.input, drags.output
