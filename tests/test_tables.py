"""Lookup tables (docs/cycles.md): the three layouts agree, and reading a table back and
interpolating equals the model within the grid's own error."""

import numpy as np
import pytest
from scipy.interpolate import RegularGridInterpolator
from scipy.io import loadmat

from ballcvt import Variator, load_builtin
from ballcvt.analysis.tables import read_modelica_tables
from ballcvt.interfaces.cli import main as cli
from drives import fixed_oil_hub


@pytest.fixture(scope="module")
def tables(tmp_path_factory):
    out = tmp_path_factory.mktemp("tables")
    assert cli.main(["table", "--design", "hub", "--oil-temperature", "fixed", "--clamp-law", "cam", "--ratio-range", "0.6",
                     "1.6", "--n-ratio", "6", "--speed-range", "500", "2500", "--n-speed",
                     "3", "--torque-max", "120", "--n-torque", "7", "--out", str(out),
                     "--quiet"]) == 0
    return out


def test_layouts_agree(tables):
    import pandas as pd
    mat = loadmat(tables / "table.mat", squeeze_me=True)
    assert mat["eta"].shape == (6, 3, 7)
    csv = pd.read_csv(tables / "table.csv")
    eta_csv = csv["eta [1]"].to_numpy().reshape(6, 3, 7)
    ok = mat["status"] == 0
    assert ok.all()                                   # 120 N m is within the cam's capacity
    assert np.allclose(eta_csv[ok], mat["eta"][ok], rtol=0, atol=1e-15)
    mo = read_modelica_tables(tables / "table_modelica.txt")
    for k in range(3):
        u1, u2, table = mo[f"eta_w{k + 1}"]
        assert np.array_equal(u1, mat["ratio"]) and np.array_equal(u2, mat["output_torque"])
        assert np.array_equal(table, mat["eta"][:, k, :])
    u1, u2, lim = mo["limit_torque"]
    assert np.array_equal(u2, mat["input_speed_rpm"])
    assert np.array_equal(lim, mat["limit_torque"])


def test_round_trip_interpolation_matches_the_model(tables):
    mat = loadmat(tables / "table.mat", squeeze_me=True)
    grid = (mat["ratio"], mat["input_speed_rpm"], mat["output_torque"])
    interp = RegularGridInterpolator(grid, mat["eta"])
    v = Variator(*fixed_oil_hub())
    rng = np.random.default_rng(3)
    for _ in range(6):
        i, j, k = rng.integers(0, 5), rng.integers(0, 2), rng.integers(1, 6)
        # the centre of a grid cell: the worst place for linear interpolation
        point = [0.5 * (g[n] + g[n + 1]) for g, n in zip(grid, (i, j, k))]
        exact = v.solve(point[0], point[2], clamp_law="cam", input_speed_rpm=point[1]).eta
        corners = mat["eta"][i:i + 2, j:j + 2, k:k + 2]
        # the grid's own error: linear interpolation of a function that varies this much
        # over the cell cannot miss it by more than the cell's spread of values
        spread = float(corners.max() - corners.min())
        got = float(interp([point])[0])
        assert abs(got - exact) <= spread
        assert abs(got - exact) < 0.02


def test_beyond_capacity_holds_no_number_and_is_marked(tmp_path):
    # issue 25: beyond-capacity cells used to hold the last admissible value, which a
    # system model ignoring status takes for a real drive; now NaN / empty / sentinel
    import pandas as pd
    from ballcvt.analysis.tables import MODELICA_BEYOND
    out = tmp_path / "t"
    assert cli.main(["table", "--ratio-range", "0.8", "1.2", "--n-ratio", "2",
                     "--speed-range", "1000", "2000", "--n-speed", "2", "--torque-max", "300",
                     "--n-torque", "4", "--out", str(out), "--quiet"]) == 0
    mat = loadmat(out / "table.mat", squeeze_me=True)
    beyond = mat["status"] == 1
    assert beyond.any()
    assert np.isnan(mat["eta"][beyond]).all() and np.isnan(mat["loss_total"][beyond]).all()
    assert np.isfinite(mat["eta"][mat["status"] == 0]).all()
    for i, j in np.ndindex(2, 2):
        b = np.flatnonzero(beyond[i, j])
        if b.size:
            assert mat["output_torque"][b[0]] > mat["limit_torque"][i, j]
    csv = pd.read_csv(out / "table.csv")
    assert csv.loc[csv["status"] == 1, "eta [1]"].isna().all()
    mo = read_modelica_tables(out / "table_modelica.txt")
    for k in range(2):
        cells = mo[f"eta_w{k + 1}"][2]
        assert np.all(cells[beyond[:, k, :]] == MODELICA_BEYOND)
        assert np.all(cells[~beyond[:, k, :]] >= 0.0)
