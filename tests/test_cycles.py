"""Duty cycles (docs/cycles.md): reading and validating cycle files, energy bookkeeping,
strategies, flags, and the command line."""

import json
import math

import numpy as np
import pytest

from ballcvt import InputError, Variator, load_builtin
from ballcvt.analysis.cycle_files import cycle_from_arrays, read_cycle
from ballcvt.analysis.cycles import run_cycle
from ballcvt.interfaces.cli import main as cli
from drives import fixed_oil_hub

RPM = math.pi / 30


@pytest.fixture(scope="module")
def hub():
    return Variator(*fixed_oil_hub())


@pytest.fixture(scope="module")
def cruise():
    """Output side: 20 s of steady cruising, a stop, and 5 s of braking."""
    t = np.arange(0.0, 30.0)
    w2 = np.where(t < 20, 190.0, np.where(t < 25, 0.0, 150.0)) * RPM
    t2 = np.where(t < 20, 12.0, np.where(t < 25, 0.0, -5.0))
    return cycle_from_arrays(time=t, output_speed=w2, output_torque=t2, name="cruise")


def test_steady_steps_equal_single_points(hub, cruise):
    res = run_cycle(hub, cruise, target_input_speed=180 * RPM, clamp_law="cam",
                    progress=False)
    row = res.steps.iloc[5]
    r = hub.solve(row["ratio"], 12.0, clamp_law="cam", input_speed=180 * RPM)
    assert row["eta"] == pytest.approx(r.eta, abs=1e-9)
    assert row["input_speed_rpm"] == pytest.approx(180.0)
    # the output turns at the cycle's speed (second pass corrects the creep)
    assert row["output_speed_rpm"] == pytest.approx(190.0, rel=1e-4)
    assert row["loss_total"] == pytest.approx(r.losses["total"], rel=1e-9)


def test_energy_bookkeeping(hub, cruise):
    res = run_cycle(hub, cruise, target_input_speed=180 * RPM, clamp_law="cam",
                    progress=False)
    s = res.summary
    steps = res.steps
    assert s["steps"] == 30
    assert s["flags"]["idle"]["steps"] == 5 and s["flags"]["negative_torque"]["steps"] == 5
    assert s["steps_flagged"] == 5                     # braking only; idle is not a fault
    # energy in - energy out = the losses (Eq. 39 integrated over the cycle)
    assert s["energy_in_J"] - s["energy_out_J"] == pytest.approx(s["losses_J"]["total"],
                                                                 rel=1e-9)
    assert s["efficiency"] == pytest.approx(s["energy_out_J"] / s["energy_in_J"])
    ok = steps["flag"] == "ok"
    dt = steps["duration"]
    assert s["energy_out_J"] == pytest.approx(float((steps["output_power"] * dt)[ok].sum()))
    assert float(dt.sum()) == pytest.approx(29.0)
    assert sum(f["time_s"] for f in s["flags"].values()) == pytest.approx(29.0)


def test_max_efficiency_beats_a_fixed_target(hub, cruise):
    a = run_cycle(hub, cruise, target_input_speed=180 * RPM, clamp_law="cam",
                  progress=False)
    b = run_cycle(hub, cruise, strategy="max-efficiency", clamp_law="cam",
                  ratio_range=(0.5, 2.0), progress=False)
    assert b.summary["efficiency"] >= a.summary["efficiency"] - 1e-9
    # and the chosen ratio is no worse than its neighbours on the candidate grid
    row = b.steps.iloc[3]
    best = hub.solve(row["ratio"], 12.0, clamp_law="cam",
                     input_speed=row["input_speed_rpm"] * RPM).eta
    for r in (0.9 * row["ratio"], 1.1 * row["ratio"]):
        other = hub.solve(r, 12.0, clamp_law="cam", input_speed=190 * RPM / r).eta
        assert best >= other - 1e-6


def test_beyond_capacity_and_ratio_limits_are_flagged(hub):
    c = cycle_from_arrays(time=[0.0, 1.0, 2.0], output_speed=np.array([190, 190, 5]) * RPM,
                          output_torque=[10.0, 5000.0, 10.0])
    res = run_cycle(Variator(), c, target_input_speed=180 * RPM, clamp_force=2000.0,
                    progress=False)
    assert list(res.steps["flag"]) == ["ok", "beyond_capacity", "ratio_limited"]
    assert res.summary["energy_not_delivered_J"] == pytest.approx(190 * RPM * 5000.0 * 1.0)
    assert math.isnan(res.steps["eta"][1])


