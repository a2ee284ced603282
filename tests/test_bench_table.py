"""The benchmark table's formatter and README writer (benchmarks/bench_table.py) and
bench_evaluations.py's counter; no timing is asserted here (one 3 x 3 sweep checks that
the counter still reaches the solvers, by its counts alone)."""

from __future__ import annotations

import importlib.util
import json
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def _load(name):
    """The benchmark script ``benchmarks/<name>.py`` as the module ``name``."""
    spec = importlib.util.spec_from_file_location(name, ROOT / "benchmarks" / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module  # its dataclasses look their module up
    spec.loader.exec_module(module)
    return module


def _bench():
    return _load("bench_table")


ROWS = [
    {"key": "sweep-isothermal-constant", "what": "base", "figure": 0.2, "unit": "ms/point",
     "target": ">= 2,000 points/s", "met": True, "note": ""},
    {"key": "sweep-thermal-constant", "what": "thermal", "figure": 0.5, "unit": "ms/point",
     "target": "", "met": None, "note": "2,000 points/s"},
    {"key": "map-1000", "what": "big map", "figure": 900.0, "unit": "MiB",
     "target": "< 1 GB", "met": True, "note": ""},
]


def test_table_ratios_to_baseline_and_previous():
    b = _bench()
    previous = [dict(ROWS[1], figure=1.0)]
    lines = b.table(ROWS, previous).splitlines()
    assert lines[0].startswith("| path | measured | x baseline")
    thermal = next(line for line in lines if line.startswith("| thermal"))
    cells = [c.strip() for c in thermal.split("|")[1:-1]]
    assert cells[1] == "0.500 ms/point (2,000 points/s)"
    assert cells[2] == "2.50"  # 0.5 / 0.2 ms per point
    assert cells[5] == "1.00 ms/point" and cells[6] == "0.500"
    big = next(line for line in lines if line.startswith("| big map"))
    assert "| yes |" in big and big.split("|")[3].strip() == ""  # no ratio for MiB


def test_write_readme_replaces_between_markers(tmp_path):
    b = _bench()
    readme = tmp_path / "README.md"
    readme.write_text(f"intro\n{b.MARKERS[0]}\nold table\n{b.MARKERS[1]}\nrest\n")
    b.write_readme("| new |", readme)
    assert readme.read_text() == f"intro\n{b.MARKERS[0]}\n| new |\n{b.MARKERS[1]}\nrest\n"


def test_markdown_from_saved_rows(tmp_path, capsys):
    b = _bench()
    saved = tmp_path / "rows.json"
    saved.write_text(json.dumps({"rows": ROWS}))
    b.main(["--from-json", str(saved), "--markdown"])
    out = capsys.readouterr().out
    assert "| base | 0.200 ms/point | 1.00 |" in out


def test_readme_table_is_the_scripts():
    """The README's performance tables (quick and full runs) sit between the script's
    markers."""
    b = _bench()
    text = (ROOT / "README.md").read_text()
    for mode, markers in b.README_MARKERS.items():
        a, z = (text.index(m) for m in markers)
        assert f"{mode} run" in text[a:z] and "| path | measured | x baseline" in text[a:z]


def test_write_readme_puts_each_mode_in_its_place(tmp_path):
    b = _bench()
    quick, full = b.README_MARKERS["quick"], b.README_MARKERS["full"]
    readme = tmp_path / "README.md"
    readme.write_text(f"{quick[0]}\nq\n{quick[1]}\n{full[0]}\nf\n{full[1]}\n")
    b.write_readme("| full |", readme, full)
    assert readme.read_text() == f"{quick[0]}\nq\n{quick[1]}\n{full[0]}\n| full |\n{full[1]}\n"


def _evaluations():
    _bench()  # bench_evaluations imports bench_table's rows and README writer
    return _load("bench_evaluations")


def test_evaluations_table_against_the_first_row():
    """bench_evaluations.py's table: each row against the first (the baseline), its phases
    and its capacity scan's counts (no timings run here)."""
    e = _evaluations()
    rows = [e.Counted("isothermal", "constant", 0.2, 8.0, 20.0, 0.8, {"sweep": 8.0}),
            e.Counted("thermal", "cam", 2.0, 64.0, 25.0, 0.8,
                      {"capacity scan": 50.0, "sweep": 14.0}, 0, (1470, 294),
                      {"sweep": 0.4, "capacity scan": 1.5, "limit search": 0.1,
                       "capacity bisections": 0.001},
                      {"32 x 24": (40.0, 38.0), "12 x 8": (24.0, 15.5)})]
    lines = e.table(rows, 30).splitlines()
    thermal = [c.strip() for c in lines[-1].split("|")[1:-1]]
    assert thermal[:4] == ["thermal, cam", "2.000 (10.00)", "64.0 (8.00)", "25.0 (1.25)"]
    # phases with evaluations, or 1 % of the time or more (each with its own time)
    assert thermal[5] == "capacity scan 50.0 (1.500), sweep 14.0 (0.400), limit search 0.0 (0.100)"
    assert thermal[6] == "1,470 (294)"
    assert thermal[7] == "32 x 24: 40.0 (38.0); 12 x 8: 24.0 (15.5)"
    baseline = [c.strip() for c in lines[-2].split("|")[1:-1]]
    assert baseline[5] == "sweep 8.0" and baseline[6] == "-" and baseline[7] == "-"


def test_evaluations_by_rule_and_phase_time():
    """The counter tallies evaluations per quadrature rule and each phase's own CPU time
    (without the phases inside it)."""
    e = _evaluations()
    c = e._Counter()
    rule = type("Q", (), {"n_radial": 32, "n_angular": 24})()
    evaluate = c.wrap(lambda *a: None, lambda problem, creep, *a: len(creep),
                      lambda problem, creep, h, q, *a: (q.n_radial, q.n_angular))
    inner = c.in_phase("capacity scan", lambda: evaluate(None, [0, 0, 0], None, rule))
    c.in_phase("limit search", lambda: (inner(), evaluate(None, [0], None, rule)))()
    assert c.by_rule[(32, 24)][0] == 4
    assert c.by_phase == {"capacity scan": 3, "limit search": 1}
    assert set(c.phase_seconds) == {"capacity scan", "limit search"}
    assert all(s >= 0.0 for s in c.phase_seconds.values())


def test_readme_evaluations_table_is_the_scripts():
    e = _evaluations()
    text = (ROOT / "README.md").read_text()
    a, z = (text.index(m) for m in e.MARKERS)
    assert "| law, clamp | ms/point (x baseline) |" in text[a:z]


def test_evaluations_counted_on_a_small_sweep():
    """The counter's hooks still reach the solvers: on a 3 x 3 cam sweep every evaluation
    is counted once by phase and once by rule, the capacity scan's 49 torques per curve are
    seen, and both rules run (the scan's screen on the coarse one)."""
    e = _evaluations()
    r = e.measure("isothermal", "cam", 3, repeat=1)
    assert r.scan[0] == 3 * 49 and r.numpy_calls == 0
    assert list(r.rules) == ["32 x 24", "12 x 8"]  # the full rule first
    assert {"capacity scan", "sweep"} <= set(r.phases)
    by_rule = sum(p for p, _ in r.rules.values())
    assert by_rule == pytest.approx(r.evaluations_per_point)
    assert sum(r.phases.values()) == pytest.approx(r.evaluations_per_point)
    assert sum(r.phase_ms.values()) == pytest.approx(r.ms_per_point)
