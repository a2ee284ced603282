"""Issue 26 item 1: the faster thermal law (compiled film-temperature solve, the film
column of Newton's Jacobian) gives the answers it gave before.

The stored values were computed on main at 202cf3f (before the change) by the same calls
as the tests make, in a checkout of that commit:

    PYTHONPATH=src python -c "from tests.test_law_speed import _efficiency;
        print(repr(_efficiency('thermal', 'constant', 0.8, 40.0)))"

(`_efficiency`: ``Variator(traction_law=law).solve(ratio=..., output_torque=...,
input_speed_rpm=2000)`` at 2000 N or the cam; the hub drive at 2000 N), and
``thermal_law_coefficients(STATE, fluid)``, ``temperature_rise(STATE, fluid)``;
tolerance 1e-8 on the efficiencies, 1e-9 relative on the coefficients. Since the thermal
law's solves stop at its residual floor (`THERMAL_RESIDUAL_FLOOR`, 1e-9 of the torque scale
``n F_N0 r_S``, ~480 N m here, instead of 1e-11), its efficiencies are compared to 1e-7:
four balances each off by up to 1e-9 of the scale move an efficiency at 20-60 N m by up
to ~1e-7.
"""

from __future__ import annotations

import numpy as np
import pytest

import ballcvt
from ballcvt.api import with_oil_temperature
from ballcvt import load_builtin
from ballcvt.model.traction.contact import ContactState
from ballcvt.model.traction.quadrature import Quadrature
from ballcvt.model.traction.thermal import (
    temperature_rise,
    thermal_law_coefficients,
    thermal_law_film_coefficients,
)
from drives import fixed_oil_hub

BEFORE = {
    ("isothermal", "constant", 0.8, 40.0): 0.8632021072826955,
    ("isothermal", "cam", 1.5, 60.0): 0.9110476303116669,
    ("viscoelastic", "constant", 1.76, 20.0): 0.8163953885109277,
    ("viscoelastic", "cam", 0.8, 40.0): 0.9052743236377692,
    ("thermal", "constant", 0.8, 40.0): 0.8720244266581315,
    ("thermal", "constant", 1.5, 60.0): 0.921763309986895,
    ("thermal", "constant", 1.76, 20.0): 0.8371855503203212,
    ("thermal", "cam", 1.76, 20.0): 0.9362533836218152,
    ("hub", "drive", 1.5, 60.0): 0.8870565286232844,
}
#: Three contacts under Table I's fluid with the thermal law, and their coefficients and
#: rises on main at 202cf3f (`thermal_law_coefficients`, `temperature_rise`).
STATE = ContactState(
    np.array([0.004, 0.01, -0.002]),
    np.array([0.2, -0.3, 0.1]),
    np.full(3, 1.5e-3),
    np.full(3, 1e-3),
    np.full(3, 1.8e9),
    np.full(3, 1500.0),
    np.full(3, 0.02),
    np.full(3, 15.0),
    np.full(3, 2.5e-7),
)
MU = [0.14111516288862175, 0.21323730105372787, -0.14354511136439568]
CHI = [0.010973129449306333, -0.008725762321706155, 0.010942842202858445]
RISE = [9.101367478608514, 15.66910662194601, 4.55672420662208]


def _efficiency(law, clamp, ratio, torque):
    if law == "hub":
        # the hub's mixed lubrication at the fluid's fixed 40 C, as stored (the drive's
        # own oil balance is another model: tests/test_oil_paths.py)
        v = with_oil_temperature(ballcvt.Variator(*fixed_oil_hub()), "fixed")
        force = {"clamp_force": 2000.0}
    else:
        v = ballcvt.Variator(traction_law=law)
        force = {"clamp_law": "cam"} if clamp == "cam" else {"clamp_force": 2000.0}
    got = v.solve(ratio=ratio, output_torque=torque, input_speed_rpm=2000, **force)
    return float(got.eta)


@pytest.mark.parametrize("key", sorted(BEFORE), ids=lambda k: "-".join(map(str, k)))
def test_efficiency_unchanged(key):
    tol = 1e-7 if key[0] == "thermal" else 1e-8
    assert _efficiency(*key) == pytest.approx(BEFORE[key], abs=tol)


def _fluid():
    return ballcvt.Variator(traction_law="thermal").fluid


def test_thermal_coefficients_unchanged():
    mu, chi = thermal_law_coefficients(STATE, _fluid())
    np.testing.assert_allclose(mu, MU, rtol=1e-9)
    np.testing.assert_allclose(chi, CHI, rtol=1e-9)
    np.testing.assert_allclose(temperature_rise(STATE, _fluid()), RISE, rtol=1e-9)


def test_compiled_thermal_matches_numpy_path():
    fluid = _fluid()
    fast = thermal_law_coefficients(STATE, fluid, Quadrature(), True)
    slow = thermal_law_coefficients(STATE, fluid, Quadrature(engine="numpy"), True)
    for a, b in zip(fast, slow):
        np.testing.assert_allclose(a, b, rtol=1e-7, atol=1e-12)


def test_film_column_is_the_derivative_at_fixed_u_over_h():
    fluid, e = _fluid(), 1e-6
    mu, chi, dmu, dchi = thermal_law_film_coefficients(STATE, fluid)
    assert dmu.shape == (3, 4)
    three = thermal_law_coefficients(STATE, fluid, derivatives=True)
    np.testing.assert_array_equal(dmu[:, :3], three[2])

    def at(k):
        return np.array(
            thermal_law_coefficients(
                STATE._replace(u_ref=STATE.u_ref * np.exp(k), film=STATE.film * np.exp(k)),
                fluid,
            )
        )

    diff = (at(e) - at(-e)) / (2 * e)
    np.testing.assert_allclose(dmu[:, 3], diff[0], rtol=2e-3)
    np.testing.assert_allclose(dchi[:, 3], diff[1], rtol=2e-3)
