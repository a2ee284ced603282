"""Habits of a maintained project: ruff (lint and format) and mypy report nothing on src/,
with the configuration in pyproject.toml."""

import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _run(*args):
    return subprocess.run(args, cwd=ROOT, capture_output=True, text=True)


@pytest.mark.skipif(shutil.which("ruff") is None, reason="ruff is not installed ([test] extra)")
def test_ruff_lint_and_format_report_nothing():
    lint = _run("ruff", "check", "src")
    assert lint.returncode == 0, lint.stdout + lint.stderr
    fmt = _run("ruff", "format", "--check", "src")
    assert fmt.returncode == 0, fmt.stdout + fmt.stderr


def test_mypy_reports_nothing():
    pytest.importorskip("mypy", reason="mypy is not installed ([test] extra)")
    got = _run(sys.executable, "-m", "mypy")
    assert got.returncode == 0, got.stdout + got.stderr


def test_benchmarks_and_examples_compile(tmp_path):
    """The scripts outside the package (benchmarks, examples) are not imported by the other
    tests; a syntax error there would otherwise go unnoticed."""
    import py_compile

    scripts = sorted((ROOT / "benchmarks").glob("*.py")) + sorted((ROOT / "examples").rglob("*.py"))
    assert scripts
    for path in scripts:
        py_compile.compile(str(path), doraise=True, cfile=str(tmp_path / "out.pyc"))
