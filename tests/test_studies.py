"""Design studies (issue 11): Dask equals in-process, the Pareto front, resume, errors."""

import json
from pathlib import Path

import numpy as np
import pytest

from ballcvt.status import Status
from hypothesis import given
from hypothesis import strategies as st

from ballcvt import InputError
from ballcvt.analysis.studies import run as run_module
from ballcvt.analysis.studies.pareto import pareto_mask
from ballcvt.analysis.studies.run import local_client, run_study
from ballcvt.analysis.studies.spec import parse_study, read_study
from ballcvt.interfaces.cli import main as cli
from ballcvt.params.io import load_drive

DATA = Path(__file__).parent / "data"
TINY = DATA / "study_tiny.toml"
ROOT = Path(__file__).resolve().parents[1]


def same(a, b):
    for name in a.data_vars:
        x, y = a[name].values, b[name].values
        if x.dtype.kind == "f":
            np.testing.assert_array_equal(x, y, err_msg=name)   # bitwise, NaN where NaN
        else:
            assert np.array_equal(x, y), name


@pytest.fixture(scope="module")
def tiny(tmp_path_factory):
    return run_study(read_study(TINY), tmp_path_factory.mktemp("tiny"), in_process=True,
                     progress=False)


def test_two_worker_cluster_equals_in_process(tiny, tmp_path):
    client = local_client(2)
    try:
        remote = run_study(read_study(TINY), tmp_path, client=client, progress=False)
    finally:
        cluster = client.cluster
        client.close()
        cluster.close()
    same(tiny.dataset, remote.dataset)
    assert remote.chosen == tiny.chosen


def test_study_outcome(tiny):
    ds = tiny.dataset
    assert ds.sizes["design"] == 8 and sorted(ds["design"].values) == list(range(8))
    counts = tiny.counts()
    assert sum(counts[k] for k in ("evaluated", "cannot be built", "constraint violated",
                                   "not solved")) == 8
    assert counts["evaluated"] >= 3 and counts["cannot be built"] >= 1   # 9 balls do not fit
    ok = ds["status"].values == 0
    assert np.all(np.isfinite(ds["eta_mean"].values[ok]))
    assert np.all(np.isnan(ds["eta_mean"].values[~ok]))
    assert np.all(ds["outer_diameter"].values[ok] <= 0.23)
    # the chosen design is a drive every command loads
    design, _ = load_drive(tiny.files[[p.name for p in tiny.files].index("chosen_design.toml")])
    assert design == tiny.chosen_design


def test_front_has_no_dominated_and_no_infeasible_design(tiny):
    ds = tiny.dataset
    front = ds["pareto"].values
    ok = ds["status"].values == 0
    assert front.any() and not np.any(front & ~ok)
    cost = np.column_stack([-ds["eta_mean"].values, -ds["capacity"].values])
    for i in np.flatnonzero(front):
        dominated = np.all(cost[ok] <= cost[i], axis=1) & np.any(cost[ok] < cost[i], axis=1)
        assert not dominated.any()
    for i in np.flatnonzero(ok & ~front):                 # the rest is dominated by the front
        assert np.any(np.all(cost[front] <= cost[i], axis=1)
                      & np.any(cost[front] < cost[i], axis=1))
    assert ds["chosen"].values.sum() == 1 and front[ds["chosen"].values].all()


@given(st.lists(st.tuples(st.floats(-10, 10), st.floats(-10, 10), st.booleans()),
                min_size=1, max_size=30))
def test_pareto_mask_invariants(rows):
    v = np.array([[a, b] for a, b, _ in rows])
    feasible = np.array([f for *_, f in rows])
    front = pareto_mask(v, ["max", "min"], feasible)
    cost = v * np.array([-1.0, 1.0])
    assert not np.any(front & ~feasible)
    for i in range(len(rows)):
        if feasible[i]:
            dom = (np.all(cost[feasible] <= cost[i], axis=1)
                   & np.any(cost[feasible] < cost[i], axis=1)).any()
            assert front[i] == (not dom)


def test_resume_after_interruption_evaluates_no_design_twice(tiny, tmp_path, monkeypatch):
    calls = []
    real = run_module.evaluate_chunk

    def interrupted(ctx, index, x):
        if len(calls) == 2:
            raise KeyboardInterrupt
        calls.append(list(index))
        return real(ctx, index, x)

    monkeypatch.setattr(run_module, "evaluate_chunk", interrupted)
    with pytest.raises(KeyboardInterrupt):
        run_study(read_study(TINY), tmp_path, in_process=True, progress=False)
    monkeypatch.setattr(run_module, "evaluate_chunk",
                        lambda ctx, index, x: calls.append(list(index)) or real(ctx, index, x))
    with pytest.raises(InputError, match="--resume"):
        run_study(read_study(TINY), tmp_path, in_process=True, progress=False)
    resumed = run_study(read_study(TINY), tmp_path, in_process=True, resume=True,
                        progress=False)
    done = [i for chunk in calls for i in chunk]
    assert sorted(done) == list(range(8)) and resumed.evaluated_now == 4
    same(tiny.dataset, resumed.dataset)
    again = run_study(read_study(TINY), tmp_path, in_process=True, resume=True, progress=False)
    assert again.evaluated_now == 0


def test_nsga2_runs_and_resumes_without_reevaluating(tmp_path):
    text = TINY.read_text().replace('method = "sobol"', 'method = "nsga2"\npopulation = 6\n'
                                    'generations = 2')
    spec = parse_study(text, base=DATA)
    first = run_study(spec, tmp_path, in_process=True, progress=False)
    ds = first.dataset
    assert first.evaluated_now == ds.sizes["design"] >= 6
    assert ds["pareto"].values.any()
    keys = {tuple(np.round(r, 12)) for r in np.column_stack(
        [ds[n].values for n in spec.names])}
    assert len(keys) == ds.sizes["design"]                # no design evaluated twice
    again = run_study(spec, tmp_path, in_process=True, resume=True, progress=False)
    assert again.evaluated_now == 0


