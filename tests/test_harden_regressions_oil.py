"""Harden task 4242:951 (session 16, the campaign run with the drives' own oil models,
``HARDEN_OIL=drive``): the optimal clamp under the hub's oil heat balance at a point where
no clamping force carries even zero torque. The balance's limit point then found no
admissible torque, and `api.oil.limit_with_oil` compared the empty `Capacity` itself with
zero: a TypeError. It is now refused in one line, as at a fixed oil."""

import json

import pytest

from ballcvt import Variator, load_builtin
from ballcvt.errors import TractionLimitError

FIELDS = json.loads(
    '{"aspect_ratio": 3.984068845432138, "roller_radius": 0.016744705901889763, '
    '"theta0_deg": 40.13702294699061, "theta2_deg": 52.38991569735095, '
    '"alpha_deg": 18.172229153658957, "n_rollers": 7, '
    '"roller_bearing_diameter": 0.0022580547806748683, '
    '"idler_bearing_diameter": 0.011813279421136661, "disc_groove_ratio": 4.402706008328007, '
    '"idler_groove_ratio": 2.984465193360027, "single_idler_groove_ratio": 18.140661686734365, '
    '"tilt_safety_factor": 0.6850785918427186, "creep_limit": 0.11031957063366421, '
    '"min_roller_gap": 0.0015013946237711882, "cam": {"disc": "output", '
    '"preload": 2284.416153297007, "ramp_angle_deg": 6.129778976338305, '
    '"mean_radius": 0.027114616069329158, "friction": 0.0007028691859399805}}'
)


def test_no_admissible_torque_under_the_oil_balance_is_refused():
    design, fluid = load_builtin("hub")
    v = Variator(design.replace(name="random", **FIELDS), fluid, "single",
                 traction_law="viscoelastic")  # fmt: skip
    assert v.design.models.oil_temperature == "balance"
    with pytest.raises(TractionLimitError, match="no clamping force"):
        v.solve(0.798144430811826, 0.0, clamp_law="optimal", input_speed_rpm=64928.38950606848)


FIELDS_863 = json.loads(
    '{"aspect_ratio": 1.2191992264694425, "roller_radius": 0.02810016206953253, '
    '"theta0_deg": 35.25840373900531, "theta2_deg": 51.3040266005169, '
    '"alpha_deg": 2.8799870311459337, "n_rollers": 6, '
    '"roller_bearing_diameter": 0.02575861020657367, '
    '"idler_bearing_diameter": 0.0031997092835864206, "disc_groove_ratio": 2.323546693444718, '
    '"idler_groove_ratio": 1.5203818306257366, "single_idler_groove_ratio": 9.72351911273427, '
    '"tilt_safety_factor": 0.6582755574992313, "creep_limit": 0.15579692221733976, '
    '"min_roller_gap": 0.0006827891313145859}'
)


def test_a_point_beyond_the_capacity_on_the_way_to_its_balance_has_losses():
    """Harden task 4242:863: a sweep's limit under the oil balance 0.26 % under
    `limit_torque`'s (94.240 against 94.490 N m, where the oil runs away above 150 C). At
    94.287 N m the point is carried at its balance (148.7 C, creep 0.141 < 0.156) but
    beyond the creep limit at 109 C (creep 0.1564), where the admissibility test stopped
    its run as soon as the creep passed the limit: no losses at that rung, so the ladder
    refused it there. `evaluate_points(beyond=True)` now solves such points on (as `solve`
    with ``check_capacity=False`` does); the sweep's limit is then limit_torque's to 1e-15
    (a 131-rung ladder: 46 s, not run here)."""
    import numpy as np

    from ballcvt.analysis.sweeps.curves import OperatingRows
    from ballcvt.analysis.sweeps.points import evaluate_points
    from ballcvt.model.oil import fluid_at
    from ballcvt.params.drive import Drive

    design, fluid = load_builtin("hub")
    design = design.replace(name="random", **FIELDS_863)
    fluid = fluid_at(fluid.with_traction_law("viscoelastic"), 382.15)
    rows = OperatingRows.of(Drive(design, fluid, "single"), [0.2913899611465347],
                            [697.2780370252146 * np.pi / 30], [2985.521529660266], None)  # fmt: skip
    got = evaluate_points(rows, np.array([94.287]), beyond=True)
    assert got["status"][0] == 1  # beyond the creep limit at this oil temperature
    assert 0.76 < got["eta"][0] < 0.77 and got["losses"][0].min() >= 0.0  # 0.76618
    assert np.isnan(evaluate_points(rows, np.array([94.287]))["eta"][0])  # the default
