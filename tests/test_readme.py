"""Every code block and command-line example of README.md runs as written.

Python blocks run in order in one namespace (as a reader would paste them); every line of a
``bash`` block that starts with ``ballcvt`` runs through the command line's ``main`` and
must exit 0. The set-up commands (``python3 -m venv ...``) are what CI itself runs.
"""

import re
import shlex
from pathlib import Path

import pytest

from ballcvt.interfaces.cli.main import main

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
BLOCKS = re.findall(r"```(\w*)\n(.*?)```", README.read_text(), re.S)
#: Other documents whose command lines must run (continuation lines joined).
DOCS = [ROOT / "docs" / "cycles.md", ROOT / "docs" / "studies.md", ROOT / "docs" / "shifting.md"]


def test_readme_has_examples():
    kinds = [kind for kind, _ in BLOCKS]
    assert kinds.count("python") >= 4 and kinds.count("bash") >= 3


def test_python_blocks_run_in_order(tmp_path, monkeypatch):
    import matplotlib
    matplotlib.use("Agg")                 # the test has no display
    monkeypatch.chdir(tmp_path)
    (tmp_path / "examples").symlink_to(ROOT / "examples")   # as in a clone
    namespace: dict = {}
    for i, (kind, code) in enumerate(BLOCKS):
        if kind == "python":
            exec(compile(code, f"README.md python block {i}", "exec"), namespace)  # noqa: S102
    assert (tmp_path / "point.json").exists() and (tmp_path / "sweep.csv").exists()


def _run_line(line):
    """Run one documented command line, with the repository's example files."""
    args = [str(ROOT / a) if a.startswith("examples/") else a for a in shlex.split(line)[1:]]
    return main(args)


def _cli_lines(blocks=BLOCKS):
    for kind, code in blocks:
        if kind == "bash":
            for line in code.replace("\\\n", " ").splitlines():
                if line.startswith("ballcvt "):
                    yield " ".join(line.split())


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    return tmp_path_factory.mktemp("readme-cli")


@pytest.mark.parametrize("line", list(_cli_lines()))
def test_cli_examples_run(line, workdir, monkeypatch, capsys):
    monkeypatch.chdir(workdir)
    if "--design my_drive.toml" in line and not (workdir / "my_drive.toml").exists():
        assert main(["design", "export", "my_drive.toml"]) == 0
    assert _run_line(line) == 0, capsys.readouterr().err


DOC_LINES = [(doc.name, line) for doc in DOCS
             for line in _cli_lines(re.findall(r"```(\w*)\n(.*?)```", doc.read_text(), re.S))]


#: Documentation pages whose python blocks must run (each page in its own namespace).
PAGES = sorted((ROOT / "docs" / "capabilities").glob("*.md")) + [
    ROOT / "docs" / "getting-started.md"]


@pytest.mark.parametrize("page", PAGES, ids=lambda p: p.name)
def test_docs_python_blocks_run(page, tmp_path, monkeypatch):
    import matplotlib
    matplotlib.use("Agg")
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    for i, (kind, code) in enumerate(re.findall(r"```(\w*)\n(.*?)```", page.read_text(), re.S)):
        if kind == "python":
            exec(compile(code, f"{page.name} python block {i}", "exec"), namespace)  # noqa: S102


@pytest.mark.parametrize("doc, line", DOC_LINES)
def test_doc_cli_examples_run(doc, line, workdir, monkeypatch, capsys):
    monkeypatch.chdir(workdir)
    assert _run_line(line) == 0, (doc, capsys.readouterr().err)
