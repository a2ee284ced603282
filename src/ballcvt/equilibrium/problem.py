"""The creep-independent part of an equilibrium problem: geometry, loads, Hertz contacts.

An `EquilibriumProblem` holds one operating point or a batch of them (leading axes of
every array); the per-contact arrays have the contacts on the last axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from typing import Any

import numpy as np

from .._compat import moved_names
from ..model.architectures import ContactLayout, contact_layout
from ..model.hertz import hertz_contact, rolling_curvature_ratio, transverse_curvature_ratio
from ..model.inertia import (
    centrifugal_force,
    gyro_factor,
    idler_share,
    max_carrier_speed,
    roller_mass,
)
from ..model.kinematics import (
    body_speeds,
    rolling_radius,
    spin_axis_projection,
    tilt_from_ratio,
)
from ..model.losses import PARASITIC_KINDS, drag_magnitudes
from ..params.drive import Drive
from ..params.models import Design, Fluid
from .checks import (  # noqa: F401 (MIN_POSITIVE: named here as before)
    MIN_POSITIVE,
    check_idler_loads,
    check_inputs,
    check_no_drags,
    check_positive,
    check_pressure,
)

__all__ = [
    "EquilibriumProblem",
    "OperatingInputs",
    "CarrierFrame",
    "make_problem",
    "build_problem",
    "with_clamp_force",
    # the inertia of the balls lives in the model layer; named here as before
    "roller_mass",
    "centrifugal_force",
    "idler_share",
    "gyro_factor",
    "max_carrier_speed",
]

#: Renamed (one name per body: the paper's "roller"); answered with a warning.
__getattr__ = moved_names(__name__, {"ball_mass": "ballcvt.model.inertia:roller_mass"})

#: Fields with the batch shape ``(...)`` and with a trailing axis, ``(..., n_c)`` or
#: ``(..., n_kinds)``.
_BATCH = (
    "ratio",
    "tilt",
    "output_torque",
    "clamp_force",
    "input_speed",
    "carrier_speed",
    "gyro_factor",
)
_PER_CONTACT = (
    "rho",
    "sz",
    "load",
    "ax",
    "ay",
    "p_max",
    "roller_drag",
    "input_drag",
    "output_drag",
    "disc_drag",
)


@dataclass(frozen=True)
class EquilibriumProblem:
    """Everything about an operating point that does not depend on the creeps.

    Attributes
    ----------
    design, fluid : Design, Fluid
        Parameter sets.
    layout : ContactLayout
        Contact layout of the architecture.
    ratio, tilt, output_torque, clamp_force, input_speed : ndarray
        Ideal ratio [-], tilt [rad], ``T_2`` [N m], ``F_N0`` [N], ``omega_0`` [rad/s];
        shape ``(...)``.
    rho, sz : ndarray
        Rolling radius factor ``rho_c`` and ``s . z_c`` (docs/model.md §1), ``(..., n_c)`` [-].
    load : ndarray
        Normal loads ``F_Nc`` [N], ``(..., n_c)``.
    radius : ndarray
        Contact radii ``r_c`` [m], ``(n_c,)``.
    rx : ndarray
        Equivalent rolling-direction radii ``R_x`` [m], ``(n_c,)``.
    ax, ay, p_max : ndarray
        Hertz semi-axes [m] and peak pressure [Pa], ``(..., n_c)``.
    roller_drag : ndarray
        Parasitic drag torque on each ball about its spin axis by kind (``drag_kinds``)
        [N m], ``(..., n_kinds)``; zero without ``design.parasitic`` and user loss terms
        (docs/model.md §12).
    input_drag, output_drag : ndarray
        Magnitudes of the parasitic drag torques on the input and output shafts by kind
        [N m], ``(..., n_kinds)``; each opposes its shaft's solved rotation
        (`ballcvt.model.losses.shaft_drags`).
    disc_drag : ndarray
        Magnitudes of the drag torques between the discs by kind (the disc thrust
        bearing) [N m], ``(..., n_kinds)``; each opposes the discs' solved relative speed.
    carrier_speed : ndarray
        Carrier speed ``omega_c`` [rad/s], ``(...)``; zero for the paper's drive. The
        other speeds are relative to the carrier (docs/model.md §13).
    gyro_factor : ndarray
        ``I omega_c sin(gamma) / r_S`` [kg m/s]: times ``omega_S``, the force at each
        axle bearing that carries the ball's gyroscopic moment (docs/model.md §13); zero
        without it.
    torque_weights : tuple of float
        ``(a, b)`` of the torque condition ``a T_0 + b T_2 = output_torque`` closing the
        last balance; ``(0, 1)`` (the output torque given) by default. Then
        ``output_torque`` is the condition's target and may be negative.
    drag_kinds : tuple of str
        The loss kinds of the last axis of the drags (`ballcvt.model.losses.drag_kinds`):
        ``churning, seals, disc_bearings, hub_bearings``, then those of user loss terms.
    """

    design: Design
    fluid: Fluid
    layout: ContactLayout
    ratio: np.ndarray
    tilt: np.ndarray
    output_torque: np.ndarray
    clamp_force: np.ndarray
    input_speed: np.ndarray
    rho: np.ndarray
    sz: np.ndarray
    load: np.ndarray
    radius: np.ndarray
    rx: np.ndarray
    ax: np.ndarray
    ay: np.ndarray
    p_max: np.ndarray
    roller_drag: np.ndarray
    input_drag: np.ndarray
    output_drag: np.ndarray
    disc_drag: np.ndarray
    carrier_speed: np.ndarray = None  # type: ignore[assignment]
    gyro_factor: np.ndarray = None  # type: ignore[assignment]
    torque_weights: tuple = (0.0, 1.0)
    drag_kinds: tuple[str, ...] = PARASITIC_KINDS

    def __post_init__(self):
        for name in ("carrier_speed", "gyro_factor"):
            if getattr(self, name) is None:
                object.__setattr__(self, name, np.zeros(self.tilt.shape))

    @property
    def shape(self) -> tuple[int, ...]:
        """Batch shape ``(...)``."""
        return self.tilt.shape

    @property
    def size(self) -> int:
        """Number of operating points in the batch."""
        return math.prod(self.tilt.shape)  # (np.prod: some 5 us a call, many a Newton run)

    def _map(self, batch, per_contact) -> EquilibriumProblem:
        # a new instance without `replace`'s __init__ (a fifth of a sub-batch's cost in a
        # Newton iteration): the fields copied, the batch's reshaped, no memos
        out = object.__new__(EquilibriumProblem)
        mine, new = self.__dict__, out.__dict__
        new.update((n, mine[n]) for n in _FIELDS)
        new.update((n, batch(mine[n])) for n in _BATCH)
        new.update((n, per_contact(mine[n])) for n in _PER_CONTACT)
        for name in mine.get("_carried", ()):
            value = _carry(mine["_memo_" + name], len(self.shape), batch, per_contact)
            if value is not None:
                out.memo(name, lambda v=value: v, carried=True)
        return out

    def flat(self) -> EquilibriumProblem:
        """The same points as a 1-D batch (C order)."""
        return self._map(lambda a: a.reshape(-1), lambda a: a.reshape(-1, a.shape[-1]))

    def take(self, index) -> EquilibriumProblem:
        """The points ``index`` (integer or boolean array) of a 1-D batch."""
        return self._map(lambda a: a[index], lambda a: a[index])

    def expand(self) -> EquilibriumProblem:
        """Insert a trailing batch axis of length 1 (to broadcast over perturbations).

        Kept on the instance after the first call (every Newton iteration of a solve asks
        for it; the problem is immutable, so the cache cannot go stale)."""
        return self.memo(
            "expanded", lambda: self._map(lambda a: a[..., None], lambda a: a[..., None, :])
        )

    def memo(self, name: str, build, carried: bool = False):
        """``build()``, computed once per instance and kept under ``name``: for quantities
        derived from the problem alone (the problem is immutable, so they cannot go
        stale; `replace` gives a new instance without them).

        ``carried``: the value is computed point by point, and `flat`, `take` and `expand`
        hand it on, reshaped as they reshape the fields (a Newton iteration on the points
        still iterating then builds no constants again): an array with the batch's
        dimensions or one more, or a dict of such arrays, flags and None; a dict holding
        anything else is built again."""
        key = "_memo_" + name
        value = self.__dict__.get(key)
        if value is None:
            value = build()
            object.__setattr__(self, key, value)
            if carried:
                object.__setattr__(self, "_carried", self.__dict__.get("_carried", ()) + (name,))
        return value

    @property
    def reduced_modulus(self) -> float:
        """``E'`` [Pa]."""
        return self.design.material.reduced_modulus

    @property
    def torque_scale(self) -> np.ndarray:
        """``n F_N0 r_S``, the scale of the body-torque residuals [N m]."""
        return self.design.n_rollers * self.clamp_force * self.design.roller_radius


