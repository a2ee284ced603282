"""Read and write drive definitions (design + fluid) as TOML.

A drive file has two tables, ``[design]`` (with ``[design.material]`` and
``[design.bearings]``) and ``[fluid]``, and optionally ``[operating]`` and ``[uncertainty]``
(`ballcvt.params.uncertainty`). Every key is required; unknown keys are
rejected. The built-in Table I drive ships as ``data/table1.toml`` with its citations, and
the same drive built as a hub (cam and parasitic losses, ASSUMED) as ``data/hub.toml``.
"""

from __future__ import annotations

import tomllib
from importlib import resources
from pathlib import Path

import tomlkit

from ..errors import InputError
from .models import Design, Fluid
from .uncertainty import UncertaintyTable, parse_uncertainty

__all__ = [
    "BUILTIN_DRIVES",
    "BUILTIN_FLUIDS",
    "builtin_text",
    "load_builtin",
    "load_drive",
    "parse_drive",
    "drive_to_toml",
    "load_fluid",
    "load_builtin_fluid",
    "parse_fluid",
    "fluid_to_toml",
    "read_text",
    "parse_toml",
    "resolve_drive",
    "resolve_fluid",
    "parse_uncertain_drive",
    "uncertain_drive_text",
]

#: Named, cited drive definitions shipped with the package.
BUILTIN_DRIVES = {"table1": "table1.toml", "hub": "hub.toml"}
#: Named, cited fluids: Table I's (in its drive file) and fluid-only files.
BUILTIN_FLUIDS = {"table1": "table1.toml", "mineral-oil": "mineral_oil.toml"}


def builtin_text(name: str = "table1") -> str:
    """TOML text (with its citation comments) of a built-in drive."""
    if name not in BUILTIN_DRIVES:
        raise InputError("drive", name, "one of " + ", ".join(BUILTIN_DRIVES))
    return _data_text(BUILTIN_DRIVES[name])


def load_builtin(name: str = "table1") -> tuple[Design, Fluid]:
    """The built-in ``(design, fluid)`` pair ``name`` (default: the paper's Table I)."""
    return parse_drive(builtin_text(name), source=f"built-in drive '{name}'")


def resolve_drive(name: str | Path | None = None) -> tuple[Design, Fluid]:
    """A built-in drive by name (`BUILTIN_DRIVES`; Table I when None), else a drive file."""
    if name is None:
        return load_builtin()
    if str(name) in BUILTIN_DRIVES and not Path(name).exists():
        return load_builtin(str(name))
    return load_drive(name)


def resolve_fluid(name: str | Path) -> Fluid:
    """A built-in fluid by name (`BUILTIN_FLUIDS`), else the ``[fluid]`` table of a file."""
    if str(name) in BUILTIN_FLUIDS and not Path(name).exists():
        return load_builtin_fluid(str(name))
    return load_fluid(name)


def _data_text(filename: str) -> str:
    return resources.files("ballcvt.params").joinpath("data", filename).read_text()


def load_builtin_fluid(name: str = "table1") -> Fluid:
    """The built-in fluid ``name`` (`BUILTIN_FLUIDS`)."""
    if name not in BUILTIN_FLUIDS:
        raise InputError("fluid", name, "one of " + ", ".join(BUILTIN_FLUIDS))
    return parse_fluid(_data_text(BUILTIN_FLUIDS[name]), source=f"built-in fluid '{name}'")


def load_fluid(path: str | Path) -> Fluid:
    """The ``[fluid]`` table of a TOML file (a drive file, or a fluid-only file such as
    ``fit-fluid`` writes), validated."""
    return parse_fluid(read_text(path, "fluid file"), source=f"fluid file {path}")


