"""Harden task 3504:220 (a thermal-only campaign, session 35): a fold passed on the way
to the creep bound.

The climb in a held creep stepped from the walk's last rising point (creep 0.102, 36.07
N m) onto the creep bound (0.122, 36.20 N m): more torque than the point before, so the
bound was taken for the limit. But the torque peaks between the two (36.25 N m at a creep
of 0.115) and falls to the bound: the limit came out 36.201 N m, and `solve` carried
36.24 N m (1.001 times it) on the branch, unflagged. The climb now checks that the torque
still rises at the bound (`ballcvt.solvers.fold._falls_at_pin`).
"""

import json

import numpy as np
import pytest

from ballcvt import TractionLimitError, Variator, load_builtin
from ballcvt.api import with_oil_temperature
from ballcvt.equilibrium.problem import OperatingInputs, make_problem
from ballcvt.solvers.newton import solve_pinned
from ballcvt.solvers.peak import FOLD_MARGIN

FIELDS = json.loads("""{"aspect_ratio": 1.8091394437390527, "roller_radius": 0.05672692510140505, "theta0_deg": 56.623828258963385, "theta2_deg": 28.930162291807903, "alpha_deg": 4.925584870801001, "n_rollers": 6, "roller_bearing_diameter": 0.01528809879040453, "idler_bearing_diameter": 0.014993196552315154, "disc_groove_ratio": 4.017646723214346, "idler_groove_ratio": 5.073786342810804, "single_idler_groove_ratio": 8.053362595592464, "tilt_safety_factor": 0.8445886359265418, "creep_limit": 0.12214365097861826, "min_roller_gap": 0.00044824727017822206, "cam": {"disc": "output", "preload": 955.6224713805325, "ramp_angle_deg": 13.482950502779298, "mean_radius": 0.06600913929117125, "friction": 0.049866264409273}}""")  # noqa: E501
RATIO = 5.27880853212548
POINT = {"clamp_force": 3019.2757889908626, "input_speed_rpm": 535.3021513580849}


@pytest.fixture(scope="module")
def drive():
    design, fluid = load_builtin("table1")
    design = design.replace(name="random", **FIELDS)
    return with_oil_temperature(Variator(design, fluid, "double", traction_law="thermal"), "fixed")


def _fold(v):
    """The largest torque along the branch in the input disc's held creep, by a dense
    scan and a parabola through the best three [N m]."""
    w = POINT["input_speed_rpm"] * np.pi / 30.0
    pb = make_problem(v, OperatingInputs(np.array([RATIO]), 36.0, POINT["clamp_force"], w))
    r = v.solve(RATIO, 36.0, **POINT)
    start = np.array([[c.creep for c in r.contacts.values()]])
    creeps = np.linspace(0.105, 0.122, 35)
    torques = []
    for c in creeps:
        x0 = start.copy()
        x0[0, 0] = c
        t, _ = solve_pinned(pb.flat(), 0, x0, v.options)
        torques.append(float(t[0]))
    j = int(np.argmax(torques))
    a, b, cc = np.polyfit(creeps[j - 1 : j + 2], torques[j - 1 : j + 2], 2)
    return cc - b * b / (4 * a), creeps[j]


def test_the_limit_is_the_fold_inside_the_creep_bound(drive):
    fold, creep = _fold(drive)
    assert creep < drive.design.creep_limit * 0.97  # the fold lies inside the bound
    limit = drive.limit_torque(RATIO, **POINT)
    assert limit == pytest.approx(fold * (1.0 - FOLD_MARGIN), rel=2e-5)  # was 36.2013
    assert 0.0 < drive.solve(RATIO, limit * 0.999, **POINT).eta < 1.0
    with pytest.raises(TractionLimitError):
        drive.solve(RATIO, limit * 1.001, **POINT)
