"""The batched efficiency-optimal clamp (issue 26): the same optimum as the one-point
search (`search_optimum`) to 1e-6 in efficiency, zero torque, refusals unchanged."""

import math

import numpy as np
import pytest

from ballcvt import InputError, Variator, load_builtin
from ballcvt.analysis.sweeps.curves import at_optimal_forces
from ballcvt.equilibrium.problem import build_problem
from ballcvt.model.clamping import OptimalClamp
from ballcvt.performance.efficiency import efficiency
from ballcvt.solvers.clamped import with_clamp
from ballcvt.solvers.newton import solve_batch
from ballcvt.solvers.optimal_batch import optimal_forces
from ballcvt.solvers.optimal_search import ClampCase, search_optimum
from drives import fixed_oil_hub

W = 2000.0 * math.pi / 30


def _points(v, ratio, torque, speed=W):
    return build_problem(v.design, v.fluid, v.architecture, np.asarray(ratio, float),
                         np.asarray(torque, float), 1000.0, speed)


def _eta(v, pb, force):
    at = with_clamp(pb, force)
    return efficiency(at, solve_batch(at, v.options).state).overall


def _old(v, pb, law=OptimalClamp()):
    out = []
    for j in range(pb.size):
        case = ClampCase(v.design, v.fluid, v.architecture, float(pb.ratio[j]),
                         float(pb.output_torque[j]), float(pb.input_speed[j]))
        out.append(search_optimum(case, law, v.options))
    return out


@pytest.mark.parametrize("traction_law", [None, "viscoelastic"])
def test_same_optimum_as_the_one_point_search(traction_law):
    d, f = load_builtin("table1")
    v = Variator(d, f, "double", traction_law=traction_law) if traction_law else Variator()
    ratio, torque = np.meshgrid([0.6, 1.0, 1.8], [0.0, 5.0, 40.0])
    pb = _points(v, ratio.ravel(), torque.ravel())
    got = optimal_forces(pb, OptimalClamp(), v.options)
    assert got.fast.all() and not got.refused.any()
    old = _old(v, pb)
    eta = _eta(v, pb, got.force)
    ref = np.array([o.eta for o in old])
    assert np.max(np.abs(eta - ref)) <= 1e-6
    zero = pb.output_torque == 0
    assert np.all(got.force[zero] == OptimalClamp().min_force)
    assert np.allclose(got.force, [o.clamp_force for o in old], rtol=5e-3)


def test_hub_speeds_and_creep_limited_zero_torque():
    """The hub at 5000 rpm: zero torque needs more than min_force to hold the drag (the
    one-point search's creep bound, handed over), the others are found batched."""
    v = Variator(*fixed_oil_hub())
    pb = _points(v, [2.0, 2.0, 0.8], [0.0, 30.0, 60.0], 5000.0 * math.pi / 30)
    got = optimal_forces(pb, OptimalClamp(), v.options)
    old = _old(v, pb)
    assert not got.fast[0] and got.force[0] == old[0].clamp_force > OptimalClamp().min_force
    assert got.fast[1:].all()
    eta = _eta(v, pb, got.force)
    assert np.max(np.abs(eta - [o.eta for o in old])) <= 1e-6


def test_refusals_unchanged():
    v = Variator()
    with pytest.raises(InputError, match=">= 0 N m"):
        optimal_forces(_points(v, [1.0, 1.0], [10.0, -1.0]), OptimalClamp(), v.options)
    with pytest.raises(InputError, match="max_pressure"):
        optimal_forces(_points(v, [1.0], [10.0]), OptimalClamp(max_pressure=float("nan")),
                       v.options)
    pb = _points(v, [1.0, 1.0], [20.0, 1e4])
    got = optimal_forces(pb, OptimalClamp(), v.options)
    assert list(got.refused) == [False, True] and math.isnan(got.force[1])
    at = at_optimal_forces(pb, OptimalClamp(), v.options)  # a refused point keeps its force
    assert at.clamp_force[1] == pb.clamp_force[1] and at.clamp_force[0] == got.force[0]
