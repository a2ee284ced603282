"""Validation of the rolling-contact fatigue physics (ballcvt.model.life, docs/life.md).

Each test names its source and its tolerance.
"""

import math

import numpy as np
import pytest

from ballcvt.errors import InputError
from ballcvt.model.hertz import hertz_contact
from ballcvt.model.life import (
    LIFE_MODELS,
    a_iso,
    bearing_l10,
    contact_l10,
    deep_groove_rating,
    miner_damage,
    miner_life,
    orthogonal_shear,
    system_l10,
)
from ballcvt.params.material import FatigueMaterial

MATERIAL = FatigueMaterial.builtin()


def _contact(load, rx=5e-3, ry=40e-3):
    """Semi-axes (transverse, rolling) of a ball-in-groove contact under ``load``."""
    ax, ay, _, _ = hertz_contact(load, rx, ry, MATERIAL.reduced_modulus)
    return ay, ax


def test_6206_rating_from_geometry_matches_catalogue():
    """ISO 281:2007 Eq. 2 for a 6206 (9 x 9.525 mm balls, d_m = 46 mm) against the SKF
    catalogue's C = 20.3 kN: within 5 % (the catalogue's improved b_m of modern steel)."""
    rating = deep_groove_rating(9.525e-3, 9, 46e-3)
    assert rating == pytest.approx(20.3e3, rel=0.05)
    assert rating == pytest.approx(19.44e3, rel=1e-3)  # 1.3 * 59.9 * 9^(2/3) * 9.525^1.8


@pytest.mark.parametrize(
    ("model", "ratio"),
    [("lundberg-palmgren", 1 / 8), ("zaretsky", 1 / 16)],
)
def test_load_life_exponent(model, ratio):
    """At fixed curvatures (Hertz semi-axes ~ Q^(1/3)): LP L ~ Q^-3 (Lundberg and
    Palmgren 1947), Zaretsky L ~ p0^-12 = Q^-4 (Zaretsky et al., NASA/TM-2008-214265): to 1e-9."""
    length = 0.2
    lives = [contact_l10(q, *_contact(q), length, MATERIAL, model) for q in (1000.0, 2000.0)]
    assert lives[1] / lives[0] == pytest.approx(ratio, rel=1e-9)


def test_lp_stress_life_exponent_is_nine():
    """LP at fixed geometry: L ~ p0^-9 (Harris and Kotzalas, 5th ed., §23.3): to 1e-9."""
    q = np.array([500.0, 4000.0])
    a, b = _contact(q)
    life = contact_l10(q, a, b, 0.1, MATERIAL)
    p0 = 1.5 * q / (np.pi * a * b)
    assert life[1] / life[0] == pytest.approx((p0[1] / p0[0]) ** -9, rel=1e-9)


def test_lp_volume_effect():
    """LP: L ~ l^(-1/e) (stressed volume a z0 l; Lundberg and Palmgren 1947): to 1e-12."""
    a, b = _contact(1000.0)
    short, long_ = contact_l10(1000.0, a, b, [0.1, 0.2], MATERIAL)
    assert long_ / short == pytest.approx(2 ** (-0.9), rel=1e-12)


def test_orthogonal_shear_limits():
    """Lundberg and Palmgren (1947) Eqs. 8-10: line contact tau0 = p0/4 at z0 = b/2;
    circle (b/a = 1: t = (1 + sqrt 17)/4) tau0 = 0.2139 p0 at 0.3509 b: to 1e-12."""
    tau, z = orthogonal_shear(1.0, [1e-9, 1.0], 1.0)
    assert tau[0] == pytest.approx(0.25, rel=1e-9)
    assert z[0] == pytest.approx(0.5e-9, rel=1e-9)
    t = (1 + math.sqrt(17)) / 4
    assert tau[1] == pytest.approx(math.sqrt(2 * t - 1) / (2 * t * (t + 1)), rel=1e-12)
    assert z[1] == pytest.approx(1 / ((t + 1) * math.sqrt(2 * t - 1)), rel=1e-12)
    assert (tau[1], z[1]) == pytest.approx((0.2139, 0.3509), abs=1e-4)


def test_orthogonal_shear_solves_auxiliary_equation():
    """(b/a)^2 = (t^2 - 1)(2t - 1) recovered from tau0/p0 and z0/b to 1e-12."""
    ratio = np.geomspace(1e-3, 1e2, 40)
    tau, z = orthogonal_shear(1.0, ratio, 1.0)
    root = 1.0 / (z / ratio)  # (t + 1) sqrt(2t - 1)
    t = np.array([next(x for x in np.roots([2, 3, 0, -1 - r**2]).real if x > 0.99)
                  for r in root])  # fmt: skip
    assert np.allclose((t**2 - 1) * (2 * t - 1), ratio**2, rtol=1e-9)
    assert np.allclose(tau, np.sqrt(2 * t - 1) / (2 * t * (t + 1)), rtol=1e-9)


def test_fatigue_limit_model():
    """ISO 281 fatigue limit (p_u = 1.5 GPa): infinite life below it; above it the LP
    life times (1 - p_u/p0)^(-c/e) (docs/life.md §3.3): to 1e-9."""
    loads = np.array([50.0, 5000.0])
    a, b = _contact(loads)
    p0 = 1.5 * loads / (np.pi * a * b)
    assert p0[0] < 1.5e9 < p0[1]
    lp = contact_l10(loads, a, b, 0.2, MATERIAL)
    limited = contact_l10(loads, a, b, 0.2, MATERIAL, "iso-fatigue-limit")
    assert math.isinf(limited[0])
    expected = lp[1] * (1 - 1.5e9 / p0[1]) ** (-MATERIAL.stress_exponent / MATERIAL.weibull_slope)
    assert limited[1] == pytest.approx(expected, rel=1e-9)