def parse_fluid(text: str, source: str = "fluid file") -> Fluid:
    """Parse and validate the ``[fluid]`` table of TOML text (other tables are ignored)."""
    data = parse_toml(text, source)
    if not isinstance(data.get("fluid"), dict):
        raise InputError(
            "fluid", None, "a table", message=f"{source} is incomplete: table [fluid] is missing"
        )
    try:
        return Fluid(**data["fluid"])
    except InputError as exc:
        raise InputError(
            exc.quantity, exc.value, exc.allowed, message=f"{source}: {exc}"
        ) from None


def fluid_to_toml(fluid: Fluid, header: str = "") -> str:
    """TOML text of a fluid-only file (``[fluid]``) that `load_fluid` reads back.

    ``header`` is written first as comment lines (sources, how the values were found).
    """
    doc = tomlkit.document()
    for line in header.splitlines():
        doc.add(tomlkit.comment(line))
    table = tomlkit.table()
    for name, value in fluid.model_dump().items():
        if value is not None:
            table[name] = value
    doc["fluid"] = table
    return tomlkit.dumps(doc)


def read_text(path: str | Path, what: str) -> str:
    path = Path(path)
    try:
        return path.read_text(encoding="utf-8")
    except OSError as exc:
        raise InputError(
            what,
            str(path),
            "a readable TOML file",
            message=f"{what} {path}: cannot be read ({exc.strerror})",
        ) from None
    except UnicodeDecodeError:
        raise InputError(
            what,
            str(path),
            "a UTF-8 TOML file",
            message=f"{what} {path}: not a text file (not UTF-8)",
        ) from None


def parse_toml(text: str, source: str) -> dict:
    """The tables of TOML ``text`` (a leading UTF-8 byte-order mark, as some editors on
    Windows write, is ignored); `InputError` naming ``source`` if it is not TOML."""
    try:
        return tomllib.loads(text.removeprefix("\ufeff"))
    except tomllib.TOMLDecodeError as exc:
        raise InputError(
            source,
            None,
            "valid TOML",
            message=f"{source} is not valid TOML: {str(exc).splitlines()[0]}",
        ) from None


def load_drive(path: str | Path) -> tuple[Design, Fluid]:
    """Load and validate a drive TOML file.

    Raises
    ------
    InputError
        If the file is missing, is not TOML, or has a missing, unknown or out-of-range key.
    """
    return parse_drive(read_text(path, "design file"), source=f"design file {path}")


def parse_drive(text: str, source: str = "design file") -> tuple[Design, Fluid]:
    """Parse and validate the TOML text of a drive definition."""
    data = parse_toml(text, source)
    for table in ("design", "fluid"):
        if not isinstance(data.get(table), dict):
            raise InputError(
                table,
                None,
                "a table",
                message=f"{source} is incomplete: table [{table}] is missing",
            )
    extra = sorted(set(data) - {"design", "fluid", "uncertainty", *_DRIVE_TABLES})
    if extra:
        raise InputError(
            extra[0],
            None,
            "[design], [fluid], [operating], [models] and [uncertainty]",
            message=f"{source}: unknown table [{extra[0]}]",
        )
    design = dict(data["design"])
    for table in _DRIVE_TABLES:
        if table in data:
            if table in design:
                raise InputError(
                    table, None, "one table", message=f"{source}: [{table}] given twice"
                )
            design[table] = data[table]
    try:
        built = Design(**design)
        drive = built, _fluid_of(built, data["fluid"])
    except InputError as exc:
        raise InputError(
            exc.quantity, exc.value, exc.allowed, message=f"{source}: {exc}"
        ) from None
    parse_uncertainty(data.get("uncertainty"), *drive, source=source)  # checked, kept aside
    return drive


def parse_uncertain_drive(
    text: str, source: str = "design file"
) -> tuple[Design, Fluid, UncertaintyTable]:
    """Parse a drive definition and its ``[uncertainty]`` table (empty if it has none)."""
    design, fluid = parse_drive(text, source)
    table = parse_toml(text, source).get("uncertainty")
    return design, fluid, parse_uncertainty(table, design, fluid, source)


