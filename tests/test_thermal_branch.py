"""The thermal law in the drive (issue 23): empty row sets through the batched solvers,
and the branch of equilibria reached from zero torque (docs/model.md §8, §14)."""

import math
from dataclasses import replace

import numpy as np
import pytest

from ballcvt import Variator
from ballcvt.errors import TractionLimitError
from ballcvt.equilibrium.problem import build_problem
from ballcvt.solvers.clamped import solve_clamped
from ballcvt.solvers.limit import limit_search, solve_admissible
from ballcvt.solvers.newton import on_branch, solve_batch, solve_pinned
from ballcvt.solvers.options import SolverOptions, at_residual_floor
from ballcvt.solvers.peak import peak_limits
from ballcvt.registry import TRACTION_LAWS

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


#: Where the thermal drive has two equilibria (docs/model.md §14): Table I's drive at 2 kN,
#: 1000 rpm, the second of 12 ratios across its range (0.7176) and 130 N m (limit 131.9 N m):
#: efficiency 0.9247 on the branch from zero torque, 0.8935 past its fold.
RATIOS = np.linspace(*THERMAL.ratio_range, 12)
SLOW = {"clamp_force": 2000.0, "input_speed_rpm": 1000.0}
ON_BRANCH = 0.9246607  # at RATIOS[1] (0.92466273 at 0.718, followed in 1 N m steps)


def test_registry_says_which_law_follows_the_branch():
    assert TRACTION_LAWS.get("thermal").multiple_equilibria
    assert not TRACTION_LAWS.get("isothermal").multiple_equilibria
    assert not TRACTION_LAWS.get("viscoelastic").multiple_equilibria


def test_solve_and_sweeps_return_the_equilibrium_reached_from_zero_torque():
    """Before: the sweep over 0-160 N m reached the other equilibrium (0.8935) at 130 N m
    where `Variator.solve` reached 0.9247."""
    ds = THERMAL.sweep(ratio=RATIOS, output_torque=np.linspace(0.0, 160.0, 17), **SLOW)
    swept = float(np.asarray(ds.eta).reshape(12, 17)[1, 13])
    alone = THERMAL.sweep(ratio=[RATIOS[1]], output_torque=[130.0], **SLOW)
    solved = THERMAL.solve(ratio=float(RATIOS[1]), output_torque=130.0, **SLOW).eta
    assert solved == pytest.approx(ON_BRANCH, abs=1e-6)
    assert swept == pytest.approx(solved, abs=1e-8)
    assert float(np.asarray(alone.eta).squeeze()) == pytest.approx(solved, abs=1e-8)


def test_thermal_solve_ignores_its_start():
    """`solve_batch` under the thermal law follows each point from zero torque whatever
    ``x0``: a start past the fold gives the same equilibrium."""
    pb = build_problem(THERMAL.design, THERMAL.fluid, THERMAL.architecture,
                       np.array([RATIOS[1]]), np.array([130.0]), 2000.0, 1000.0 * RPM)
    cold = solve_batch(pb)
    far = solve_batch(pb, x0=np.array([0.06, 0.0, 0.0, 0.06]))
    assert cold.converged.all() and far.converged.all()
    np.testing.assert_allclose(far.state.creep, cold.state.creep, rtol=0, atol=1e-12)


@pytest.mark.parametrize("ratio, rpm", [(0.5, 2000.0), (float(RATIOS[1]), 1000.0),
                                        (1.8, 5000.0), (float(RATIOS[8]), 1000.0)])
def test_thermal_limit_is_the_largest_torque_solve_reaches(ratio, rpm):
    """The limit search follows the same branch as the solve: the solve succeeds 1e-3
    below the limit and is refused 1e-3 above it. Before, at high ratios (the ninth of
    12, 4.64), the limit search found no limit where the solve succeeded."""
    kw = {"clamp_force": 2000.0, "input_speed_rpm": rpm}
    limit = THERMAL.limit_torque(ratio=ratio, **kw)
    assert limit > 0
    below = THERMAL.solve(ratio=ratio, output_torque=limit * (1 - 1e-3), **kw)
    creeps = [abs(c.creep) for c in below.contacts.values()]
    assert max(creeps) <= THERMAL.design.creep_limit * (1 + 1e-9)
    with pytest.raises(TractionLimitError):
        THERMAL.solve(ratio=ratio, output_torque=limit * (1 + 1e-3), **kw)


