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
