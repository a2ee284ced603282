"""Saved results: strict JSON files with a checksum of what ballcvt computed (the results
layer).

`JsonFile.save` writes a result's `to_dict` as JSON (atomically, strict: an infinity is the
string ``"inf"``, a NaN ``null``) with the key ``checksum``: ``"sha256:<hex>"`` of the
canonical JSON of the rest (keys sorted, no spaces). `read_result` checks it: a file whose
numbers were edited after ballcvt wrote it loads with a `ResultChecksumWarning` saying it
no longer matches what ballcvt computed; a file saved before results carried a checksum
loads with the same warning, ``modified`` false (a note: it cannot be checked).
"""

from __future__ import annotations

import hashlib
import json
import math
import warnings
from pathlib import Path
from typing import Any

from ..errors import InputError, ResultChecksumWarning
from ..files import write_json

__all__ = ["JsonFile", "read_result", "checksum"]

#: The key of a saved result that holds its checksum.
CHECKSUM_KEY = "checksum"


def checksum(data: Any) -> str:
    """``"sha256:<hex>"`` of the canonical JSON of ``data`` (keys sorted, no spaces)."""
    text = json.dumps(data, sort_keys=True, separators=(",", ":"), allow_nan=False)
    return "sha256:" + hashlib.sha256(text.encode()).hexdigest()


class JsonFile:
    """JSON output shared by the result classes (each has ``to_dict``)."""

    def to_json(self: Any, **kwargs: Any) -> str:
        """JSON text of `to_dict` (non-finite numbers are written as ``null``)."""
        return json.dumps(_finite(self.to_dict()), **kwargs)

    def save(self: Any, path: str | Path) -> None:
        """Write the result as JSON with its checksum (atomically: never a truncated file;
        `read_result` warns if the numbers are edited afterwards)."""
        data = _finite(self.to_dict())
        data[CHECKSUM_KEY] = checksum(data)
        write_json(path, data)


def read_result(path: str | Path, keep=("design", "fluid", "mode")):
    """``(data, source)`` of a result file written by ``save``: its JSON object with
    ``null`` and ``"inf"`` restored to floats outside the ``keep`` tables (parameter sets
    keep ``null``: an absent table). Warns (`ResultChecksumWarning`) if the content does
    not match its checksum, or has none."""
    source = f"result file {path}"
    try:
        data = json.loads(Path(path).read_text(), parse_constant=float)
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        raise InputError(
            "result file",
            str(path),
            "a readable JSON result",
            message=f"{source}: cannot be read ({exc})",
        ) from None
    if isinstance(data, dict):
        _check_sum(data, source)
        data = {k: v if k in keep else _unfinite(v) for k, v in data.items()}
    return data, source


def _check_sum(data: dict, source: str) -> None:
    """Remove the stored checksum from ``data`` and warn if the rest does not match it."""
    stored = data.pop(CHECKSUM_KEY, None)
    if stored is None:
        warnings.warn(
            ResultChecksumWarning(
                f"{source}: has no checksum (saved by an earlier ballcvt): its numbers "
                "cannot be checked against what ballcvt computed",
                modified=False,
            ),
            stacklevel=4,
        )
        return
    try:
        actual = checksum(data)
    except ValueError:  # a NaN or infinity written by hand
        actual = None
    if actual != stored:
        warnings.warn(
            ResultChecksumWarning(
                f"{source}: its content no longer matches the checksum ballcvt stored "
                "with it: the numbers were edited after ballcvt computed them"
            ),
            stacklevel=4,
        )


def _unfinite(obj: Any) -> Any:
    """Inverse of `_finite`: ``"inf"``/``"-inf"`` strings back to floats, ``null`` to NaN."""
    if obj is None:
        return math.nan
    if obj in ("inf", "-inf"):
        return float(obj)
    if isinstance(obj, dict):
        return {k: _unfinite(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [_unfinite(v) for v in obj]
    return obj


def _finite(obj: Any) -> Any:
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else (str(obj) if math.isinf(obj) else None)
    if isinstance(obj, dict):
        return {k: _finite(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [_finite(v) for v in obj]
    return obj
