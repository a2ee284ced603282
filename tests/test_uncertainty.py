"""Uncertainty propagation (issue 27 item 5): the [uncertainty] table, sampling, bands,
rank sensitivity, reproducibility, saving, the command line and Dask."""

import json

import numpy as np
import pytest

from ballcvt import InputError
from ballcvt.analysis.uncertainty import UncertaintyResult, draw
from ballcvt.analysis.uncertainty.sampling import scale
from ballcvt.api import builtin_text, load_builtin, uncertainty
from ballcvt.interfaces.cli import main as cli
from ballcvt.params.io import parse_drive, parse_uncertain_drive
from ballcvt.params.uncertainty import parse_uncertainty

HUB = builtin_text("hub")
# the hub without its table, its oil fixed at the fluid's 40 C: these tests check the
# propagation (a capacity under the hub's oil balance costs ~10 s of CPU a drive)
BASE = HUB.split("\n[uncertainty]")[0].replace(
    'oil_temperature = "balance"', 'oil_temperature = "fixed"')
POINT = {"ratio": (1.0,), "input_speed_rpm": (114.0,), "progress": False}


def drive_file(tmp_path, table: str, name="drive.toml"):
    path = tmp_path / name
    path.write_text(BASE + "\n[uncertainty]\n" + table)
    return path


def table_of(entries: dict):
    d, f = load_builtin("hub")
    return parse_uncertainty(entries, d, f, "test")


def test_hub_table_parses_and_old_files_still_load():
    d, f, table = parse_uncertain_drive(HUB, "hub")
    assert {"design.cam.preload", "design.cam.ramp_angle_deg"} <= set(table.paths)
    assert all(v.source.startswith("ASSUMED") for v in table.values)
    assert parse_uncertain_drive(builtin_text("table1"), "t1")[2].values == ()
    assert parse_drive(HUB)[0] == load_builtin("hub")[0]
    with pytest.raises(InputError, match=r"unknown table \[extra\]"):
        parse_drive(BASE + "\n[extra]\nx = 1\n")


def test_entries_resolve_against_the_nominal_value():
    t = table_of({
        "design.cam.preload": {"relative": 0.5},
        "operating.rated_torque": {"range": [50.0, 150.0], "source": "s"},
        "fluid.limiting_shear_stress": {"distribution": "normal", "std": 1e6},
        "design.cam.friction": {"distribution": "triangular", "range": [0.002, 0.01]},
        "design.n_rollers": {"range": [6, 10]},
    })
    pre, rated, tau, mu, n = t.values
    assert (pre.lo, pre.hi) == (500.0, 1500.0) and rated.source == "s"
    assert tau.mean == 2e7 and tau.std == 1e6 and not np.isfinite(tau.lo)
    assert mu.mode == 0.005 and n.integer and not pre.integer
    assert set(scale(n, np.linspace(0.01, 0.99, 50))) <= {6.0, 7.0, 8.0, 9.0, 10.0}


@pytest.mark.parametrize("entries, match", [
    ({"design.cam.preloadd": {"relative": 0.1}}, "names no finite number"),
    ({"design.cam": {"relative": 0.1}}, "names no finite number"),
    ({"design.name": {"relative": 0.1}}, "names no finite number"),
    ({"preload": {"relative": 0.1}}, "names no finite number"),
    ({"design.cam.preload": {"range": [2.0, 1.0]}}, "lo < hi"),
    ({"design.cam.preload": {"range": [1.0, 2.0], "relative": 0.1}}, "one of"),
    ({"design.cam.preload": {"distribution": "normal"}}, "std or relative"),
    ({"design.cam.preload": {"distribution": "normal", "std": -1.0}}, "> 0"),
    ({"design.cam.preload": {"distribution": "lognormal", "std": 1.0}}, "distribution"),
    ({"design.cam.preload": {"distribution": "loguniform", "range": [0.0, 1.0]}}, "0 < lo"),
    ({"design.cam.preload": {"distribution": "triangular", "range": [1.0, 2.0]}}, "mode"),
    ({"design.cam.preload": {"relative": 0.1, "sigma": 3}}, "sigma"),
    ({"design.cam.preload": 0.2}, "inline table"),
])
def test_bad_entries_are_refused_in_one_line_naming_the_path(entries, match):
    with pytest.raises(InputError, match=match) as exc:
        table_of(entries)
    assert "\n" not in str(exc.value)


