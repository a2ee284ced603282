"""The checks an equilibrium problem's inputs pass before it is built
(`ballcvt.equilibrium.problem.make_problem`): each refuses a value with the quantity's
name, the value and the range allowed (`ballcvt.errors.InputError`)."""

from __future__ import annotations

import numpy as np

from ..errors import InputError
from ..model.inertia import max_carrier_speed
from ..model.kinematics import check_ratio
from ..model.losses import active_terms
from ..model.rheology import roelands_pressure_limit
from ..params.models import Design, Fluid

__all__ = [
    "MIN_POSITIVE",
    "check_inputs",
    "check_no_drags",
    "check_idler_loads",
    "check_pressure",
    "check_positive",
]

#: Smallest clamping force [N] and input speed [rad/s] accepted: far below any physical
#: use (one revolution in 72 days), and above the range where the film thickness and the
#: traction integrals underflow double precision (docs/model.md §10).
MIN_POSITIVE = 1e-6


def check_inputs(design: Design, torque_given: bool, inputs) -> None:
    """Refuse out-of-range operating inputs ``(ratio, T_2, F_N0, omega_0, omega_c)``."""
    ratio, t2, fn0, w0, wc = inputs
    if torque_given:
        check_positive("output_torque", t2, "N m", strict=False)
    elif not np.all(np.isfinite(t2)):
        raise InputError("load_torque", float(t2[~np.isfinite(t2)].flat[0]), "finite")
    if not np.all(np.isfinite(wc)):
        raise InputError("carrier_speed", float(wc[~np.isfinite(wc)].flat[0]), "finite")
    check_positive("clamp_force", fn0, "N", floor=MIN_POSITIVE)
    check_positive("input_speed", w0, "rad/s", floor=MIN_POSITIVE)
    check_ratio(design, ratio)


def check_no_drags(design: Design) -> None:
    """Refuse parasitic losses with the carrier turning (not modelled yet, §13)."""
    terms = active_terms(design)
    if not terms:
        return
    name, value = (
        ("design.parasitic", "set")
        if design.parasitic is not None
        else ("loss term", terms[0].name)
    )
    raise InputError(
        name,
        value,
        "absent with the carrier turning (the shaft drags need the absolute speeds; "
        "not modelled yet, docs/model.md §13)",
    )


def check_idler_loads(design, layout, clamp_force, carrier_speed) -> None:
    """Refuse carrier speeds at which the balls' centrifugal force lifts them off the idler."""
    w_max = max_carrier_speed(design, layout, clamp_force)
    bad = np.abs(carrier_speed) >= w_max
    if np.any(bad):
        i = np.argmax(bad)
        raise InputError(
            "carrier_speed",
            float(carrier_speed.flat[i]),
            f"|carrier_speed| < {float(w_max.flat[i]):.4g} rad/s at clamp_force "
            f"{float(clamp_force.flat[i]):g} N: faster, the balls' centrifugal "
            "force lifts them off the idler",
        )


def check_pressure(fluid: Fluid, clamp_force: np.ndarray, p_max: np.ndarray) -> None:
    """Refuse clamping forces whose peak pressure has no finite Roelands viscosity."""
    p_lim = roelands_pressure_limit(
        fluid.viscosity, fluid.pole_viscosity, fluid.pole_pressure, fluid.roelands_index
    )
    worst = np.max(p_max, axis=-1) if p_max.size else p_max
    bad = worst > p_lim
    if np.any(bad):
        i = np.argmax(np.where(bad, worst, -np.inf))
        f, p = float(clamp_force.flat[i]), float(worst.flat[i])
        raise InputError(
            "clamp_force",
            f,
            f"<= {f * (p_lim / p) ** 3:.4g} N: its peak "
            f"pressure {p / 1e9:.4g} GPa exceeds the {p_lim / 1e9:.4g} GPa beyond "
            "which the Roelands viscosity (Eq. 51) overflows",
        )


def check_positive(
    name: str, value: np.ndarray, unit: str, strict: bool = True, floor: float = 0.0
) -> None:
    ok = np.isfinite(value) & (
        (value >= floor) if floor else (value > 0) if strict else (value >= 0)
    )
    if not ok.all():
        bad = float(value[~ok].flat[0]) if value.ndim else float(value)
        allowed = (
            f">= {floor:g} {unit} and finite"
            if floor
            else f"{'>' if strict else '>='} 0 {unit} and finite"
        )
        raise InputError(name, bad, allowed)
