"""Sweeps, maps and tables solve in chunks of curves (bounded memory, issue 26): the
answers do not depend on the chunk size, nor on the number of worker processes."""

from __future__ import annotations

import filecmp

import numpy as np
import pandas as pd
import pytest

import ballcvt.analysis.sweeps.chunks as chunks
import ballcvt.analysis.sweeps.export as export
from ballcvt import Variator, load_builtin
from ballcvt.api import MapGrid, TableGrid, to_csv, to_frame
from drives import fixed_oil_hub


def _values(ds):
    return {name: ds[name].values for name in ds.data_vars}


def _same(a, b, rtol=0.0):
    """Equal variables (NaN where NaN); floats to ``rtol`` (0: bit for bit)."""
    assert a.keys() == b.keys()
    for name in a:
        x, y = a[name], b[name]
        assert x.dtype == y.dtype and x.shape == y.shape, name
        if name in ("iterations", "residual_norm"):  # how the solver got there
            continue
        if rtol == 0.0 or x.dtype.kind != "f":
            np.testing.assert_array_equal(x, y, err_msg=name)
        else:
            np.testing.assert_allclose(x, y, rtol=rtol, atol=1e-300, err_msg=name)


def _sweep(v, **kw):
    return v.sweep(
        ratio=np.linspace(0.5, 2.0, 20),
        output_torque=np.linspace(5.0, 90.0, 30),
        input_speed_rpm=2000.0,
        progress=False,
        **kw,
    )


# Chunks of a few hundred points: each chunk's batch is long enough for the solver's
# predictor stage (`SolverOptions.predictor_min_points`), as every chunk of the default
# size is; on batches of a few points the solver takes another path, and the answers
# move by its tolerance (1e-9 relative).
@pytest.mark.parametrize("size", [300, 450])
def test_map_same_bits_whatever_the_chunk(monkeypatch, size):
    v = Variator()
    grid = MapGrid((0.5, 2.0), 20, None, 30)
    whole = _values(v.efficiency_map(grid, clamp_force=2000.0, progress=False))
    monkeypatch.setattr(chunks, "CHUNK_POINTS", size)
    assert len(chunks.curve_chunks(20, 30)) > 1
    _same(_values(v.efficiency_map(grid, clamp_force=2000.0, progress=False)), whole)


def test_sweep_same_answers_whatever_the_chunk(monkeypatch):
    """The limits are searched for every curve at once; each chunk's points are then
    solved in their own batch: the same statuses and limits, values to round-off."""
    v = Variator()
    whole = _values(_sweep(v, clamp_force=[1500.0, 2500.0]))
    monkeypatch.setattr(chunks, "CHUNK_POINTS", 300)
    part = _values(_sweep(v, clamp_force=[1500.0, 2500.0]))
    for name in ("status", "limit_torque"):
        np.testing.assert_array_equal(part[name], whole[name], err_msg=name)
    _same(part, whole, rtol=1e-13)


def test_cam_sweep_whatever_the_chunk(monkeypatch):
    v = Variator(*fixed_oil_hub())
    kw = {"ratio": np.linspace(0.6, 1.6, 20), "output_torque": np.linspace(2.0, 60.0, 30)}
    whole = _values(v.sweep(**kw, clamp_law="cam", input_speed_rpm=150.0, progress=False))
    monkeypatch.setattr(chunks, "CHUNK_POINTS", 300)
    part = _values(v.sweep(**kw, clamp_law="cam", input_speed_rpm=150.0, progress=False))
    np.testing.assert_array_equal(part["status"], whole["status"])
    np.testing.assert_array_equal(part["limit_torque"], whole["limit_torque"])
    _same(part, whole, rtol=1e-10)  # the cam's force iteration, batch by batch


def test_table_same_bits_whatever_the_chunk(monkeypatch):
    v = Variator()
    grid = TableGrid(
        ratio_range=(0.6, 1.6), n_ratio=10, n_torque=30, speed_range_rpm=(1000.0, 3000.0), n_speed=3
    )
    whole = _values(v.lookup_table(grid, clamp_force=2000.0, progress=False))
    monkeypatch.setattr(chunks, "CHUNK_POINTS", 300)
    _same(_values(v.lookup_table(grid, clamp_force=2000.0, progress=False)), whole)


