"""Holding and tilt-direct shift moments of solved points (docs/model.md §17).

The contacts of solved points (their creeps, evaluated once by
`ballcvt.equilibrium.evaluate`) with the lateral creep of a tilt rate
(`ballcvt.model.shift`): per point or over a sweep or efficiency map (the variables
``holding_moment``, ``shift_moment``, ``shifter_moment`` and ``skew_moment``, like ``l10_hours`` of
``map --life``).
"""

from __future__ import annotations

import numpy as np

from ..equilibrium.problem import build_problem
from ..equilibrium.residual import evaluate
from ..model.architectures import CONTACT_NAMES
from ..model.shift import TiltContacts, TiltMoments, tilt_moments
from ..model.traction.quadrature import Quadrature
from ..params.drive import Drive
from ..results.moments import tilt_contacts
from ..status import Status

__all__ = ["solved_tilt_contacts", "point_tilt_moments", "sweep_shift_effort", "SHIFT_VARIABLES"]

#: The variables `sweep_shift_effort` adds: units and long name.
SHIFT_VARIABLES = {
    "holding_moment": ("N m", "moment per ball about its tilt axis to hold the ratio"),
    "shift_moment": ("N m", "extra moment per ball to tilt at the tilt rate (tilt-direct)"),
    "shifter_moment": ("N m", "holding plus shift moment of all the balls, at the shifter"),
    "shift_saturated": ("1", "1 where a contact's lateral force is at its traction limit"),
    "skew_moment": ("N m", "moment per ball about its skew (radial) axis at the tilt rate"),
}


def solved_tilt_contacts(drive: Drive, inputs, creep, quadrature: Quadrature) -> TiltContacts:
    """The contacts of solved points, carrier held.

    Parameters
    ----------
    drive : Drive
        Design, fluid and architecture.
    inputs : tuple of array_like
        ``(ratio [-], output_torque [N m], clamp_force [N], input_speed [rad/s])``, each
        ``(m,)``.
    creep : array_like
        The solved creeps ``(m, n_c)`` [-].
    quadrature : Quadrature
        Rule of the traction integrals.
    """
    pb = build_problem(drive.design, drive.fluid, drive.architecture, *inputs)
    return tilt_contacts(pb, evaluate(pb, creep, quadrature), quadrature)


def point_tilt_moments(result, tilt_rate: float, quadrature: Quadrature) -> TiltMoments:
    """`tilt_moments` of one solved point (an `OperatingResult`), arrays of one point."""
    names = CONTACT_NAMES[result.architecture]
    creep = np.array([[result.contacts[n].creep for n in names]])
    inputs = tuple(
        np.array([v])
        for v in (result.ratio, result.output_torque, result.clamp_force, result.input_speed)
    )
    drive = Drive(result.design, result.fluid, result.architecture)
    return tilt_moments(solved_tilt_contacts(drive, inputs, creep, quadrature), tilt_rate)


def sweep_shift_effort(ds, drive, tilt_rate: float, quadrature: Quadrature | None = None):
    """``ds`` with the holding and shift moments of every converged point.

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep or an efficiency map of ``drive``'s design and fluid.
    drive : Drive or Variator
        Its design and fluid (the architectures are the sweep's own).
    tilt_rate : float
        ``d gamma / dt`` [rad/s].
    quadrature : Quadrature, optional
        Rule of the traction integrals (the solver's default when None).

    Returns
    -------
    xarray.Dataset
        A copy with `SHIFT_VARIABLES` on the dimensions of ``status`` [N m] (NaN where a
        point is beyond the capacity or not converged) and ``tilt_rate`` in its attributes.
    """
    q = quadrature or Quadrature()
    names = tuple(SHIFT_VARIABLES)
    out_values = {k: np.full(ds.status.shape, np.nan) for k in names}
    for i, arch in enumerate(ds.architecture.values):
        sub = ds.isel(architecture=i)
        status = sub.status
        keys = ("ratio", "output_torque", "clamp_force", "input_speed")
        inputs = [np.ravel(sub[k].broadcast_like(status).values) for k in keys]
        cn = list(CONTACT_NAMES[str(arch)])
        creep = sub.creep.sel(contact=cn).transpose(*status.dims, "contact").values
        creep = creep.reshape(-1, len(cn))
        ok = (status.values.ravel() == Status.CONVERGED) & np.all(np.isfinite(creep), axis=-1)
        if not ok.any():
            continue
        here = Drive(drive.design, drive.fluid, str(arch))
        got = tilt_moments(
            solved_tilt_contacts(here, [a[ok] for a in inputs], creep[ok], q), tilt_rate
        )
        n = drive.design.n_rollers
        each = {
            "holding_moment": got.holding,
            "shift_moment": got.shift,
            "shifter_moment": n * (got.holding + got.shift),
            "shift_saturated": got.saturated.astype(float),
            "skew_moment": got.skew,
        }
        for k, v in each.items():
            flat = np.full(ok.size, np.nan)
            flat[ok] = v
            out_values[k][i] = flat.reshape(status.shape)
    out = ds.copy()
    for k in names:
        units, long_name = SHIFT_VARIABLES[k]
        out[k] = (ds.status.dims, out_values[k], {"units": units, "long_name": long_name})
    out.attrs["tilt_rate"] = float(tilt_rate)
    return out
