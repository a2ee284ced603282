"""Under the thermal law every solve ends near the residual's noise (session 35).

A solve stops anywhere below its tolerance (the law's floor, 1e-9); the direct Newton of
a sweep and the continuation from zero torque of `solve` then differed by up to 2.2e-8 in
efficiency, and `solve` at a limit 2e-4 below its fold by 7.8e-8 from the solution.
Both paths now run on towards a hundredth of the tolerance (`POLISH_SHARE`).
"""

from dataclasses import replace

import numpy as np
import pytest

from ballcvt import Variator
from ballcvt.equilibrium.problem import OperatingInputs, make_problem
from ballcvt.performance.efficiency import efficiency
from ballcvt.solvers.newton import _solve_flat

RATIOS = np.linspace(0.5, 2.0, 7)
TORQUES = np.linspace(5.0, 70.0, 6)
POINT = {"clamp_force": 2000.0, "input_speed_rpm": 2000.0}


@pytest.fixture(scope="module")
def swept():
    v = Variator(traction_law="thermal")
    ds = v.sweep(ratio=RATIOS, output_torque=TORQUES, **POINT, progress=False)
    return v, ds


def _exact(v, ratio, torque, creep):
    """The efficiency of the equilibrium near ``creep`` solved to 1e-14 [-]."""
    pb = make_problem(v, OperatingInputs(np.array([ratio]), torque, 2000.0, 2000 * np.pi / 30))
    tight = replace(v.options, tol=1e-14, max_iterations=40)
    sol = _solve_flat(pb.flat(), np.array([creep], dtype=float), tight, False, False)
    assert sol.residual_norm[0] < 1e-12
    return float(efficiency(pb.flat(), sol.state).overall[0])


def test_a_sweep_and_solve_agree_to_the_residual_noise(swept):
    v, ds = swept
    eta = ds["eta"].values.reshape(RATIOS.size, TORQUES.size)
    checked = 0
    for i in range(0, RATIOS.size, 2):
        for j in range(0, TORQUES.size, 2):
            if np.isfinite(eta[i, j]):
                alone = v.solve(RATIOS[i], TORQUES[j], **POINT).eta
                assert alone == pytest.approx(eta[i, j], abs=2e-9)  # was 2.2e-8 apart
                checked += 1
    assert checked >= 8


def test_the_efficiency_at_the_limit_is_the_solution_there(swept):
    v, ds = swept
    limit = ds["limit_torque"].values.ravel()
    at_limit = ds["eta_at_limit"].values.ravel()
    for i in range(RATIOS.size):
        r = v.solve(RATIOS[i], limit[i], **POINT)
        creep = [c.creep for c in r.contacts.values()]
        exact = _exact(v, RATIOS[i], limit[i], creep)
        assert r.eta == pytest.approx(exact, abs=2e-9)  # was up to 7.8e-8 off
        assert at_limit[i] == pytest.approx(exact, abs=2e-9)
