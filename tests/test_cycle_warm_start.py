"""A duty cycle's second pass starts from its first pass's creeps (session 24, issue 26)."""

import numpy as np
import pytest

from ballcvt import Variator
from ballcvt.analysis.cycle_files import cycle_from_arrays
from ballcvt.equilibrium.problem import build_problem
from ballcvt.model.clamping import OptimalClamp
from ballcvt.solvers.options import coarse_options
from ballcvt.solvers.optimal_batch import STEP, optimal_forces

W = 2000 * np.pi / 30
CYCLE = cycle_from_arrays(time=np.arange(6.0), output_speed=[15.0, 20.0, 25.0, 30.0, 35.0, 40.0],
                          output_torque=[5.0, 12.0, 20.0, 30.0, 0.0, 25.0])


def _points(v, ratio, torque):
    return build_problem(v.design, v.fluid, v.architecture, np.asarray(ratio, float),
                         np.asarray(torque, float), 1000.0, W)


@pytest.mark.parametrize("clamp", [{"clamp_force": 1500.0}, {"clamp_law": "cam"},
                                   {"clamp_law": "optimal"}])
def test_the_second_pass_starts_from_the_first_pass_creeps(monkeypatch, clamp):
    """The first pass's creeps (coarse rule, nearby ratio) start the second pass's solves
    without the predictor stage (under the optimal clamp: its search's first stencils),
    and the answer is the cold start's to the solver's tolerance."""
    import ballcvt.analysis.cycles as cycles
    import ballcvt.analysis.sweeps.points as points

    v = Variator()
    starts, real = [], points.evaluate_points

    def spy(rows, torque, *args, **kwargs):
        starts.append(kwargs.get("start"))
        return real(rows, torque, *args, **kwargs)

    monkeypatch.setattr(cycles, "evaluate_points", spy)
    speed = 180 * np.pi / 30
    warm = cycles.run_cycle(v, CYCLE, target_input_speed=speed, progress=False, **clamp)
    assert starts[0] is None and starts[1].shape == (CYCLE.size - 1, 4)  # idle step left
    assert np.isfinite(starts[1]).all()

    monkeypatch.setattr(cycles, "evaluate_points",
                        lambda rows, torque, *a, **k: real(rows, torque, *a,
                                                           **{**k, "start": None}))
    cold = cycles.run_cycle(v, CYCLE, target_input_speed=speed, progress=False, **clamp)
    np.testing.assert_allclose(warm.steps["eta"], cold.steps["eta"], rtol=0, atol=1e-8)
    # the optimal force to the search's resolution in ln F_N0 (its solves stop at
    # SCORE_TOL, so the vertex moves with the start by up to some 5e-5)
    np.testing.assert_allclose(warm.steps["clamp_force"], cold.steps["clamp_force"],
                               rtol=STEP)


def test_optimal_forces_from_guessed_creeps_point_by_point():
    """Given forces and creeps near the optima (a coarse pass's), each point starts from its
    own creeps (the cold start where it has none): a batch with a missing row certifies
    the forces each point gets alone, and those of the search without creeps."""
    v = Variator()
    pb = _points(v, [0.6, 1.0, 1.5, 2.0], [10.0, 25.0, 40.0, 20.0])
    first = optimal_forces(pb, OptimalClamp(), coarse_options(v.options, search=True))
    creep = first.creep.copy()
    creep[2] = np.nan  # no creeps for the third point
    got = optimal_forces(pb, OptimalClamp(), v.options, guess=first.force, creep=creep)
    assert got.fast.all()
    alone = [optimal_forces(pb.take([j]), OptimalClamp(), v.options, guess=first.force[j],
                            creep=creep[j:j + 1]).force[0] for j in range(pb.size)]
    np.testing.assert_allclose(got.force, alone, rtol=1e-9)
    plain = optimal_forces(pb, OptimalClamp(), v.options, guess=first.force)
    np.testing.assert_allclose(got.force, plain.force, rtol=1e-5)
