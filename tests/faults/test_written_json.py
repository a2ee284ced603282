"""A study's summary.json parses under a strict parser (RFC 8259: no NaN, no Infinity),
whatever non-finite figure reaches it (here one planted in its counts)."""

import json
from pathlib import Path

from ballcvt.analysis.studies import parse_study, run_study
from ballcvt.analysis.studies import run as run_module

TINY = Path(__file__).resolve().parents[1] / "data" / "study_tiny.toml"


def _strict(text: str):
    def refuse(constant):
        raise ValueError(f"non-standard JSON constant {constant}")

    return json.loads(text, parse_constant=refuse)


def test_a_study_writes_strict_json(tmp_path, monkeypatch):
    counts = run_module.StudyResult.counts
    monkeypatch.setattr(run_module.StudyResult, "counts",
                        lambda self: {**counts(self), "planted": float("inf")})
    run_study(parse_study(TINY.read_text()), tmp_path / "s", in_process=True, progress=False)
    summary = _strict((tmp_path / "s" / "summary.json").read_text())
    assert summary["counts"]["planted"] is None and summary["non_finite"] == ["counts.planted"]
