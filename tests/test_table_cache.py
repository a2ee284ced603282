"""The kernels' viscosity tables are cached by the fluid values they depend on (issue 26).

An oil balance or an uncertainty run meets hundreds of oil temperatures, each a new
`Fluid`: keyed by the whole fluid, the boundary law's table (16 MB, the same for every
temperature) was rebuilt at each, and the film's thrashed a 32-entry cache (2,415 builds
for 426 fluids in a two-sample `ballcvt uncertainty`: 138 s, now 88 s).
"""

from __future__ import annotations

import numpy as np

from ballcvt import load_builtin
from ballcvt.model import oil
from ballcvt.model.lubrication import _coulomb_fluid, asperities
from ballcvt.model.traction import isothermal
from ballcvt.model.traction.isothermal import TableFluid, kernel_table
from ballcvt.model.traction.kernels import viscosity_table


def _fresh(monkeypatch, budget=None):
    from collections import OrderedDict

    monkeypatch.setattr(isothermal, "_tables", OrderedDict())
    if budget is not None:
        monkeypatch.setattr(isothermal, "TABLE_CACHE_BYTES", budget)


def test_the_boundary_law_shares_one_table_across_oil_temperatures(monkeypatch):
    _fresh(monkeypatch)
    d, f = load_builtin("hub")
    asp = asperities(d)
    warm, hot = (oil.fluid_at(f, t) for t in (313.15, 353.15))
    assert warm.roelands_index != hot.roelands_index  # the oil's own values differ
    a, b = (_coulomb_fluid(x, asp.boundary_friction, asp.creep_stiffness) for x in (warm, hot))
    assert a != b and TableFluid.of(a) == TableFluid.of(b)
    first, second = kernel_table(a, 1e9), kernel_table(b, 1e9)
    assert first is second and len(isothermal._tables) == 1
    # the same bits as the table of the fluid itself (the keyed-away values multiply zero)
    fl, tab = viscosity_table(b, isothermal.table_pressure(1e9))
    assert np.array_equal(first[0], fl) and np.array_equal(first[1], tab)


def test_a_fluid_with_pressure_growth_keeps_its_own_table(monkeypatch):
    _fresh(monkeypatch)
    _, f = load_builtin("table1")
    other = f.model_copy(update={"roelands_index": f.roelands_index * 1.01})
    assert kernel_table(f, 1e9) is not kernel_table(other, 1e9)
    fl, tab = viscosity_table(f, isothermal.table_pressure(1e9))
    assert np.array_equal(kernel_table(f, 1e9)[1], tab)


def test_the_cache_keeps_within_its_byte_budget(monkeypatch):
    _, f = load_builtin("table1")
    one = viscosity_table(f, isothermal.table_pressure(1e9))[1].nbytes
    _fresh(monkeypatch, budget=int(2.5 * one))
    fluids = [f.model_copy(update={"viscosity": f.viscosity * (1 + k / 100)}) for k in range(5)]
    tables = [kernel_table(x, 1e9) for x in fluids]
    assert len(isothermal._tables) == 2  # the two most recent
    assert kernel_table(fluids[-1], 1e9) is tables[-1]
    assert kernel_table(fluids[0], 1e9) is not tables[0]  # dropped, rebuilt: equal
    assert np.array_equal(kernel_table(fluids[0], 1e9)[1], tables[0][1])
