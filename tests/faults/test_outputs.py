"""Issue 24: outputs replace nothing they should not, and runs leave nothing behind.

A regular file or a new path is written atomically; a symbolic link is written through
(the link stays); a FIFO, a socket, a device node or a folder named as an output file is
refused with an InputError (exit 2) and left as it was. A refused run leaves no empty
``--out`` folder; the temporary files of a killed run are removed by the next run into
the folder (only ballcvt's own, of dead processes). Each of these failed before.
"""

from __future__ import annotations

import logging
import os
import socket
import stat
import subprocess
import sys
from pathlib import Path

import pytest
from test_cli_support import one_line, run, spawn

from ballcvt.errors import InputError
from ballcvt.files import atomic_path, atomic_write_text, check_output_dir, check_output_file


def _device(tmp_path: Path) -> Path:
    """A character device like /dev/null, made in tmp_path (root only)."""
    node = tmp_path / "null"
    try:
        os.mknod(node, stat.S_IFCHR | 0o666, os.makedev(1, 3))
    except (PermissionError, OSError) as exc:
        pytest.skip(f"cannot make a device node here: {exc}")
    return node


def _fifo(tmp_path: Path) -> Path:
    node = tmp_path / "pipe"
    try:
        os.mkfifo(node)
    except (AttributeError, OSError) as exc:
        pytest.skip(f"no FIFOs here: {exc}")
    return node


def _socket(tmp_path: Path) -> tuple[Path, socket.socket]:
    node = tmp_path / "sock"
    s = socket.socket(socket.AF_UNIX)
    s.bind(str(node))
    return node, s


@pytest.mark.parametrize("kind", ["fifo", "device", "socket", "folder"])
def test_special_files_are_refused_and_kept(tmp_path, kind):
    keep = None
    if kind == "fifo":
        node, test = _fifo(tmp_path), stat.S_ISFIFO
    elif kind == "device":
        node, test = _device(tmp_path), stat.S_ISCHR
    elif kind == "socket":
        (node, keep), test = _socket(tmp_path), stat.S_ISSOCK
    else:
        node, test = tmp_path / "folder", stat.S_ISDIR
        node.mkdir()
    for write in (check_output_file, lambda p: atomic_write_text(p, "x")):
        with pytest.raises(InputError) as err:
            write(node)
        assert str(node) in str(err.value) and "\n" not in str(err.value)
        assert test(os.lstat(node).st_mode), "the special file was replaced"
    assert not [p for p in tmp_path.iterdir() if ".part" in p.name]
    if keep is not None:
        keep.close()


def test_dev_null_is_refused_before_anything_is_written():
    with pytest.raises(InputError, match="character device"):
        check_output_file("/dev/null")
    with pytest.raises(InputError, match="/dev/null"):
        atomic_write_text("/dev/null", "x")
    assert stat.S_ISCHR(os.stat("/dev/null").st_mode)


def test_a_link_to_a_special_file_is_refused(tmp_path):
    link = tmp_path / "link"
    link.symlink_to(_fifo(tmp_path))
    with pytest.raises(InputError, match="symbolic link to .*FIFO"):
        atomic_write_text(link, "x")
    assert link.is_symlink() and stat.S_ISFIFO(os.stat(link).st_mode)


def test_a_symlink_is_written_through(tmp_path):
    (tmp_path / "real").mkdir()
    target = tmp_path / "real" / "design.toml"
    target.write_text("old\n")
    os.chmod(target, 0o600)
    link = tmp_path / "design.toml"
    link.symlink_to(target)
    atomic_write_text(link, "new\n")
    assert link.is_symlink() and os.readlink(link) == str(target)
    assert target.read_text() == "new\n"
    assert stat.S_IMODE(os.stat(target).st_mode) == 0o600  # the replaced file's mode kept
    # a dangling link: the file it names is created, the link stays
    dangling = tmp_path / "new.toml"
    dangling.symlink_to(tmp_path / "real" / "created.toml")
    with atomic_path(dangling) as tmp:
        assert tmp.parent == tmp_path / "real"  # the temporary file is in the target's folder
        tmp.write_text("made\n")
    assert dangling.is_symlink() and (tmp_path / "real" / "created.toml").read_text() == "made\n"


