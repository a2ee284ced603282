"""One batch of held-creep solves whatever contact each point holds (session 36): the
walk along a thermal branch, the climb to its fold and the fold test each ran one batch
of `solve_pinned` per held contact, one after the other."""

from __future__ import annotations

import math

import numpy as np

from ballcvt import Variator
from ballcvt.equilibrium.problem import build_problem
from ballcvt.solvers.newton import solve_pinned
from ballcvt.solvers.newton_step import free_creeps
from ballcvt.solvers.options import at_residual_floor

THERMAL = Variator(traction_law="thermal")
OPTIONS = at_residual_floor(THERMAL.options, THERMAL.fluid)


def test_free_creeps():
    """All creeps, or all but the held one per point, in increasing order."""
    assert free_creeps(4, 2).tolist() == [[0, 1, 2, 3]] * 2
    assert free_creeps(4, 2, 3).tolist() == [[0, 1, 2]] * 2
    assert free_creeps(4, 3, np.array([0, 3, 1])).tolist() == [[1, 2, 3], [0, 1, 2], [0, 2, 3]]


def test_one_batch_gives_each_points_own_solve_to_the_bit():
    """Table I under the thermal law, four ratios, each held at the input disc's contact
    and at the output disc's: one batch with the held contact per point gives the torques
    and creeps of the two batches of one held contact each, bit for bit (a point's
    iterates do not depend on its batch, `ballcvt.solvers.secant`)."""
    ratios = np.array([0.6, 0.9, 1.4, 1.9])
    pb = build_problem(THERMAL.design, THERMAL.fluid, THERMAL.architecture, ratios,
                       np.zeros(4), 2000.0, 2000.0 * math.pi / 30).flat()  # fmt: skip
    nc = pb.layout.n_contacts
    held = np.array([0, nc - 1, nc - 1, 0])
    x0 = np.zeros((4, nc))
    x0[np.arange(4), held] = 0.003
    torque, sol = solve_pinned(pb, held, x0, OPTIONS)
    for k in (0, nc - 1):
        j = np.flatnonzero(held == k)
        t_k, sol_k = solve_pinned(pb.take(j), k, x0[j], OPTIONS)
        assert np.array_equal(torque[j], t_k)
        assert np.array_equal(sol.state.creep[j], sol_k.state.creep)
        assert np.array_equal(sol.state.creep[j, k], x0[j, k])  # held where it was put
    assert np.all(sol.converged) and np.all(torque > 0)  # (both creeps grow with T_2)
