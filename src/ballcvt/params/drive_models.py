"""`DriveModels`: the models a drive names, the optional ``[models]`` table of a drive file.

A drive file may say under which models it is to be computed: its clamping law, the
film's traction law, the lubrication model and the oil's temperature
(docs/drive-files.md). The built-in ``hub`` names the models of a real hub, so that
``--design hub`` on the command line and ``load_builtin("hub")`` in Python give the whole
hub model with no extra flag; a drive without the table (the paper's Table I drive) keeps
the paper's models. `effective_models` says which model a call uses: an explicit choice
(a typed flag, a keyword argument) wins over the drive file, which wins over the
package's default.

Each name is checked against its registry (`ballcvt.registry`): ``clamp_law`` against
``CLAMP_LAWS``, ``traction_law`` against ``TRACTION_LAWS``, ``lubrication`` against
``LUBRICATION_MODELS`` and ``oil_temperature`` against ``OIL_TEMPERATURE_MODELS``.
"""

from __future__ import annotations

from typing import Any

from pydantic import model_validator

from ..errors import InputError
from ..registry import (
    CLAMP_LAWS,
    LUBRICATION_MODELS,
    OIL_TEMPERATURE_MODELS,
    TRACTION_LAWS,
    Registry,
)
from .base import ParameterModel, _opt
from .lubrication import Lubrication

__all__ = [
    "DriveModels",
    "MODEL_KEYS",
    "PACKAGE_DEFAULTS",
    "effective_models",
    "drive_clamp",
    "with_oil_model",
]

#: ``[models]`` key -> the registry its names are checked against.
MODEL_KEYS: dict[str, Registry[Any]] = {
    "clamp_law": CLAMP_LAWS,
    "traction_law": TRACTION_LAWS,
    "lubrication": LUBRICATION_MODELS,
    "oil_temperature": OIL_TEMPERATURE_MODELS,
}

#: The package's models where neither a call nor the drive names one (the paper's: a
#: constant clamping force, a full film at a fixed oil temperature; the traction law is
#: the fluid's own).
PACKAGE_DEFAULTS = {
    "clamp_law": "constant",
    "lubrication": "full-film",
    "oil_temperature": "fixed",
}


class DriveModels(ParameterModel):
    """The models a drive is computed with (every key optional; docs/drive-files.md)."""

    clamp_law: str | None = _opt("-", "clamping law, a name in ballcvt.registry.CLAMP_LAWS")
    traction_law: str | None = _opt(
        "-", "traction law of the film (sets the fluid's), a name in TRACTION_LAWS"
    )
    lubrication: str | None = _opt(
        "-", "lubrication model, a name in ballcvt.registry.LUBRICATION_MODELS"
    )
    oil_temperature: str | None = _opt(
        "-", "oil temperature model, a name in ballcvt.registry.OIL_TEMPERATURE_MODELS"
    )

    @model_validator(mode="after")
    def _registered(self) -> DriveModels:
        for key, registry in MODEL_KEYS.items():
            value = getattr(self, key)
            if value is not None and value not in registry:
                raise InputError(f"models.{key}", value, "one of: " + ", ".join(registry.names()))
        return self

    def given(self) -> dict[str, str]:
        """The keys the table gives, with their names."""
        return {k: v for k in MODEL_KEYS if (v := getattr(self, k)) is not None}


def with_oil_model(design: Any, choice: str) -> Any:
    """``design`` whose ``[models]`` name the oil temperature model ``choice`` (e.g.
    ``"fixed"``, ``"balance"``), its other models kept."""
    models = design.models
    named = (
        models.model_copy(update={"oil_temperature": choice})
        if models is not None
        else DriveModels(oil_temperature=choice)
    )
    return design.model_copy(update={"models": named})


def _drive_clamp_law(design: Any) -> str | None:
    """The clamping law the drive file names: ``[models]``, else ``[operating]``."""
    models, operating = getattr(design, "models", None), getattr(design, "operating", None)
    if models is not None and models.clamp_law is not None:
        return str(models.clamp_law)
    if operating is not None and operating.clamp_law is not None:
        return str(operating.clamp_law)
    return None


def drive_clamp(design: Any, clamp_law: Any = None, clamp_force: Any = None) -> tuple[Any, Any]:
    """The ``(clamp_law, clamp_force)`` a call uses: the call's when it gives either (a
    force alone is the constant law's), else the drive file's law (``[models]``, else
    ``[operating]``) with, for the constant law, ``[operating] clamp_force``."""
    if clamp_law is not None or clamp_force is not None:
        return clamp_law, clamp_force
    law = _drive_clamp_law(design)
    if law is None:
        return None, None
    operating = getattr(design, "operating", None)
    if CLAMP_LAWS.get(law).fixed_force and operating is not None:
        return law, operating.clamp_force
    return law, None


def effective_models(design: Any, fluid: Any = None, **chosen: Any) -> dict[str, str]:
    """The model of each kind a call uses: ``chosen`` > the drive file > the package.

    Parameters
    ----------
    design : Design
        The drive (its ``models`` and ``operating`` tables).
    fluid : Fluid, optional
        Its fluid: the traction law's default is the fluid's own.
    **chosen : str or None
        The call's explicit choices by `MODEL_KEYS` key (a typed flag, a keyword); None
        where not chosen. ``clamp_force`` given alone means the constant clamping law.

    Returns
    -------
    dict
        `MODEL_KEYS` key -> model name (a clamp law given as an object by its ``name``).
    """
    unknown = sorted(set(chosen) - set(MODEL_KEYS) - {"clamp_force"})
    if unknown:
        raise InputError(unknown[0], chosen[unknown[0]], "one of " + ", ".join(MODEL_KEYS))
    models = getattr(design, "models", None)
    file = models.given() if models is not None else {}
    law, _ = drive_clamp(design, chosen.get("clamp_law"), chosen.get("clamp_force"))
    out: dict[str, str] = {
        "clamp_law": str(getattr(law, "name", law) or PACKAGE_DEFAULTS["clamp_law"])
    }
    own_law = getattr(fluid, "traction_law", None) or "isothermal"
    out["traction_law"] = chosen.get("traction_law") or file.get("traction_law") or own_law
    for key in ("lubrication", "oil_temperature"):
        out[key] = chosen.get(key) or file.get(key) or PACKAGE_DEFAULTS[key]
    return out


def reconcile_models(design) -> None:
    """Check a design's ``[models]`` against its other tables, and apply its lubrication.

    A clamping law named in both ``[models]`` and ``[operating]`` must be the same. A
    ``[models] lubrication`` becomes the model of ``[design.lubrication]`` (the table's
    asperity parameters kept, the typical ones without it), so that the solvers read one
    place; a table stating another model is refused (one place only).

    Parameters
    ----------
    design : Design
        A validated design (its ``lubrication`` is set in place: called by its validator).
    """
    said = (
        getattr(design.models, "clamp_law", None),
        getattr(design.operating, "clamp_law", None),
    )
    if None not in said and said[0] != said[1]:
        raise InputError(
            "models.clamp_law",
            said[0],
            f"the [operating] clamp_law {said[1]!r} (or one of them only)",
        )
    named = getattr(design.models, "lubrication", None)
    own = design.lubrication
    if named is None or (own is not None and own.model == named):
        return
    if own is not None and "model" in own.model_fields_set:
        raise InputError(
            "design.lubrication.model",
            own.model,
            f"the [models] lubrication {named!r} (or one of them only)",
        )
    table = own.model_dump() if own is not None else {}
    object.__setattr__(design, "lubrication", Lubrication(**{**table, "model": named}))
