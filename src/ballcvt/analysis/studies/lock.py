"""One run per output folder: a lock file holding the pid and host of the run.

The lock ``.ballcvt.lock`` is created with ``O_CREAT | O_EXCL`` (exactly one process
creates it) and removed when the run ends, normally or by an exception. A lock whose
process is no longer running on this host (a run killed with ``kill -9``) is stale: the
next run takes it over and says so on stderr. The lock is re-entrant within one process
(an outer caller may hold the folder across a run and its report).
"""

from __future__ import annotations

import contextlib
import json
import os
import socket
import sys
import time
from collections.abc import Iterator
from pathlib import Path

from ...errors import InputError

__all__ = ["LOCK", "folder_lock"]

LOCK = ".ballcvt.lock"
#: Locks this process holds -> how many times (re-entrant).
_HELD: dict[Path, int] = {}
#: Seconds an unreadable lock (its writer killed between creating and writing it) is
#: taken as being written, before it counts as stale.
_GRACE = 5.0


def _alive(pid: int) -> bool:
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process
        return True
    return True


def _holder(lock: Path) -> dict | None:
    """The lock's content, None if it is stale (its process is gone) or missing."""
    try:
        text = lock.read_text()
        age = time.time() - lock.stat().st_mtime
    except FileNotFoundError:
        return None
    try:
        info = json.loads(text)
        pid, host = int(info["pid"]), str(info["host"])
    except (ValueError, KeyError, TypeError):
        return {"pid": "?", "host": "?"} if age < _GRACE else None
    if host == socket.gethostname() and not _alive(pid):
        return None
    return info


def _take(lock: Path) -> bool:
    """Create the lock with this process's pid and host; False if it exists."""
    try:
        fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_WRONLY, 0o644)
    except FileExistsError:
        return False
    info = {"pid": os.getpid(), "host": socket.gethostname(), "started": time.time()}
    with os.fdopen(fd, "w") as f:
        f.write(json.dumps(info))
    return True


def _take_over(lock: Path) -> None:
    """Move a stale lock aside (one process wins the rename) and remove it."""
    aside = lock.with_name(f"{LOCK}.stale.{os.getpid()}")
    try:
        os.rename(lock, aside)
    except FileNotFoundError:
        return  # another run took it over first
    try:
        info = json.loads(aside.read_text())
    except ValueError:
        info = {"pid": "?", "host": "?"}
    pid = info.get("pid")
    if isinstance(pid, int) and info.get("host") == socket.gethostname() and _alive(pid):
        os.rename(aside, lock)  # a live lock taken a moment ago by another run: give back
        return
    print(
        f"ballcvt: taking over the stale lock of {lock.parent} (process {info.get('pid')} "
        f"on {info.get('host')} is no longer running)",
        file=sys.stderr,
    )
    aside.unlink()


def _acquire(folder: Path) -> None:
    lock = folder / LOCK
    for _ in range(10):
        if _take(lock):
            return
        holder = _holder(lock)
        if holder is not None:
            raise InputError(
                "out",
                str(folder),
                "a folder no other run is writing",
                message=f"{folder} is in use by another ballcvt run (process "
                f"{holder.get('pid')} on {holder.get('host')}; lock {lock}): wait for it "
                "or choose another --out",
            )
        _take_over(lock)
    raise InputError("out", str(folder), "a folder no other run is writing")


@contextlib.contextmanager
def folder_lock(folder) -> Iterator[Path]:
    """Hold ``folder`` for this run (re-entrant in one process); released on exit.

    Raises
    ------
    InputError
        If another running process holds the folder.
    """
    folder = Path(folder).resolve()
    lock = folder / LOCK
    if folder not in _HELD:
        _acquire(folder)
    _HELD[folder] = _HELD.get(folder, 0) + 1
    try:
        yield lock
    finally:
        _HELD[folder] -= 1
        if _HELD[folder] == 0:
            del _HELD[folder]
            with contextlib.suppress(FileNotFoundError):
                lock.unlink()
