"""Extension points (issue 22): traction and clamping laws registered from user code.

The two scripts of examples/extending run in a fresh interpreter; the registries refuse a
duplicate name, list the choices for an unknown one, and a user law reaches `solve`,
`sweep` and `limit_torque`, and is gone once unregistered."""

import importlib.util
import math
import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from ballcvt import Fluid, InputError, Variator, load_builtin
from ballcvt.model.clamping import ClampLaw, ConstantClamp, clamp_law
from ballcvt.model.traction import ContactState, TractionLaw, contact_coefficients
from ballcvt.params.io import fluid_to_toml, parse_fluid
from ballcvt.registry import CLAMP_LAWS, TRACTION_LAWS

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples" / "extending"
NUMBER = re.compile(r"[-+]?\d+\.\d+(?:e[-+]?\d+)?|nan|inf", re.IGNORECASE)


def _load(name):
    """The example module (its law registered), without running its main block."""
    spec = importlib.util.spec_from_file_location(f"_example_{name}", EXAMPLES / f"{name}.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # (its dataclasses look their module up)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("script", ["traction_law.py", "clamp_law.py"])
def test_example_runs_in_a_fresh_interpreter(script):
    got = subprocess.run([sys.executable, str(EXAMPLES / script)], capture_output=True,
                         text=True, timeout=600, cwd=ROOT)
    assert got.returncode == 0, got.stderr
    numbers = [float(x) for x in NUMBER.findall(got.stdout)]
    assert len(numbers) >= 6, got.stdout
    assert all(math.isfinite(x) for x in numbers), got.stdout


@pytest.fixture
def circular():
    module = _load("traction_law")
    yield module
    TRACTION_LAWS.unregister("circular")


@pytest.fixture
def spring():
    module = _load("clamp_law")
    yield module
    CLAMP_LAWS.unregister("spring_torque")


def _fluid(law="circular", **params):
    _, table1 = load_builtin()
    return Fluid(**{**table1.model_dump(), "traction_law": law,
                    "law_parameters": params or {"sharpness": 2.0}})


def test_duplicate_names_are_refused():
    with pytest.raises(InputError, match="not yet registered"):
        TRACTION_LAWS.register(TRACTION_LAWS.get("isothermal"))
    with pytest.raises(InputError, match="not yet registered"):
        CLAMP_LAWS.register(ConstantClamp, name="constant")


def test_unknown_names_list_the_choices():
    with pytest.raises(InputError, match="one of: isothermal, thermal, viscoelastic"):
        Fluid(**{**load_builtin()[1].model_dump(), "traction_law": "eyring"})
    with pytest.raises(InputError, match="one of: constant, cam, optimal"):
        clamp_law("spring", load_builtin()[0])


def test_a_user_traction_law_reaches_solve_sweep_and_limit(circular):
    v = Variator(fluid=_fluid())
    r = v.solve(1.0, 40.0, clamp_force=2000.0, input_speed_rpm=2000.0)
    assert r.traction_law == "circular" and 0.5 < r.eta < 1.0
    lim = v.limit_torque(1.0, clamp_force=2000.0, input_speed_rpm=2000.0)
    assert 50.0 < lim < 400.0
    ds = v.sweep(ratio=[1.0], output_torque=[40.0], clamp_force=2000.0,
                 input_speed_rpm=2000.0, progress=False)
    assert float(ds.eta.squeeze()) == pytest.approx(r.eta, abs=1e-6)
    assert ds.attrs["traction_law"] == "circular"


def test_a_user_law_is_newtonian_at_small_creep_saturates_at_large_and_has_derivatives(
        circular):
    """The circular law meets Eq. 53 at both ends (Newtonian slope, limiting shear stress)
    and its analytic derivatives (Newton's Jacobians) match finite differences."""
    _, table1 = load_builtin()
    x = (1.2e-3, 0.45e-3, 1.5e9, 2000.0, 0.03)
    ends = ContactState(np.array([1e-9, 0.5]), 0.0, *x, 15.0, 1.5e-7)
    mu_c, _ = contact_coefficients(ends, _fluid())
    mu_i, _ = contact_coefficients(ends, table1)
    assert mu_c == pytest.approx(mu_i, rel=2e-3)
    c, s, u = 0.004, 0.1, 15.0
    _, _, dmu, dchi = contact_coefficients(ContactState(c, s, *x, u, 1.5e-7), _fluid(),
                                           derivatives=True)
    for k, (dc, ds, du) in enumerate([(1e-7, 0, 0), (0, 1e-6, 0), (0, 0, 1e-6)]):
        hi = contact_coefficients(ContactState(c + dc, s + ds, *x, u * np.exp(du), 1.5e-7),
                                  _fluid())
        lo = contact_coefficients(ContactState(c - dc, s - ds, *x, u * np.exp(-du), 1.5e-7),
                                  _fluid())
        step = 2 * (dc + ds + du)
        assert dmu[k] == pytest.approx((hi[0] - lo[0]) / step, rel=1e-3, abs=1e-9)
        assert dchi[k] == pytest.approx((hi[1] - lo[1]) / step, rel=1e-3, abs=1e-9)


def test_law_parameters_are_required_and_survive_toml(circular, tmp_path):
    with pytest.raises(InputError, match="law_parameters.sharpness"):
        _fluid(other=1.0)
    fluid = _fluid(sharpness=3.0)
    back = parse_fluid(fluid_to_toml(fluid))
    assert back == fluid and hash(back) == hash(fluid)
    assert "law_parameters" not in load_builtin()[1].model_dump()


def test_unregister_removes_the_law():
    law = TractionLaw("tmp_law", TRACTION_LAWS.get("isothermal").coefficients)
    TRACTION_LAWS.register(law)
    assert "tmp_law" in TRACTION_LAWS
    TRACTION_LAWS.unregister("tmp_law")
    assert "tmp_law" not in TRACTION_LAWS
    with pytest.raises(InputError, match="one of"):
        TRACTION_LAWS.unregister("tmp_law")


def test_a_user_clamp_law_reaches_solve_sweep_and_limit(spring):
    v = Variator()
    law = spring.SpringTorqueClamp(preload=800.0, gain=25.0)
    for given in ("spring_torque", law):
        r = v.solve(1.0, 40.0, clamp_law=given, input_speed_rpm=2000.0)
        assert r.clamp_force == pytest.approx(800.0 + 25.0 * 40.0)
        assert r.clamp_law == "spring_torque"
    lim = v.limit_torque(1.0, clamp_law=law, input_speed_rpm=2000.0)
    assert lim > 40.0
    ds = v.sweep(ratio=[1.0], output_torque=[20.0, 40.0], clamp_law="spring_torque",
                 input_speed_rpm=2000.0, progress=False)
    assert np.allclose(ds.clamp_force.squeeze(), [1300.0, 1800.0])
    assert ds.attrs["clamp_law"] == "spring_torque"
    with pytest.raises(InputError, match="not given with clamp_law"):
        v.solve(1.0, 40.0, clamp_law="spring_torque", clamp_force=1.0, input_speed_rpm=2000.0)


def test_clamp_law_properties_replace_names():
    assert ConstantClamp.fixed_force and not ConstantClamp.optimises
    assert CLAMP_LAWS.get("optimal").optimises and not CLAMP_LAWS.get("optimal").fixed_force
    assert not CLAMP_LAWS.get("cam").fixed_force and issubclass(CLAMP_LAWS.get("cam"), ClampLaw)