def _carry(value, ndim: int, batch, per_contact):
    """A carried memo through `EquilibriumProblem._map` (``ndim``: the batch's
    dimensions), or None where it must be built again."""
    if isinstance(value, np.ndarray):
        return batch(value) if value.ndim == ndim else per_contact(value)
    out = {}
    for k, v in value.items():
        if isinstance(v, np.ndarray):
            out[k] = batch(v) if v.ndim == ndim else per_contact(v)
        elif v is None or isinstance(v, bool):  # the same for every point
            out[k] = v
        else:
            return None
    return out


#: The fields of an `EquilibriumProblem` (`EquilibriumProblem._map` copies them).
_FIELDS = tuple(f.name for f in fields(EquilibriumProblem))


@dataclass(frozen=True)
class OperatingInputs:
    """The operating inputs of an equilibrium problem (arrays broadcast together).

    Attributes
    ----------
    ratio : array_like
        Ideal speed ratio ``tau_ID`` within `ratio_range` [-].
    output_torque : array_like
        Output torque ``T_2`` >= 0 [N m] (or the target of `CarrierFrame.torque_weights`).
    clamp_force : array_like
        Input-contact normal load ``F_N0`` > 0 [N].
    input_speed : array_like
        Input speed ``omega_0`` > 0 [rad/s] (relative to the carrier).
    """

    ratio: Any
    output_torque: Any
    clamp_force: Any
    input_speed: Any


