"""The mixed model's film-thickness column of the Jacobian on a coarse rule (session 25).

`mixed_coefficients` differences the film's share of the load by the film thickness
(the fourth column of ``dmu, dchi``). Since session 25 that difference runs on
`FILM_SHARE_RULE` (12 x 8 centred nodes) where the law's rule has more nodes: a plain
pass of the kernels fewer per Newton iteration on the hub. The column is a Jacobian's: the
equilibrium Newton converges to does not depend on it.
"""

import numpy as np
import pytest
from drives import fixed_oil_hub

import ballcvt.model.lubrication as lub
from ballcvt import Variator
from ballcvt.model.lubrication import Asperities, lubricated_coefficients
from ballcvt.model.traction.contact import ContactState
from ballcvt.model.traction.quadrature import Quadrature

DESIGN, FLUID = fixed_oil_hub()[:2]
ASP = Asperities("mixed", 0.07e-6, 2.31e11, 0.1, 0.04, 1e-3)
# a hub input contact (as tests/test_lubrication.py)
STATE = ContactState(0.0175, -2.64, 4.04e-4, 4.87e-4, 7.55e8, 311.0, 0.07, 0.24, 8.28e-8)


def _law_rule(monkeypatch):
    """The difference on the law's own rule, as before session 25."""
    monkeypatch.setattr(lub, "FILM_SHARE_RULE", Quadrature())


@pytest.mark.parametrize("film", [0.5, 1.0, 2.0])
def test_the_column_on_the_coarse_rule_is_close_to_the_law_rules(monkeypatch, film):
    state = STATE.replace(film=film * ASP.roughness)
    coarse = lubricated_coefficients(state, FLUID, ASP, derivatives=True)
    _law_rule(monkeypatch)
    full = lubricated_coefficients(state, FLUID, ASP, derivatives=True)
    # the values and the other three columns are the law's rule's, exactly
    for a, b in zip(coarse[:2], full[:2]):
        assert a == b
    for a, b in zip(coarse[2:], full[2:]):
        assert np.array_equal(a[..., :3], b[..., :3])
        assert a[..., 3] != 0.0 and np.sign(a[..., 3]) == np.sign(b[..., 3])
    # measured: mu's column within 2.6 %, chi's within 10 %; both under 0.3 % of dmu's
    # largest entry, well inside the analytic Jacobian's own error (about 1 %, secant.py)
    assert coarse[2][..., 3] == pytest.approx(full[2][..., 3], rel=0.05)
    assert coarse[3][..., 3] == pytest.approx(full[3][..., 3], rel=0.15)
    assert abs(coarse[2][..., 3] - full[2][..., 3]) < 1e-3 * np.max(np.abs(full[2]))


def test_a_rule_coarser_than_it_keeps_its_own(monkeypatch):
    rule = Quadrature("centred", 8, 6, 6)
    got = lubricated_coefficients(STATE, FLUID, ASP, rule, derivatives=True)
    _law_rule(monkeypatch)
    want = lubricated_coefficients(STATE, FLUID, ASP, rule, derivatives=True)
    for a, b in zip(got, want):
        assert np.array_equal(a, b)


def test_the_equilibrium_does_not_depend_on_it(monkeypatch):
    v = Variator(DESIGN, FLUID)
    kw = {"ratio": 1.0, "output_torque": 4.19, "input_speed_rpm": 114.0, "clamp_law": "cam"}
    coarse = v.solve(**kw)
    _law_rule(monkeypatch)
    full = Variator(DESIGN, FLUID).solve(**kw)
    assert max(c.asperity_fraction for c in coarse.contacts.values()) > 0.0
    assert coarse.eta == pytest.approx(full.eta, abs=1e-10)
    assert coarse.clamp_force == pytest.approx(full.clamp_force, rel=1e-9)