def test_a_start_past_the_fold_is_refused_by_the_branch_check():
    """`solve_batch` with ``below`` (the creeps at the limit, as a sweep passes them):
    Newton from a start past the fold reaches the other equilibrium (0.8935), whose
    output creep lies beyond the limit's; `on_branch` refuses it and the point is
    followed from zero torque to the branch's (0.9247). From a start on the branch the
    direct solve is kept, with fewer residual evaluations than the continuation."""
    pb = build_problem(THERMAL.design, THERMAL.fluid, THERMAL.architecture,
                       np.array([RATIOS[1]]), np.array([130.0]), 2000.0, 1000.0 * RPM)
    options = at_residual_floor(SolverOptions(), THERMAL.fluid)
    flat = pb.flat()
    limit, at_limit = peak_limits(replace(flat, output_torque=np.zeros(1)), 0.1, options)
    assert limit[0] > 130.0
    far = np.array([[0.06, 0.0, 0.0, 0.06]])
    branch = solve_batch(pb, options, far)  # followed from zero torque
    alone = _newton_alone(flat, options, far)
    assert alone.converged.all() and not on_branch(alone.state.creep, at_limit)[0]
    checked = solve_batch(pb, options, far, below=at_limit)
    assert checked.converged.all()
    np.testing.assert_allclose(checked.state.creep, branch.state.creep, rtol=0, atol=1e-9)
    near = solve_batch(pb, options, branch.state.creep * 0.98, below=at_limit)
    assert near.converged.all() and near.iterations[0] < branch.iterations[0]
    np.testing.assert_allclose(near.state.creep, branch.state.creep, rtol=0, atol=1e-9)


def _newton_alone(flat, options, x0):
    """Newton from ``x0`` without the continuation (what `solve_batch` tries first when
    given ``below``)."""
    from ballcvt.solvers.newton import _solve_flat

    return _solve_flat(flat, np.array(x0, dtype=float), options, False, True)


def test_a_solve_next_to_the_cam_limit_stays_below_the_fold():
    """Table I's thermal cam sweep at ratio 1.83 (2000 rpm): its capacity is the fold of the
    branch. Before session 29 the continuation's step onto a torque within 1e-4 of the
    fold could land on the equilibrium past it (at 0.9999 of the limit an input creep of
    0.04674, above the limit's 0.04652; the efficiency 0.91232, below the limit's), and
    the sweep reported that equilibrium's efficiency at the limit. Along the branch the
    creep grows and the efficiency falls with the torque up to the fold
    (`ballcvt.solvers.held_creep.turned_back` tells the two equilibria apart)."""
    ratio, kw = 1.8333333333333333, {"clamp_law": "cam", "input_speed_rpm": 2000.0}
    limit = THERMAL.limit_torque(ratio, **kw)
    got = [THERMAL.solve(ratio, limit * f, **kw) for f in (0.999, 0.9999, 0.99999, 1.0)]
    creep = [r.contacts["input"].creep for r in got]
    eta = [r.eta for r in got]
    assert np.all(np.diff(creep) > 0) and np.all(np.diff(eta) < 0)


def test_a_solve_from_nearby_creeps_keeps_the_branch():
    """`solve_near` (the optimal clamp's stencils): from the creeps of the branch at a
    force 2 % away, Newton's solution is kept (the branch's, to 1e-8); from the creeps
    of the equilibrium past the fold at the same torque (Table I, ratio 1, 2 kN, fold at
    114.78 N m: the input creep held at 0.05, past the fold's, gives 108.0 N m there),
    Newton converges at once to that equilibrium, which the fold test refuses, and the
    point is followed from zero torque to the branch's."""
    from ballcvt.solvers.newton import solve_near

    options = at_residual_floor(SolverOptions(), THERMAL.fluid)

    def at(torque, force):
        return build_problem(THERMAL.design, THERMAL.fluid, THERMAL.architecture,
                             np.array([1.0]), np.array([torque]), force,
                             np.array([2000.0 * RPM])).flat()  # fmt: skip

    near = solve_batch(at(100.0, 2040.0), options)
    ref = solve_batch(at(100.0, 2000.0), options)
    got = solve_near(at(100.0, 2000.0), options, near.state.creep)
    assert near.converged.all() and ref.converged.all() and got.converged.all()
    np.testing.assert_allclose(got.state.creep, ref.state.creep, rtol=0, atol=1e-8)

    x_up = np.array(ref.state.creep)
    x_up[:, 0] = 0.05
    t_up, up = solve_pinned(at(0.0, 2000.0), 0, x_up, options)
    assert up.converged.all() and 100.0 < t_up[0] < 114.78
    below = solve_batch(at(float(t_up[0]), 2000.0), options)
    got = solve_near(at(float(t_up[0]), 2000.0), options, up.state.creep)
    assert below.converged.all() and got.converged.all()
    assert below.state.creep[0, 0] < 0.045  # the branch's, below the fold
    np.testing.assert_allclose(got.state.creep, below.state.creep, rtol=0, atol=1e-8)
