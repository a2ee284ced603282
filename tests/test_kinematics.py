"""Geometry and kinematics: analytic limits and the printed Eqs. 4, 8, 11-14."""

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ballcvt import InputError
from ballcvt.model.architectures import contact_layout
from ballcvt.model.kinematics import body_speeds, check_ratio, ideal_ratio, ratio_range, rolling_radius, spin, tilt_from_ratio, tilt_limits

angles = st.floats(np.radians(15), np.radians(75))


def test_zero_tilt_gives_unit_ratio_on_symmetric_design():
    for theta in np.radians([20, 45, 60]):
        assert ideal_ratio(0.0, theta, theta, 1.7) == pytest.approx(1.0, abs=1e-15)


@given(t0=angles, t2=angles, k=st.floats(0.5, 3.0), frac=st.floats(-0.95, 0.95))
def test_ratio_tilt_round_trip(t0, t2, k, frac):
    lo, hi = tilt_limits(t0, t2)
    g = frac * (hi if frac > 0 else -lo)
    tau = ideal_ratio(g, t0, t2, k)
    assert tilt_from_ratio(tau, t0, t2, k) == pytest.approx(g, abs=1e-12)


def test_tilt_limits_give_zero_and_infinite_ratio():
    t = np.radians(45)
    lo, hi = tilt_limits(t, t)
    assert ideal_ratio(lo + 1e-9, t, t, 1.7) < 1e-8
    assert ideal_ratio(hi - 1e-9, t, t, 1.7) > 1e8


def test_ratio_range_and_check(drive):
    lo, hi = ratio_range(drive[0])
    # Fig. 3: 0.8 x the Eq. 6 limits, theta = 45 deg: tau = cos(9 deg)/cos(81 deg).
    assert hi == pytest.approx(np.cos(np.radians(9)) / np.cos(np.radians(81)))
    assert lo == pytest.approx(1.0 / hi)
    check_ratio(drive[0], [0.5, 1.0, 2.0])
    with pytest.raises(InputError, match="ratio = 7"):
        check_ratio(drive[0], 7.0)


def test_spin_matches_printed_eqs_11_to_14(drive):
    d = drive[0]
    lay = contact_layout(d, "double")
    g = tilt_from_ratio(1.76, d.theta0, d.theta2, d.aspect_ratio)
    c = np.array([0.01, 1e-3, -2e-3, 0.02])
    ws, om = body_speeds(lay, g, c, 209.4)
    s = spin(lay, g, ws, om)
    r, t0, a = lay.radius, d.theta0, d.alpha
    printed = [-r[0] * np.tan(t0 + g) * (1 - c[0]) + np.sin(t0),
               -np.sin(a) - r[1] * np.tan(a - g) / (1 - c[1]),
               r[2] * np.tan(a + g) / (1 - c[2]) + np.sin(a),
               r[3] * np.tan(t0 - g) / (1 - c[3]) - np.sin(t0)]
    np.testing.assert_allclose(s, printed, rtol=1e-13)
    # Eq. 8: actual ratio.
    assert om[-1] / om[0] == pytest.approx(1.76 * (1 - c[0]) * (1 - c[-1]), rel=1e-13)


def test_rolling_radii_eq_1(drive):
    d = drive[0]
    lay = contact_layout(d, "double")
    g = 0.2
    rho = rolling_radius(lay, g)
    np.testing.assert_allclose(np.abs(rho), [np.cos(d.theta0 + g), np.cos(d.alpha - g),
                                             np.cos(d.alpha + g), np.cos(d.theta2 - g)])


def test_single_idler_spin_vanishes_at_unit_ratio(drive):
    lay = contact_layout(drive[0], "single")
    ws, om = body_speeds(lay, 0.0, np.array([1e-3, 1e-6, 1e-3]), 200.0)
    assert spin(lay, 0.0, ws, om)[1] == 0.0


def test_unknown_architecture(drive):
    with pytest.raises(InputError, match="architecture = 'triple'"):
        contact_layout(drive[0], "triple")
