"""`uncertainty`: a drive file's uncertain parameters propagated to bands of efficiency and
capacity, with the parameters ranked by influence (docs/uncertainty.md)."""

from __future__ import annotations

from dataclasses import fields, replace
from pathlib import Path

from ..errors import InputError
from ..model.clamping.base import names_fixed_force
from ..params import PAPER_POINT, Drive
from ..params.drive_models import drive_clamp
from ..params.io import parse_uncertain_drive, uncertain_drive_text
from ..units import rad_s_to_rpm
from .oil import with_oil_temperature
from .variator import Variator

__all__ = ["uncertainty", "HOW_TO_ADD"]

#: What a drive without uncertain parameters is told.
HOW_TO_ADD = (
    "add an [uncertainty] table to the drive file, e.g. "
    '[uncertainty] "design.cam.preload" = { range = [500.0, 1500.0] } (docs/uncertainty.md)'
)


def uncertainty(design: str | Path = "hub", request=None, compute=None, **keywords):
    """Propagate the ``[uncertainty]`` table of a drive file to its efficiency and
    capacity (Monte Carlo on a seeded quasi-random design; docs/uncertainty.md).

    Parameters
    ----------
    design : str or path-like
        A built-in drive's name (``"hub"``) or a drive file with an ``[uncertainty]`` table.
    request : UncertaintyRequest, optional
        Samples, seed, method and operating points; or give its fields as keywords
        (``samples=256``, ``seed=0``, ``method="sobol"``, ``ratio=(1.0,)``,
        ``output_torque=(...)`` [N m] or ``input_power=(...)`` [W], ``input_speed_rpm=(...)``,
        ``chunk=16``). The speed defaults to the drive's ``[operating]`` input speed (else
        the paper's 2000 rpm), the load to the paper's 40 N m output torque.
    compute : Compute, optional
        Where the samples are evaluated; or give its fields as keywords (``workers=2``,
        ``scheduler="tcp://..."``, ``client=...``, ``progress=False``). Default: in this
        process; a ``workers``, ``scheduler`` or ``client`` keyword runs on Dask.
    architecture : str, keyword
        Idler architecture (default ``"double"``).
    oil_temperature : str or float, keyword
        The oil model of every drawn drive: ``"fixed"``, ``"balance"`` or a temperature
        [K] (`ballcvt.api.with_oil_temperature`); default the drive file's ``[models]``.

    Returns
    -------
    UncertaintyResult
        Bands (``band()``), sensitivity (``sensitivity()``, ``ranking()``), ``save``.

    Raises
    ------
    InputError
        Bad input, or a drive file with no ``[uncertainty]`` table (saying how to add one).

    Examples
    --------
    >>> from ballcvt.api import uncertainty
    >>> r = uncertainty("hub", samples=16, input_power=(100.0,), input_speed_rpm=(114.0,))
    >>> r.band()[["output", "q05", "q50", "q95"]]  # doctest: +SKIP
    """
    from ..analysis.studies.run import Compute
    from ..analysis.uncertainty.run import UncertainDrive, UncertaintyRequest, run_uncertainty

    architecture = keywords.pop("architecture", "double")
    oil = keywords.pop("oil_temperature", None)
    asked = {k: keywords.pop(k) for k in list(keywords) if k in _names(Compute)}
    unknown = sorted(set(keywords) - _names(UncertaintyRequest))
    if unknown:
        raise InputError(unknown[0], keywords[unknown[0]], "a field of UncertaintyRequest")
    text, source = uncertain_drive_text(design)
    d, fluid, table = parse_uncertain_drive(text, source)
    if not len(table):
        raise InputError(
            "design",
            str(design),
            "a drive with uncertain parameters",
            message=f"{source} has no uncertain parameters: {HOW_TO_ADD}",
        )
    # checks the drive as every command does; the oil model asked for, else the file's
    v = with_oil_temperature(Variator(d, fluid, architecture), oil)
    req = _defaults(replace(request or UncertaintyRequest(input_speed_rpm=None), **keywords), d)
    dask = any(asked.get(k) is not None for k in ("workers", "scheduler", "client"))
    base = compute or Compute(in_process=not dask)
    comp = replace(base, **{"in_process": not dask, **asked}) if asked else base
    law, force = drive_clamp(d)  # the drive file's ([models], else [operating])
    law = law or "constant"
    if names_fixed_force(law):
        force = force or PAPER_POINT.clamp_force
    target = UncertainDrive(
        Drive(v.design, v.fluid, architecture), table, law, force, v.options, str(design)
    )
    return run_uncertainty(target, req, comp)


def _names(cls) -> set[str]:
    return {f.name for f in fields(cls)}


def _defaults(request, design):
    """The request with the drive's speed and the paper's torque where none was given."""
    speed = request.input_speed_rpm
    if speed is None:
        op = design.operating
        rpm = op.input_speed_rpm if op is not None and op.input_speed_rpm else None
        speed = (rpm or float(rad_s_to_rpm(PAPER_POINT.input_speed)),)
    torque = request.output_torque
    if torque is None and request.input_power is None:
        torque = (PAPER_POINT.output_torque,)
    return replace(
        request,
        input_speed_rpm=tuple(float(s) for s in speed),
        output_torque=None if torque is None else tuple(float(t) for t in torque),
        ratio=tuple(float(r) for r in request.ratio),
        input_power=(
            None if request.input_power is None else tuple(float(p) for p in request.input_power)
        ),
    )