def test_cli_refuses_special_files_with_exit_2(tmp_path, capsys):
    pipe = _fifo(tmp_path)
    code, _, err = run(capsys, "design", "export", pipe)
    assert code == 2 and one_line(err) and "FIFO" in err and str(pipe) in err
    assert stat.S_ISFIFO(os.lstat(pipe).st_mode)
    folder = tmp_path / "out"
    folder.mkdir()
    code, _, err = run(capsys, "design", "export", folder)
    assert code == 2 and one_line(err) and "folder" in err


def test_cli_writes_through_a_symlink(tmp_path, capsys):
    target = tmp_path / "drive.toml"
    target.write_text("old\n")
    link = tmp_path / "link.toml"
    link.symlink_to(target)
    code, _, _ = run(capsys, "design", "export", link)
    assert code == 0
    assert link.is_symlink() and "[design]" in target.read_text()


def test_replacing_a_file_says_so_once_per_folder(tmp_path, caplog):
    first, second = tmp_path / "a.txt", tmp_path / "b.txt"
    first.write_text("earlier result\n")
    second.write_text("earlier result\n")
    with caplog.at_level(logging.WARNING, logger="ballcvt.files"):
        atomic_write_text(tmp_path / "new.txt", "x")  # a new file: nothing to say
        assert not caplog.records
        atomic_write_text(first, "x")
        atomic_write_text(second, "x")
        atomic_write_text(first, "y")  # a file this process wrote: not news
    notes = [r.getMessage() for r in caplog.records]
    assert len(notes) == 1 and notes[0].startswith("ballcvt: note: replaced the earlier")
    assert str(first) in notes[0]


def test_overwriting_from_the_cli_is_one_note_and_succeeds(tmp_path):
    path = tmp_path / "drive.toml"
    path.write_text("earlier\n")
    proc = spawn("design", "export", path, capture_output=True)
    assert proc.returncode == 0, proc.stderr
    lines = proc.stderr.splitlines()
    assert lines[0] == f"ballcvt: note: replaced the earlier {path} (further files replaced " \
        f"in {tmp_path} are not listed)"
    assert "[design]" in path.read_text()


def test_a_refused_run_leaves_no_out_folder(tmp_path):
    bad = tmp_path / "cycle.csv"
    bad.write_text("time [s],output_speed [rpm],output_torque [lbf ft]\n0,100,10\n")
    out = tmp_path / "new" / "out"
    proc = spawn("cycle", bad, "--out", out, capture_output=True)
    assert proc.returncode == 2 and one_line(proc.stderr), proc.stderr
    assert not (tmp_path / "new").exists()
    # an existing folder stays, and so does a folder the run wrote into
    out.mkdir(parents=True)
    proc = spawn("cycle", bad, "--out", out, capture_output=True)
    assert proc.returncode == 2 and out.is_dir()


KILLED = """
import os, signal, sys
from ballcvt.files import atomic_path
with atomic_path(sys.argv[1]) as tmp:
    tmp.write_text("half a result")
    print(tmp.name, flush=True)
    os.kill(os.getpid(), signal.SIGKILL)
"""


def test_a_killed_run_leaves_a_part_file_that_the_next_run_removes(tmp_path):
    out = tmp_path / "out"
    out.mkdir()
    proc = subprocess.run([sys.executable, "-c", KILLED, str(out / "report.md")],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == -9
    part = out / proc.stdout.strip()
    assert part.exists() and ".ballcvt-" in part.name and part.name.endswith(".part.md")
    foreign = out / ".notes.md.part"  # not ballcvt's pattern: never touched
    foreign.write_text("someone else's")
    live = out / f".x.abc.ballcvt-{os.getpid()}.part.csv"  # a running process's: kept
    live.write_text("in progress")
    check_output_dir(out)  # a re-run into the folder (reproduce, cycle, ...)
    assert not part.exists()
    assert foreign.exists() and live.exists()
    assert not (out / "report.md").exists()