def test_a_bad_table_in_a_drive_file_is_refused_when_the_file_is_read(tmp_path):
    path = drive_file(tmp_path, '"design.cam.rampp" = { relative = 0.1 }\n')
    with pytest.raises(InputError, match="design.cam.rampp"):
        parse_drive(path.read_text(), str(path))


def test_sampling_is_seeded_and_follows_the_distribution():
    t = table_of({"design.cam.preload": {"range": [500.0, 1500.0]},
                  "fluid.density": {"distribution": "normal", "std": 10.0}})
    for method in ("sobol", "lhs", "random"):
        a, b = draw(t, 256, method, 3), draw(t, 256, method, 3)
        np.testing.assert_array_equal(a, b)
        assert not np.array_equal(a, draw(t, 256, method, 4))
        assert 500 <= a[:, 0].min() and a[:, 0].max() <= 1500
        assert abs(a[:, 1].mean() - 850.0) < 2.0 and abs(a[:, 1].std() - 10.0) < 1.5


def _toy(n=512):
    """A result whose efficiency is linear in its first parameter and ignores the second."""
    t = table_of({"design.cam.preload": {"range": [500.0, 1500.0]},
                  "fluid.density": {"range": [830.0, 880.0]}})
    x = draw(t, n, "sobol", 0)
    eta = (0.8 + 1e-4 * x[:, 0])[:, None]
    inputs = {"parameters": [{"path": p} for p in t.paths], "method": "sobol", "seed": 0,
              "samples": n, "points": [{"ratio": 1.0, "input_speed_rpm": 100.0,
                                        "output_torque": 10.0}], "capacity_points": []}
    return UncertaintyResult(inputs, x, np.ones(n, bool), np.full(n, ""), eta,
                             np.zeros((n, 1), np.int8), np.full((n, 1), 10.0),
                             np.zeros((n, 0)), {"eta": np.array([0.9]), "capacity": []})


def test_linear_toy_gives_the_analytic_band_and_ranks_the_idle_parameter_last():
    r = _toy()
    b = r.band().iloc[0]
    # eta uniform on [0.85, 0.95]: mean 0.9, std 0.1/sqrt(12), quantiles 0.855/0.9/0.945
    assert b["mean"] == pytest.approx(0.9, abs=1e-4)
    assert b["std"] == pytest.approx(0.1 / np.sqrt(12), rel=0.01)
    for q, want in (("q05", 0.855), ("q50", 0.9), ("q95", 0.945)):
        assert b[q] == pytest.approx(want, abs=5e-4)
    rank = r.ranking()
    assert list(rank.index) == ["design.cam.preload", "fluid.density"]
    assert rank["score_eta"].iloc[0] == pytest.approx(1.0)
    assert rank["score_eta"].iloc[1] < 0.05
    srrc = r.sensitivity("srrc")
    assert srrc.loc["R^2"].iloc[0] == pytest.approx(1.0)


def test_save_and_load_round_trip(tmp_path):
    r = _toy(16)
    back = UncertaintyResult.load(r.save(tmp_path / "u.json"))
    np.testing.assert_array_equal(back.values, r.values)
    np.testing.assert_array_equal(back.eta, r.eta)
    assert back.band().equals(r.band()) and back.inputs == r.inputs
    assert "q95" in r.to_csv().splitlines()[0]
    json.loads(r.to_json())


@pytest.fixture(scope="module")
def linear(tmp_path_factory):
    """The hub with a seal constant (a loss on the input shaft, affine in it) and a
    parameter its isothermal law does not read."""
    path = drive_file(tmp_path_factory.mktemp("lin"),
                      '"design.parasitic.seal_k2" = { range = [0.0, 20.0] }\n'
                      '"fluid.thermal_conductivity" = { relative = 0.5 }\n')
    return path, uncertainty(path, samples=64, seed=2, output_torque=(10.0,), **POINT)