def test_unloaded_contact_lives_forever():
    a, b = _contact(1000.0)
    for model in LIFE_MODELS:
        assert np.isinf(contact_l10(0.0, a, b, 0.1, MATERIAL, model))


def test_unknown_model_is_an_input_error():
    with pytest.raises(InputError, match="lundberg-palmgren"):
        contact_l10(1.0, 1e-3, 1e-4, 0.1, MATERIAL, "palmgren")


def test_system_life_of_two_equal_elements():
    """Strict series Weibull (Lundberg and Palmgren 1947): two equal lives L give
    L 2^(-1/e): to 1e-12; an element that never fails does not count."""
    e = MATERIAL.weibull_slope
    assert system_l10([3.0e7, 3.0e7], e) == pytest.approx(3.0e7 * 2 ** (-1 / e), rel=1e-12)
    assert system_l10([3.0e7, np.inf], e) == pytest.approx(3.0e7, rel=1e-12)
    assert np.isinf(system_l10([np.inf, np.inf], e))
    assert system_l10([[1.0, 1.0], [2.0, np.inf]], e) == pytest.approx([2 ** (-0.9), 2.0])


def test_miner_two_step_cycle():
    """Palmgren-Miner on two steps: 30 % of the cycles at life 1e6, 70 % at 1e8:
    L = 1 / (0.3/1e6 + 0.7/1e8) (Harris and Kotzalas Eq. 11.21): to 1e-12."""
    expected = 1.0 / (0.3 / 1e6 + 0.7 / 1e8)
    assert miner_life([0.3, 0.7], [1e6, 1e8]) == pytest.approx(expected, rel=1e-12)
    assert miner_damage([3e5, 7e5], [1e6, 1e8]) == pytest.approx(0.307, rel=1e-12)
    assert np.isinf(miner_life([1.0, 1.0], [np.inf, np.inf]))


def test_bearing_l10():
    """ISO 281:2007 Eq. 5: L10 = (C/P)^3 [10^6 rev]; P = C gives 1."""
    assert bearing_l10(20.3e3, 20.3e3) == pytest.approx(1.0)
    assert bearing_l10(20.3e3, 2.03e3) == pytest.approx(1000.0)
    assert bearing_l10(1.0, 0.5, 10 / 3) == pytest.approx(2 ** (10 / 3))


def test_a_iso():
    """ISO 281:2007 §9.3.2 radial ball bearings: a_ISO = 0.1 at e_C C_u/P = 0; the three
    kappa branches meet at 0.4 and 1 (to 2e-3: the printed constants are rounded); the cap 50; kappa > 4 counts as 4."""
    assert a_iso(0.0, 1.0) == pytest.approx(0.1)
    for kappa in (0.4, 1.0):
        below, above = a_iso(0.2, [kappa * (1 - 1e-9), kappa])
        assert below == pytest.approx(above, rel=2e-3)  # the printed constants
    assert a_iso(5.0, 4.0) == 50.0
    assert a_iso(0.1, 10.0) == a_iso(0.1, 4.0)
    # hand value: kappa = 1, x = 0.1: 0.1 (1 - 0.5684^0.83 * 0.1^(1/3))^-9.3
    hand = 0.1 * (1 - (2.5671 - 1.9987) ** 0.83 * 0.1 ** (1 / 3)) ** -9.3
    assert a_iso(0.1, 1.0) == pytest.approx(hand, rel=1e-12)
    with pytest.raises(InputError):
        a_iso(0.1, 0.05)


def test_unloaded_contact_with_zero_ellipse():
    """Hertz gives zero semi-axes at zero load: still an infinite life, no warning."""
    with np.errstate(all="raise"):
        for model in LIFE_MODELS:
            lives = contact_l10([0.0, 1000.0], [0.0, 1e-3], [0.0, 2e-4], 0.1, MATERIAL, model)
            assert np.isinf(lives[0]) and np.isfinite(lives[1])


@pytest.mark.parametrize("field", ["semi_major", "semi_minor", "track_length"])
def test_loaded_contact_needs_a_positive_geometry(field):
    args = {"semi_major": 1e-3, "semi_minor": 2e-4, "track_length": 0.1, field: 0.0}
    with pytest.raises(InputError, match=field):
        contact_l10(100.0, material=MATERIAL, **args)


def test_a_registered_life_model_is_usable_by_name():
    """A new life model is one LifeModel in LIFE_MODELS (docs/life.md §3)."""
    from ballcvt.model.life import LifeModel

    def half_lp(contact, material):
        return 0.5 * contact_l10(
            contact.load, contact.semi_major, contact.semi_minor, contact.track_length, material
        )

    LIFE_MODELS.register(LifeModel("half-lp", half_lp, "half the LP life"))
    try:
        a, b = _contact(1000.0)
        lp = contact_l10(1000.0, a, b, 0.1, MATERIAL)
        assert contact_l10(1000.0, a, b, 0.1, MATERIAL, "half-lp") == pytest.approx(0.5 * lp)
    finally:
        LIFE_MODELS.unregister("half-lp")
