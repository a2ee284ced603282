"""The fast batched solver against the high-order reference (issue: >= 2000 points/s at
|eta error| <= 1e-4). Targets: max |eta - eta_ref| <= 1e-4, relative creep error <= 1e-3
(creeps above 1e-6), reference = pole-centred rule at 64 x 64 (centred part 128)."""

import warnings

import numpy as np
import pytest
from hypothesis import given
from test_invariants import cases

from ballcvt import Quadrature, SolverOptions
from ballcvt.equilibrium.problem import build_problem
from ballcvt.equilibrium.residual import evaluate, evaluate_with_jacobian
from ballcvt.model.traction.contact import ContactState, contact_coefficients
from ballcvt.performance.efficiency import efficiency
from ballcvt.solvers.limit import limit_search, limit_torque_batch
from ballcvt.solvers.newton import solve_batch
from ballcvt.solvers.point import solve_point
from drives import fixed_oil_hub

REF = SolverOptions(quadrature=Quadrature("pole", 64, 64, 128))
FAST = SolverOptions()
SPEED = 2000.0 * np.pi / 30.0


def _errors(problem):
    fast = solve_batch(problem, FAST)
    ref = solve_batch(problem, REF, x0=fast.state.creep)
    assert fast.converged.all() and ref.converged.all()
    eta = np.abs(efficiency(problem, fast.state).overall - efficiency(problem, ref.state).overall)
    c, cr = fast.state.creep, ref.state.creep
    big = np.abs(cr) > 1e-6
    return eta.max(), np.max(np.abs(c[big] / cr[big] - 1))


@pytest.mark.parametrize("arch", ["double", "single"])
def test_fast_matches_reference_on_grid(drive, arch):
    design, fluid = drive
    ratio = np.linspace(0.5, 2.0, 6)
    base = build_problem(design, fluid, arch, ratio, 0.0, 2000.0, SPEED)
    limit = limit_torque_batch(base, design.creep_limit, FAST)
    torque = 5.0 + np.linspace(0, 1, 6)[None, :] * (0.9 * limit[:, None] - 5.0)
    eta_err, creep_err = _errors(build_problem(design, fluid, arch, ratio[:, None], torque,
                                               2000.0, SPEED))
    assert eta_err <= 1e-4
    assert creep_err <= 1e-3


@given(cases())
def test_fast_matches_reference_on_random_designs(case):
    """eta within the target everywhere. The creep target (1e-3) is met on the benchmark
    map; on extreme random designs (four balls, k = 2.5, 300 rpm) the worst case found is
    1.0e-3, where the pole sits at |Y_p| ~ 0.94 of a disc contact (the angular
    convergence of the pole rule is slowest there), so this bound is 2e-3."""
    v, ratio, clamp, rpm, frac = case
    limit = v.limit_torque(ratio=ratio, clamp_force=clamp, input_speed_rpm=rpm)
    pb = build_problem(v.design, v.fluid, v.architecture, ratio, frac * limit, clamp,
                       rpm * np.pi / 30)
    eta_err, creep_err = _errors(pb)
    assert eta_err <= 1e-4
    assert creep_err <= 2e-3


def test_batch_flags_unconverged_points(drive):
    """A torque far beyond capacity has no equilibrium: flagged, not hidden, not raised."""
    design, fluid = drive
    pb = build_problem(design, fluid, "double", 1.0, np.array([40.0, 1000.0]), 2000.0, SPEED)
    sol = solve_batch(pb, SolverOptions(max_iterations=8), fallback=False)
    assert sol.converged.tolist() == [True, False]
    assert sol.residual_norm[1] > FAST.tol


@pytest.mark.parametrize("compiled_rest", [True, False])
def test_trial_states_that_overflow_are_flagged_without_a_warning(drive, compiled_rest,
                                                                  monkeypatch):
    """A start at infinite creeps evaluates NaN states: the point is flagged, and numpy's
    RuntimeWarnings about the trial stay inside the solver (solvers/trials.py); the
    residual's compiled kernels (equilibrium/compiled.py) raise none, the NumPy path
    (the reference, and the path of the problems they do not cover) does."""
    from ballcvt.equilibrium import compiled

    if not compiled_rest:
        monkeypatch.setattr(compiled, "covers", lambda problem, constants: False)
    design, fluid = drive
    pb = build_problem(design, fluid, "double", 1.0, np.array([10.0, 10.0]), 2000.0, SPEED)
    x0 = np.zeros((2, pb.layout.n_contacts))
    x0[:, [0, -1]] = [[1e-3, 1e-3], [np.inf, -np.inf]]
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)
        sol = solve_batch(pb, x0=x0, fallback=False)
    assert sol.converged.tolist() == [True, False]
    if not compiled_rest:
        with pytest.warns(RuntimeWarning):  # the same solve, unwrapped, warns
            solve_batch.__wrapped__(pb, x0=x0, fallback=False)


