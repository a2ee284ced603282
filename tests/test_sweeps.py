"""Sweeps (xarray), export, the clamp optimiser and the quick end-to-end reproduction."""

import numpy as np
import pytest

from ballcvt import InputError
from ballcvt.reports import reproduce
from ballcvt.reports.figures import FIGURES
from ballcvt.analysis.sweeps.export import load_dataset, to_csv, to_netcdf
from ballcvt.analysis.sweeps.variables import VARIABLES
from ballcvt.interfaces.cli.main import main

OP = {"clamp_force": 2000.0, "input_speed_rpm": 2000.0}


@pytest.fixture(scope="module")
def small(double):
    return double.sweep(ratio=[0.5, 1.0, 2.0], output_torque=[0.0, 40.0, 100.0, 150.0],
                        architecture=("double", "single"), progress=False, **OP)


def test_dataset_dims_units_and_flags(small):
    assert dict(small.sizes) == {"architecture": 2, "clamp_force": 1, "input_speed_rpm": 1,
                                 "ratio": 3, "output_torque": 4, "contact": 5, "loss": 10, "subtotal": 2}
    # the speed coordinate is in the units the user passed, exactly as passed
    assert small.input_speed_rpm.values.tolist() == [2000.0]
    assert small.sel(input_speed_rpm=2000).input_speed.attrs["units"] == "rad/s"
    for name in list(small.data_vars) + ["ratio", "output_torque", "clamp_force",
                                         "input_speed_rpm", "input_speed"]:
        if name in ("status", "warnings"):      # CF flag variables: meanings, no units
            assert small[name].attrs["flag_meanings"], name
        else:
            assert small[name].attrs["units"] and small[name].attrs["long_name"], name
    assert list(small.status.attrs["flag_values"]) == [0, 1, 2]
    assert list(small.warnings.attrs["flag_masks"]) == [1, 2, 4, 8]
    status = small.status.sel(architecture="double").squeeze(drop=True)
    limit = small.limit_torque.sel(architecture="double").squeeze(drop=True)
    beyond = small.output_torque > limit                    # 100 and 150 N m at ratio 2
    assert (status.where(beyond) == 1).sum() == beyond.sum() > 0
    assert small.eta.sel(architecture="double").squeeze(drop=True).where(beyond).isnull().all()
    assert (status.where(~beyond) == 0).sum() == (~beyond).sum()   # nothing dropped
    # contacts a single idler does not have are NaN, not zero
    assert small.creep.sel(architecture="single", contact="idler_a").isnull().all()


def test_sweep_names_match_results(double, small):
    """The same quantity has the same name in a result and in a sweep."""
    r = double.solve(ratio=1.0, output_torque=40.0, **OP)
    point = small.sel(architecture="double", ratio=1.0, output_torque=40.0).squeeze(drop=True)
    for name in ("eta", "eta_loss", "eta_speed", "eta_torque", "input_torque", "actual_ratio",
                 "tilt_deg"):
        assert float(point[name]) == pytest.approx(getattr(r, name), rel=1e-6, abs=1e-9), name
    for kind, value in r.losses.items():
        assert float(point.losses.sel(loss=kind)) == pytest.approx(value, rel=1e-6), kind
    for name in ("creep", "spin", "mu", "chi", "p_max", "film_thickness", "normal_load",
                 "creep_loss", "spin_loss", "lambda_ratio"):
        got = float(point[name].sel(contact="output"))
        assert got == pytest.approx(getattr(r.contacts["output"], name), rel=1e-5), name


def test_netcdf_and_csv_round_trip(small, tmp_path):
    import pandas as pd

    from ballcvt import Design, Fluid
    from ballcvt.analysis.sweeps.export import parameters
    path = to_netcdf(small, tmp_path / "s.nc")
    assert path.read_bytes()[:4] == b"\x89HDF"                 # NetCDF-4 (HDF5)
    back = load_dataset(path)
    assert np.allclose(back.eta.values, small.eta.values, equal_nan=True)
    assert back.eta.attrs["units"] == "1" and back.attrs["ballcvt_version"]
    assert back.attrs["Conventions"].startswith("CF-")
    assert list(back.status.attrs["flag_values"]) == [0, 1, 2]
    assert back.status.attrs["flag_meanings"] == "converged beyond_limit not_converged"
    design = Design(**parameters(back, "design"))
    assert design == Design(**parameters(small, "design")) and design.n_rollers == 8
    assert Fluid(**parameters(back, "fluid")).viscosity == 3.25e-3
    frame = pd.read_csv(to_csv(small, tmp_path / "s.csv"))      # no options needed
    assert len(frame) == 2 * 3 * 4
    assert "output_torque [N m]" in frame and "eta [1]" in frame and "status" in frame
    assert "creep_output [1]" in frame and "loss_total [W]" in frame
    assert "p_max_idler_a [Pa]" in frame


def test_limit_torque_monotone_in_clamp(double):
    ds = double.sweep(ratio=[0.7, 1.5], output_torque=0.0,
                      clamp_force=[800.0, 1400.0, 2000.0, 2600.0], input_speed_rpm=2000.0,
                      progress=False)
    lim = ds.limit_torque.squeeze(drop=True).transpose("ratio", "clamp_force").values
    assert np.all(np.diff(lim, axis=1) > 0)


