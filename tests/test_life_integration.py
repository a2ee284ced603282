"""Fatigue life as a user meets it (docs/life.md): `Variator.life`, ``ballcvt life`` for both
architectures and every clamping law, Miner's rule over a duty cycle, life on a map and in
a study, and the bearing ratings of the design."""

import json
import math
from pathlib import Path

import numpy as np
import pytest

from ballcvt import InputError, Variator, load_builtin
from ballcvt.analysis.cycle_files import cycle_from_arrays, read_cycle
from ballcvt.api import LifeResult, MapGrid, SolveSettings, read_study
from ballcvt.interfaces.cli import main as cli
from drives import fixed_oil_hub

RPM = math.pi / 30
HUB = ("--design", "hub", "--oil-temperature", "fixed", "--ratio", "1.5", "--torque", "30", "--speed", "180")


@pytest.fixture(scope="module")
def hub():
    return Variator(*fixed_oil_hub())


def _life_json(capsys, *args):
    code = cli.main(["life", *args, "--json"])
    out = capsys.readouterr()
    assert code == 0, out.err
    return json.loads(out.out)


@pytest.mark.parametrize("arch", ["double", "single"])
@pytest.mark.parametrize("law", ["constant", "cam", "optimal"])
def test_cli_life_every_architecture_and_clamp_law(capsys, arch, law):
    got = _life_json(capsys, *HUB, "--arch", arch, "--clamp-law", law)
    assert {"l10_hours", "limiting_element", "elements", "model", "notes"} <= set(got)
    assert math.isfinite(got["l10_hours"]) and got["l10_hours"] > 0
    assert got["limiting_element"] in got["elements"]
    tracks = [k for k, e in got["elements"].items() if e["kind"] == "track"]
    assert {"input_disc", "output_disc", "ball_input", "ball_output"} <= set(tracks)
    for e in got["elements"].values():
        assert e["l10_hours"] > 0 and e["l10_cycles"] > 0
    # the system is every element in series: shorter than the shortest
    shortest = min(e["l10_hours"] for e in got["elements"].values() if e["l10_hours"])
    assert got["l10_hours"] <= shortest * (1 + 1e-12)


def test_life_models_and_the_text_table(hub, capsys):
    lives = {m: hub.life(1.0, 40.0, clamp_force=2000.0, input_speed_rpm=2000, life_model=m)
             for m in ("lundberg-palmgren", "zaretsky", "iso-fatigue-limit")}
    for m, r in lives.items():
        assert isinstance(r, LifeResult) and r.model == m and r.l10_hours > 0
    assert cli.main(["life", *HUB]) == 0
    assert "system L10" in capsys.readouterr().out


def test_drive_without_ratings_leaves_bearings_out_with_a_note():
    r = Variator().life(1.0, 40.0, clamp_force=2000.0, input_speed_rpm=2000)
    assert not any(e.kind == "bearing" for e in r.elements.values())
    assert len(r.notes) == 3 and all("left out" in n for n in r.notes)
    assert math.isfinite(r.l10_hours) and r.limiting_element.startswith(("idler", "ball"))


def test_single_idler_bearing_carries_no_load(hub):
    single = Variator(hub.design, hub.fluid, "single")
    r = single.life(1.5, 30.0, clamp_law="cam", input_speed_rpm=180)
    assert "idler_bearing" not in r.elements and any("no load" in n for n in r.notes)


def test_planetary_point_counts_speeds_relative_to_the_carrier(hub):
    from ballcvt import Design
    from ballcvt.api import OperatingMode
    mode = OperatingMode("disc0", "carrier", True, True, 0.0)
    plain = Design(**{**hub.design.model_dump(), "parasitic": None})  # no shaft drags (§13)
    hub = Variator(plain, hub.fluid)
    p = hub.solve(0.8, 20.0, clamp_force=2000.0, input_speed_rpm=600,
                  settings=SolveSettings(mode=mode))
    r = hub.life(0.8, 20.0, clamp_force=2000.0, input_speed_rpm=600,
                 settings=SolveSettings(mode=mode))
    assert r.point["ratio"] == p.relative.ratio and r.l10_hours > 0


