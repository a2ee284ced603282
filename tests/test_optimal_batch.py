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


def test_a_guess_near_the_optimum_gives_it_in_one_round_with_its_creeps():
    """Started from a force near the optimum (what a duty cycle's first pass hands its
    second), the search certifies its lattice stencil in one round (session 32): one
    batched solve of three forces per point, then one of the fourth force of each point's
    cubic, or, in a batch of at most `PREFETCH` points, one solve of the five lattice
    forces around each guess; the same force as from the cold start (both end on the same
    lattice stencil); its creeps start the solve that follows."""
    import ballcvt.solvers.optimal_lattice as ol
    import ballcvt.solvers.optimal_batch as ob

    v = Variator()
    pb = _points(v, [0.6, 1.0, 1.6], [10.0, 30.0, 50.0])
    cold = optimal_forces(pb, OptimalClamp(), v.options)
    calls = []
    score = ob._Scorer.__call__

    def counted(self, index, u, x0=None):
        calls.append(index.size)
        return score(self, index, u, x0)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(ob._Scorer, "__call__", counted)
        warm = optimal_forces(pb, OptimalClamp(), v.options, guess=cold.force * (1 + 1e-3))
        assert warm.fast.all() and calls == [15]
        calls.clear()
        mp.setattr(ol, "PREFETCH", 0)
        again = optimal_forces(pb, OptimalClamp(), v.options, guess=cold.force * (1 + 1e-3))
        assert again.fast.all() and calls == [9, 3]
        np.testing.assert_allclose(again.force, warm.force, rtol=1e-5)
    # the same lattice stencil: the forces to the cubic's sensitivity to the solves'
    # tolerance (SCORE_TOL), the efficiencies to far less
    np.testing.assert_allclose(warm.force, cold.force, rtol=1e-5)
    assert np.max(np.abs(_eta(v, pb, warm.force) - _eta(v, pb, cold.force))) <= 1e-10
    at = with_clamp(pb, warm.force)
    sol = solve_batch(at, v.options, warm.creep, predict=False)
    cold_start = solve_batch(at, v.options)
    assert sol.converged.all() and np.all(sol.iterations < cold_start.iterations)
    assert np.allclose(sol.state.creep, cold_start.state.creep, rtol=1e-8, atol=1e-12)
    # a guess far off still finds the optimum (the stencil walks to it)
    far = optimal_forces(pb, OptimalClamp(), v.options, guess=cold.force * 1.3)
    np.testing.assert_allclose(far.force, cold.force, rtol=1e-5)


def test_a_cycle_hands_its_first_pass_forces_to_the_second():
    """Under the optimal law a duty cycle's final pass starts each step's search from the
    first pass's force; each step's efficiency is still `solve`'s at its conditions
    (within the certification's bound, 1e-7)."""
    from ballcvt.analysis.cycle_files import cycle_from_arrays
    from ballcvt.analysis.cycles import run_cycle

    v = Variator()
    cycle = cycle_from_arrays(time=np.arange(4.0), output_speed=[150.0, 200.0, 260.0, 320.0],
                              output_torque=[8.0, 25.0, 40.0, 15.0])
    steps = run_cycle(v, cycle, target_input_speed=W, clamp_law="optimal",
                      progress=False).steps
    assert (steps["status"] == 0).all()
    for _, s in steps.iterrows():
        p = v.solve(s.ratio, s.output_torque, clamp_law="optimal",
                    input_speed_rpm=s.input_speed_rpm)
        assert abs(p.eta - s.eta) <= 1e-7


def test_the_first_round_runs_on_the_coarse_rule_in_a_batch_of_any_size(monkeypatch):
    """Without a guess the first round of stencils is solved on the coarse rule (session
    22; from session 24 a whole search, on the smooth search rule, to stencils of
    half-width 0.02; since session 32 one round on a wide stencil there, then the full
    rule's lattice from its vertex), alike in a batch of any size: the batch gives each
    point the force it gets
    searched alone (the same path: a table, a sweep and `solve` agree even where the
    efficiency has a kink near its optimum, harden task 0:28), and the one-point search's
    optimum to 1e-6 in efficiency."""
    import ballcvt.solvers.optimal_batch as ob

    v = Variator()
    ratio, torque = np.meshgrid([0.6, 0.9, 1.3, 1.8], [5.0, 20.0, 40.0])
    pb = _points(v, ratio.ravel(), torque.ravel())
    assert 3 * pb.size >= v.options.predictor_min_points
    rules, call = [], ob._Scorer.__call__

    def spy(self, index, u, x0=None):
        rules.append(self.options.quadrature)
        return call(self, index, u, x0)

    monkeypatch.setattr(ob._Scorer, "__call__", spy)
    got = optimal_forces(pb, OptimalClamp(), v.options)
    assert rules[0] == v.options.search_rule and rules[-1] == v.options.quadrature
    assert got.fast.all()
    rules.clear()
    alone = np.array([optimal_forces(pb.take([j]), OptimalClamp(), v.options).force[0]
                      for j in range(pb.size)])
    assert rules.count(v.options.search_rule) >= pb.size  # a coarse round each
    # the same lattice stencil and cubic (alone, its five forces solved in one call, from
    # other creeps: the values to SCORE_TOL, the cubic's maximum to ~1e-7)
    np.testing.assert_allclose(got.force, alone, rtol=1e-5)
    eta = _eta(v, pb, got.force)
    assert np.max(np.abs(eta - _eta(v, pb, alone))) <= 1e-10
    ref = np.array([o.eta for o in _old(v, pb)])
    assert np.max(np.abs(eta - ref)) <= 1e-6