@dataclass(frozen=True)
class CarrierFrame:
    """How the carrier turns and what closes the last balance (docs/model.md §13).

    Attributes
    ----------
    carrier_speed : array_like
        Carrier speed ``omega_c`` [rad/s]; 0: the paper's drive.
    torque_weights : (float, float)
        ``(a, b)`` of the torque condition ``a T_0 + b T_2 = output_torque``; with the
        default ``(0, 1)`` ``output_torque`` is ``T_2 >= 0``, otherwise any finite target.
    centrifugal, gyroscopic : bool
        Include the balls' centrifugal force and gyroscopic moment when the carrier turns.
    signed_torque : bool
        Accept a negative ``output_torque`` (the output disc driving the balls, as a
        planetary mode may have it in the carrier frame).
    """

    carrier_speed: Any = 0.0
    torque_weights: tuple = (0.0, 1.0)
    centrifugal: bool = True
    gyroscopic: bool = True
    signed_torque: bool = False


def build_problem(
    design: Design,
    fluid: Fluid,
    architecture: str,
    ratio,
    output_torque,
    clamp_force,
    input_speed,
) -> EquilibriumProblem:
    """`make_problem` for the paper's drive (carrier held, output torque given), with the
    drive and the operating inputs given one by one.

    Parameters
    ----------
    design, fluid : Design, Fluid
        Parameter sets.
    architecture : str
        Idler architecture (`ballcvt.registry.ARCHITECTURES`).
    ratio, output_torque, clamp_force, input_speed : array_like
        The fields of `OperatingInputs`.

    Returns
    -------
    EquilibriumProblem
    """
    return make_problem(
        Drive(design, fluid, architecture),
        OperatingInputs(ratio, output_torque, clamp_force, input_speed),
    )


