"""Traction laws (docs/model.md §14): limits, analytic slope, trends, fitting, the CLI."""

import json

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ballcvt import InputError, Variator, load_builtin
from ballcvt.analysis.fitting import Curves, fit_fluid, model_mu, read_curves
from ballcvt.interfaces.cli import main as cli
from ballcvt import _compat
from ballcvt._compat import BallCVTDeprecationWarning
from ballcvt.model.traction import base as laws
from ballcvt.model.traction.base import THERMAL_RESIDUAL_FLOOR
from ballcvt.model.traction import isothermal, thermal
from ballcvt.model.traction.contact import ContactState, contact_coefficients
from ballcvt.model.traction.curve import traction_curve
from ballcvt.model.traction.isothermal import shear_coefficients
from ballcvt.model.traction.quadrature import Quadrature
from ballcvt.model.traction.thermal import FLASH_FACTOR, temperature_rise, thermal_law_coefficients
from ballcvt.params.io import load_builtin_fluid, load_fluid
from ballcvt.params.models import LAW_FIELDS, Fluid

DESIGN, FLUID = load_builtin()
E_RED = DESIGN.material.reduced_modulus
#: A twin-disc contact: R_x 20 mm, R_y 50 mm, 1.6 GPa.
DISC = {"rx": 0.02, "ry": 0.05, "p_max": 1.6e9, "reduced_modulus": E_RED}


def _of_state(function):
    """``function(ContactState(*nine arrays), *rest)``: the tests keep the nine arrays."""
    return lambda *args, **kw: function(ContactState(*args[:9]), *args[9:], **kw)


traction_coefficients = _of_state(contact_coefficients)
thermal_coefficients = _of_state(thermal_law_coefficients)
film_temperature_rise = _of_state(temperature_rise)


def law(name, **changes):
    return Fluid(**{**FLUID.model_dump(), "traction_law": name, **changes})


def curve(fluid, creep, speed=10.0, spin=0.0, **kw):
    return traction_curve(fluid, speed=speed, creep=creep, spin=spin, **{**DISC, **kw})


# ------------------------------------------------------------------ the fluid and its law

def test_default_law_is_the_papers_and_dispatch_is_the_integrals():
    assert FLUID.traction_law == "isothermal"
    args = (np.array([0.001, 0.01, 0.05]), 0.3, 4.9e-4, 8.7e-4, 1.6e9, 1422.0, 0.03, 10.0,
            2.5e-7)
    np.testing.assert_array_equal(contact_coefficients(ContactState(*args), FLUID)[0],
                                  shear_coefficients(ContactState(*args), FLUID)[0])


def test_old_twelve_argument_functions_warn_and_agree():
    """The old signatures (nine arrays, then the fluid) answer with one deprecation
    warning and the same numbers (issue 22)."""
    args = (np.array([0.001, 0.01]), 0.3, 4.9e-4, 8.7e-4, 1.6e9, 1422.0, 0.03, 10.0, 2.5e-7)
    hot = law("thermal")
    for old, fluid, new in (
        (laws.law_coefficients, FLUID, contact_coefficients),
        (isothermal.traction_coefficients, FLUID, contact_coefficients),
        (thermal.thermal_coefficients, hot, thermal_law_coefficients),
        (thermal.film_temperature_rise, hot, temperature_rise),
    ):
        _compat._warned.clear()  # warn_renamed warns once per process
        with pytest.warns(BallCVTDeprecationWarning, match="ContactState"):
            got = old(*args, fluid)
        want = new(ContactState(*args), fluid)
        for a, b in zip(np.atleast_2d(got), np.atleast_2d(want)):
            np.testing.assert_array_equal(a, b)
    _compat._warned.clear()
    with pytest.warns(BallCVTDeprecationWarning, match="TRACTION_LAWS"):
        assert laws.MONOTONE["thermal"] is False
        assert laws.LAWS["isothermal"] is shear_coefficients


