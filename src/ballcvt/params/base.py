"""`ParameterModel`: the frozen, validated base of every parameter set, and the field
helpers that give each field its unit and description (`ballcvt.params.models`).

A value out of range becomes one `ballcvt.errors.InputError` naming the field, its unit,
the value and the allowed range; an unknown key suggests the nearest known one.
"""

from __future__ import annotations

import difflib
import math
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, ValidationError

from ..errors import InputError

__all__ = ["ParameterModel"]


def _f(unit: str, description: str, **constraints: Any) -> Any:
    """A required field with its unit recorded in the schema."""
    return Field(
        ..., description=f"{description} [{unit}]", json_schema_extra={"unit": unit}, **constraints
    )


def _opt(unit: str, description: str, **constraints: Any) -> Any:
    """An optional field (None: not given) with its unit recorded in the schema."""
    return Field(
        None,
        description=f"{description} [{unit}]",
        json_schema_extra={"unit": unit},
        **constraints,
    )


_BOUND_TEXT = {"gt": ">", "ge": ">=", "lt": "<", "le": "<="}


class ParameterModel(BaseModel):
    """Frozen, strict base model whose validation errors are one-line `InputError`."""

    model_config = ConfigDict(frozen=True, extra="forbid", allow_inf_nan=True)

    def __init__(self, **data: Any) -> None:
        try:
            super().__init__(**data)
        except ValidationError as exc:
            raise _as_input_error(type(self), exc) from None

    def _summary(self) -> tuple[str, list]:
        rows = []
        for key, value in self:
            if key == "name" or value is None:
                continue
            if isinstance(value, BaseModel):
                rows.append((key, type(value).__name__, ""))
            else:
                rows.append((key, value, self.unit(key)))
        name = getattr(self, "name", None)
        return f"{type(self).__name__}" + (f": {name}" if name else ""), rows

    def __repr__(self) -> str:
        from .._display import text_summary

        return text_summary(*self._summary())

    def _repr_html_(self) -> str:
        from .._display import html_summary

        return html_summary(*self._summary())

    @classmethod
    def unit(cls, name: str) -> str:
        """Unit of field ``name`` (``"-"`` for a dimensionless one)."""
        extra = cls.model_fields[name].json_schema_extra
        return str(extra.get("unit", "-")) if isinstance(extra, dict) else "-"

    def replace(self, **changes: Any):
        """Return a validated copy with some fields changed.

        A copy whose values differ from this one and that is not given a new ``name`` is
        named after this one with the changed keys, e.g. ``"... Table I (edited:
        n_rollers)"``, so that results never carry the name of a design they do not use.
        """
        data = self.model_dump()
        if "name" in type(self).model_fields and "name" not in changes:
            changed = _changed_keys(data, changes)
            if changed:
                base = str(data["name"]).split(" (edited: ")[0]
                changes = {**changes, "name": f"{base} (edited: {', '.join(changed)})"}
        return type(self)(**{**data, **changes})


def _changed_keys(data: dict, changes: dict, prefix: str = "") -> list[str]:
    """Dotted names of the keys whose value ``changes`` alters in ``data``."""
    out = []
    for key, value in changes.items():
        old = data.get(key)
        if isinstance(value, BaseModel):
            value = value.model_dump()
        if isinstance(value, dict) and isinstance(old, dict):
            out += _changed_keys(old, value, f"{prefix}{key}.")
        elif value != old:
            out.append(prefix + key)
    return out


def _as_input_error(model: type[BaseModel], exc: ValidationError) -> InputError:
    errors = exc.errors()
    # A misspelt key shows as an unknown key and a missing one: report the typo first.
    err = next((e for e in errors if e["type"] == "extra_forbidden"), errors[0])
    loc = [str(p) for p in err["loc"]]
    name = ".".join(loc) or model.__name__
    kind = err["type"]
    inner = (err.get("ctx") or {}).get("error")
    if isinstance(inner, InputError):  # a nested parameter model already explained itself
        qualified = ".".join(loc + [inner.quantity])
        return InputError(
            qualified,
            inner.value,
            inner.allowed,
            message=str(inner).replace(inner.quantity, qualified, 1),
        )
    if kind == "missing":
        return InputError(
            name,
            None,
            "a value",
            message=f"{model.__name__} is incomplete: required key '{name}' is missing",
        )
    if kind == "extra_forbidden":
        parent = _field(model, loc[:-1]).annotation if len(loc) > 1 else model
        close = difflib.get_close_matches(loc[-1], list(getattr(parent, "model_fields", {})), 1)
        hint = f" (did you mean '{close[0]}'?)" if close else ""
        return InputError(
            name,
            err.get("input"),
            "known keys only",
            message=f"{model.__name__}: unknown key '{name}'{hint}",
        )
    field = _field(model, loc)
    bounds = []
    for meta in field.metadata if field is not None else ():
        for attr, text in _BOUND_TEXT.items():
            value = getattr(meta, attr, None)
            if value is not None and value not in (math.inf, -math.inf):
                bounds.append(f"{text} {value:g}")
    unit = str((field.json_schema_extra or {}).get("unit", "")) if field is not None else ""
    if bounds:
        allowed = " and ".join(bounds) + (f" {unit}" if unit not in ("", "-") else "")
    else:
        allowed = err["msg"].replace("Input should be ", "")
    return InputError(name, err.get("input"), allowed)


def _field(model: type[BaseModel], loc: list[str]) -> Any:
    cls: Any = model
    field = None
    for part in loc:
        field = getattr(cls, "model_fields", {}).get(part)
        if field is None:
            return None
        cls = field.annotation
    return field
