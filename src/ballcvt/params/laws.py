"""What a `ballcvt.params.models.Fluid` needs for its traction law (docs/model.md §14).

The laws are the entries of `ballcvt.registry.TRACTION_LAWS`
(`ballcvt.model.traction.base.TractionLaw`); each names the `Fluid` fields it needs
(``fields``) and the keys of ``Fluid.law_parameters`` (``parameters``, for a law defined
outside the package). This module reads only those names, so params stays below model.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from ..errors import InputError
from ..registry import TRACTION_LAWS

__all__ = ["LAW_FIELDS", "check_law"]


class _LawFields(Mapping):
    """Traction-law name -> the `Fluid` fields it needs, read from the registry entries
    (``TRACTION_LAWS.get(name).fields``; a law registered later is in it)."""

    def __getitem__(self, name: str) -> tuple[str, ...]:
        return tuple(TRACTION_LAWS.get(name).fields)

    def __iter__(self):
        return iter(TRACTION_LAWS)

    def __len__(self) -> int:
        return len(TRACTION_LAWS)


#: Law name -> `Fluid` fields the law needs (a view of `ballcvt.registry.TRACTION_LAWS`).
LAW_FIELDS: Mapping[str, tuple[str, ...]] = _LawFields()


def check_law(fluid: Any) -> None:
    """`InputError` unless ``fluid``'s traction law is registered and has what it needs
    (its fields and its ``law_parameters``), saying what is missing."""
    name = fluid.traction_law
    law = TRACTION_LAWS.get(name)  # InputError listing the laws
    given = fluid.law_parameters or {}
    absent = [k for k in getattr(law, "parameters", ()) if k not in given]
    if absent:
        raise InputError(
            f"law_parameters.{absent[0]}",
            None,
            "a value",
            message=f"fluid '{fluid.name}' has no law_parameters.{absent[0]}, which the "
            f"{name} traction law needs (it needs {', '.join(law.parameters)})",
        )
    missing = [k for k in LAW_FIELDS[name] if getattr(fluid, k) is None]
    if missing:
        raise InputError(
            missing[0],
            None,
            "a value",
            message=(
                f"fluid '{fluid.name}' has no {missing[0]} [{fluid.unit(missing[0])}], which "
                f"the {name} traction law needs: add it to [fluid] (the "
                f"{name} law needs {', '.join(LAW_FIELDS[name])})"
            ),
        )
