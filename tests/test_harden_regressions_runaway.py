"""Harden task 2032:2993 (issue 23): an input-disc cam whose clamping force runs away.

With the carrier held, a 93 N preload and a 3.1 deg ramp, the drag the clamping force
causes raises the input torque faster than the cam turns torque into force: the fixed point
``F <- law(T_0(F))`` has no balance, its steps grew, and 30 plain iterations crept up to
the Roelands ceiling (~6e7 N), each capacity scan then repeating them through the point
solver. A map of two ratios took more than 600 s (the campaign's timeout). The steps of a
runaway now grow geometrically, the search stops at the force of ``max_pressure`` where
only admissibility is asked, and the refusal says the force finds no balance. The inputs
are the campaign's (``python benchmarks/harden.py --task 2032:2993``).
"""

import json

import numpy as np
import pytest
from drives import fixed_oil_hub

from ballcvt import Variator
from ballcvt.api import SolveSettings
from ballcvt.errors import NoEquilibriumError
from ballcvt.solvers.clamped import MAX_RUNAWAY_GAIN, _wegstein

FIELDS = json.loads(
    '{"aspect_ratio": 4.870931814022875, "roller_radius": 0.012513509549943685, '
    '"theta0_deg": 31.67009590621365, "theta2_deg": 45.15249463684644, '
    '"alpha_deg": 12.621678154677134, "n_rollers": 6, '
    '"roller_bearing_diameter": 0.0033099096320791067, '
    '"idler_bearing_diameter": 0.0020262847378394247, "disc_groove_ratio": 3.4728890549010205, '
    '"idler_groove_ratio": 3.1151616462245406, "single_idler_groove_ratio": Infinity, '
    '"tilt_safety_factor": 0.744392920839346, "creep_limit": 0.17450963800961522, '
    '"min_roller_gap": 0.001447124263828652, "cam": {"disc": "input", '
    '"preload": 92.94410885897173, "ramp_angle_deg": 3.122058015975688, '
    '"mean_radius": 0.019746113063177563, "friction": 0.008598729577470083}}'
)
RATIO = 1.521221639758668
RPM = 1787.1646238876656
MODE = SolveSettings(mode="carrier_held")


@pytest.fixture(scope="module")
def drive() -> Variator:
    d, f = fixed_oil_hub()
    return Variator(d.replace(name="random", **FIELDS), f, "double", traction_law="isothermal")


def test_runaway_is_refused_saying_the_force_finds_no_balance(drive):
    with pytest.raises(NoEquilibriumError) as err:
        drive.solve(RATIO, 0.95, clamp_law="cam", input_speed_rpm=RPM, settings=MODE)
    msg = str(err.value)
    assert "finds no balance" in msg and "max_pressure" in msg
    assert "\n" not in msg
    # the force it names is the force of max_pressure, not the Roelands ceiling (6.4e7 N)
    assert float(err.value.phrases["clamp_force"].split()[1]) < 1e4


def test_runaway_map_flags_every_point(drive):
    from ballcvt.api import MapGrid

    grid = MapGrid(ratio_range=(RATIO, RATIO * 1.001), n_ratio=2, torque_max=2.0, n_torque=3)
    ds = drive.efficiency_map(grid, input_speed_rpm=RPM, clamp_law="cam", mode="carrier_held")
    assert np.all(ds.status.values != 0)
    assert np.all(np.isnan(ds.eta.values))


def test_a_runaway_steps_geometrically():
    # g(F) = 1.05 F + 10 has no fixed point above F = 0: the plain step grows by 5 % a
    # step (some 140 steps from 100 N to 1e5 N); the gain doubles it each step instead
    force, memory, steps = np.array([100.0]), {}, 0
    while force[0] < 1e5 and steps < 100:
        force, steps = _wegstein(force, 1.05 * force + 10.0, memory), steps + 1
    assert steps < 15
    assert memory["gain"][0] == MAX_RUNAWAY_GAIN


def test_a_contraction_keeps_the_secant_step():
    # g(F) = 0.5 F + 100 contracts to 200 N: no gain, the secant lands on it
    force, memory = np.array([100.0]), {}
    for _ in range(3):
        force = _wegstein(force, 0.5 * force + 100.0, memory)
    assert memory["gain"][0] == 1.0
    assert force[0] == pytest.approx(200.0, rel=1e-12)


def test_a_step_past_zero_force_is_the_plain_step():
    # harden task 3103:847 (a study of a visco-elastic input cam): a curved g measured at
    # 1,411 N and 1,192 N (slope 0.18) sent Wegstein's step from 1,192 N with g = 137 N to
    # -93 N, and the study's whole design failed on the negative force
    force, memory = np.array([1411.0]), {}
    _wegstein(force, np.array([176.3]), memory)
    step = _wegstein(np.array([1192.1]), np.array([137.1]), memory)
    assert memory["slope"][0] == pytest.approx(0.1790, abs=1e-3)
    assert step[0] == 137.1  # the plain step: the law's own force
    memory = {"force": np.array([1.0]), "new": np.array([-5.0])}
    assert _wegstein(np.array([2.0]), np.array([-1.0]), memory)[0] == 1.0  # half the force
