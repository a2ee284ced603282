"""Hygiene, measured (docs/architecture.md): sizes, parameter lists, one place per idea.

The figures come from tools/codemap.py, which also prints them (``python
tools/codemap.py``) and writes them into the documentation.
"""

from __future__ import annotations

import re
import shutil
import subprocess
import sys

import pytest
from codemap import (
    JUSTIFICATION,
    MAX_BODY,
    MAX_MODULE,
    MAX_PARAMETERS,
    ROOT,
    functions,
    module_lines,
)

#: The compiled kernels take scalars (a parameter object would cost speed); no more.
MAX_JUSTIFIED = 5


def test_no_module_is_too_long():
    assert {k: v for k, v in module_lines().items() if v > MAX_MODULE} == {}


def test_no_function_body_is_too_long():
    assert [f"{w} {n} ({b} lines)" for w, n, _, b, _ in functions() if b > MAX_BODY] == []


def test_long_parameter_lists_are_few_and_justified():
    many = [(w, n, p, why) for w, n, p, _, why in functions() if p > MAX_PARAMETERS]
    assert [f"{w} {n} ({p})" for w, n, p, why in many if not why] == [], (
        f"group the parameters into an object, or justify with '{JUSTIFICATION} ...' "
        "on the line above the def"
    )
    assert len(many) <= MAX_JUSTIFIED, many


def _source_lines():
    for path in sorted(ROOT.rglob("*.py")):
        for number, line in enumerate(path.read_text().splitlines(), 1):
            yield path.relative_to(ROOT), number, line


def test_speed_conversions_live_in_units():
    pattern = re.compile(r"pi\s*/\s*30|30(\.0)?\s*/\s*(math\.|np\.)?pi|3\.14159")
    found = [f"{p}:{n}" for p, n, line in _source_lines()
             if pattern.search(line) and p.name != "units.py"]
    assert found == [], "use ballcvt.units (rpm_to_rad_s, rad_s_to_rpm)"


def test_one_status_enumeration():
    found = [f"{p}:{n}" for p, n, line in _source_lines()
             if re.match(r"\s*\w*STATUS\w*\s*(:[^=]*)?=", line) and p.name != "status.py"]
    assert found == [], "status codes come from ballcvt.status.Status"


@pytest.mark.skipif(shutil.which("vulture") is None and
                    subprocess.run([sys.executable, "-m", "vulture", "--version"],
                                   capture_output=True).returncode != 0,
                    reason="vulture is not installed ([test] extra)")
def test_no_dead_code():
    got = subprocess.run([sys.executable, "-m", "vulture", str(ROOT), "--min-confidence", "80"],
                         capture_output=True, text=True)
    assert got.stdout.strip() == "", got.stdout
