"""The asperities' boundary shear of the mixed model (docs/model.md §16, issue 27 item 1):
a regularised Coulomb law whose slip scale is the contact's tangential compliance."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ballcvt import load_builtin
from ballcvt.model.lubrication import (
    LAMBDA_CUTOFF,
    STEEL_CREEP_STIFFNESS,
    Asperities,
    asperities,
    boundary_coefficients,
    creep_stiffness,
    load_sharing,
    lubricated_coefficients,
)
from ballcvt.model.traction.contact import ContactState, contact_coefficients
from ballcvt.model.traction.quadrature import Quadrature
from drives import fixed_oil_hub

DESIGN, FLUID = fixed_oil_hub()[:2]
MU_B = 0.1
SIGMA = 0.07e-6
ASP = Asperities("mixed", SIGMA, 2.31e11, MU_B, 0.04, 1e-3)
# a hub input contact (ballcvt point --design hub --ratio 1 --torque 4.19 --speed 114)
STATE = ContactState(0.0175, -2.64, 4.04e-4, 4.87e-4, 7.55e8, 311.0, 0.07, 0.24, 8.28e-8)
#: Local slip scale ``mu_b p_max / k`` at the hub contact's peak pressure [-].
SLIP_SCALE = MU_B * 7.55e8 / STEEL_CREEP_STIFFNESS
#: Relative error of the default quadrature on the Hertz pressure's integral (a uniform
#: Coulomb shear gives mu = 1.00036 mu_b): the tolerance of the limits below.
QUAD = 1e-3


def _boundary(state, derivatives=False):
    return boundary_coefficients(state, FLUID, MU_B, Quadrature(), derivatives)


def test_stiffness_and_slip_scale():
    """``k = C_11 G / pi`` with Kalker's ``C_11`` (4.12 at nu 0.25 for a circle; 4.34 at
    0.3 interpolated): steel 1.11e11 Pa, and the slip scale at the hub's 0.76 GPa is
    6.8e-4, of Carter's full-slip creep ``2 mu p_0 / E*`` (1.3e-3) order."""
    g = 210e9 / 2.6
    assert creep_stiffness(210e9, 0.25) == pytest.approx(4.12 * 210e9 / 2.5 / math.pi)
    assert STEEL_CREEP_STIFFNESS == pytest.approx(4.336 * g / math.pi, rel=1e-9)
    assert SLIP_SCALE == pytest.approx(6.8e-4, rel=0.01)
    carter = 2 * MU_B * 7.55e8 / (210e9 / (2 * (1 - 0.09)))
    assert 0.3 < SLIP_SCALE / carter < 1.0
    assert asperities(DESIGN).creep_stiffness == pytest.approx(STEEL_CREEP_STIFFNESS)


def test_asperity_share_reaches_boundary_friction_in_sliding():
    """The strict xfail of h27-stribeck (tests/test_validation_mixed.py), now passing: in
    sliding (creep 0.5, as in a ball-on-disc Stribeck test) the asperities carry their
    load with the boundary friction coefficient, at the film of their share."""
    state = STATE.replace(creep_term=np.array([0.1, 0.5, 2.0]))
    _, lam = load_sharing(state.film, state.load, state.ax, state.ay, ASP)
    mu, _ = _boundary(state.replace(film=lam * SIGMA))
    assert np.all(mu >= 0.09)


@pytest.mark.parametrize("spin", [0.0, -2.64])
def test_sliding_reaches_mu_b(spin):
    """Creep >> slip scale: ``|mu| -> mu_b`` (the spin's share of the sliding fades)."""
    for c in (0.5, 2.0):
        mu, _ = _boundary(STATE.replace(creep_term=c, spin=spin))
        assert float(mu) == pytest.approx(MU_B, rel=QUAD)
        mu, _ = _boundary(STATE.replace(creep_term=-c, spin=spin))
        assert float(mu) == pytest.approx(-MU_B, rel=QUAD)
    mu, _ = _boundary(STATE.replace(creep_term=0.1, spin=spin))
    assert 0.99 * MU_B < float(mu) < (1 + QUAD) * MU_B


def test_was_the_films_viscous_shear_before():
    """The old law gave 0.0038 at the hub contact (the film's shear); now near mu_b."""
    mu, _ = _boundary(STATE)
    assert 0.085 < float(mu) < MU_B


def test_pure_spin_moment_is_the_dry_contacts():
    """Pure spin of a circle: the moment tends to ``(3 pi / 16) mu_b F a`` (Johnson 1985
    §8.4), ``chi = M / (F r_c)``: within the quadrature's error (1e-3) at an edge slip of
    180x the slip scale (spin 20; measured 2e-6), 0.5 % at 18x (spin 2: the elastic core
    round the pole, measured 0.17 %)."""
    a, p0, rc = 4.2e-4, 7.55e8, 0.07
    load = 2.0 / 3.0 * math.pi * a * a * p0
    for spin, tol in ((20.0, QUAD), (-20.0, QUAD), (2.0, 5e-3)):
        state = ContactState(0.0, spin, a, a, p0, load, rc, 0.24, 8e-8)
        mu, chi = _boundary(state)
        assert abs(float(mu)) < 1e-12
        dry = math.copysign(3 * math.pi / 16 * MU_B * a / rc, spin)
        assert float(chi) == pytest.approx(dry, rel=tol)
        assert abs(float(chi)) < abs(dry) * (1 + QUAD)


