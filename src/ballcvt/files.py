"""Atomic file output and early checks of output locations.

Every file ballcvt writes goes through `atomic_path`: the content is written to a temporary
file in the same folder and renamed over the target only when complete, so an interrupted
run never leaves a truncated file that looks complete. `check_output_dir` and
`check_output_file` run before any computing, so a location that cannot be written is a
one-line `InputError` at once, not after minutes of work.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Iterator
from pathlib import Path

from .errors import InputError

__all__ = ["atomic_path", "atomic_write_text", "check_output_dir", "check_output_file"]


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; rename it to ``path`` if the block succeeds.

    The temporary file keeps the target's suffix (writers such as matplotlib pick the
    format from it). On an exception it is removed and ``path`` is left untouched.
    """
    path = Path(path)
    fd, tmp = tempfile.mkstemp(
        prefix=f".{path.stem}.", suffix=f".part{path.suffix}", dir=path.parent
    )
    os.close(fd)
    try:
        yield Path(tmp)
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def atomic_write_text(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` to ``path`` atomically; returns the path."""
    with atomic_path(path) as tmp:
        tmp.write_text(text)
    return Path(path)


def check_output_dir(path: str | os.PathLike, name: str = "--out") -> Path:
    """Create the output folder ``path`` if needed and check that it can be written.

    Raises
    ------
    InputError
        If ``path`` is a file, cannot be created or is not writable.
    """
    path = Path(path)
    if path.exists() and not path.is_dir():
        raise InputError(
            name, str(path), "a folder", message=f"{name} {path}: exists and is not a folder"
        )
    try:
        path.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=path):
            pass
    except OSError as exc:
        raise InputError(
            name,
            str(path),
            "a writable folder",
            message=f"{name} {path}: cannot be written ({exc.strerror or exc})",
        ) from None
    return path


def check_output_file(path: str | os.PathLike, name: str = "path") -> Path:
    """Check that the file ``path`` can be written (its folder exists and is writable).

    Raises
    ------
    InputError
        If ``path`` is a folder, or its folder is missing or not writable.
    """
    path = Path(path)
    if path.is_dir():
        raise InputError(name, str(path), "a file", message=f"{name} {path}: is a folder")
    parent = path.parent
    if not parent.is_dir():
        raise InputError(
            name,
            str(path),
            "a file in an existing folder",
            message=f"{name} {path}: folder {parent} does not exist",
        )
    if not os.access(parent, os.W_OK):
        raise InputError(
            name,
            str(path),
            "a writable location",
            message=f"{name} {path}: folder {parent} is not writable",
        )
    return path