def test_input_side_cycle_meets_the_power(hub):
    c = cycle_from_arrays(time=[0.0, 1.0, 2.0, 3.0], input_speed=np.full(4, 2000 * RPM),
                          input_power=[3000.0, 5000.0, 8000.0, 300.0],
                          ratio=[0.6, 1.0, 1.8, 1.0])
    res = run_cycle(hub, c, clamp_force=2000.0, progress=False)
    assert np.allclose(res.steps["input_power"][:3], [3000.0, 5000.0, 8000.0], rtol=1e-6)
    assert np.allclose(res.steps["ratio"], [0.6, 1.0, 1.8, 1.0])
    # 300 W cannot even turn the hub's churning, seals and bearings at 2000 rpm
    assert list(res.steps["flag"]) == ["ok", "ok", "ok", "power_below_drag"]


def test_cycle_file_errors(tmp_path):
    good = tmp_path / "c.csv"
    good.write_text("time [s],output_speed [rpm],output_torque [N m]\n0,100,10\n1,120,12\n")
    c = read_cycle(good)
    assert c.kind == "output" and c.output_speed[1] == pytest.approx(120 * RPM)
    cases = {
        "time [s],output_speed [rpm],output_torque [N m]\n0,100,10\n0,120,12\n": "time",
        "time [s],output_speed [rpm],torque [N m]\n0,100,10\n": "unknown column",
        "time [s],output_speed [mph],output_torque [N m]\n0,100,10\n": "unit",
        "time [s],output_speed,output_torque [N m]\n0,100,10\n": "unit",
        "time [s],output_speed [rpm],output_torque [N m]\n0,abc,10\n": "not a number",
        "time [s],output_speed [rpm],output_torque [N m]\n0,-100,10\n": "output_speed",
        "time [s],input_speed [rpm]\n0,100\n": "cycle columns",
        "": "cannot be read",
    }
    for text, fragment in cases.items():
        good.write_text(text)
        with pytest.raises(InputError, match=fragment) as err:
            read_cycle(good)
        assert "\n" not in str(err.value)


def test_strategy_errors(hub, cruise):
    with pytest.raises(InputError, match="target_input_speed"):
        run_cycle(hub, cruise, strategy="target-input-speed", clamp_law="cam", progress=False)
    with pytest.raises(InputError, match="strategy"):
        run_cycle(hub, cruise, strategy="fastest", clamp_law="cam", progress=False)
    with pytest.raises(InputError, match="ratio_range"):
        run_cycle(hub, cruise, strategy="max-efficiency", clamp_law="cam",
                  ratio_range=(2.0, 1.0), progress=False)


