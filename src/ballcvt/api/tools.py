"""Drive files, single contacts and studies: the public functions besides `Variator`."""

from __future__ import annotations

from pathlib import Path

from ..analysis.studies import StudySpec
from ..analysis.studies import read_study as _read_study
from ..params.io import BUILTIN_DRIVES, builtin_text, drive_to_toml, resolve_drive, resolve_fluid
from ..params.models import Design, Fluid

__all__ = ["open_drive", "contact_fluid", "drive_text", "read_study"]


def open_drive(design=None, fluid=None, traction_law: str | None = None) -> tuple[Design, Fluid]:
    """The design and fluid of a drive given by name or file, with another fluid or law.

    Parameters
    ----------
    design : str or path, optional
        A built-in drive's name (``table1``, ``hub``) or a drive TOML file; Table I by
        default.
    fluid : str or path, optional
        A built-in fluid's name or a TOML file with a ``[fluid]`` table, replacing the
        drive's.
    traction_law : str, optional
        Shear law of the film (docs/model.md §14); by default the drive file's ``[models]
        traction_law`` (also for a replacing fluid), else the fluid's own.

    Returns
    -------
    (Design, Fluid)
    """
    d, f = resolve_drive(design)
    if fluid is not None:
        f = resolve_fluid(fluid)
    named = d.models.traction_law if d.models is not None else None
    return d, f.with_traction_law(traction_law or named)


def contact_fluid(design=None, fluid=None, traction_law: str | None = None) -> tuple[Fluid, float]:
    """The fluid and reduced modulus ``E'`` [Pa] of a single contact (a traction-curve
    test pair of the drive's material), as `open_drive` resolves them."""
    d, f = open_drive(design, fluid, traction_law)
    return f, d.material.reduced_modulus


def drive_text(
    design=None, fluid=None, traction_law: str | None = None, lubrication: str | None = None
) -> str:
    """TOML text of a drive definition: the built-in or given file as it is (with its
    sources), or rewritten with another fluid or law (`open_drive`'s arguments) or
    lubrication model (`Design.with_lubrication`)."""
    d, f = resolve_drive(design)  # validated first
    if design is None or (design in BUILTIN_DRIVES and not Path(design).exists()):
        template = builtin_text(design or "table1")
    else:
        template = Path(design).read_text(encoding="utf-8")
    new_fluid = (f if fluid is None else resolve_fluid(fluid)).with_traction_law(traction_law)
    new_design = d.with_lubrication(lubrication)
    if new_fluid == f and new_design is d and design in (None, *BUILTIN_DRIVES):
        return template
    return drive_to_toml(new_design, new_fluid, template=template)


def read_study(path, *, traction_law: str | None = None) -> StudySpec:
    """A study file (docs/studies.md), optionally with another traction law for every
    design (``[study] traction_law``)."""
    spec = _read_study(path)
    if traction_law is None:
        return spec
    return spec.model_copy(
        update={"study": spec.study.model_copy(update={"traction_law": traction_law})}
    )
