"""Drives the tests build (a helper module, not a test file)."""

from __future__ import annotations

import ballcvt


def fixed_oil_hub():
    """``load_builtin("hub")`` with its ``[models] oil_temperature`` set to ``"fixed"``:
    ``(design, fluid)`` with the fluid at its own 40 C.

    The hub's drive file balances the oil against its shell (docs/model.md §15). Tests of
    other physics (clamping, losses, capacity, cycles, life, shifting) pin the oil so that
    their figures do not move with the balance and run at the fixed oil's cost; the
    balance itself is tested in tests/test_oil_*.py and tests/test_hub_models.py.
    """
    design, fluid = ballcvt.load_builtin("hub")
    models = design.models.model_copy(update={"oil_temperature": "fixed"})
    return design.model_copy(update={"models": models}), fluid
