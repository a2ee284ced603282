"""Mixed lubrication (docs/model.md §16, `ballcvt.model.lubrication`)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from drives import fixed_oil_hub
from scipy.integrate import quad

from ballcvt import Variator, load_builtin
from ballcvt.model.greenwood_tripp import _gt, _hermite, solve_share, solve_share_numpy
from ballcvt.model.lubrication import (
    LAMBDA_CUTOFF,
    Asperities,
    asperity_integral,
    load_sharing,
    lubricated_coefficients,
)
from ballcvt.model.traction.contact import ContactState, contact_coefficients
from ballcvt.params.models import Design
from ballcvt.registry import LUBRICATION_MODELS

DESIGN, FLUID = fixed_oil_hub()[:2]
ASP = Asperities("mixed", 0.07e-6, 2.31e11, 0.1, 0.04, 1e-3)
# a hub input contact (ballcvt point --design hub --ratio 1 --torque 4.19 --speed 114)
STATE = ContactState(0.0175, -2.64, 4.04e-4, 4.87e-4, 7.55e8, 311.0, 0.07, 0.24, 8.28e-8)


def test_registry_and_design_table():
    assert LUBRICATION_MODELS.names()[:2] == ("full-film", "mixed")
    assert DESIGN.lubrication is not None and DESIGN.lubrication.model == "mixed"
    table1 = load_builtin("table1")[0]
    assert table1.lubrication is None and "lubrication" not in table1.model_dump()
    assert table1.with_lubrication("mixed").lubrication.boundary_friction == 0.1
    assert table1.with_lubrication(None) is table1
    with pytest.raises(Exception, match="lubrication|model"):
        Design(**{**table1.model_dump(), "lubrication": {"model": "wet"}})


def test_gt_integral_exact():
    """F_5/2 against its definition (Greenwood and Tripp 1970) by quadrature, 1e-6
    relative below lambda 2 (the C1 truncation at 4 changes it by ~5e-5 absolute)."""
    for lam in (0.0, 0.5, 1.0, 2.0):
        exact = quad(lambda s: (s - lam) ** 2.5 * math.exp(-s * s / 2), lam, np.inf)[0]
        exact /= math.sqrt(2 * math.pi)
        value, _ = asperity_integral(lam)
        assert value == pytest.approx(exact, abs=6e-5)
    v, s = asperity_integral([LAMBDA_CUTOFF - 1e-9, LAMBDA_CUTOFF, 10.0])
    assert np.all(np.abs(v) < 1e-12) and np.all(np.abs(s) < 1e-8)
    # the tables against the parabolic-cylinder form, between their nodes
    t = np.linspace(0.0, LAMBDA_CUTOFF, 7919)
    for n in (2.5, 1.5):
        assert np.max(np.abs(_hermite(t, n) - _gt(t, n))) < 1e-13


def test_limits_of_the_share():
    """f_a = 0 exactly above the cutoff; rises as lambda falls; tends to 1 as lambda -> 0
    when the asperities can carry the whole load at zero separation (K E' F_5/2(0) >=
    p_mean), else to K E' F_5/2(0) / p_mean (Johnson, Greenwood and Poon 1972: the
    asperity pressure is bounded by Greenwood-Tripp's at zero separation)."""
    load, ax, ay = 311.0, 4.04e-4, 4.87e-4
    lam = np.array([10.0, 4.0, 2.0, 1.0, 0.5, 0.1, 1e-4])
    f, lam_h = load_sharing(lam * ASP.roughness, load, ax, ay, ASP)
    assert f[0] == 0.0 and f[1] == 0.0 and lam_h[0] == 10.0
    assert np.all(np.diff(f[1:]) > 0) and np.all(lam_h >= lam)
    g0 = ASP.pressure_scale * asperity_integral(0.0)[0] * math.pi * ax * ay / load
    assert f[-1] == pytest.approx(g0, rel=1e-3)
    rough = Asperities("mixed", 0.07e-6, 2.31e11, 0.1, 0.5, 1e-2)
    f, _ = load_sharing(np.array([1e-6, 1e-3]) * rough.roughness, load, ax, ay, rough)
    assert f[0] > 0.999 and f[1] > 0.99