def test_batch_equals_point_solver(double):
    r = double.solve(ratio=1.3, output_torque=50.0, clamp_force=2000.0, input_speed_rpm=2000)
    pb = build_problem(double.design, double.fluid, "double", [1.3, 1.3], 50.0, 2000.0, SPEED)
    sol = solve_batch(pb)
    assert sol.converged.all()
    assert np.allclose(sol.state.creep[0], [c.creep for c in r.contacts.values()], rtol=1e-8,
                       atol=1e-14)


def test_numba_kernels_equal_numpy_path(drive):
    _, fluid = drive
    rng = np.random.default_rng(3)
    n = 50
    args = (rng.uniform(-0.05, 0.05, n) * rng.choice([1.0, 1e-3], n), rng.uniform(-0.2, 0.2, n),
            1.2e-3, 0.45e-3, rng.uniform(0.8e9, 2.5e9, n), 2000.0, 0.03, 15.0, 1.5e-7, fluid)
    for method in ("pole", "centred"):
        state = ContactState(*args[:-1])
        fast = contact_coefficients(state, args[-1], Quadrature(method), derivatives=True)
        slow = contact_coefficients(state, args[-1], Quadrature(method, engine="numpy"),
                                    derivatives=True)
        for a, b in zip(fast[:2], slow[:2]):                      # mu, chi
            assert np.allclose(a, b, rtol=1e-9, atol=1e-12 * np.max(np.abs(b)))
        # derivatives (Newton only): g + k |V|^2 cancels in the saturated regime
        for a, b in zip(fast[2:], slow[2:]):
            scale = np.max(np.abs(b), axis=0)
            assert np.all(np.abs(a - b) <= 1e-5 * scale)


@pytest.mark.parametrize("n_radial", [10, 12, 13, 20])
def test_kernels_pad_rays_to_whole_vectors_without_changing_the_sums(drive, n_radial):
    """Rays of 10-20 radial nodes (the predictor's 12 among them) are padded with zero-weight
    copies of the last node to a multiple of 8 where that adds 3 or more (`_ray_nodes`,
    session 23): the compiled sums equal those on the unpadded rays to round-off (both
    rules and their blend, derivatives, the visco-elastic factor), and stay finite."""
    from ballcvt.model.traction import kernels
    from ballcvt.model.traction.isothermal import VECTOR_NODES, kernel_rule, kernel_table
    from ballcvt.model.traction.quadrature import radial_rule

    _, fluid = drive
    padded = kernel_rule(Quadrature("pole", n_radial, 8, 12))
    r01, wr = radial_rule(n_radial)
    pad = -n_radial % VECTOR_NODES
    assert padded[0].size == (n_radial + pad if pad >= 3 else n_radial)
    assert np.all(padded[1][n_radial:] == 0.0) and np.all(padded[0][n_radial:] == r01[-1])
    plain = (r01, wr) + padded[2:]
    rng = np.random.default_rng(n_radial)
    n = 60
    state = ContactState(rng.uniform(-0.05, 0.05, n), rng.uniform(-0.2, 0.2, n), 1.2e-3,
                         0.45e-3, rng.uniform(0.8e9, 2.5e9, n), 2000.0, 0.03, 15.0, 1.5e-7)
    par = np.ascontiguousarray(state.stacked()[0])
    assert np.any(np.abs(par[0] / (par[1] * par[3] / par[6])) > 0.8)  # blend, centred rule
    for modulus in (0.0, 0.5e9):
        table = kernel_table(fluid, float(par[4].max()), modulus)
        for deriv in (False, True):
            a, b = np.empty((n, kernels.N_OUT)), np.empty((n, kernels.N_OUT))
            kernels.traction_kernel(par, padded, table, deriv, a)
            kernels.traction_kernel(par, plain, table, deriv, b)
            k = kernels.N_OUT if deriv else 2
            assert np.all(np.isfinite(a[:, :k]))
            assert np.all(np.abs(a - b)[:, :k] <= 1e-13 * np.max(np.abs(b[:, :k]), axis=0))