@pytest.mark.parametrize("change, match", [
    (("[objectives]", "[objectives]\nspeed = \"max\""), "objectives.speed"),
    (("roller_radius = {", "roler_radius = {"), "roler_radius: not a design field"),
    (("min = 0.024, max = 0.032", "min = 0.04, max = 0.032"), "max = 0.032"),
    (("samples = 8", "samples = 0"), "study.samples"),
    (("clamp_force = 2000.0", ""), "needs clamp_force"),
    (("[study]", "[studdy]"), "unknown key 'studdy'"),
    (("chunk = 2", "chunk = \"two\""), "study.chunk"),
])
def test_malformed_study_file_gets_one_line(tmp_path, capsys, change, match):
    path = tmp_path / "bad.toml"
    path.write_text(TINY.read_text().replace(*change))
    with pytest.raises(InputError, match=match):
        read_study(path)
    assert cli.main(["explore", str(path), "--out", str(tmp_path / "o"), "--in-process"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and match.split(":")[0].split("'")[0] in err


def test_explore_cli_writes_everything(tmp_path, capsys):
    out = tmp_path / "study"
    assert cli.main(["explore", str(TINY), "--out", str(out), "--in-process", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["designs"] == 8 and summary["chosen"] is not None
    for name in ("designs.zarr", "designs.csv", "pareto.csv", "chosen_design.toml",
                 "summary.json", "study_pareto.png", "study_parameters.png", "study_maps.png",
                 "report.md", "report.html"):
        assert (out / name).exists(), name
    assert cli.main(["point", "--design", str(out / "chosen_design.toml"), "--json"]) == 0
    capsys.readouterr()
    assert cli.main(["explore", str(TINY), "--out", str(out), "--in-process"]) == 2
    assert "--resume" in capsys.readouterr().err


def test_quick_example_is_valid():
    spec = read_study(ROOT / "examples" / "studies" / "study_quick.toml")
    assert spec.study.samples == 32 and set(spec.objectives) == {"eta_mean",
                                                                 "torque_per_volume"}


@pytest.mark.parametrize("path", sorted((ROOT / "examples" / "studies").glob("*.toml")))
def test_example_studies_parse_and_their_first_design_evaluates(path):
    from ballcvt.analysis.studies.evaluate import evaluate_chunk, make_context
    from ballcvt.analysis.studies.run import design_vectors
    spec = read_study(path)
    ctx = make_context(spec)
    n = 2
    if spec.study.method == "nsga2":
        spec = spec.model_copy(update={"study": spec.study.model_copy(
            update={"method": "sobol", "samples": n})})
    got = evaluate_chunk(ctx, np.arange(n), design_vectors(spec, n))
    assert got["status"].shape == (n,) and set(got["status"]) <= {Status.CONVERGED, Status.CANNOT_BE_BUILT,
                                                          Status.CONSTRAINT_VIOLATED}  # none "not solved"


def test_cycle_study_constrains_pressure_and_film(tmp_path):
    """A duty-cycle study computes the peak pressure and film ratio over its steps, so
    its pressure and film constraints accept some designs and reject others."""
    from ballcvt.analysis.studies.evaluate import evaluate_chunk, make_context
    from ballcvt.analysis.studies.run import design_vectors
    (tmp_path / "c.csv").write_text("time [s],output_speed [rpm],output_torque [N m]\n"
                                    "0,1500,10\n1,2000,20\n2,2000,0\n3,1800,15\n")
    (tmp_path / "s.toml").write_text(
        '[study]\nname = "cycle-limits"\nmethod = "sobol"\nsamples = 4\nseed = 3\n'
        'capacity_ratios = [1.0]\n[parameters]\n'
        'roller_radius = { min = 0.024, max = 0.032 }\n'
        'theta0_deg = { min = 40.0, max = 50.0 }\n'
        '[operating]\ncycle = "c.csv"\nclamp_force = 2000.0\n'
        'target_input_speed_rpm = 2000.0\n[objectives]\ncycle_efficiency = "max"\n'
        '[constraints]\nmax_pressure_max = 1.7e9\nmin_lambda_min = 3.6\n')
    spec = read_study(tmp_path / "s.toml")
    got = evaluate_chunk(make_context(spec), np.arange(4), design_vectors(spec, 4))
    assert np.all(np.isfinite(got["max_pressure"])) and np.all(np.isfinite(got["min_lambda"]))
    ok = got["status"] == Status.CONVERGED
    assert 0 < ok.sum() < 4
    assert np.all(got["max_pressure"][ok] <= 1.7e9) and np.all(got["min_lambda"][ok] >= 3.6)
    reasons = " ".join(got["reason"])
    assert "max_pressure" in reasons and "min_lambda" in reasons


def test_cycle_study_refuses_eta_min_min(tmp_path):
    text = TINY.read_text().replace('ratio = [1.0]\noutput_torque = [20.0, 40.0]\n'
                                    'input_speed_rpm = [2000.0]\n',
                                    'cycle = "c.csv"\ntarget_input_speed_rpm = 2000.0\n')
    text = text.replace('eta_mean = "max"', 'cycle_efficiency = "max"')
    text += "eta_min_min = 0.5\n"
    with pytest.raises(InputError, match="eta_min_min"):
        parse_study(text)