def test_a_loss_that_enters_linearly_gives_the_analytic_band(linear):
    path, r = linear
    ends = uncertainty(path, samples=2, seed=2, output_torque=(10.0,), **POINT)
    # 1/eta is affine in K_S2 (it adds the same moment to the input torque): its quantiles
    # are those of the uniform K_S2 mapped through the line through two solved drives
    k, inv = ends.values[:, 0], 1.0 / ends.eta[:, 0]
    slope = (inv[1] - inv[0]) / (k[1] - k[0])
    for q, col in ((0.05, "q95"), (0.5, "q50"), (0.95, "q05")):
        want = 1.0 / (inv[0] + slope * (20.0 * q - k[0]))
        assert r.band().iloc[0][col] == pytest.approx(want, abs=0.02 * abs(slope) * 20.0)
    rank = r.ranking()
    assert rank.index[0] == "design.parasitic.seal_k2"
    assert rank["score_eta"].iloc[0] > 0.99 and rank["score_eta"].iloc[-1] < 0.2


def test_the_same_seed_gives_the_same_numbers(linear):
    path, r = linear
    again = uncertainty(path, samples=64, seed=2, output_torque=(10.0,), **POINT)
    np.testing.assert_array_equal(again.eta, r.eta)
    np.testing.assert_array_equal(again.capacity, r.capacity)
    assert r.inputs["seed"] == 2 and r.version


def test_drives_that_cannot_be_built_are_counted_with_their_reason(tmp_path):
    path = drive_file(tmp_path, '"design.cam.ramp_angle_deg" = { range = [40.0, 70.0] }\n')
    r = uncertainty(path, samples=8, seed=0, output_torque=(10.0,), **POINT)
    c = r.counts()
    assert c["samples"] == 8 and c["cannot_be_built"] == (r.values[:, 0] >= 60).sum() > 0
    assert any("ramp_angle_deg" in k for k in c["reasons"])
    assert r.band().iloc[0]["solved"] <= c["built"]


def test_cli_json_and_files(tmp_path, capsys):
    path = drive_file(tmp_path, '"design.cam.preload" = { relative = 0.5 }\n')
    code = cli.main(["uncertainty", "--design", str(path), "--samples", "4", "--power", "100",
                     "--speed", "114", "--ratio", "1", "--out", str(tmp_path / "o"), "--json"])
    assert code == 0
    data = json.loads(capsys.readouterr().out)
    assert {"inputs", "counts", "band", "ranking", "run_time_s", "ballcvt_version",
            "files"} <= set(data)
    assert data["inputs"]["points"][0]["input_power"] == 100.0
    for name in ("band.csv", "ranking.csv", "uncertainty.json", "uncertainty.png"):
        assert (tmp_path / "o" / name).is_file()


@pytest.mark.parametrize("argv, match", [
    (["--design", "table1"], "no uncertain parameters: add an [uncertainty] table"),
    (["--design", "nosuch.toml"], "not found"),
    (["--samples", "0"], "out of range"),
    (["--power", "100", "--torque", "10"], "not allowed with"),
    (["--ratio", "-1"], "ratio"),
])
def test_cli_bad_input_is_one_line_and_exit_2(argv, match, tmp_path, capsys):
    try:
        code = cli.main(["uncertainty", *argv, "--out", str(tmp_path / "o")])
    except SystemExit as exc:  # argparse's usage errors
        code = exc.code
    assert code == 2
    err = capsys.readouterr().err.strip()
    assert match in err and "\n" not in err


def test_dask_gives_the_in_process_numbers(linear):
    from ballcvt.analysis.studies.run import local_client

    path, r = linear
    client = local_client(1)
    try:
        on = uncertainty(path, samples=8, seed=2, output_torque=(10.0,), client=client,
                         **POINT)
    finally:
        cluster = client.cluster
        client.close()
        cluster.close()
    np.testing.assert_array_equal(on.eta, uncertainty(path, samples=8, seed=2,
                                                      output_torque=(10.0,), **POINT).eta)
    assert on.execution.startswith("Dask client")


