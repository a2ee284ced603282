"""The thermal law's total derivatives (the film temperature's response included) are
computed by a compiled loop with the NumPy path's operations in the NumPy path's order
(issue 26): the same bits, NaN where the NumPy path gives NaN."""

import numpy as np
import pytest

from ballcvt import Variator
from ballcvt.model.traction import thermal, thermal_kernels
from ballcvt.model.traction.contact import ContactState

pytestmark = pytest.mark.skipif(
    thermal_kernels.total_derivatives is None, reason="numba is not installed"
)


@pytest.fixture(scope="module")
def fluid():
    return Variator(traction_law="thermal").fluid


def _state(n, seed):
    rng = np.random.default_rng(seed)
    return ContactState(rng.uniform(-0.05, 0.05, n), rng.uniform(-0.2, 0.2, n), 1.2e-3,
                        0.45e-3, rng.uniform(0.8e9, 2.5e9, n), 2000.0, 0.03,
                        rng.uniform(2.0, 30.0, n), 1.5e-7)  # fmt: skip


@pytest.mark.parametrize("film", [False, True])
def test_compiled_totals_are_the_numpy_paths_bits(fluid, film, monkeypatch):
    con, shape = thermal._Contacts.from_state(_state(300, 3), fluid)
    values = list(thermal._rise_and_coefficients(con, thermal.Quadrature())[1:])
    values[0] = values[0].copy()
    values[0][:3] = np.nan  # a NaN coefficient propagates alike
    compiled = thermal._with_derivatives(con, values, shape, film)
    monkeypatch.setattr(thermal_kernels, "total_derivatives", None)
    reference = thermal._with_derivatives(con, values, shape, film)
    assert compiled[2].shape == (300, 4 if film else 3)
    for got, want in zip(compiled, reference):
        assert np.array_equal(got, want, equal_nan=True)
    assert np.all(np.isnan(compiled[2][:3])) and np.all(np.isfinite(compiled[2][3:]))


def test_a_subset_of_contacts_drops_the_stacked_inputs(fluid):
    con, _ = thermal._Contacts.from_state(_state(10, 4), fluid)
    assert con.par.shape == (9, 10)
    sub = con.take(np.arange(4))
    assert sub.par is None and sub.c.shape == (4,)
    # the sub-batch's coefficients are those of the same contacts in the whole batch
    whole = thermal._rise_and_coefficients(con, thermal.Quadrature())
    part = thermal._rise_and_coefficients(sub, thermal.Quadrature())
    np.testing.assert_allclose(part[1], whole[1][:4], rtol=1e-12)