def test_a_first_stencil_below_the_creep_bound_moves_up_past_it():
    """The hub at 5000 rpm, ratios 1.67-2, light torques: the first stencil, about
    ``F = 200 + 14 T``, lies wholly below the creep bound (no admissible force in it). The
    batched search moves up past it and certifies the one-point search's optimum; until
    session 22 these points left it for the one-point search (as did five of a 4 x 4
    thermal sweep's sixteen, 1.8 s each)."""
    v = Variator(*fixed_oil_hub())
    ratio = [5 / 3, 11 / 6, 11 / 6, 2.0, 2.0, 2.0]
    torque = [2.0, 2.0, 86 / 9, 2.0, 86 / 9, 154 / 9]
    pb = _points(v, ratio, torque, 5000.0 * math.pi / 30)
    first = optimal_forces(pb, OptimalClamp(), v.options, fallback=False)
    assert first.fast.all()
    eta = _eta(v, pb, first.force)
    ref = np.array([o.eta for o in _old(v, pb)])
    assert np.max(np.abs(eta - ref)) <= 1e-6


def test_a_large_batch_without_a_predictor_starts_from_its_seeds(monkeypatch):
    """A batch of at least SEED_MIN points on a rule without a predictor (a duty cycle's
    first pass) searches one point in SEED_STRIDE from `_guess` and starts the others'
    climbs from their nearest seed's optimum (session 34): the lattice's answer does not
    depend on its start, so the forces are the unseeded search's (to the solves' tolerance:
    on the search rule to 1e-11, the scores to 1e-9), with fewer evaluations."""
    from dataclasses import replace

    from ballcvt.solvers import optimal_batch
    from ballcvt.solvers.optimal_stencil import _Scorer

    v = Variator()
    rule = replace(v.options, quadrature=v.options.search_rule, predictor=None)
    rng = np.random.default_rng(34)
    n = 320
    assert n >= optimal_batch.SEED_MIN
    pb = _points(v, rng.uniform(0.6, 1.8, n), rng.uniform(2.0, 50.0, n),
                 rng.uniform(0.5, 1.5, n) * W)  # fmt: skip
    calls = []
    score = _Scorer.__call__

    def counted(self, index, u, x0=None):
        calls.append(np.size(index))
        return score(self, index, u, x0)

    monkeypatch.setattr(_Scorer, "__call__", counted)
    seeded = optimal_forces(pb, OptimalClamp(), rule, fallback=False)
    forces_seeded = sum(calls)
    calls.clear()
    monkeypatch.setattr(optimal_batch, "SEED_MIN", 10**9)
    plain = optimal_forces(pb, OptimalClamp(), rule, fallback=False)
    assert seeded.fast.sum() >= n - 2 and np.array_equal(seeded.fast, plain.fast)
    fast = seeded.fast
    np.testing.assert_allclose(seeded.force[fast], plain.force[fast], rtol=1e-5)
    assert forces_seeded < 0.8 * sum(calls)  # the wide round and most lattice moves saved


def test_seeds_start_their_neighbours_at_their_own_optima():
    from ballcvt.solvers.optimal_batch import _nearest

    v = Variator()
    pb = _points(v, [1.0, 1.0, 1.5, 1.0, 1.5], [10.0, 40.0, 10.0, 11.0, 12.0])
    seeds, u_seeds = np.array([0, 1, 2]), np.log([500.0, 900.0, 600.0])
    got = _nearest(pb, seeds, u_seeds, np.array([3, 4]))
    # each from its nearest seed, moved by `_guess`'s change: point 3 (ratio 1, 11 N m)
    # from seed 0 (10 N m); point 4 (ratio 1.5, 12 N m) from seed 2 (10 N m; the torque
    # times the ratio above 1)
    g = np.log(200 + 14 * np.array([10.0, 11.0, 15.0, 18.0]))
    assert got == pytest.approx([np.log(500.0) + g[1] - g[0], np.log(600.0) + g[3] - g[2]])
    assert np.isnan(_nearest(pb, np.array([], int), np.array([]), np.array([3]))).all()
