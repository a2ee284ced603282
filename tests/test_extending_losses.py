"""The extending example: a loss term defined outside the package, registered, used by
solve, sweep and the limit search, and shown in the loss breakdown under its name."""

import json
import subprocess
import sys
from pathlib import Path

import pytest

SCRIPT = Path(__file__).resolve().parents[1] / "examples" / "extending" / "loss_term.py"


def test_loss_term_example_runs_in_a_fresh_interpreter():
    got = subprocess.run([sys.executable, str(SCRIPT)], capture_output=True, text=True,
                         timeout=600)
    assert got.returncode == 0, got.stdout + got.stderr
    line = next(s for s in got.stdout.splitlines() if s.startswith("RESULT "))
    result = json.loads(line[len("RESULT "):])
    assert result["lip_seal_W"] > 0
    assert "lip_seal" in result["breakdown"]
    # the paper's drive has no other parasitic loss: the sweep's are the lip seals'
    assert all(p > 0 for p in result["sweep_parasitic_W"])
    # the same point through the sweep and through solve: the same loss to round-off (the
    # creeps, and with them the output shaft's speed, agree to the solver's tolerance)
    assert result["sweep_parasitic_W"][1] == pytest.approx(result["lip_seal_W"], rel=1e-12)
    # the output shaft's seal adds to the load: a slightly lower limit
    assert result["limit_with"] < result["limit_without"]
