"""The thermal law in the drive (issue 23): empty row sets through the batched solvers,
and the branch of equilibria reached from zero torque (docs/model.md §8, §14)."""

import math

import numpy as np
import pytest

from ballcvt import Variator
from ballcvt.equilibrium.problem import build_problem
from ballcvt.solvers.clamped import solve_clamped
from ballcvt.solvers.limit import limit_search, solve_admissible
from ballcvt.solvers.newton import solve_batch, solve_pinned
from ballcvt.solvers.options import SolverOptions
from ballcvt.solvers.peak import peak_limits

RPM = math.pi / 30.0
THERMAL = Variator(traction_law="thermal")


def _empty(v):
    """A 1-D batch of no operating point, and its empty creeps ``(0, n_c)``."""
    pb = build_problem(v.design, v.fluid, v.architecture, np.array([0.5, 1.0]),
                       np.array([10.0, 10.0]), 2000.0, 2000.0 * RPM)
    none = pb.flat().take(np.array([], dtype=int))
    return none, np.zeros((0, none.layout.n_contacts))


@pytest.mark.parametrize("law", ["isothermal", "thermal"])
def test_batched_solvers_take_no_rows(law):
    """Every batched solver function answers an empty row set with empty arrays (before:
    `solve_pinned` raised "cannot reshape array of size 0 into shape (0,newaxis)", reached
    from `peak_limits` when no pinned solve of a disc contact was admissible)."""
    v = Variator(traction_law=law)
    none, x0 = _empty(v)
    options = SolverOptions()
    torque, sol = solve_pinned(none, 0, x0, options)
    assert torque.shape == (0,) and sol.state.creep.shape == x0.shape
    assert sol.converged.shape == (0,)
    assert solve_batch(none, options, x0).converged.shape == (0,)
    torque, creep = peak_limits(none, 0.1, options, x0)
    assert torque.shape == (0,) and creep.shape == x0.shape
    assert limit_search(none, 0.1, options).torque.shape == (0,)
    assert solve_admissible(none, 0.1, options).ok.shape == (0,)
    _, clamped = solve_clamped(none, v.clamp_law("cam"), lambda p, x: solve_batch(p, options, x))
    assert clamped.converged.shape == (0,)


def test_thermal_limit_where_a_contact_has_no_admissible_pin():
    """`ballcvt limit --traction-law thermal --ratio 0.5` crashed (internal error, exit 1):
    the input contact pinned at the first scanned creep is inadmissible there."""
    limit = THERMAL.limit_torque(ratio=0.5, clamp_force=2000.0, input_speed_rpm=2000.0)
    assert 100.0 < limit < 140.0
