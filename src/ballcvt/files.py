"""Atomic file output, the rules of what an output may replace, and strict JSON (a leaf).

Every file ballcvt writes goes through `atomic_path` (docs/cli.md, "Output files"):

* a regular file or a new path is written atomically: the content goes to a temporary file
  in the same folder, renamed over the target only when complete, so an interrupted run
  never leaves a truncated file that looks complete;
* a symbolic link is written *through*: the link stays and the file it points to is
  replaced atomically, in that file's folder;
* a FIFO, a socket, a device node or a folder named as an output file is refused with an
  `InputError` naming the path and what it is: it is never replaced;
* replacing a file this process did not write says so, once per folder, as a one-line note
  on stderr (the ``ballcvt.files`` logger, level WARNING);
* temporary files are named ``.<stem>.<random>.ballcvt-<pid>.part<suffix>``; the first
  write into a folder removes those of processes that are no longer running (a killed run),
  and only those.

`check_output_dir` and `check_output_file` run before any computing, so a location that
cannot be written is a one-line `InputError` at once, not after minutes of work; a folder
`check_output_dir` created is removed again at exit if the run wrote nothing into it (a
refused run leaves no empty ``--out`` folder). `write_json` writes JSON that any strict
parser reads: a NaN or an infinity becomes ``null`` and the key ``non_finite`` lists where.
"""

from __future__ import annotations

import atexit
import contextlib
import json
import logging
import os
import re
import stat
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from .errors import InputError

__all__ = [
    "atomic_path",
    "atomic_write_text",
    "check_output_dir",
    "check_output_file",
    "output_target",
    "remove_stale_parts",
    "strict_json",
    "write_json",
]

_LOG = logging.getLogger("ballcvt.files")
#: Temporary files of `atomic_path`: ``.<stem>.<random>.ballcvt-<pid>.part<suffix>``.
_PART = re.compile(r"^\..*\.ballcvt-(\d+)\.part(\.[^.]*)?$")
#: Folders whose stale temporary files were removed, where a replacement was noted, and
#: the files this process wrote (replacing those is not news) and folders it created.
_SWEPT: set[Path] = set()
_NOTED: set[Path] = set()
_WRITTEN: set[Path] = set()
_CREATED: list[Path] = []

_KINDS = (
    (stat.S_ISDIR, "a folder"),
    (stat.S_ISFIFO, "a FIFO (named pipe)"),
    (stat.S_ISSOCK, "a socket"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
)


def output_target(path: str | os.PathLike, name: str = "path") -> Path:
    """The regular file that writing ``path`` replaces (or creates).

    A symbolic link is followed to its final target (written through: the link stays);
    a new path is returned as is.

    Raises
    ------
    InputError
        If ``path`` is, or links to, a folder, a FIFO, a socket or a device node, or its
        links cannot be resolved (a loop).
    """
    path = Path(path)
    target = Path(os.path.realpath(path)) if path.is_symlink() else path
    via = f" (a symbolic link to {target})" if target != path else ""
    try:
        mode = os.stat(target).st_mode
    except FileNotFoundError:
        return target
    except OSError as exc:
        raise InputError(
            name,
            str(path),
            "a regular file or a new path",
            message=f"{name} {path}{via}: cannot be resolved ({exc.strerror or exc})",
        ) from None
    if stat.S_ISREG(mode):
        return target
    kind = next((k for test, k in _KINDS if test(mode)), "not a regular file")
    raise InputError(
        name,
        str(path),
        "a regular file or a new path",
        message=f"{name} {path}{via}: is {kind}; ballcvt writes only regular files "
        "and never replaces anything else",
    )


def remove_stale_parts(folder: str | os.PathLike) -> list[Path]:
    """Remove the temporary files of `atomic_path` in ``folder`` whose process is no longer
    running (a killed run); returns them. Other files, and the temporary files of running
    processes, are left alone."""
    removed = []
    with contextlib.suppress(OSError):
        for entry in os.scandir(os.fspath(folder)):
            m = _PART.match(entry.name)
            if m and entry.is_file(follow_symlinks=False) and not _alive(int(m.group(1))):
                with contextlib.suppress(OSError):
                    os.unlink(entry.path)
                    removed.append(Path(entry.path))
    return removed


def _alive(pid: int) -> bool:
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError):
        return pid > 0
    return True