def test_workers_give_the_same_bits(monkeypatch):
    """Chunks do not depend on ``workers``: a pool solves the same batches."""
    monkeypatch.setattr(chunks, "CHUNK_POINTS", 300)
    v = Variator()
    one = _values(_sweep(v, clamp_force=2000.0))
    two = _values(_sweep(v, clamp_force=2000.0, workers=2))
    _same(two, one)
    for name in ("iterations", "residual_norm"):
        np.testing.assert_array_equal(two[name], one[name])


def test_curve_chunks_cover_every_curve_once():
    for n, nt in ((1, 1), (7, 9000), (31, 35), (1000, 1000), (301, 300)):
        got = chunks.curve_chunks(n, nt)
        idx = np.concatenate([np.arange(c.start, c.stop) for c in got])
        np.testing.assert_array_equal(idx, np.arange(n))
        assert all((c.stop - c.start) * nt <= max(nt, chunks.CHUNK_POINTS) for c in got)
    assert len(chunks.curve_chunks(50, 100, workers=2)) == 2  # work for both workers
    assert len(chunks.curve_chunks(30, 30, workers=2)) == 1  # too small to share


def test_csv_streams_the_same_table(monkeypatch, tmp_path):
    ds = Variator().sweep(
        ratio=[0.8, 1.2, 1.6],
        output_torque=[10.0, 30.0],
        clamp_force=[1500.0, 2500.0],
        input_speed=[100.0, 200.0],
        architecture=["double", "single"],
        progress=False,
    )
    monkeypatch.setattr(export, "CSV_ROWS", 10**9)
    to_csv(ds, tmp_path / "whole.csv")
    for rows in (1, 5, 1000):
        monkeypatch.setattr(export, "CSV_ROWS", rows)
        to_csv(ds, tmp_path / f"rows{rows}.csv")
        assert filecmp.cmp(tmp_path / "whole.csv", tmp_path / f"rows{rows}.csv", shallow=False)
    # the values of pandas' table to the bit: the same columns, NaN in the same places
    ours, frame = pd.read_csv(tmp_path / "whole.csv"), to_frame(ds)
    assert list(ours.columns) == list(frame.columns)
    for name in frame.columns:
        want = frame[name].to_numpy()
        if want.dtype.kind == "f":
            np.testing.assert_array_equal(ours[name].to_numpy(), want)  # NaN == NaN here
        else:
            assert ours[name].astype(str).tolist() == frame[name].astype(str).tolist()


def test_csv_writes_pandas_spellings(tmp_path):
    """Booleans as ``True``/``False`` and NaN as an empty field, as pandas writes them;
    floats in their shortest round-trip form."""
    frame = pd.DataFrame({"a": [1.0, np.nan, 3.5e-8], "b": [True, False, True], "c": ["x", "y", "z"]})
    with open(tmp_path / "t.csv", "wb") as fh:
        export._write_csv(frame, fh, True)
    assert (tmp_path / "t.csv").read_text().splitlines() == [
        "a,b,c", "1.0,True,x", ",False,y", "3.5e-8,True,z"
    ]


def test_map_cli_workers_same_data(tmp_path, monkeypatch):
    """``ballcvt map --workers 2`` shares the chunks with a worker process: the same data."""
    from ballcvt.api import load_dataset
    from ballcvt.interfaces.cli.main import main

    monkeypatch.setattr(chunks, "CHUNK_POINTS", 300)
    got = {}
    for workers in (1, 2):
        out = tmp_path / f"w{workers}"
        argv = ["map", "--out", str(out), "--n-ratio", "20", "--n-torque", "30", "--quiet"]
        assert main([*argv, "--workers", str(workers)]) == 0
        got[workers] = _values(load_dataset(out / "map.nc"))
    _same(got[2], got[1])