def test_full_film_exact_above_cutoff_and_bounds():
    thick = STATE.replace(film=5.0 * ASP.roughness)
    assert lubricated_coefficients(thick, FLUID, ASP) == contact_coefficients(thick, FLUID)
    for film in (0.2, 0.5, 1.0):
        state = STATE.replace(film=film * ASP.roughness)
        mu, chi = lubricated_coefficients(state, FLUID, ASP)
        f, _ = load_sharing(state.film, state.load, state.ax, state.ay, ASP)
        mu_film = contact_coefficients(
            state.replace(
                load=state.load * (1 - f),
                p_max=state.p_max * (1 - f),
                film=state.film * (1 - f) ** -0.14,
            ),
            FLUID,
        )[0]
        assert min(mu_film, ASP.boundary_friction) <= mu <= max(mu_film, ASP.boundary_friction)


def test_derivatives_against_differences():
    """The four columns (creep term, spin, log u_ref at fixed film, log h at fixed
    u/h) against central differences: 2 % of the largest entry (the law's Jacobian
    omits the pole's motion, `shear_coefficients`)."""
    state = STATE.replace(film=0.5 * ASP.roughness)
    mu, chi, dmu, dchi = lubricated_coefficients(state, FLUID, ASP, derivatives=True)
    eps = 1e-5
    moves = [
        lambda s, e: s.replace(creep_term=s.creep_term + e),
        lambda s, e: s.replace(spin=s.spin + e),
        lambda s, e: s.replace(u_ref=s.u_ref * math.exp(e)),
        lambda s, e: s.replace(u_ref=s.u_ref * math.exp(e), film=s.film * math.exp(e)),
    ]
    for k, move in enumerate(moves):
        hi = lubricated_coefficients(move(state, eps), FLUID, ASP)
        lo = lubricated_coefficients(move(state, -eps), FLUID, ASP)
        for got, a, b, scale in ((dmu, hi[0], lo[0], dmu), (dchi, hi[1], lo[1], dchi)):
            fd = (a - b) / (2 * eps)
            assert got[k] == pytest.approx(fd, abs=0.02 * np.max(np.abs(scale)))


def test_paper_drive_untouched_and_hub_mixed():
    """table1 keeps full film (golden values: tests/test_golden.py); on the hub, the
    asperity fraction and film parameter are reported per contact and the full-film
    option reproduces the drive without the table exactly."""
    r = Variator().solve(
        ratio=1.0, output_torque=40.0, clamp_force=2000.0, input_speed_rpm=2000.0
    )
    assert all(c.asperity_fraction == 0.0 for c in r.contacts.values())
    speed = 114.0
    torque = 50.0 / (speed * math.pi / 30.0)
    mixed = Variator(DESIGN, FLUID).solve(
        ratio=1.0, output_torque=torque, input_speed_rpm=speed, clamp_law="cam"
    )
    assert mixed.converged
    share = [c.asperity_fraction for c in mixed.contacts.values()]
    assert all(0.0 < s < 0.05 for s in share)
    plain = DESIGN.model_copy(update={"lubrication": None})
    full = Variator(DESIGN.with_lubrication("full-film"), FLUID).solve(
        ratio=1.0, output_torque=torque, input_speed_rpm=speed, clamp_law="cam"
    )
    ref = Variator(plain, FLUID).solve(
        ratio=1.0, output_torque=torque, input_speed_rpm=speed, clamp_law="cam"
    )
    assert full.eta == ref.eta and full.losses["total"] == ref.losses["total"]


def test_the_compiled_share_has_the_numpy_paths_bits():
    """`solve_share` (compiled, issue 26) against the NumPy iteration it replaced, over
    film parameters from the boundary to the cutoff and load scales over six decades."""
    rng = np.random.default_rng(5)
    lam_s = np.concatenate([rng.uniform(0.0, LAMBDA_CUTOFF, 4000), [0.0, 1e-9, 3.999999]])
    scale = np.concatenate([10 ** rng.uniform(-4, 2, 4000), [1e-3, 50.0, 1.0]])
    fast, ref = solve_share(lam_s, scale), solve_share_numpy(lam_s, scale)
    assert np.array_equal(fast, ref)
    assert np.all((fast >= 0.0) & (fast < 1.0))
