"""Side slip in the contact model (docs/model.md §17): `lateral_coefficients`."""

from __future__ import annotations


import numpy as np
import pytest

from ballcvt import Variator
from ballcvt.analysis.shift_effort import solved_tilt_contacts
from ballcvt.model.traction import (
    ContactState,
    Quadrature,
    contact_coefficients,
    lateral_coefficients,
    limiting_traction,
)
from ballcvt.params.drive import Drive

LAWS = ("isothermal", "viscoelastic", "thermal")


@pytest.fixture(scope="module")
def paper_contacts():
    """The four contacts of the paper's point (ratio 1, 40 N m, 2 kN, 2000 rpm)."""
    v = Variator()
    r = v.solve(1.0, 40.0, clamp_force=2000.0, input_speed_rpm=2000.0)
    creep = np.array([[c.creep for c in r.contacts.values()]])
    inputs = [np.array([x]) for x in (r.ratio, r.output_torque, r.clamp_force, r.input_speed)]
    tc = solved_tilt_contacts(Drive(v.design, v.fluid, "double"), inputs, creep, Quadrature())
    return tc.state, v.fluid


def _law(fluid, law):
    return fluid.with_traction_law(law)


@pytest.mark.parametrize("law", ("isothermal", "viscoelastic"))
def test_zero_side_slip_gives_the_solvers_coefficients(paper_contacts, law):
    """At s_lat = 0 the lateral path has the nodes and integrand of the NumPy reference."""
    state, fluid = paper_contacts
    fl = _law(fluid, law)
    q = Quadrature(engine="numpy")
    mu0, chi0 = contact_coefficients(state, fl, q)
    mu, mu_y, chi = lateral_coefficients(state, fl, 0.0, q)
    np.testing.assert_allclose(mu, mu0, rtol=1e-12, atol=0)
    np.testing.assert_allclose(chi, chi0, rtol=1e-10, atol=0)
    if law == "isothermal":  # X -> -X symmetry: no lateral force without side slip
        assert np.all(np.abs(mu_y) < 1e-15)


def test_zero_side_slip_thermal(paper_contacts):
    """The thermal law's side-slip form finds the same film temperature (to its tolerance)."""
    state, fluid = paper_contacts
    fl = _law(fluid, "thermal")
    mu0, chi0 = contact_coefficients(state, fl)
    mu, mu_y, chi = lateral_coefficients(state, fl, 0.0)
    np.testing.assert_allclose(mu, mu0, rtol=1e-5)
    np.testing.assert_allclose(chi, chi0, rtol=1e-4)
    assert np.all(np.abs(mu_y) < 1e-15)


@pytest.mark.parametrize("law", ("isothermal", "thermal"))
def test_lateral_force_is_odd_in_the_side_slip(paper_contacts, law):
    state, fluid = paper_contacts
    fl = _law(fluid, law)
    s = np.array([1e-5, 1e-3, 3e-2])[:, None]
    plus = lateral_coefficients(state, fl, s)
    minus = lateral_coefficients(state, fl, -s)
    np.testing.assert_allclose(minus[1], -plus[1], rtol=1e-6, atol=1e-15)
    np.testing.assert_allclose(minus[0], plus[0], rtol=1e-6)  # mu even
    assert np.all(np.sign(plus[1]) == 1.0)


def test_viscoelastic_odd_without_spin(paper_contacts):
    """Without spin the sliding field is uniform: odd in s_lat under the Maxwell law too."""
    state, fluid = paper_contacts
    st = state.replace(spin=0.0 * np.asarray(state.spin))
    fl = _law(fluid, "viscoelastic")
    plus = lateral_coefficients(st, fl, 2e-3)
    minus = lateral_coefficients(st, fl, -2e-3)
    np.testing.assert_allclose(minus[1], -plus[1], rtol=1e-12)


@pytest.mark.parametrize("law", LAWS)
def test_linear_range(paper_contacts, law):
    """mu_y proportional to s_lat for small side slip."""
    state, fluid = paper_contacts
    fl = _law(fluid, law)
    s = np.array([1e-7, 2e-7, 4e-7])[:, None]
    base = lateral_coefficients(state, fl, 0.0)[1]
    slope = (lateral_coefficients(state, fl, s)[1] - base) / s
    np.testing.assert_allclose(slope[1], slope[0], rtol=2e-3)
    np.testing.assert_allclose(slope[2], slope[0], rtol=2e-3)