def test_analytic_jacobian_matches_finite_differences(drive):
    design, fluid = drive
    pb = build_problem(design, fluid, "double", 0.8, 40.0, 2000.0, SPEED)
    x = np.array([3e-3, 2e-4, -1e-4, 4e-3])
    _, jac = evaluate_with_jacobian(pb, x)
    fd = np.empty_like(jac)
    for j in range(4):
        h = np.zeros(4)
        h[j] = 1e-8
        fd[:, j] = (evaluate(pb, x + h).residual - evaluate(pb, x - h).residual) / 2e-8
    # the node motion with the pole is not differentiated: a Newton Jacobian, ~1 % off
    assert np.allclose(jac, fd, rtol=0.02, atol=0.02 * np.max(np.abs(fd)))


# --- the fast user-facing paths (issue 13) against the straightforward ones ------------

def _bisection(problem, creep_limit):
    """The bisection limit and its final bracket from T_2 = 0 (the former method)."""
    from dataclasses import replace

    from ballcvt.solvers.limit import LIMIT_RTOL, limit_torque_bisection, solve_admissible
    zero = solve_admissible(replace(problem, output_torque=np.zeros(problem.size)),
                            creep_limit, FAST)
    lo = np.full(problem.size, np.nan)
    ok = np.flatnonzero(zero.ok)
    if ok.size:
        lo[ok], _ = limit_torque_bisection(problem.take(ok), creep_limit, FAST, LIMIT_RTOL,
                                           lambda: None, None, zero.creep[ok])
    return lo, LIMIT_RTOL


def test_pinned_limits_equal_bisection_on_the_map(drive):
    design, fluid = drive
    for arch in ("double", "single"):
        base = build_problem(design, fluid, arch, np.linspace(0.5, 2.0, 12), 0.0, 2000.0,
                             SPEED)
        fast = limit_search(base, design.creep_limit, FAST)
        lo, rtol = _bisection(base, design.creep_limit)
        # the exact limit lies in the bisection's last bracket [lo, lo + rtol hi]
        assert np.all(fast.torque >= lo * (1 - 1e-9))
        assert np.all(fast.torque <= lo * (1 + 1.01 * rtol / (1 - rtol)))
        # at the limit a creep is at C_lim, none beyond it
        big = np.max(np.abs(fast.creep), axis=-1)
        assert np.allclose(big, design.creep_limit, rtol=1e-9)


@given(cases())
def test_pinned_limits_equal_bisection_on_random_designs(case):
    v, ratio, clamp, rpm, _ = case
    pb = build_problem(v.design, v.fluid, v.architecture, np.array([ratio]), 0.0, clamp,
                       rpm * np.pi / 30)
    fast = limit_search(pb, v.design.creep_limit, FAST).torque
    lo, rtol = _bisection(pb, v.design.creep_limit)
    assert np.isnan(fast[0]) == np.isnan(lo[0])
    if not np.isnan(lo[0]):
        assert lo[0] * (1 - 1e-9) <= fast[0] <= lo[0] * (1 + 1.01 * rtol / (1 - rtol))
        # the solve at the limit converges within it: the limit is admissible
        r = v.solve(ratio=ratio, output_torque=float(fast[0]), clamp_force=clamp,
                    input_speed_rpm=rpm)
        assert max(abs(c.creep) for c in r.contacts.values()) <= v.design.creep_limit * (
            1 + 1e-8)


@pytest.mark.parametrize("law", [None, "cam"])
def test_one_batch_sweep_equals_torque_continuation(law):
    """The sweep's single batch from interpolated creeps (its limits found here) against
    the former walk up the torque axis (taken when the limits are given): the same points
    converge, to the same values."""
    from ballcvt import Variator, load_builtin
    v = Variator(*fixed_oil_hub()) if law else Variator()
    kw = {"clamp_law": "cam"} if law else {"clamp_force": 2000.0}
    grid = {"ratio": np.linspace(0.5, 2.0, 6), "output_torque": np.linspace(0.0, 120.0, 9),
            "input_speed_rpm": 2000.0, **kw}
    fast = v.sweep(**grid)
    walk = v.sweep(**grid, limit_torque=fast.limit_torque.squeeze().values)
    assert (fast.status.values == walk.status.values).all()
    assert (fast.status.values == 0).sum() > 20
    assert np.allclose(fast.eta, walk.eta, rtol=0, atol=1e-9, equal_nan=True)
    assert np.allclose(fast.creep, walk.creep, rtol=1e-6, atol=1e-12, equal_nan=True)