def make_problem(
    drive: Drive, point: OperatingInputs, frame: CarrierFrame = CarrierFrame()
) -> EquilibriumProblem:
    """Assemble an `EquilibriumProblem`; the operating inputs broadcast together.

    Parameters
    ----------
    drive : Drive
        Design, fluid and architecture (any object with these three attributes).
    point : OperatingInputs
        Ratio, output torque, clamping force and input speed.
    frame : CarrierFrame
        Carrier speed and torque condition; by default the paper's drive (carrier held,
        output torque given).

    Returns
    -------
    EquilibriumProblem
    """
    design, fluid = drive.design, drive.fluid
    layout = contact_layout(design, drive.architecture)
    ratio, t2, fn0, w0, wc = np.broadcast_arrays(
        *(
            np.asarray(v, dtype=float)
            for v in (
                point.ratio,
                point.output_torque,
                point.clamp_force,
                point.input_speed,
                frame.carrier_speed,
            )
        )
    )
    weights = (float(frame.torque_weights[0]), float(frame.torque_weights[1]))
    check_inputs(
        design, weights == (0.0, 1.0) and not frame.signed_torque, (ratio, t2, fn0, w0, wc)
    )
    tilt = tilt_from_ratio(ratio, design.theta0, design.theta2, design.aspect_ratio)
    rs = design.roller_radius
    rx = rolling_curvature_ratio(layout.radius, design.aspect_ratio) * rs
    turning = bool(np.any(wc != 0.0))
    if turning:
        check_no_drags(design)
    centrifugal = None
    if turning and frame.centrifugal:
        check_idler_loads(design, layout, fn0, wc)
        centrifugal = centrifugal_force(design, wc)[..., None] * idler_share(layout, design)
    forced = _force_fields(drive, layout, (tilt, rx), (fn0, w0, t2), centrifugal)
    return EquilibriumProblem(
        design=design,
        fluid=fluid,
        layout=layout,
        ratio=ratio,
        tilt=tilt,
        output_torque=t2,
        input_speed=w0,
        rho=rolling_radius(layout, tilt),
        sz=spin_axis_projection(layout, tilt),
        radius=layout.radius * rs,
        rx=rx,
        carrier_speed=wc,
        gyro_factor=(
            gyro_factor(design, tilt, wc) if turning and frame.gyroscopic else np.zeros(wc.shape)
        ),
        torque_weights=weights,
        **forced,
    )


def _force_fields(drive, layout: ContactLayout, geometry, inputs, centrifugal=None) -> dict:
    """The fields of `make_problem` that depend on the clamping force: the loads, the
    Hertz contacts (Eqs. 48-50, their peak pressure checked) and the parasitic drags'
    magnitudes at the creep-free speeds (their directions follow the solved speeds in the
    residual, docs/model.md §12). ``geometry``: ``(tilt, R_x)``; ``inputs``: ``(F_N0,
    omega_0, T_2)``; ``centrifugal``: the balls' centrifugal force on each contact [N],
    or None."""
    design, fluid = drive.design, drive.fluid
    (tilt, rx), (fn0, w0, t2) = geometry, inputs
    load = fn0[..., None] * layout.load_factor
    if centrifugal is not None:
        load = load - centrifugal
    ry = transverse_curvature_ratio(layout.groove_ratio) * design.roller_radius
    ax, ay, p_max, _ = hertz_contact(load, rx, ry, design.material.reduced_modulus)
    check_pressure(fluid, fn0, p_max)
    omega_s, omega = body_speeds(layout, tilt, np.zeros(layout.n_contacts), w0)
    thrust = design.n_rollers * fn0 * np.sin(design.theta0)
    drags = drag_magnitudes(design, fluid, w0, omega[..., -1], omega_s, thrust, t2)
    return {
        "clamp_force": fn0,
        "load": load,
        "ax": ax,
        "ay": ay,
        "p_max": p_max,
        "roller_drag": drags.roller,
        "input_drag": drags.input,
        "output_drag": drags.output,
        "disc_drag": drags.between,
        "drag_kinds": drags.kinds,
    }


def with_clamp_force(problem: EquilibriumProblem, clamp_force) -> EquilibriumProblem:
    """The points of ``problem`` at the clamping forces ``clamp_force`` [N]: the problem
    `build_problem` makes of its ratio, torque and speed at those forces (the paper's
    frame: carrier held, output torque given).

    Where the forces have the batch's shape and the problem is in that frame, only the
    fields that depend on the force are built again (`_force_fields`), the same values in
    half the time (a clamping law's or the optimal clamp's search builds one such problem
    per round); otherwise the whole problem is (`build_problem`).
    """
    fn0 = np.asarray(clamp_force, dtype=float)
    t2 = problem.output_torque
    paper = problem.torque_weights == (0.0, 1.0) and not np.any(problem.carrier_speed)
    if fn0.shape != problem.shape or not paper:
        return build_problem(
            problem.design,
            problem.fluid,
            problem.layout.architecture,
            problem.ratio,
            t2,
            fn0,
            problem.input_speed,
        )
    check_positive("output_torque", t2, "N m", strict=False)  # as `build_problem` would
    check_positive("clamp_force", fn0, "N", floor=MIN_POSITIVE)
    geometry, inputs = (problem.tilt, problem.rx), (fn0, problem.input_speed, t2)
    return replace(problem, **_force_fields(problem, problem.layout, geometry, inputs))
