"""The boundary shear's own rule (`ballcvt.model.lubrication.boundary_rule`, session 36):
half the law's angular nodes, as accurate as the law's rule against a fine one."""

from __future__ import annotations

import numpy as np
import pytest
from drives import fixed_oil_hub

from ballcvt.model.lubrication import BOUNDARY_ANGULAR, boundary_coefficients, boundary_rule
from ballcvt.model.traction.contact import ContactState
from ballcvt.model.traction.quadrature import Quadrature

FLUID = fixed_oil_hub()[1]
MU_B = 0.1
# a hub input contact (as in tests/test_lubrication_boundary.py), over creeps from the
# elastic range (slip scale 6.8e-4) to sliding and spins of either sign, the pole inside
# and outside the ellipse
CREEP, SPIN = np.meshgrid([2e-4, 1e-3, 5e-3, 0.05, 0.5], [-12.0, -2.64, -0.3, 0.0, 1.5, 6.0])
STATE = ContactState(CREEP.ravel(), SPIN.ravel(), 4.04e-4, 4.87e-4, 7.55e8, 311.0, 0.07,
                     0.24, 8.28e-8)  # fmt: skip
FINE = Quadrature("pole", 64, 48, 64)


def _error(q):
    """Largest error of ``M`` and of ``N`` on ``q`` against `FINE`."""
    got = boundary_coefficients(STATE, FLUID, MU_B, q, False)
    ref = boundary_coefficients(STATE, FLUID, MU_B, FINE, False)
    return [float(np.max(np.abs(g - r))) for g, r in zip(got, ref)]


def test_the_rule():
    """Half the angular nodes of a pole-centred rule, no fewer than `BOUNDARY_ANGULAR`;
    the radial and the centred fan's nodes and the engine as the law's."""
    assert boundary_rule(Quadrature()) == Quadrature("pole", 32, 12, 32)
    assert boundary_rule(Quadrature("pole", 64, 48, 64, "numpy")) == Quadrature(
        "pole", 64, 24, 64, "numpy"
    )
    assert boundary_rule(Quadrature("pole", 32, 16, 32)).n_angular == BOUNDARY_ANGULAR
    for q in (Quadrature("pole", 16, 8, 16), Quadrature("centred", 32, 24, 32)):
        assert boundary_rule(q) is q


def test_as_accurate_as_the_laws_rule():
    """Against 64 x 48 x 64 nodes, ``M`` and ``N`` on the boundary rule of the default
    32 x 24 x 32 are off by what the default is off by, within 5 % (the radial nodes set
    it); 8 angular nodes instead of 12 are at least 3 times worse (the floor)."""
    default = _error(Quadrature())
    halved = _error(boundary_rule(Quadrature()))
    for d, h in zip(default, halved):
        assert h <= 1.05 * d + 1e-9
    eight = _error(Quadrature("pole", 32, 8, 32))
    assert eight[0] >= 3.0 * halved[0]


@pytest.mark.parametrize("engine", ["auto", "numpy"])
def test_both_engines(engine):
    """The compiled kernels and the NumPy path give the same sums on the halved rule."""
    q = boundary_rule(Quadrature(engine=engine))
    got = boundary_coefficients(STATE, FLUID, MU_B, q, True)
    ref = boundary_coefficients(STATE, FLUID, MU_B, boundary_rule(Quadrature()), True)
    for g, r in zip(got, ref):
        np.testing.assert_allclose(g, r, rtol=1e-9, atol=1e-12)