def test_every_cli_flag_reaches_the_computation(tmp_path, monkeypatch, capsys):
    import ballcvt.api
    from ballcvt.interfaces.cli import uncertainty as command

    calls = []

    def fake(design, **kw):
        calls.append({"design": design, **kw})
        return _toy(8)

    monkeypatch.setattr(ballcvt.api, "uncertainty", fake)
    monkeypatch.setattr(command, "check_scheduler", lambda address: None)
    base = ["uncertainty", "--out", str(tmp_path / "a"), "--json"]
    variants = {
        "--design": ["--design", "table1"], "--samples": ["--samples", "9"],
        "--seed": ["--seed", "3"], "--method": ["--method", "lhs"],
        "--ratio": ["--ratio", "0.5", "1.8"], "--power": ["--power", "50", "200"],
        "--torque": ["--torque", "20"], "--speed": ["--speed", "114"],
        "--arch": ["--arch", "single"], "--workers": ["--workers", "2"],
        "--scheduler": ["--scheduler", "tcp://127.0.0.1:8786"],
        "--oil-temperature": ["--oil-temperature", "40"],
    }
    parser = cli.build_parser()
    sub = next(a for a in parser._subparsers._group_actions[0].choices.items()
               if a[0] == "uncertainty")[1]
    flags = {s for a in sub._actions for s in a.option_strings if s.startswith("--")}
    assert flags - {"--help"} == set(variants) | {"--out", "--json", "--quiet"}
    assert cli.main(base) == 0
    reference = calls[-1]
    for flag, extra in variants.items():
        assert cli.main(base + extra) == 0, flag
        assert calls[-1] != reference, flag
    capsys.readouterr()
    assert cli.main(["uncertainty", "--out", str(tmp_path / "b"), "--quiet"]) == 0
    assert capsys.readouterr().out == "" and (tmp_path / "b" / "band.csv").is_file()
    assert cli.main(["uncertainty", "--out", str(tmp_path / "c")]) == 0
    assert "most influential" in capsys.readouterr().out


def test_real_hub_page_script_writes_its_page(tmp_path):
    import runpy
    from pathlib import Path

    script = Path(__file__).resolve().parents[1] / "docs" / "scripts" / "real_hub.py"
    page = runpy.run_path(str(script))["page"]
    # the hub with its oil fixed (its capacities under the balance cost ~25 s a sample):
    # the page then compares with the balance at its nine points
    drive = tmp_path / "hub_fixed_oil.toml"
    drive.write_text(HUB.replace('oil_temperature = "balance"', 'oil_temperature = "fixed"'))
    text = page(str(drive), 4, 0, tmp_path).read_text()
    assert "The same points with `--oil-temperature balance`" in text
    for heading in ("## Models used", "## Efficiency", "## Loss breakdown",
                    "## Film parameter lambda", "## Uncertainty band", "## Assumptions"):
        assert heading in text
    assert "`models.clamp_law` = `cam`" in text and "`design.cam.preload`" in text
    assert (tmp_path / "real-hub-efficiency.png").is_file()
    assert (tmp_path / "real-hub-band.png").is_file()


def test_the_oil_model_asked_for_reaches_every_drawn_drive(tmp_path):
    """`oil_temperature=` overrides the drive file's oil model for every sample (the
    hub's file names the balance): a given temperature runs each drive at it."""
    path = drive_file(tmp_path, '"design.cam.preload" = { relative = 0.5 }\n')
    balanced = path.with_name("balanced.toml")
    balanced.write_text(path.read_text().replace(
        'oil_temperature = "fixed"', 'oil_temperature = "balance"'))
    at40 = uncertainty(balanced, samples=2, seed=1, output_torque=(10.0,),
                       oil_temperature=313.15, **POINT)
    fixed = uncertainty(path, samples=2, seed=1, output_torque=(10.0,), **POINT)
    np.testing.assert_allclose(at40.eta, fixed.eta, rtol=1e-12)
    np.testing.assert_allclose(at40.capacity, fixed.capacity, rtol=1e-12)
