"""The branch from zero torque followed in a disc contact's held creep
(`ballcvt.solvers.held_creep`), and the thermal law's residual floor (harden task 2028:592:
the limiting torque at one force ranged from 55 % to 99.98 % of the fold with the batch)."""

import math
from dataclasses import replace

import numpy as np
import pytest

from ballcvt import Variator
from ballcvt.equilibrium.problem import build_problem
from ballcvt.equilibrium.residual import evaluate
from ballcvt.model.traction.base import THERMAL_RESIDUAL_FLOOR, residual_floor
from ballcvt.solvers.continuation import solve_twice
from ballcvt.solvers.held_creep import reach_torque
from ballcvt.solvers.limit import limit_torque_batch
from ballcvt.solvers.newton import branch_pinned, branch_solver, solve_batch
from ballcvt.solvers.options import SolverOptions, at_residual_floor
from drives import fixed_oil_hub

RPM = math.pi / 30.0
THERMAL = Variator(traction_law="thermal")
OPTIONS = at_residual_floor(SolverOptions(), THERMAL.fluid)


def _problem(torque, ratio=0.7176, force=2000.0, rpm=1000.0):
    torque = np.atleast_1d(np.asarray(torque, dtype=float))
    pb = build_problem(THERMAL.design, THERMAL.fluid, THERMAL.architecture,
                       np.full(torque.size, ratio), torque, force, rpm * RPM)
    return pb.flat()


def _reach(target, start):
    """`reach_torque` to ``target`` from the equilibrium the solver finds at ``start``."""
    low = solve_batch(_problem(start), OPTIONS)
    assert low.converged.all()
    solve = branch_solver(OPTIONS)
    pinned, tol = branch_pinned(OPTIONS)

    def at_torque(pb, x0):
        good, x, _ = solve_twice(solve, pb, x0)
        return good, x

    flat = _problem(target)
    return flat, reach_torque(flat, pinned, at_torque, tol, np.full(flat.size, start),
                              low.state.creep)


def test_the_thermal_law_declares_its_residual_floor():
    """The thermal law's solves stop at 1e-9, the paper's law's at the options' 1e-11."""
    assert residual_floor(THERMAL.fluid) == THERMAL_RESIDUAL_FLOOR == 1e-9
    assert residual_floor(Variator().fluid) == 0.0
    assert at_residual_floor(SolverOptions(), Variator().fluid) == SolverOptions()
    assert OPTIONS.tol == 1e-9
    assert at_residual_floor(replace(SolverOptions(), tol=1e-6), THERMAL.fluid).tol == 1e-6


def test_reach_meets_the_equilibrium_solve_finds_below_the_fold():
    """From the equilibrium at 40 % of the limit, the held-creep walk reaches the one the
    continuation reaches at 99 % of it (the branch's, not the one past its fold)."""
    limit = float(limit_torque_batch(_problem(0.0), THERMAL.design.creep_limit, OPTIONS)[0])
    target = 0.99 * limit
    flat, (ok, creep) = _reach(target, 0.4 * limit)
    ref = solve_batch(flat, OPTIONS)
    assert ok.all() and ref.converged.all()
    np.testing.assert_allclose(creep, ref.state.creep, rtol=1e-6, atol=1e-9)
    assert np.abs(evaluate(flat, creep, OPTIONS.quadrature).residual).max() <= OPTIONS.tol


def test_reach_refuses_a_torque_past_the_fold():
    """Past the fold there is no equilibrium on the branch: not reached, start returned."""
    limit = float(limit_torque_batch(_problem(0.0), THERMAL.design.creep_limit, OPTIONS)[0])
    low = solve_batch(_problem(0.4 * limit), OPTIONS)
    flat, (ok, creep) = _reach(1.01 * limit, 0.4 * limit)
    assert not ok.any()
    np.testing.assert_array_equal(creep, low.state.creep)


@pytest.mark.parametrize("n", [1, 4])
def test_the_thermal_limit_does_not_depend_on_the_batch(n):
    """One force, solved alone or among neighbours 1e-9 apart: one limiting torque (at
    1e-11 the limits of harden task 2028:592 scattered from 55 % to 99.98 % of its fold;
    here Table I's drive near its fold at 2 kN, 1000 rpm)."""
    force = 2000.0 * (1.0 + 1e-9 * np.arange(n))
    flat = _problem(np.zeros(n), force=force)
    got = limit_torque_batch(flat, THERMAL.design.creep_limit, OPTIONS)
    alone = limit_torque_batch(_problem(0.0), THERMAL.design.creep_limit, OPTIONS)
    np.testing.assert_allclose(got, alone[0], rtol=1e-7)


#: Harden task 2028:592's drive (thermal law, single idler, a table point at ratio 3.2449,
#: 2,923 rpm): ``python benchmarks/harden.py --task 2028:592``.
TASK_592 = {
    "aspect_ratio": 4.06510489508759, "roller_radius": 0.01301462966409797,
    "theta0_deg": 61.84685716541423, "theta2_deg": 58.77649566144684,
    "alpha_deg": 3.0978972058559826, "n_rollers": 11,
    "roller_bearing_diameter": 0.002127010627997154,
    "idler_bearing_diameter": 0.0013707809295214492,
    "disc_groove_ratio": 2.5610840866965194, "idler_groove_ratio": 2.0640373328550536,
    "single_idler_groove_ratio": math.inf, "tilt_safety_factor": 0.8011692459418861,
    "creep_limit": 0.17678138423074236, "min_roller_gap": 0.002819800692452254,
}


def test_task_592_limit_at_one_force_whatever_the_batch():
    """At 1e-11 the limits at forces 1e-6 apart near 1,384 N were 3.86, 3.79, 3.87, 2.16 N m
    (a continuation step failing at the noise floor ended the branch early), and a table
    called a torque the drive carries "beyond capacity"; at the floor they are the fold's
    (3.873 N m, the march to the fold's 3.874 less `FOLD_MARGIN`) to 1e-5."""
    from ballcvt import load_builtin

    design, fluid = fixed_oil_hub()
    v = Variator(design.replace(name="random", **TASK_592), fluid, "single",
                 traction_law="thermal")
    force = 1384.09 * (1.0 + 1e-6 * np.arange(4))
    pb = build_problem(v.design, v.fluid, v.architecture, np.full(4, 3.24493014),
                       np.zeros(4), force, 2923.41384283 * RPM).flat()
    got = limit_torque_batch(pb, v.design.creep_limit, SolverOptions())
    np.testing.assert_allclose(got, got[0], rtol=1e-5)
    assert 3.85 < got[0] < 3.88