@pytest.mark.parametrize("law", LAWS)
def test_resultant_bounded_by_the_limiting_shear(paper_contacts, law):
    """|(mu, mu_y)| <= (1/F_N) int tau_L dA at any side slip; it saturates (a monotone
    law) or peaks and falls (the thermal law)."""
    state, fluid = paper_contacts
    fl = _law(fluid, law)
    s = np.logspace(-6, 1, 15)[:, None]
    mu, mu_y, _ = lateral_coefficients(state, fl, s)
    bound = limiting_traction(state, fl)
    assert np.all(np.hypot(mu, mu_y) <= bound * (1.0 + 1e-9))
    if law != "thermal":  # the thermal law's traction falls past its peak (shear heat)
        assert np.all(np.abs(mu_y[-1] - mu_y[-2]) < 0.05 * np.abs(mu_y[-1]))  # saturated


@pytest.mark.parametrize("law", LAWS)
def test_isotropy_lateral_equals_longitudinal_without_spin(paper_contacts, law):
    """Pure lateral slip, zero spin: the same magnitude as a longitudinal creep of the size."""
    state, fluid = paper_contacts
    fl = _law(fluid, law)
    zero = 0.0 * np.asarray(state.spin)
    for size in (1e-6, 1e-3, 5e-2):
        lat = lateral_coefficients(state.replace(spin=zero, creep_term=zero), fl, size)
        lon = lateral_coefficients(state.replace(spin=zero, creep_term=zero + size), fl, 0.0)
        np.testing.assert_allclose(lat[1], lon[0], rtol=1e-9)
        assert np.all(np.abs(lat[0]) < 1e-15) and np.all(np.abs(lon[1]) < 1e-15)


def test_newtonian_hand_calculation():
    """Constant viscosity, no spin, tiny slip: F_y = (eta / h) pi a_x a_y u s_lat."""
    fluid = Variator().fluid
    fl = fluid.model_copy(update={"pole_viscosity": fluid.viscosity})  # Roelands: eta = eta_0
    ax, ay, h, u, fn, s = 2e-4, 6e-4, 1e-7, 5.0, 1500.0, 1e-9
    state = ContactState(0.0, 0.0, ax, ay, 1.5 * fn / (np.pi * ax * ay), fn, 0.04, u, h)
    _, mu_y, _ = lateral_coefficients(state, fl, s)
    hand = fluid.viscosity / h * np.pi * ax * ay * u * s / fn
    np.testing.assert_allclose(mu_y, hand, rtol=1e-6)


def test_viscoelastic_entry_edge_flips_the_spin_lateral_force(paper_contacts):
    """A Maxwell film's lateral force at zero side slip changes sign with the edge where
    the film enters (X -> -X); mu and chi do not depend on it."""
    state, fluid = paper_contacts
    fl = _law(fluid, "viscoelastic")
    plus = lateral_coefficients(state, fl, 0.0, entry=1.0)
    minus = lateral_coefficients(state, fl, 0.0, entry=-1.0)
    assert np.all(np.abs(plus[1]) > 0.0)
    np.testing.assert_allclose(minus[1], -plus[1], rtol=1e-9)
    np.testing.assert_allclose(minus[0], plus[0], rtol=1e-12)
    np.testing.assert_allclose(minus[2], plus[2], rtol=1e-9)


def test_default_rule_near_the_reference_as_the_pole_moves(paper_contacts):
    """The pole moves to X_p = -s_lat / s_x; the default rule stays within 2e-3 of the
    converged rule across it (inside, in the blend, outside)."""
    from ballcvt.model.traction import REFERENCE

    state, fluid = paper_contacts
    sx = np.asarray(state.spin) * np.asarray(state.ax) / np.asarray(state.radius)
    for xp in (0.3, 0.6, 0.9, 1.2):
        got = lateral_coefficients(state, fluid, -xp * sx)
        ref = lateral_coefficients(state, fluid, -xp * sx, REFERENCE)
        for a, b in zip(got, ref, strict=True):
            assert np.all(np.abs(a - b) <= 2e-3 * np.abs(b) + 1e-12)


def test_a_law_without_a_side_slip_form_is_refused(paper_contacts):
    import dataclasses

    from ballcvt.errors import InputError
    from ballcvt.registry import TRACTION_LAWS

    state, fluid = paper_contacts
    law = dataclasses.replace(TRACTION_LAWS.get("isothermal"), name="no_side_slip", lateral=None)
    TRACTION_LAWS.register(law)
    try:
        fl = fluid.with_traction_law("no_side_slip")
        with pytest.raises(InputError, match="a law with side slip: isothermal"):
            lateral_coefficients(state, fl, 1e-3)
    finally:
        TRACTION_LAWS.unregister("no_side_slip")