def test_cli_cycle(tmp_path, capsys):
    path = tmp_path / "c.csv"
    path.write_text("time [s],output_speed [rpm],output_torque [N m]\n"
                    + "".join(f"{t},190,12\n" for t in range(10)))
    out = tmp_path / "run"
    assert cli.main(["cycle", str(path), "--design", "hub", "--oil-temperature", "fixed", "--clamp-law", "cam",
                     "--target-speed", "180", "--out", str(out), "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    for key in ("energy_in_J", "energy_out_J", "efficiency", "losses_J", "steps",
                "steps_flagged"):
        assert key in s
    assert s["steps"] == 10 and s["steps_flagged"] == 0
    for name in ("steps.csv", "summary.json", "cycle.png", "cycle.svg"):
        assert (out / name).stat().st_size > 0
    import pandas as pd
    frame = pd.read_csv(out / "steps.csv")
    assert "eta [1]" in frame.columns and "loss_total [W]" in frame.columns
    assert cli.main(["cycle", str(path), "--out", str(out), "--strategy",
                     "target-input-speed"]) == 2      # no target speed
    err = capsys.readouterr().err
    assert "--target-speed" in err and len(err.strip().splitlines()) == 1
    assert cli.main(["cycle", str(tmp_path / "none.csv"), "--target-speed", "180",
                     "--out", str(out)]) == 2


def test_workers_give_the_same_results(hub):
    n = 1100                                   # more than one chunk of evaluate_points
    t = np.arange(float(n))
    c = cycle_from_arrays(time=t, output_speed=(150 + 40 * np.sin(t / 30)) * RPM,
                          output_torque=10 + 8 * np.cos(t / 17))
    # the hub as this test was written for (full film); its mixed lubrication below
    full = Variator(hub.design.with_lubrication("full-film"), hub.fluid)
    one = run_cycle(full, c, target_input_speed=180 * RPM, clamp_law="cam", progress=False)
    two = run_cycle(full, c, target_input_speed=180 * RPM, clamp_law="cam", progress=False,
                    workers=2)
    # the same chunks are solved either way: equal to round-off (batch-size dependent sums)
    assert np.allclose(one.steps["eta"], two.steps["eta"], rtol=0, atol=1e-12)
    assert one.summary["energy_in_J"] == pytest.approx(two.summary["energy_in_J"], rel=1e-12)
    # mixed lubrication (docs/model.md §16): the film's law at each contact's own reduced
    # pressure rounds by batch (NumPy's vectorised exp), measured 2.2e-12 in eta here
    one = run_cycle(hub, c, target_input_speed=180 * RPM, clamp_law="cam", progress=False)
    two = run_cycle(hub, c, target_input_speed=180 * RPM, clamp_law="cam", progress=False,
                    workers=2)
    assert np.allclose(one.steps["eta"], two.steps["eta"], rtol=0, atol=1e-11)
    assert one.summary["energy_in_J"] == pytest.approx(two.summary["energy_in_J"], rel=1e-11)


def test_default_strategy_without_a_target_speed(hub, cruise, tmp_path, capsys):
    """No strategy and no target speed: max-efficiency picks the ratio."""
    res = run_cycle(hub, cruise, clamp_law="cam", progress=False)
    assert res.summary["strategy"] == "max-efficiency"
    assert res.summary["steps_flagged"] == 5          # the braking steps only
    path = tmp_path / "c.csv"
    path.write_text("time [s],output_speed [rpm],output_torque [N m]\n0,190,12\n1,190,12\n")
    assert cli.main(["cycle", str(path), "--clamp-law", "cam",
                     "--out", str(tmp_path / "run"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["strategy"] == "max-efficiency"
    # a drive file with an [operating] input speed holds it (docs/drive-files.md)
    assert cli.main(["cycle", str(path), "--design", "hub", "--oil-temperature", "fixed",
                     "--out", str(tmp_path / "run_hub"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["strategy"] == "target-input-speed"
    assert summary["target_input_speed_rpm"] == pytest.approx(150.0)


def test_options_a_strategy_does_not_use_are_refused(hub, cruise, tmp_path, capsys):
    target = 180 * RPM
    with pytest.raises(InputError, match="candidates.*max-efficiency") as err:
        run_cycle(hub, cruise, target_input_speed=target, candidates=15, clamp_law="cam",
                  progress=False)
    assert "\n" not in str(err.value)
    with pytest.raises(InputError, match="target_input_speed.*target-input-speed"):
        run_cycle(hub, cruise, strategy="max-efficiency", target_input_speed=target,
                  clamp_law="cam", progress=False)
    rig = cycle_from_arrays(time=[0.0, 1.0], input_speed=np.full(2, 2000 * RPM),
                            input_power=[3000.0, 5000.0], ratio=[0.6, 1.8])
    for bad in ({"strategy": "max-efficiency"}, {"candidates": 5},
                {"target_input_speed": target}):
        with pytest.raises(InputError, match=next(iter(bad))):
            run_cycle(hub, rig, clamp_force=2000.0, progress=False, **bad)
    path = tmp_path / "c.csv"
    path.write_text("time [s],output_speed [rpm],output_torque [N m]\n0,190,12\n1,190,12\n")
    assert cli.main(["cycle", str(path), "--design", "hub", "--oil-temperature", "fixed", "--target-speed", "180",
                     "--candidates", "15", "--out", str(tmp_path / "run")]) == 2
    err = capsys.readouterr().err
    assert "candidates" in err and "max-efficiency" in err and len(err.strip().splitlines()) == 1


def test_ratio_range_restricts_every_strategy(hub, cruise):
    held = run_cycle(hub, cruise, target_input_speed=180 * RPM, clamp_law="cam",
                     ratio_range=(1.2, 1.5), progress=False)
    run = held.steps[held.steps["flag"] != "idle"]
    assert run["ratio"].dropna().between(1.2, 1.5).all()
    assert (held.steps["flag"] == "ratio_limited").sum() == 20   # 190/180 rpm wants 1.06
    best = run_cycle(hub, cruise, clamp_law="cam", ratio_range=(1.2, 1.5), candidates=5,
                     progress=False)
    assert best.steps["ratio"].dropna().between(1.2, 1.5).all()
    rig = cycle_from_arrays(time=[0.0, 1.0], input_speed=np.full(2, 2000 * RPM),
                            input_power=[3000.0, 5000.0], ratio=[0.6, 1.8])
    res = run_cycle(hub, rig, clamp_force=2000.0, ratio_range=(0.8, 1.5), progress=False)
    assert np.allclose(res.steps["ratio"], [0.8, 1.5])
    assert list(res.steps["flag"]) == ["ratio_limited", "ratio_limited"]


def test_take_keeps_every_column_of_the_steps():
    """`Cycle.take`: the steps asked for, every array column cut alike, the rest kept."""
    c = cycle_from_arrays(time=[0.0, 1.0, 2.0, 3.0], input_speed=np.full(4, 2000 * RPM),
                          input_power=[100.0, 200.0, 300.0, 400.0], ratio=[0.8, 0.9, 1.0, 1.1],
                          vehicle_speed=[1.0, 2.0, 3.0, 4.0], name="ramp")
    one = c.take(slice(2, 3))
    assert (one.kind, one.name, one.size) == (c.kind, "ramp", 1)
    assert one.time.tolist() == [2.0] and one.ratio.tolist() == [1.0]
    assert one.input_power.tolist() == [300.0] and one.vehicle_speed.tolist() == [3.0]
    assert one.output_speed is None and one.output_torque is None


def test_optimal_clamp_cycle_meets_the_speed_and_equals_single_points(hub, cruise):
    """The first pass (coarse rule, the predictor's tolerance: `cycles._coarse`) only
    corrects the ratio for the creep and starts the optimiser: the output still turns at
    the cycle's speed, and a step equals `solve` at its ratio with the optimal clamp."""
    from ballcvt.analysis.cycles import _coarse
    from ballcvt.solvers.options import SolverOptions

    fine = SolverOptions()
    assert _coarse(fine).tol == fine.predictor_tol
    assert _coarse(fine).quadrature == fine.predictor
    res = run_cycle(hub, cruise, target_input_speed=180 * RPM, clamp_law="optimal",
                    progress=False)
    row = res.steps.iloc[5]
    # the creep correction is the coarse rule's: 3.4e-4 off here at the optimal clamp's
    # lower force, with the first pass at 1e-11 (before session 22) as at 1e-6
    assert row["output_speed_rpm"] == pytest.approx(190.0, rel=1e-3)
    r = hub.solve(row["ratio"], 12.0, clamp_law="optimal", input_speed=180 * RPM)
    assert row["eta"] == pytest.approx(r.eta, abs=1e-6)
    assert row["clamp_force"] == pytest.approx(r.clamp_force, rel=1e-3)


def test_a_long_optimal_cycle_seeds_its_first_pass_and_still_equals_single_points(hub):
    """300 distinct steps: the first pass searches every 16th step from the guess and
    starts the others from their nearest seed's optimum (`optimal_batch._seeded`, session
    34); every checked step, seed or not, equals `solve` at its ratio with the optimal
    clamp (the lattice's answer does not depend on where its climb started)."""
    from ballcvt.solvers import optimal_batch

    n = 300
    assert n >= optimal_batch.SEED_MIN
    rng = np.random.default_rng(26)
    t2 = rng.uniform(2.0, 25.0, n)
    w2 = rng.uniform(120.0, 260.0, n) * RPM
    c = cycle_from_arrays(time=np.arange(float(n)), output_speed=w2, output_torque=t2,
                          name="random")  # fmt: skip
    res = run_cycle(hub, c, target_input_speed=180 * RPM, clamp_law="optimal", progress=False)
    assert (res.steps["status"] == 0).all()
    for j in (0, 1, 7, 16, 150, 299):  # seeds 0, 16; the rest started from one
        row = res.steps.iloc[j]
        r = hub.solve(row["ratio"], t2[j], clamp_law="optimal", input_speed=180 * RPM)
        # measured: within 3.6e-11 and 7.9e-6 over every 7th step (session 34)
        assert row["eta"] == pytest.approx(r.eta, abs=1e-9), j
        assert row["clamp_force"] == pytest.approx(r.clamp_force, rel=1e-4), j
