"""The traction integrals' derivatives at high pressure (session 35, harden task 3402:113).

The slope of Eq. 53's saturation factor, ``dS/da``, was computed as ``((1 - S) - a S) /
a``: for large ``a`` a difference of two terms near 1, with a rounding error of ``1e-16 a``
relative. In a contact at 3-4 GPa ``a`` reaches 1e10 and more over most of the ellipse,
and the creep derivatives of ``mu`` came out as noise (up to 100 % at a creep of 1e-3).
The paper's law only uses them in Newton's Jacobians; the thermal law's coefficients
use them too (the film temperature's Newton step), so its residual carried that noise
(5.7e-9 at 3.5 GPa, above its 1e-9 floor): Newton stalled, the continuation from zero
torque failed short of the fold, and a planetary mode's capacity came out at 106.8 N m
where `solve` carried 145.5 N m. Now ``(exp(-a) - S) / a``.
"""

import json

import numpy as np
import pytest

from ballcvt import TractionLimitError, Variator, load_builtin
from ballcvt.api import SolveSettings, with_oil_temperature
from ballcvt.equilibrium.problem import OperatingInputs, make_problem
from ballcvt.equilibrium.residual import evaluate
from ballcvt.model.rheology import saturation_factor, saturation_slope
from ballcvt.model.traction.contact import ContactState
from ballcvt.model.traction.isothermal import shear_coefficients
from ballcvt.model.traction.quadrature import Quadrature
from ballcvt.solvers.newton import solve_batch


def test_the_saturation_slope_at_large_arguments_is_its_analytic_limit():
    # dS/da = -(1 - (1 + a) e^-a) / a^2: for a >= 40, e^-a < 5e-18 and a^2 dS/da = -1
    a = np.logspace(np.log10(40.0), 14, 60)
    np.testing.assert_allclose(a * a * saturation_slope(a), -1.0, rtol=1e-13)
    # and below, against the closed form (no cancellation there: the terms are O(1))
    b = np.linspace(0.5, 30.0, 60)
    exact = -(1.0 - (1.0 + b) * np.exp(-b)) / (b * b)
    np.testing.assert_allclose(saturation_slope(b, saturation_factor(b)), exact, rtol=1e-13)


def _contact(creep):
    """One idler-like contact of harden task 3402:113: 3.8 GPa, strong spin."""
    one = lambda v: np.array([v])  # noqa: E731
    return ContactState(one(creep), one(0.317318), one(0.001633), one(0.003014),
                        one(3.79736e9), one(39142.21), one(0.05625), one(1.420072),
                        one(6.555373e-8))  # fmt: skip


@pytest.mark.parametrize("engine", ["auto", "numpy"])
@pytest.mark.parametrize("creep", [1e-4, 1e-3])
def test_derivatives_at_high_pressure_are_smooth_in_the_creep(engine, creep):
    fluid = Variator().fluid
    q = Quadrature(engine=engine)
    rows = []
    for e in np.linspace(0.0, 1e-15, 4):  # steps of ~1e-19: the derivatives cannot move
        mu, chi, dmu, dchi = shear_coefficients(_contact(creep * (1 + e)), fluid, q, True)
        rows.append(np.r_[dmu[0], dchi[0]])
    rows = np.array(rows)
    spread = (rows.max(axis=0) - rows.min(axis=0)) / np.abs(rows).max(axis=0)
    assert spread.max() < 1e-11  # was up to 1.27 (d mu / d log u at 1e-3)


def test_the_thermal_residual_is_smooth_at_high_pressure():
    v = Variator(traction_law="thermal")
    pb = make_problem(v, OperatingInputs(np.linspace(0.6, 1.8, 5), 300.0, 20000.0, 209.44))
    assert np.max(pb.p_max) > 3.4e9
    sol = solve_batch(pb, v.options)
    assert sol.converged.all()
    x = sol.state.creep
    r0 = evaluate(pb, x, v.options.quadrature).residual
    rng = np.random.default_rng(0)
    for _ in range(10):
        r = evaluate(pb, x * (1 + 1e-15 * rng.standard_normal(x.shape)), v.options.quadrature)
        assert np.max(np.abs(r.residual - r0)) < 1e-13  # was 5.7e-9


FIELDS_3402 = json.loads("""{"aspect_ratio": 0.9983348935512835, "roller_radius": 0.0563435951432665, "theta0_deg": 55.12342743174357, "theta2_deg": 49.747385183648774, "alpha_deg": 13.057964262154862, "n_rollers": 3, "roller_bearing_diameter": 0.010512262443558048, "idler_bearing_diameter": 0.006113566239845695, "disc_groove_ratio": 4.127801506407027, "idler_groove_ratio": 3.5213587617928144, "single_idler_groove_ratio": 4.245118834923883, "tilt_safety_factor": 0.5055746442723617, "creep_limit": 0.08023933542630658, "min_roller_gap": 0.0005754240703321165, "cam": {"disc": "output", "preload": 1461.9254868014145, "ramp_angle_deg": 4.608185738450271, "mean_radius": 0.18533056268484116, "friction": 0.04629765928493589}, "parasitic": null}""")  # noqa: E501


def test_a_thermal_mode_capacity_covers_every_load_solve_carries():
    """Harden task 3402:113: the capacity was 106.8 N m (a continuation step stalled in
    the noise at 106.9 N m and the bisection took it for the fold); `solve` carried
    145.5 N m with every creep within the limit, unflagged."""
    design, fluid = load_builtin("table1")
    design = design.replace(name="random", **FIELDS_3402)
    v = with_oil_temperature(Variator(design, fluid, "single", traction_law="thermal"), "fixed")
    point = {"clamp_force": 30913.44069696699, "input_speed_rpm": 51.32586075976362}
    mode, ratio = "disc0_held_disc2_drives", 2.7768700471046768
    limit = v.limit_torque(ratio, mode=mode, **point)
    assert limit > 145.5
    r = v.solve(ratio, -145.48522215725586, settings=SolveSettings(mode=mode), **point)
    assert 0.0 < r.eta < 1.0
    with pytest.raises(TractionLimitError):
        v.solve(ratio, -limit * 1.01, settings=SolveSettings(mode=mode), **point)
