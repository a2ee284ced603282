"""Fatigue life over a sweep or an efficiency map: the ``l10_hours`` variable."""

from __future__ import annotations

import numpy as np

from ...model.architectures import CONTACT_NAMES
from ...model.traction.quadrature import Quadrature
from ...params.drive import Drive
from ...status import Status
from ..sweeps.variables import attrs_for
from .core import LifeSettings
from .point import SolvedPoints, creep_life

__all__ = ["sweep_life"]


def sweep_life(
    ds, drive, settings: LifeSettings | None = None, quadrature: Quadrature | None = None
):
    """``ds`` with the system L10 of every converged point as ``l10_hours`` [h].

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep or an efficiency map (`ballcvt.analysis.sweeps.grid.sweep`) of ``drive``'s
        design and fluid.
    drive : Drive or Variator
        Its design and fluid (the architectures are the sweep's own).
    settings : LifeSettings, optional
        Life model and material.
    quadrature : Quadrature, optional
        Rule for the traction integrals (the balances are evaluated once at each point's
        creeps); the solver's default rule when None.

    Returns
    -------
    xarray.Dataset
        A copy with ``l10_hours`` on the dimensions of ``status`` (NaN where a point is
        beyond the capacity or not converged) and the life model in its attributes.
    """
    s = (settings or LifeSettings()).check()
    hours = np.full(ds.status.shape, np.nan)
    dims = ds.status.dims
    for i, arch in enumerate(ds.architecture.values):
        sub = ds.isel(architecture=i)
        status = sub.status
        ratio, torque, force, speed = (sub[k].broadcast_like(status).values for k in _INPUTS)
        names = list(CONTACT_NAMES[str(arch)])
        creep = sub.creep.sel(contact=names).transpose(*status.dims, "contact").values
        creep = creep.reshape(-1, len(names))
        creep[status.values.ravel() != Status.CONVERGED] = np.nan
        here = Drive(drive.design, drive.fluid, str(arch))
        got, _, _ = creep_life(
            SolvedPoints(here, ratio, torque, force, speed, creep), s, quadrature
        )
        hours[i] = got.reshape(status.shape)
    out = ds.copy()
    out["l10_hours"] = (dims, hours, attrs_for("l10_hours"))
    out.attrs["life_model"] = s.model
    return out


#: The operating inputs of a point, in the order of `SolvedPoints`.
_INPUTS = ("ratio", "output_torque", "clamp_force", "input_speed")