def test_linear_and_small_below_the_slip_scale():
    """Creep << slip scale, no spin: ``mu = k c A / F = 3 k c / (2 p_max)`` (elastic), linear."""
    state = STATE.replace(spin=0.0)
    c = np.array([1e-6, 2e-6, 4e-6])
    mu, _ = _boundary(state.replace(creep_term=c))
    assert mu == pytest.approx(1.5 * STEEL_CREEP_STIFFNESS * c / 7.55e8, rel=0.01)
    assert mu[2] / mu[0] == pytest.approx(4.0, rel=0.01)
    assert np.all(mu < 0.01)


def test_continuous_and_monotone_in_the_creep():
    """Through zero, the slip scale and sliding: no step between close creeps."""
    c = np.linspace(-0.03, 0.03, 601)
    mu, chi = _boundary(STATE.replace(creep_term=c))
    assert np.all(np.diff(mu) > 0.0)
    assert np.max(np.abs(np.diff(mu))) < 0.01 * MU_B
    assert np.max(np.abs(np.diff(chi))) < 0.01 * MU_B * STATE.ax / STATE.radius


def test_derivatives_shapes_and_values():
    c = np.array([[0.001, 0.01], [0.05, -0.02]])
    state = STATE.replace(creep_term=c)
    mu, chi, dmu, dchi = _boundary(state, derivatives=True)
    assert mu.shape == chi.shape == (2, 2) and dmu.shape == dchi.shape == (2, 2, 3)
    step = 1e-7
    up = _boundary(state.replace(creep_term=c + step))
    assert dmu[..., 0] == pytest.approx((up[0] - mu) / step, rel=1e-3, abs=1e-6)
    up = _boundary(state.replace(spin=STATE.spin + 1e-6))
    assert dchi[..., 1] == pytest.approx((up[1] - chi) / 1e-6, rel=1e-3, abs=1e-9)
    assert np.all(dmu[..., 2] == 0.0) and np.all(dchi[..., 2] == 0.0)
    # no film, no rolling speed: the law depends on the slip alone
    other = _boundary(state.replace(film=3 * STATE.film))
    assert np.array_equal(other[0], mu)


def test_mixed_is_the_full_film_above_the_cutoff():
    thick = STATE.replace(film=np.array([1.01, 2.0]) * LAMBDA_CUTOFF * SIGMA)
    for d in (False, True):
        mixed = lubricated_coefficients(thick, FLUID, ASP, Quadrature(), d)
        film = contact_coefficients(thick, FLUID, Quadrature(), d)
        for m, f in zip(mixed[:2], film[:2]):
            assert np.array_equal(m, f)
        if d:
            assert np.array_equal(mixed[2][..., :3], film[2])
            assert np.all(mixed[2][..., 3] == 0.0)


def test_mixed_rises_towards_mu_b_as_the_film_thins():
    """In sliding the asperity share alone carries ``f_a`` of the load at nearly ``mu_b``
    (before: at the film's viscous shear, 0.018 at creep 0.1)."""
    state = STATE.replace(creep_term=0.1, film=np.array([3.0, 1.0, 0.3]) * SIGMA)
    mu, _ = lubricated_coefficients(state, FLUID, ASP, Quadrature())
    frac, _ = load_sharing(state.film, state.load, state.ax, state.ay, ASP)
    assert np.all(np.diff(frac) > 0)
    assert frac[-1] > 0.03
    assert np.all(mu >= 0.99 * MU_B * frac)


def test_boundary_law_compiled_equals_numpy_with_the_pole_at_the_edge():
    """A hub contact whose pole sits at the contact's edge (|Y_p| ~ 1: the pole rule's
    nodes crowd where the pressure is ~0): the boundary law's viscosity table, whose log E
    falls ~80-fold over its first interval, made the compiled kernel's cubic negative there
    (|mu| 324 -> 3.5e8 over 3e-7 of creep); its derivatives are now bounded (|E' h| <= 3 E)
    and the kernel agrees with the NumPy path (found by a hub duty cycle, issue 26)."""
    from ballcvt.model.traction.kernels import viscosity_table

    d, f = load_builtin("hub")
    asp = asperities(d)
    state = ContactState(*(np.atleast_1d(v) for v in (
        0.010422661314861999, 2.0421266295837968, 4.3362739757501465e-4,
        5.217377955981099e-4, 809488054.6245488, 383.5642049274727, 0.10221320343559642,
        2.349991422084524, 1.279448774760789e-07)))
    for dc in np.linspace(-3e-7, 3e-7, 7):
        s = state._replace(creep_term=state.creep_term + dc)
        fast = boundary_coefficients(s, f, asp.boundary_friction, Quadrature(), True,
                                         asp.creep_stiffness)
        ref = boundary_coefficients(s, f, asp.boundary_friction, Quadrature(engine="numpy"),
                                        True, asp.creep_stiffness)
        for a, b in zip(fast, ref):
            np.testing.assert_allclose(a, b, rtol=1e-9, atol=1e-12)
    # the bound never acts on a real fluid's table (log E changes by <= 0.01 per interval)
    _, tab = viscosity_table(f, 4e9)
    assert np.all(np.abs(tab[:, 1]) <= 0.011 * tab[:, 0])