def test_fluid_without_law_parameters_loads_for_isothermal_only(capsys, tmp_path):
    bare = {k: v for k, v in FLUID.model_dump().items() if k not in LAW_FIELDS["thermal"]
            and k not in LAW_FIELDS["viscoelastic"]}
    fluid = Fluid(**bare)                                  # the paper's law needs none
    assert fluid.traction_law == "isothermal"
    for name, fields in (("thermal", LAW_FIELDS["thermal"]), ("viscoelastic",
                                                               ("shear_modulus",))):
        with pytest.raises(InputError, match=f"no {fields[0]} .* the {name} traction law"):
            Fluid(**{**bare, "traction_law": name})
        with pytest.raises(InputError, match=fields[0]):
            Variator(fluid=fluid, traction_law=name)
    path = tmp_path / "bare.toml"
    path.write_text("[fluid]\n" + "".join(
        f"{k} = {json.dumps(v)}\n" for k, v in bare.items()))
    assert load_fluid(path) == fluid
    assert cli.main(["point", "--fluid", str(path), "--traction-law", "thermal"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "temperature_viscosity_coefficient" in err


def test_second_fluid_is_cited_and_complete():
    oil = load_builtin_fluid("mineral-oil")
    assert "Stachowiak" in oil.name and oil.viscosity == 0.034
    for name in ("thermal", "viscoelastic"):
        Fluid(**{**oil.model_dump(), "traction_law": name})
    # Z_1 derived from alpha = 20.5e-9 1/Pa with Roelands' pole values (the file says so)
    assert oil.roelands_index == pytest.approx(
        20.5e-9 * oil.pole_pressure / np.log(oil.viscosity / oil.pole_viscosity), abs=1e-3)


# ----------------------------------------------------------------------- the thermal law

def test_thermal_traction_falls_with_rolling_speed():
    """Measured traction of traction fluids falls with speed at fixed creep (Loewenthal
    and Rohn, NASA TP-2154, 1983); the isothermal law rises."""
    speeds = [5.0, 10.0, 20.0, 40.0]
    for creep in (0.01, 0.03):
        hot = [curve(law("thermal"), [creep], speed=u).mu[0] for u in speeds]
        iso = [curve(FLUID, [creep], speed=u).mu[0] for u in speeds]
        assert np.all(np.diff(hot) < 0), hot
        assert np.all(np.diff(iso) > 0), iso


def test_thermal_tends_to_isothermal_as_heating_vanishes():
    creep = np.linspace(0.0, 0.08, 9)
    iso = curve(FLUID, creep, spin=0.2)
    cold = curve(law("thermal", thermal_conductivity=1e12, surface_conductivity=1e12), creep,
                 spin=0.2)
    np.testing.assert_allclose(cold.mu, iso.mu, atol=1e-9)
    np.testing.assert_allclose(cold.chi, iso.chi, atol=1e-9)
    assert np.all(cold.temperature_rise < 1e-6)
    inert = curve(law("thermal", temperature_viscosity_coefficient=0.0,
                      limiting_shear_temperature_coefficient=0.0), creep, spin=0.2)
    np.testing.assert_allclose(inert.mu, iso.mu, rtol=1e-12, atol=1e-15)
    # and it heats: the rise grows with the creep
    hot = curve(law("thermal"), creep, spin=0.2)
    assert np.all(np.diff(hot.temperature_rise) > 0)


def test_film_temperature_is_the_fixed_point_on_the_requested_rule():
    fluid = law("thermal")
    c = np.array([0.002, 0.02, 0.06])
    ax, ay, pm, fn, rc, u, h = 4.9e-4, 8.7e-4, 1.6e9, 1422.0, 0.02, 20.0, 2.5e-7
    dt = film_temperature_rise(c, 0.1, ax, ay, pm, fn, rc, u, h, fluid)
    mu, chi = thermal_coefficients(c, 0.1, ax, ay, pm, fn, rc, u, h, fluid)
    r = (FLASH_FACTOR * np.sqrt(fluid.surface_diffusivity * ax / u)
         / (2 * fluid.surface_conductivity) + h / (8 * fluid.thermal_conductivity))
    q = fn * u * (c * mu + 0.1 * chi) / (np.pi * ax * ay)                  # Eq. 14.2
    np.testing.assert_allclose(dt, r * q, rtol=1e-4)
    # the coefficients are those of the isothermal law at the film temperature
    bl = fluid.limiting_shear_temperature_coefficient
    b = fluid.temperature_viscosity_coefficient - bl
    mu_iso, _ = traction_coefficients(c, 0.1, ax, ay, pm, fn, rc, u, h * np.exp(b * dt),
                                      FLUID)
    np.testing.assert_allclose(mu, np.exp(-bl * dt) * mu_iso, rtol=1e-5)


def test_thermal_derivatives_match_finite_differences():
    fluid = law("thermal")
    x = dict(ax=4.9e-4, ay=8.7e-4, p_max=1.6e9, load=1422.0, radius=0.03, film=2.5e-7)
    c, s, u = 0.01, 0.2, 10.0

    def coeffs(c, s, u, **kw):
        return thermal_coefficients(c, s, x["ax"], x["ay"], x["p_max"], x["load"],
                                    x["radius"], u, x["film"], fluid, **kw)

    _, _, dmu, dchi = coeffs(c, s, u, derivatives=True)
    e = 1e-6
    for i, (dc, ds, du) in enumerate([(e, 0, 0), (0, e, 0), (0, 0, e)]):
        hi, lo = coeffs(c + dc, s + ds, u * np.exp(du)), coeffs(c - dc, s - ds, u * np.exp(-du))
        # 1 % : the rise's own derivative is taken on the cheap rule (a Jacobian, not a
        # gradient: docs/model.md §14)
        assert dmu[i] == pytest.approx((hi[0] - lo[0]) / (2 * e), rel=0.01, abs=1e-6)
        assert dchi[i] == pytest.approx((hi[1] - lo[1]) / (2 * e), rel=0.01, abs=1e-6)


@given(creep=st.floats(1e-4, 0.1), speed=st.floats(1.0, 50.0), load=st.floats(300.0, 3000.0))
def test_heating_never_raises_traction(creep, speed, load):
    hot = curve(law("thermal"), [creep], speed=speed, p_max=None, load=load)
    cold = curve(FLUID, [creep], speed=speed, p_max=None, load=load)
    assert 0 < hot.mu[0] <= cold.mu[0] + 1e-12
    assert hot.temperature_rise[0] > 0


def test_thermal_solves_in_the_drive_and_batches_agree(double):
    v = Variator(traction_law="thermal")
    r = v.solve(ratio=1.2, output_torque=30.0, clamp_force=2000.0, input_speed_rpm=2000)
    assert r.traction_law == "thermal" and json.loads(r.to_json())["traction_law"] == "thermal"
    iso = double.solve(ratio=1.2, output_torque=30.0, clamp_force=2000.0,
                       input_speed_rpm=2000)
    assert r.eta != pytest.approx(iso.eta, abs=1e-4)
    # Eq. 38 (powers) equals Eq. 39 (losses) under the new law too, to the order of the
    # residual tolerance, raised to the law's residual floor
    agree = 10 * THERMAL_RESIDUAL_FLOOR
    assert r.eta_loss == pytest.approx(r.eta, abs=agree)
    ds = v.sweep(ratio=[1.2], output_torque=[30.0], clamp_force=2000.0,
                 input_speed_rpm=2000)
    assert float(ds.eta.squeeze()) == pytest.approx(r.eta, abs=agree)
    assert ds.attrs["traction_law"] == "thermal"
    assert v.limit_torque(ratio=1.0, clamp_force=2000.0, input_speed_rpm=2000) < \
        double.limit_torque(ratio=1.0, clamp_force=2000.0, input_speed_rpm=2000)


# ------------------------------------------------------------------ the visco-elastic law

def test_viscoelastic_initial_slope_is_analytic():
    """Eq. 14.1: with G t << eta everywhere the film is elastic, dmu/dc = (8/3) G a_x^2
    a_y / (h F_N) at zero creep and spin."""
    g = 1e-2
    c = curve(law("viscoelastic", shear_modulus=g), [1e-6])
    k = c.conditions
    slope = 8.0 / 3.0 * g * k["ax"] ** 2 * k["ay"] / (k["film"] * k["load"])
    assert c.mu[0] / 1e-6 == pytest.approx(slope, rel=1e-3)


def test_viscoelastic_limits_and_kernels():
    creep = np.array([1e-5, 1e-4, 1e-3, 0.01, 0.05])
    iso = curve(FLUID, creep, spin=0.2)
    stiff = curve(law("viscoelastic", shear_modulus=1e30), creep, spin=0.2)
    np.testing.assert_allclose(stiff.mu, iso.mu, rtol=1e-12)          # G -> inf: Eq. 53
    soft, rigid = curve(law("viscoelastic"), creep), curve(FLUID, creep)
    assert np.all(soft.mu <= rigid.mu + 1e-15) and soft.mu[0] < 0.5 * rigid.mu[0]
    # the compiled kernels and the NumPy reference path compute the same sums
    fluid = law("viscoelastic", shear_modulus=2e8)
    args = (np.array([1e-4, 0.003, 0.03, -0.01]), np.array([0.0, 0.3, -0.5, 1.2]), 4.9e-4,
            8.7e-4, 1.6e9, 1422.0, 0.03, 10.0, 2.5e-7)
    fast = traction_coefficients(*args, fluid, derivatives=True)
    ref = traction_coefficients(*args, fluid, Quadrature(engine="numpy"), derivatives=True)
    for a, b in zip(fast, ref):
        np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-14)


def test_viscoelastic_derivatives_match_finite_differences():
    fluid = law("viscoelastic", shear_modulus=2e8)
    x = (4.9e-4, 8.7e-4, 1.6e9, 1422.0, 0.03)
    c, s, u, h = 3e-4, 0.3, 10.0, 2.5e-7
    _, _, dmu, dchi = traction_coefficients(c, s, *x, u, h, fluid, derivatives=True)
    e = 1e-7
    for i, (dc, ds, du) in enumerate([(e, 0, 0), (0, e, 0), (0, 0, e)]):
        hi = traction_coefficients(c + dc, s + ds, *x, u * np.exp(du), h, fluid)
        lo = traction_coefficients(c - dc, s - ds, *x, u * np.exp(-du), h, fluid)
        # 1e-3: the nodes move with the pole, which the derivatives leave out (a Jacobian
        # for Newton, `traction_coefficients`)
        assert dmu[i] == pytest.approx((hi[0] - lo[0]) / (2 * e), rel=1e-3, abs=1e-8)
        assert dchi[i] == pytest.approx((hi[1] - lo[1]) / (2 * e), rel=1e-3, abs=1e-8)


# ---------------------------------------------------------------------------- fitting

def synthetic(fluid, loads, speeds=(5.0, 20.0), spins=(0.0, 0.2), noise=5e-4, seed=3):
    rows = [(f"{f}-{u}-{s}", 0.02, 0.05, f, u, s, c) for f in loads for u in speeds
            for s in spins for c in np.geomspace(2e-4, 0.06, 10)]
    cols = list(zip(*rows))
    curves = Curves(np.array(cols[0]), *(np.array(c, float) for c in cols[1:]),
                    mu=np.zeros(len(rows)))
    mu = model_mu(fluid, curves, E_RED)
    return Curves(**{**curves.__dict__,
                     "mu": mu + np.random.default_rng(seed).normal(0, noise, mu.size)})


@pytest.mark.parametrize("name", ["isothermal", "thermal", "viscoelastic"])
def test_fit_recovers_known_parameters_within_its_standard_errors(name):
    true = law(name, shear_modulus=2e8)
    curves = synthetic(true, loads=(500.0, 1500.0, 3000.0))
    start = law(name, limiting_shear_stress=3e7, limiting_shear_slope=0.06,
                temperature_viscosity_coefficient=0.02, shear_modulus=5e8)
    fit = fit_fluid(curves, start, reduced_modulus=E_RED)
    assert fit.converged and not fit.warnings
    assert fit.rms == pytest.approx(5e-4, rel=0.2)                  # the noise, no bias
    for p in fit.parameters:
        assert abs(fit.estimates[p] - getattr(true, p)) < 3 * fit.standard_errors[p], p
        assert fit.standard_errors[p] < 0.1 * fit.estimates[p], p
    assert fit.fluid.traction_law == name


def test_fit_warns_when_a_parameter_is_not_identifiable():
    curves = synthetic(FLUID, loads=(1400.0,), spins=(0.0,))
    fit = fit_fluid(curves, FLUID.replace(limiting_shear_stress=3e7), reduced_modulus=E_RED)
    assert any("limiting_shear_stress is not identifiable" in w for w in fit.warnings)
    fit = fit_fluid(curves, law("thermal"), ["limiting_shear_slope", "thermal_conductivity"],
                    reduced_modulus=E_RED)
    assert any("thermal_conductivity" in w for w in fit.warnings)


@pytest.mark.parametrize("text, match", [
    ("condition,rx,ry,load,speed,spin,creep\na,0.02,0.05,1000,10,0,0.01\n",
     "column 'mu' is missing"),
    ("condition,rx,ry,load,speed,spin,creep,mu\na,0.02,0.05,heavy,10,0,0.01,0.05\n",
     "row 2: load = 'heavy' is not a finite number"),
    ("condition,rx,ry,load,speed,spin,creep,mu\na,0.02,0.05,-5,10,0,0.01,0.05\n",
     "row 2: load = -5 .* allowed > 0"),
    ("condition,rx,ry,load,speed,spin,creep,mu\n", "no data rows"),
    ("condition,rx,ry,load,speed,spin,creep,mu\na,0.02,0.05,1000,10,0,3,0.05\n",
     "creep = 3 is out of range"),
])
def test_malformed_curves_file_gets_one_line(tmp_path, capsys, text, match):
    path = tmp_path / "curves.csv"
    path.write_text(text)
    with pytest.raises(InputError, match=match):
        read_curves(path)
    assert cli.main(["fit-fluid", str(path), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and str(path) in err


def test_fit_fluid_writes_a_fluid_every_command_loads(tmp_path, capsys):
    from pathlib import Path
    curves = Path(__file__).resolve().parents[1] / "examples" / "traction" / "curves.csv"
    out = tmp_path / "fit"
    assert cli.main(["fit-fluid", str(curves), "--law", "thermal", "--out", str(out),
                     "--params", "limiting_shear_slope,temperature_viscosity_coefficient",
                     "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["traction_law"] == "thermal" and summary["points"] == 96
    for name in ("fluid.toml", "fit.json", "fit.csv", "fit_residuals.png", "fit_residuals.svg"):
        assert (out / name).stat().st_size > 0
    fitted = load_fluid(out / "fluid.toml")
    # the example is the thermal law on Table I's fluid with noise: the fit finds it
    assert fitted.temperature_viscosity_coefficient == pytest.approx(0.03, rel=0.1)
    assert fitted.limiting_shear_slope == pytest.approx(0.085, rel=0.05)
    assert cli.main(["point", "--fluid", str(out / "fluid.toml"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["traction_law"] == "thermal"


def test_traction_curve_cli(tmp_path, capsys):
    argv = ["traction-curve", "--law", "thermal", "--rx", "0.02", "--ry", "0.05", "--load",
            "1400", "--speed", "10", "--creep-max", "0.08", "--n-creep", "9"]
    assert cli.main(argv + ["--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["creep"]) == len(data["mu"]) == len(data["chi"]) == 9
    assert data["creep"][-1] == 0.08 and data["law"] == "thermal"
    assert cli.main(argv + ["--out", str(tmp_path)]) == 0
    assert "mu peaks at" in capsys.readouterr().out
    assert (tmp_path / "traction_curve.png").exists()
    for bad in (["--creep-max", "3"], ["--speed", "-1"], ["--spin", "nan"], ["--spin", "50"]):
        try:
            code = cli.main(argv + bad + ["--json"])
        except SystemExit as exc:                        # refused by the parser
            code = exc.code
        assert code == 2
        assert capsys.readouterr().err.strip().splitlines()[-1].startswith("ballcvt")
