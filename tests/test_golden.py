"""Golden regression values (regenerate with ``python tests/make_golden.py``)."""

import json

import pytest
from make_golden import PATH, compute


def test_golden_points():
    expected = json.loads(PATH.read_text())
    for got, want in zip(compute(), expected, strict=True):
        assert got["architecture"] == want["architecture"]
        for key in ("eta", "input_torque", "losses_total"):
            assert got[key] == pytest.approx(want[key], rel=1e-8), (want, key)
        # Creeps: relative where they matter, absolute floor for the ~1e-15 idler creep.
        assert got["creep"] == pytest.approx(want["creep"], rel=1e-6, abs=1e-12)
        assert got["p_max"] == pytest.approx(want["p_max"], rel=1e-12)