def test_small_batches_skip_the_predictor_to_the_same_answer(drive):
    from dataclasses import replace
    design, fluid = drive
    pb = build_problem(design, fluid, "double", np.array([0.6, 1.2, 1.9]), 50.0, 2000.0,
                       SPEED)
    direct = solve_batch(pb)                                  # 3 points: no predictor
    staged = solve_batch(pb, replace(FAST, predictor_min_points=1))
    assert direct.converged.all() and staged.converged.all()
    assert direct.iterations.max() < staged.iterations.min()
    assert np.allclose(direct.state.creep, staged.state.creep, rtol=1e-7, atol=1e-13)


def test_kernel_exponential_matches_numpy():
    """The kernels' vectorisable exp(-a) (range reduction + Taylor) is exact to round-off,
    and clamps instead of indexing out of its table (NaN, inf, negative, huge)."""
    from ballcvt.model.traction import kernels

    a = np.concatenate([np.linspace(0.0, 60.0, 200_001), np.geomspace(1e-14, 700.0, 5000)])
    rel = np.abs(kernels.exp_neg(a) / np.exp(-a) - 1.0)
    assert np.all(rel <= 4.5e-16 + 4e-17 * a)  # the documented bound
    edge = kernels.exp_neg(np.array([745.0, 1e300, np.inf, np.nan, -1.0]))
    assert np.all(np.isfinite(edge)) and np.all(edge[:4] < 1e-300) and edge[4] == 1.0


def test_kernels_propagate_nan_and_match_without_derivatives(drive):
    """A NaN input gives NaN coefficients (never a silent number), and the kernels' cheaper
    value-only specialisation computes the same mu, chi as the NumPy path."""
    _, fluid = drive
    rng = np.random.default_rng(5)
    n = 40
    creep = rng.uniform(-0.05, 0.05, n)
    creep[3] = np.nan
    args = (
        creep,
        rng.uniform(-0.2, 0.2, n),
        1.2e-3,
        0.45e-3,
        rng.uniform(0.8e9, 2.5e9, n),
        2000.0,
        0.03,
        15.0,
        1.5e-7,
        fluid,
    )
    for method in ("pole", "centred"):
        state = ContactState(*args[:-1])
        fast = contact_coefficients(state, args[-1], Quadrature(method))
        slow = contact_coefficients(state, args[-1], Quadrature(method, engine="numpy"))
        for a, b in zip(fast, slow):
            assert np.isnan(a[3]) and np.isnan(b[3])
            ok = np.isfinite(b)
            assert np.allclose(a[ok], b[ok], rtol=1e-9, atol=1e-12 * np.max(np.abs(b[ok])))


@given(cases())
def test_compiled_path_equals_numpy_path_on_random_designs(case):
    """The compiled kernels and steps (issue 13) against the NumPy reference path of the
    same rule, solved point by point by the hybrid method: every point the straightforward
    path solves, the fast path solves, to the same creeps and efficiency."""
    v, ratio, clamp, rpm, frac = case
    limit = v.limit_torque(ratio=ratio, clamp_force=clamp, input_speed_rpm=rpm)
    torque = np.array([0.3, 0.7, 0.95]) * frac * limit
    pb = build_problem(v.design, v.fluid, v.architecture, ratio, torque, clamp, rpm * np.pi / 30)
    fast = solve_batch(pb, FAST)
    slow = SolverOptions(quadrature=Quadrature(engine="numpy"), method="hybr")
    for i in range(torque.size):
        ref = solve_point(pb.take(i), slow)
        assert fast.converged[i] or not ref.converged
        if ref.converged:
            c, cr = fast.state.creep[i], ref.state.creep
            # relative 1e-7 on creeps (as `_errors`), and what the two residuals (each
            # within the tolerance, 1e-11) leave: a single idler's tiny creep (~1e-7, a
            # traction slope ~10 per unit creep) moves by ~1e-12 within it. The bound is
            # the first-order one, |J^-1| (|r_fast| + |r_ref|), at the reference solution,
            # doubled: the analytic J is up to ~1 % off the discrete one (solvers/secant.py).
            _, jac = evaluate_with_jacobian(pb.take([i]), cr[None, :], FAST.quadrature)
            both = np.abs(fast.state.residual[i]) + np.abs(ref.state.residual)
            floor = np.abs(np.linalg.inv(jac[0])) @ both
            assert np.all(np.abs(c - cr) <= 1e-7 * np.abs(cr) + 2 * floor)
            eta = efficiency(pb.take(i), ref.state).overall
            # both solutions meet their balances to their residual norms (torques over
            # n F_N0 r_S): each of the n_c balances may move the output torque, and with it
            # eta, by up to norm x n F_N0 r_S / T_2 relative (0.19 N m at 500 N here made
            # a fixed 1e-9 depend on the machine's floating-point contractions)
            norm = fast.residual_norm[i] + ref.residual_norm
            tol = max(1e-9, c.size * norm * float(pb.take(i).torque_scale) / torque[i])
            assert efficiency(pb, fast.state).overall[i] == pytest.approx(eta, abs=tol)


