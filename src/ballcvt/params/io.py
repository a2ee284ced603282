"""Read and write drive definitions (design + fluid) as TOML.

A drive file has two tables, ``[design]`` (with ``[design.material]`` and
``[design.bearings]``) and ``[fluid]``. Every key is required; unknown keys are
rejected. The built-in Table I drive ships as ``data/table1.toml`` with its citations.
"""

from __future__ import annotations

import tomllib
from importlib import resources
from pathlib import Path

import tomli_w

from ..errors import InputError
from .models import Design, Fluid

__all__ = ["BUILTIN_DRIVES", "builtin_text", "load_builtin", "load_drive", "parse_drive",
           "drive_to_toml"]

#: Named, cited drive definitions shipped with the package.
BUILTIN_DRIVES = {"table1": "table1.toml"}


def builtin_text(name: str = "table1") -> str:
    """TOML text (with its citation comments) of a built-in drive."""
    if name not in BUILTIN_DRIVES:
        raise InputError("drive", name, "one of " + ", ".join(BUILTIN_DRIVES))
    return resources.files("ballcvt.params").joinpath("data", BUILTIN_DRIVES[name]).read_text()


def load_builtin(name: str = "table1") -> tuple[Design, Fluid]:
    """The built-in ``(design, fluid)`` pair ``name`` (default: the paper's Table I)."""
    return parse_drive(builtin_text(name), source=f"built-in drive '{name}'")


def load_drive(path: str | Path) -> tuple[Design, Fluid]:
    """Load and validate a drive TOML file.

    Raises
    ------
    InputError
        If the file is missing, is not TOML, or has a missing, unknown or out-of-range key.
    """
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as exc:
        raise InputError("design file", str(path), "a readable TOML file",
                         message=f"design file {path}: cannot be read ({exc.strerror})") from None
    return parse_drive(text, source=f"design file {path}")


def parse_drive(text: str, source: str = "design file") -> tuple[Design, Fluid]:
    """Parse and validate the TOML text of a drive definition."""
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(source, None, "valid TOML",
                         message=f"{source} is not valid TOML: {exc}") from None
    for table in ("design", "fluid"):
        if not isinstance(data.get(table), dict):
            raise InputError(table, None, "a table",
                             message=f"{source} is incomplete: table [{table}] is missing")
    extra = sorted(set(data) - {"design", "fluid"})
    if extra:
        raise InputError(extra[0], None, "[design] and [fluid]",
                         message=f"{source}: unknown table [{extra[0]}]")
    try:
        return Design(**data["design"]), Fluid(**data["fluid"])
    except InputError as exc:
        raise InputError(exc.quantity, exc.value, exc.allowed,
                         message=f"{source}: {exc}") from None


def drive_to_toml(design: Design, fluid: Fluid) -> str:
    """TOML text of a drive definition that `parse_drive` reads back unchanged."""
    return tomli_w.dumps({"design": design.model_dump(), "fluid": fluid.model_dump()})