def uncertain_drive_text(name: str | Path) -> tuple[str, str]:
    """``(text, source)`` of a built-in drive by name or of a drive file (as `resolve_drive`)."""
    if str(name) in BUILTIN_DRIVES and not Path(name).exists():
        return builtin_text(str(name)), f"built-in drive '{name}'"
    return read_text(name, "design file"), f"design file {name}"


#: The tables of a drive file read into the design beside ``[design]``.
_DRIVE_TABLES = ("operating", "models")


def _fluid_of(design: Design, table: dict) -> Fluid:
    """The ``[fluid]`` table under the traction law the drive's ``[models]`` names (as
    ``--traction-law`` sets it); a different law in ``[fluid]`` itself is refused."""
    law = design.models.traction_law if design.models is not None else None
    own = table.get("traction_law")
    if law is not None and own is not None and own != law:
        raise InputError(
            "models.traction_law",
            law,
            f"the [fluid] traction_law {own!r} (or one of them only)",
        )
    return Fluid(**table).with_traction_law(law)


def drive_to_toml(design: Design, fluid: Fluid, template: str | None = None) -> str:
    """TOML text of a drive definition that `parse_drive` reads back unchanged.

    The text keeps the layout, comments and sources of ``template`` (the built-in Table I
    file by default, or the file a drive was loaded from). A value that differs from the
    template's is written with the comment ``edited (template value: ...)``, so the
    citations of the values that were kept stay next to them and no edited value carries a
    citation it no longer deserves.

    Parameters
    ----------
    design, fluid : Design, Fluid
        The drive.
    template : str, optional
        TOML text to take the layout and comments from.

    Returns
    -------
    str
    """
    try:
        text = template if template is not None else builtin_text()
        doc = tomlkit.parse(text.removeprefix("\ufeff"))  # a byte-order mark is not TOML
    except tomlkit.exceptions.ParseError as exc:
        raise InputError(
            "template", None, "valid TOML", message=f"design template is not valid TOML: {exc}"
        ) from None
    dump = design.model_dump()
    tables = {name: dump.pop(name, None) for name in _DRIVE_TABLES}
    if (tables.get("models") or {}).get("lubrication") and dump.get("lubrication"):
        dump["lubrication"].pop("model", None)  # stated once, in [models]
    _update(doc, "design", dump)
    if "lubrication" not in dump:  # the template's table, of a drive that has none
        doc["design"].pop("lubrication", None)
    fluid_dump = fluid.model_dump()
    named = (tables["models"] or {}).get("traction_law")
    if named == fluid.traction_law and "traction_law" not in doc.get("fluid", {}):
        fluid_dump.pop("traction_law")  # stated once, in [models]
    _update(doc, "fluid", fluid_dump)
    for name, table in tables.items():
        if table is None:
            doc.pop(name, None)
        else:
            _update(doc, name, {k: _plain(v) for k, v in table.items()})
    return tomlkit.dumps(doc)


def _plain(value):
    """A tuple (a range) as the list TOML writes."""
    return list(value) if isinstance(value, tuple) else value


def _update(container, key, data) -> None:
    """Write ``data`` into ``container[key]``, keeping the comments of unchanged values."""
    if key not in container or not hasattr(container[key], "items"):
        container[key] = tomlkit.table()
    table = container[key]
    for name, value in data.items():
        if value is None:  # an optional table the drive does not have
            table.pop(name, None)
            continue
        if isinstance(value, dict):
            _update(table, name, value)
            continue
        old = table.get(name)
        plain = old.unwrap() if hasattr(old, "unwrap") else old
        if old is not None and plain == value:
            continue
        item = tomlkit.item(value)
        if old is not None and name == "name":
            comment = old.trivia.comment.lstrip("# ") if hasattr(old, "trivia") else ""
            if comment:
                item.comment(comment)
        elif old is not None:
            item.comment(f"edited (template value: {plain})")
        table[name] = item