def test_newton_update_compiled_equals_python_and_handles_singular_steps():
    """The compiled Newton update (`newton_step.advance`) against its plain-Python form on random
    points (steps, caps, back-offs), and a singular Jacobian takes the capped
    least-squares step instead of failing."""
    from ballcvt.solvers import newton as B
    from ballcvt.solvers import newton_step as S  # the compiled update's module

    rng = np.random.default_rng(11)
    n, nc = 40, 4
    free = S.free_creeps(nc, n)
    res = rng.normal(scale=10.0 ** rng.uniform(-13, -1, (n, 1)), size=(n, nc))
    jac = rng.normal(size=(n, nc, nc))
    jac[3] = 0.0  # singular
    jac[3, :, 0] = 1.0
    x = rng.uniform(-0.1, 0.5, (n, nc))
    best = np.where(rng.random(n) < 0.3, 1e-14, np.inf)  # some points got worse
    res[3], best[3] = 1e-2, np.inf  # the singular point steps
    prev_dx = rng.normal(scale=1e-3, size=(n, nc))
    outs = []
    for fn in (S.advance_compiled, S.advance_python):
        arrays = [x.copy(), best.copy(), x.copy() - prev_dx, prev_dx.copy(), np.ones(n, bool)]
        keep, singular = np.zeros(n, bool), np.zeros(n, bool)
        fn(np.arange(n), res, jac, arrays[0], free, *arrays[1:], 1e-11, B.MAX_STEP,
           *B.CREEP_BOUNDS, keep, singular)
        outs.append((keep, singular, arrays))
    (k1, s1, a1), (k2, s2, a2) = outs
    assert (k1 == k2).all() and (s1 == s2).all()
    for u, w in zip(a1, a2):
        np.testing.assert_allclose(u, w, rtol=1e-12, atol=1e-15)
    assert s1[3] and not s1[np.arange(n) != 3].any()
    x = np.array([[0.01, 0.0, 0.0, 0.01]])
    it = S.Iterates(x, np.full(1, np.inf), x.copy(), np.zeros((1, nc)), np.ones(1, bool))
    active = S.advance(it, np.arange(1), np.ones((1, nc)) * 1e-3, np.ones((1, nc, nc)),
                        free[:1], 1e-11)
    assert active.tolist() == [0] and np.all(np.isfinite(x)) and not np.allclose(x[0, 0], 0.01)


def test_viscosity_table_stays_finite_past_overflow(drive):
    """A Newton trial at a pressure where ``E = eta / tau_L`` passes e^709 (the hub under
    its oil balance reached one, ~1 TPa) gets a finite table, flat past `LOG_E_MAX`, no
    overflow warning, and finite coefficients there. Fails before the cap (inf in the table,
    numpy's overflow RuntimeWarning)."""
    import warnings

    from ballcvt.model.traction.kernels import LOG_E_MAX, viscosity_table

    _, fluid = drive
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fl, tab = viscosity_table(fluid, 5e12)
    assert np.isfinite(tab).all()
    assert tab[-1, 0] == pytest.approx(np.exp(LOG_E_MAX)) and tab[-1, 1] == 0.0
    state = ContactState(0.01, 0.0, 1.2e-3, 0.45e-3, 4e12, 2000.0, 0.03, 15.0, 1.5e-7)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mu, chi, *_ = contact_coefficients(state, fluid, Quadrature(), derivatives=True)
    assert np.isfinite(mu).all() and np.isfinite(chi).all()
