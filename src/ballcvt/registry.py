"""Named, pluggable pieces: one registry for each kind of choice (docs/architecture.md).

A traction law, a clamping law, a parasitic-loss term, an operating mode, an
architecture and a fatigue life model are each registered by name in one `Registry`
below. The solvers, the command line's choices, the study files and the documentation
read the registry, so a piece registered from a user's own code
(``ballcvt.registry.TRACTION_LAWS.register(...)``) is usable everywhere at once, without
editing the package. The built-in pieces register
themselves when their model module is imported (importing `ballcvt` imports them all).

This module is a leaf: it knows nothing of the physics, only names and objects.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any, Generic, TypeVar

from .errors import InputError

__all__ = [
    "Registry",
    "TRACTION_LAWS",
    "CLAMP_LAWS",
    "LOSS_TERMS",
    "OPERATING_MODES",
    "ARCHITECTURES",
    "LIFE_MODELS",
    "LUBRICATION_MODELS",
    "OIL_TEMPERATURE_MODELS",
    "ModelChoice",
]

T = TypeVar("T")


class Registry(Generic[T]):
    """Name -> entry, in registration order.

    Parameters
    ----------
    kind : str
        What the entries are, in the user's words ("traction law"), for messages.
    option : str
        The option or field a user sets to choose an entry (``"traction_law"``), for
        messages.
    """

    def __init__(self, kind: str, option: str) -> None:
        self.kind = kind
        self.option = option
        self._entries: dict[str, T] = {}

    def register(self, entry: T, *, name: str | None = None, replace: bool = False) -> T:
        """Add ``entry`` under ``name`` (default ``entry.name``); returns ``entry``.

        Registering a name twice is refused unless ``replace`` is true, so that a user's
        piece never silently shadows a built-in one.
        """
        key = name if name is not None else getattr(entry, "name", None)
        if not isinstance(key, str) or not key.replace("-", "_").isidentifier():
            raise InputError(f"{self.kind} name", key, "a name such as 'my_law'")
        if key in self._entries and not replace:
            raise InputError(
                f"{self.kind} name",
                key,
                f"a name not yet registered (taken: {', '.join(self._entries)}); "
                "pass replace=True to replace it",
            )
        self._entries[key] = entry
        return entry

    def unregister(self, name: str) -> None:
        """Remove ``name`` (a user's piece, e.g. at the end of a test)."""
        self.get(name)
        del self._entries[name]

    def get(self, name: str) -> T:
        """The entry called ``name``; an unknown name is an `InputError` listing the names."""
        try:
            return self._entries[name]
        except (KeyError, TypeError):
            raise InputError(self.option, name, "one of: " + ", ".join(self._entries)) from None

    def names(self) -> tuple[str, ...]:
        """The registered names, in registration order (the CLI's choices)."""
        return tuple(self._entries)

    def __contains__(self, name: object) -> bool:
        return name in self._entries

    def __iter__(self) -> Iterator[str]:
        return iter(self._entries)

    def __len__(self) -> int:
        return len(self._entries)

    def items(self):
        """``(name, entry)`` pairs in registration order."""
        return self._entries.items()

    def __repr__(self) -> str:
        return f"Registry({self.kind!r}: {', '.join(self._entries)})"


#: Shear laws of the film (`ballcvt.model.traction.base.TractionLaw` entries).
TRACTION_LAWS: Registry[Any] = Registry("traction law", "traction_law")
#: Where the clamping force comes from (`ballcvt.model.clamping` law classes).
CLAMP_LAWS: Registry[Any] = Registry("clamping law", "clamp_law")
#: Parasitic-loss terms (`ballcvt.model.losses.LossTerm` entries).
LOSS_TERMS: Registry[Any] = Registry("loss term", "loss term")
#: Which member is held (`ballcvt.model.modes.OperatingMode` entries).
OPERATING_MODES: Registry[Any] = Registry("operating mode", "mode")
#: Double or single idler, and any other (`ballcvt.model.architectures` entries).
ARCHITECTURES: Registry[Any] = Registry("architecture", "architecture")
#: Rolling-contact fatigue life models (`ballcvt.model.life.LifeModel` entries; the
#: built-ins register when `ballcvt.model.life` is imported).
LIFE_MODELS: Registry[Any] = Registry("life model", "life_model")


@dataclass(frozen=True)
class ModelChoice:
    """A named choice of model that is a switch of the solvers rather than an object
    they call (a registry entry of `LUBRICATION_MODELS`, `OIL_TEMPERATURE_MODELS`).

    Attributes
    ----------
    name : str
        Registry name.
    description : str
        What the choice computes, for messages and documentation.
    """

    name: str
    description: str


#: How the load is shared between the film and the asperities
#: (`ballcvt.model.lubrication.LubricationModel` entries: ``full-film``, ``mixed``).
LUBRICATION_MODELS: Registry[Any] = Registry("lubrication model", "lubrication")
#: Where the oil's temperature comes from (a drive file's ``[models] oil_temperature``):
#: the built-in ``fixed`` is the paper's (the fluid's data temperature, whatever the
#: losses); ``balance`` the housing's heat balance.
OIL_TEMPERATURE_MODELS: Registry[Any] = Registry("oil temperature model", "oil_temperature")
OIL_TEMPERATURE_MODELS.register(
    ModelChoice("fixed", "the oil stays at the temperature of the fluid's data (the paper's)")
)
OIL_TEMPERATURE_MODELS.register(
    ModelChoice(
        "balance",
        "the housing's heat balance sets the oil's temperature: steady for a point, the "
        "lumped transient over a cycle (docs/model.md §15, `ballcvt.api.oil`)",
    )
)