def _sweep(folder: Path) -> None:
    """`remove_stale_parts` once per folder and process."""
    if folder not in _SWEPT:
        _SWEPT.add(folder)
        remove_stale_parts(folder)


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[Path]:
    """Yield a temporary path beside the file ``path`` stands for; rename it over that file
    if the block succeeds (the rules of the module docstring).

    The temporary file keeps the target's suffix (writers such as matplotlib pick the
    format from it). On an exception it is removed and ``path`` is left untouched. A file
    replaced keeps its permissions; a new one gets 0644.

    Raises
    ------
    InputError
        If ``path`` is (or links to) a folder, a FIFO, a socket or a device node.
    """
    target = output_target(path)
    folder = target.parent
    _sweep(folder)
    try:
        old_mode: int | None = stat.S_IMODE(os.stat(target).st_mode)
    except FileNotFoundError:
        old_mode = None
    fd, tmp = tempfile.mkstemp(
        prefix=f".{target.stem}.", suffix=f".ballcvt-{os.getpid()}.part{target.suffix}", dir=folder
    )
    os.close(fd)
    try:
        yield Path(tmp)
        os.chmod(tmp, 0o644 if old_mode is None else old_mode)
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    key = target.absolute()
    if old_mode is not None and key not in _WRITTEN and folder.absolute() not in _NOTED:
        _NOTED.add(folder.absolute())
        shown = "" if target == Path(path) else f" (through the link {path})"
        _LOG.warning(
            "ballcvt: note: replaced the earlier %s%s (further files replaced in %s are "
            "not listed)",
            target,
            shown,
            folder,
        )
    _WRITTEN.add(key)


def atomic_write_text(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` to ``path`` atomically; returns the path."""
    with atomic_path(path) as tmp:
        tmp.write_text(text)
    return Path(path)


def strict_json(data: Any) -> tuple[Any, list[str]]:
    """``(clean, where)``: ``data`` with every NaN and infinity replaced by None (numpy
    scalars and arrays as Python numbers and lists), and the dotted keys replaced."""
    where: list[str] = []

    def clean(obj: Any, key: str) -> Any:
        if hasattr(obj, "tolist") and not isinstance(obj, (str, bytes)):
            obj = obj.tolist()
        if isinstance(obj, float) and (obj != obj or obj in (float("inf"), float("-inf"))):
            where.append(key)
            return None
        if isinstance(obj, dict):
            return {k: clean(v, f"{key}.{k}" if key else str(k)) for k, v in obj.items()}
        if isinstance(obj, (list, tuple)):
            return [clean(v, f"{key}[{i}]") for i, v in enumerate(obj)]
        return obj

    return clean(data, ""), where


def write_json(path: str | os.PathLike, data: Any) -> Path:
    """Write ``data`` as JSON that a strict parser reads (RFC 8259), atomically.

    NaN and the infinities are written ``null``; when any were, a top-level object gets
    the key ``non_finite``: the dotted keys written ``null`` for that reason.
    """
    clean, where = strict_json(data)
    if where and isinstance(clean, dict):
        clean["non_finite"] = where
    return atomic_write_text(path, json.dumps(clean, indent=2, allow_nan=False) + "\n")


def check_output_dir(path: str | os.PathLike, name: str = "--out") -> Path:
    """Create the output folder ``path`` if needed and check that it can be written.

    A folder created here is removed again when the process ends if it is still empty (a
    run refused after this check leaves nothing behind). Stale temporary files of killed
    runs in it are removed (`remove_stale_parts`).

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
    missing = [p for p in (path, *path.parents) if not p.exists()]
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
    _CREATED.extend(p.absolute() for p in missing)
    _sweep(path)
    return path


@atexit.register
def _remove_empty_created() -> None:
    """Remove the folders `check_output_dir` created that are still empty (deepest first)."""
    for folder in sorted(_CREATED, key=lambda p: len(p.parts), reverse=True):
        with contextlib.suppress(OSError):
            folder.rmdir()  # only if empty
    _CREATED.clear()


def check_output_file(path: str | os.PathLike, name: str = "path") -> Path:
    """Check that the file ``path`` can be written: its folder exists and is writable, and
    it is a regular file (or a link to one) or a new path (`output_target`).

    Raises
    ------
    InputError
        If ``path`` is a folder or a special file, or its folder is missing or not
        writable.
    """
    path = Path(path)
    target = output_target(path, name)
    parent = target.parent
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
    _sweep(parent)
    return path