def test_ratings_are_optional_design_fields():
    table1, _ = load_builtin("table1")
    hub, _ = fixed_oil_hub()
    assert "roller_bearing_rating" not in table1.bearings.model_dump()
    assert hub.bearings.roller_bearing_rating > 0
    with pytest.raises(InputError, match="roller_bearing_rating"):
        table1.bearings.replace(roller_bearing_rating=-1.0)


def test_miner_over_a_cycle_is_the_sum_of_the_step_damages(hub):
    base = read_cycle("tests/data/tiny_cycle.csv")
    t = np.arange(0.0, 40.0)
    w2 = np.where(t < 25, 190.0, np.where(t < 30, 0.0, 150.0)) * RPM
    t2 = np.where(t < 25, 12.0, np.where(t < 30, 0.0, -5.0))
    t2[10:20] = 25.0
    cycle = cycle_from_arrays(time=t, output_speed=w2, output_torque=t2,
                              vehicle_speed=w2 * 0.35, name="commute bit")
    assert base.vehicle_speed is None and base.distance is None
    from ballcvt.api import CycleSettings
    res = hub.cycle_life(cycle, clamp_law="cam",
                         settings=CycleSettings(target_input_speed_rpm=180, progress=False))
    steps, life = res.steps, res.summary["life"]
    ran = steps.status == 0
    hand = sum(dt / (3600.0 * h) for dt, h in zip(steps.duration[ran], steps.l10_hours[ran]))
    assert life["damage_per_pass"] == pytest.approx(hand, rel=1e-12)
    assert np.nansum(steps.damage) == pytest.approx(hand, rel=1e-12)
    assert life["l10_hours"] == pytest.approx(cycle.durations.sum() / 3600.0 / hand, rel=1e-12)
    assert life["l10_km"] == pytest.approx(life["l10_passes"] * cycle.distance / 1e3)
    assert life["steps_not_counted"] == 10  # braking
    assert (steps.damage[steps.flag == "idle"] == 0).all()
    assert life["limiting_element"] in life["elements"]
    # each element's Miner life is at least the system's
    assert all(e["l10_hours"] >= life["l10_hours"] for e in life["elements"].values())