def test_variables_are_documented():
    for name, (units, long_name) in VARIABLES.items():
        assert units and long_name, name


def test_optimal_clamp_beats_every_fixed_clamp(double):
    torque = 60.0
    opt = double.optimal_clamp_force(1.0, torque, input_speed_rpm=2000.0)
    assert opt.max_creep <= double.design.creep_limit
    assert opt.max_pressure <= double.design.max_pressure
    for f in (800.0, 1000.0, 1500.0, 2000.0, 3000.0):
        r = double.solve(ratio=1.0, output_torque=torque, clamp_force=f, input_speed_rpm=2000)
        assert opt.eta >= r.eta - 1e-9, f


@pytest.fixture(scope="module")
def quick(tmp_path_factory):
    out = tmp_path_factory.mktemp("repro")
    return reproduce(out, quick=True, progress=False)


def test_quick_reproduction_writes_everything(quick):
    out = quick.out
    for name in FIGURES:
        for ext in ("png", "svg", "csv"):
            assert (out / f"{name}.{ext}").stat().st_size > 0, (name, ext)
    for name in ("torque_curves", "clamp_curves", "ratio_curves", "efficiency_map"):
        assert (out / "data" / f"{name}.nc").exists()
    md = (out / "report.md").read_text()
    page = (out / "report.html").read_text()
    assert len(quick.claims) == 22
    for c in quick.claims:
        assert c.claim.replace("|", "\\|") in md                 # escaped in the table
        assert c.verdict in ("agrees", "differs")
    planet = ("planet_ratio", "planet_efficiency", "planet_circulation", "planet_capacity")
    assert page.count("<img") == len(FIGURES) + len(planet)
    assert "data:image/png;base64," in page
    assert "Limiting torque." in md and "Single-idler pressure." in md
    # beyond the paper, after its part: the planetary section with its figures and data
    assert md.index("## Beyond the paper: planetary modes") > md.index("## Figures")
    for name in planet:
        assert (out / f"{name}.png").stat().st_size > 0
    for name in ("planet_kinematics", "planet_curves", "planet_capacity", "planet_effects"):
        assert (out / f"{name}.csv").stat().st_size > 0


def test_envelope_never_below_a_clamp_curve(quick, tmp_path):
    import pandas as pd
    env = pd.read_csv(quick.out / "fig08c_envelope.csv")
    curves = pd.read_csv(quick.out / "fig08.csv")
    for _, row in env.iterrows():
        at = curves[np.isclose(curves["output_torque [N m]"], row["output_torque [N m]"])]
        if len(at):
            assert row["eta [1]"] >= at["eta [1]"].max() - 1e-9


def test_reproduced_fig11_numbers(quick):
    rows = {c.claim: c for c in quick.claims}
    assert float(rows["eta at tau_ID = 0.5, T_2 = 40 N m"].ours) == pytest.approx(0.82, abs=0.01)
    assert float(rows["maximum eta, T_2 = 40 N m"].ours) == pytest.approx(0.89, abs=0.01)
    assert float(rows["ratio of the maximum"].ours) == pytest.approx(1.76, abs=0.1)
    assert rows["Eq. 38 = Eq. 39"].verdict == "agrees"


def test_cli_map_clamp_and_errors(tmp_path, capsys):
    assert main(["map", "--out", str(tmp_path), "--n-ratio", "3", "--n-torque", "3",
                 "--quiet"]) == 0
    assert (tmp_path / "map.png").exists() and (tmp_path / "map.nc").exists()
    assert main(["clamp", "--torque", "40", "--json"]) == 0
    assert '"clamp_force"' in capsys.readouterr().out
    with pytest.raises(SystemExit) as exc:                   # an argparse usage error
        main(["map", "--n-torque", "1"])
    assert exc.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--n-torque" in err[0]
    assert main(["clamp", "--torque", "-5"]) == 2


def test_two_workers_give_the_same_sweep(double, small):
    two = double.sweep(ratio=[0.5, 1.0, 2.0], output_torque=[0.0, 40.0, 100.0, 150.0],
                       architecture=("double", "single"), progress=False, workers=2, **OP)
    assert np.array_equal(two.status.values, small.status.values)
    assert np.allclose(two.eta.values, small.eta.values, rtol=0, atol=1e-12, equal_nan=True)


def test_limit_torque_flag_is_refused_not_read_as_zero(double):
    with pytest.raises(InputError, match="limit_torque = False"):
        double.sweep(ratio=[1.0], output_torque=[30.0], clamp_force=2000.0,
                     input_speed_rpm=2000, limit_torque=False)


def test_a_map_with_too_few_solved_points_is_refused_in_one_line(tmp_path):
    """Two torques above the limit leave no solved point to contour: one line, exit 2
    (it was "internal error: ValueError: x and y arrays must have a length of at least 3")."""
    from ballcvt.interfaces.cli.main import main

    code = main(["map", "--n-ratio", "2", "--n-torque", "2", "--torque-max", "1e4",
                 "--out", str(tmp_path / "m"), "--quiet"])
    assert code == 2
