"""Package exports loaded on first use, so that ``import ballcvt`` stays fast.

A package lists its exports as ``name -> submodule`` and takes its ``__getattr__`` and
``__dir__`` from `lazy_exports`; ``from package import name`` then imports only the
submodule that defines ``name`` (xarray, pandas and Dask load when a sweep, a table or a
study is first used, not with the package). A leaf: imports no layer.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any

__all__ = ["lazy_exports"]


def lazy_exports(
    package: str, exports: dict[str, str], fallback: Callable[[str], Any] | None = None
):
    """``(__getattr__, __dir__)`` for ``package`` whose ``exports`` map each name to the
    relative submodule defining it (``".grid"``); ``fallback(name)`` answers any other
    name (e.g. a renamed one), or raises `AttributeError`."""

    def __getattr__(name: str) -> Any:
        if name in exports:
            value = getattr(importlib.import_module(exports[name], package), name)
            globals_of(package)[name] = value  # later lookups skip this function
            return value
        if fallback is not None:
            return fallback(name)
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__() -> list[str]:
        return sorted(set(globals_of(package)) | set(exports))

    return __getattr__, __dir__


def globals_of(package: str) -> dict:
    """The namespace of the (already imported) module ``package``."""
    import sys

    return vars(sys.modules[package])