def test_cli_life_and_cycle_on_a_cycle(tmp_path, capsys):
    cyc = tmp_path / "c.csv"
    cyc.write_text("time [s],output_speed [rpm],output_torque [N m],vehicle_speed [km/h]\n"
                   "0,190,12,25\n1,190,14,25\n2,190,20,25\n")
    got = _life_json(capsys, "--design", "hub", "--oil-temperature", "fixed", "--clamp-law", "cam", "--cycle", str(cyc),
                     "--target-speed", "180")
    assert got["l10_hours"] > 0 and got["l10_km"] > 0 and got["limiting_element"]
    out = tmp_path / "out"
    assert cli.main(["cycle", str(cyc), "--design", "hub", "--oil-temperature", "fixed", "--clamp-law", "cam",
                     "--target-speed", "180", "--life", "--out", str(out), "--quiet"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["life"]["damage_per_pass"] > 0 and "energy_in_J" in summary
    header = (out / "steps.csv").read_text().splitlines()[0]
    assert "l10_hours [h]" in header and "damage [1]" in header


@pytest.mark.parametrize("argv", [["--life-model", "nope"], ["--cycle", "missing.csv"],
                                  ["--ratio", "50"]])
def test_cli_life_errors_are_one_line_exit_2(capsys, argv):
    try:
        code = cli.main(["life", *argv])
    except SystemExit as exc:  # argparse's usage error
        code = exc.code
    assert code == 2
    err = capsys.readouterr().err.strip()
    assert err and len(err.splitlines()) == 1


def test_map_life_contours(hub, tmp_path):
    ds = hub.efficiency_map(MapGrid((0.7, 1.6), 4, 120.0, 4), input_speed_rpm=180,
                            clamp_law="cam", progress=False)
    ds = hub.map_life(ds)
    ok = ds.status.values == 0
    assert ok.any() and np.all(np.isfinite(ds.l10_hours.values[ok]))
    assert np.all(ds.l10_hours.values[ok] > 0) and np.all(np.isnan(ds.l10_hours.values[~ok]))
    # more torque, shorter life
    one = ds.l10_hours.squeeze(drop=True).transpose("ratio", "output_torque").values
    assert np.all(np.diff(one, axis=1)[np.isfinite(np.diff(one, axis=1))] < 0)
    out = tmp_path / "m"
    assert cli.main(["map", "--design", "hub", "--oil-temperature", "fixed", "--clamp-law", "cam", "--speed", "180",
                     "--life", "--n-ratio", "3", "--n-torque", "4", "--out", str(out),
                     "--quiet"]) == 0
    assert "l10_hours" in (out / "map.csv").read_text().splitlines()[0]


def test_study_life_objective_and_constraint(tmp_path):
    from ballcvt.analysis.studies.evaluate import evaluate_chunk, make_context
    from ballcvt.analysis.studies.run import design_vectors
    text = open("tests/data/study_tiny.toml").read()
    text = text.replace('capacity = "max"', 'capacity = "max"\nl10_hours = "max"')
    text = text.replace("outer_diameter_max = 0.23",
                        "outer_diameter_max = 0.23\nmin_l10_hours = 1e9")
    path = tmp_path / "s.toml"
    path.write_text(text)
    spec = read_study(path)
    got = evaluate_chunk(make_context(spec), np.arange(3), design_vectors(spec, 3))
    built = got["status"] != 4  # cannot be built
    assert np.all(got["l10_hours"][built] > 0)
    assert all("l10_hours" in r for r in got["reason"][built])  # 1e9 h: none meets it


def test_a_iso_multiplies_the_rated_bearings_only(hub):
    from ballcvt.model.life import a_iso
    point = dict(clamp_law="cam", input_speed_rpm=180)
    plain = hub.life(1.5, 30.0, **point)
    b = hub.design.bearings.replace(contamination_factor=0.5, viscosity_ratio=1.0,
                                    disc_bearing_fatigue_limit=None)
    v = Variator(hub.design.replace(bearings=b), hub.fluid)
    got = v.life(1.5, 30.0, **point)
    for name, e in got.elements.items():
        before = plain.elements[name]
        if name.startswith(("roller_bearing", "idler_bearing")):
            limit = (b.roller_bearing_fatigue_limit if name.startswith("roller")
                     else b.idler_bearing_fatigue_limit)
            factor = float(a_iso(0.5 * limit / e.load, 1.0))
            assert e.l10_cycles == pytest.approx(before.l10_cycles * factor, rel=1e-12)
        else:  # tracks, and the disc bearing without its C_u
            assert e.l10_cycles == before.l10_cycles
    # from the fluid: the traction fluid is far thinner than the bearings' rated viscosity
    thin = hub.design.bearings.replace(contamination_factor=0.5)
    got = Variator(hub.design.replace(bearings=thin), hub.fluid).life(1.5, 30.0, **point)
    assert any("below 0.1" in n for n in got.notes) and got.l10_hours < plain.l10_hours


def test_rated_viscosity_iso_281():
    from ballcvt.analysis.life.elements import rated_viscosity
    # ISO 281 Fig. 13 / SKF: d_m = 100 mm at 1000 rpm -> about 14 mm^2/s
    assert rated_viscosity(1000 / 60, 0.1) * 1e6 == pytest.approx(4500 / 1000**0.5 / 10)
    assert rated_viscosity(500 / 60, 0.1) * 1e6 == pytest.approx(45000 * 500**-0.83 / 10)


def test_study_life_over_a_duty_cycle(tmp_path):
    from ballcvt.analysis.studies.evaluate import evaluate_chunk, make_context
    from ballcvt.analysis.studies.run import design_vectors
    cyc = Path(__file__).parent / "data" / "tiny_cycle.csv"
    text = open("tests/data/study_tiny.toml").read()
    start, end = text.index("[operating]"), text.index("[objectives]")
    text = (text[:start] + f'[operating]\ncycle = "{cyc}"\ntarget_input_speed_rpm = 180.0\n'
            'clamp_force = 2000.0\n\n' + text[end:])
    text = text.replace('eta_mean = "max"', 'cycle_efficiency = "max"')
    text = text.replace('capacity = "max"', 'l10_hours = "max"')
    path = tmp_path / "s.toml"
    path.write_text(text)
    spec = read_study(path)
    got = evaluate_chunk(make_context(spec), np.arange(2), design_vectors(spec, 2))
    ok = got["status"] == 0
    assert ok.any() and np.all(got["l10_hours"][ok] > 0)
