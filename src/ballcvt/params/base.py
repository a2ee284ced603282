"""`ParameterModel`: the frozen, validated base of every parameter set, and the field
helpers that give each field its unit and description (`ballcvt.params.models`).

A value out of range becomes one `ballcvt.errors.InputError` naming the field, its unit,
the value and the allowed range; an unknown key suggests the nearest known one.
"""

from __future__ import annotations

import difflib
import json
import math
import types
from typing import Annotated, Any, Union, get_args, get_origin

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter, ValidationError, model_validator

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
#: The strings a saved result's JSON holds for infinite values (strict JSON has none).
_INFINITIES = ("inf", "-inf")


class ParameterModel(BaseModel):
    """Frozen, strict base model whose validation errors are one-line `InputError`."""

    model_config = ConfigDict(frozen=True, extra="forbid", allow_inf_nan=True)

    def __init__(self, **data: Any) -> None:
        try:
            super().__init__(**data)
        except ValidationError as exc:
            raise _as_input_error(type(self), exc) from None

    @model_validator(mode="before")
    @classmethod
    def _strict_numbers(cls, data: Any) -> Any:
        """Refuse a boolean or a string where a number is expected (``true`` is not 1,
        ``"32"`` is not 32), which pydantic's lax mode would silently convert."""
        if isinstance(data, dict):
            for name, value in data.items():
                field = cls.model_fields.get(name)
                if field is not None:
                    _check_number(name, field.annotation, value, cls.unit(name))
        return data

    @classmethod
    def check_field(cls, name: str, value: Any) -> None:
        """Check ``value`` against field ``name``'s type and bounds alone (not against the
        other fields), e.g. a study's fixed value before any design is built.

        Raises
        ------
        InputError
            Naming the field, the value and the allowed range.
        """
        field = cls.model_fields[name]
        _check_number(name, field.annotation, value, cls.unit(name))
        try:
            kind: Any = (
                Annotated[field.annotation, *field.metadata]
                if field.metadata
                else field.annotation
            )
            TypeAdapter(kind).validate_python(value)
        except ValidationError as exc:
            raise _field_error(name, field, exc.errors()[0]) from None

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


def _check_number(name: str, annotation: Any, value: Any, unit: str) -> None:
    """`InputError` if ``value`` (or an item of it) is a boolean or a string where
    ``annotation`` expects a number."""
    misfit = _misfit(annotation, value)
    if misfit is not None:
        what = "a boolean" if isinstance(misfit, bool) else "a string"
        units = f" [{unit}]" if unit not in ("", "-") else ""
        raise InputError(
            name,
            misfit,
            f"a number{units}",
            message=f"{name} = {json.dumps(misfit)} is {what}: allowed a number{units}",
        )


def _misfit(annotation: Any, value: Any) -> Any:
    """The boolean or string in ``value`` that lax validation would turn into a number of
    ``annotation`` (``float``, ``int``, optional or in a list or dict), else None."""
    origin, args = get_origin(annotation), get_args(annotation)
    if origin in (Union, types.UnionType):
        kinds = [a for a in args if a is not type(None)]
        return _misfit(kinds[0], value) if len(kinds) == 1 else None
    if annotation is float and value in _INFINITIES:
        return None  # how a saved result writes an infinite value (ballcvt.results)
    if annotation in (int, float):
        return value if isinstance(value, bool | str) else None
    if origin is list and isinstance(value, list) and args:
        return next((m for v in value if (m := _misfit(args[0], v)) is not None), None)
    if origin is dict and isinstance(value, dict) and len(args) == 2:
        return next((m for v in value.values() if (m := _misfit(args[1], v)) is not None), None)
    return None


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
    return _field_error(name, _field(model, loc), err)


def _field_error(name: str, field: Any, err: Any) -> InputError:
    """The `InputError` of a field's error ``err``: its bounds and unit, else pydantic's
    wording of what is expected."""
    inner = (err.get("ctx") or {}).get("error")
    if isinstance(inner, InputError):
        return InputError(
            f"{name}.{inner.quantity}",
            inner.value,
            inner.allowed,
            message=str(inner).replace(inner.quantity, f"{name}.{inner.quantity}", 1),
        )
    bounds = []
    for meta in field.metadata if field is not None else ():
        for attr, text in _BOUND_TEXT.items():
            value = getattr(meta, attr, None)
            if value is not None and value not in (math.inf, -math.inf):
                bounds.append(f"{text} {value:g}")
    unit = str((field.json_schema_extra or {}).get("unit", "")) if field is not None else ""
    if str(err["type"]).startswith("int_"):
        return _whole_number_error(name, err.get("input"), bounds)
    if bounds:
        allowed = " and ".join(bounds) + (f" {unit}" if unit not in ("", "-") else "")
    else:
        allowed = err["msg"].replace("Input should be ", "")
    return InputError(name, err.get("input"), allowed)


def _whole_number_error(name: str, value: Any, bounds: list[str]) -> InputError:
    """The `InputError` of a non-integer value of an integer field (``n_rollers = 6.5``):
    it says a whole number is needed, then the range."""
    allowed = "a whole number" + (f" {' and '.join(bounds)}" if bounds else "")
    within = f" (allowed {' and '.join(bounds)})" if bounds else ""
    return InputError(
        name, value, allowed, message=f"{name} = {value!r} must be a whole number{within}"
    )


def _field(model: type[BaseModel], loc: list[str]) -> Any:
    cls: Any = model
    field = None
    for part in loc:
        field = getattr(cls, "model_fields", {}).get(part)
        if field is None:
            return None
        cls = field.annotation
    return field
