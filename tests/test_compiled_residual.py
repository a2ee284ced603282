"""The residual's compiled twin (`ballcvt.equilibrium.compiled`, session 25) against the
NumPy reference path: the same states to round-off, the same Jacobians to the forward
difference's round-off, the same solutions; and the problems it leaves to NumPy."""

import numpy as np
import pytest

from ballcvt import Variator, load_builtin
from ballcvt.equilibrium import compiled
from ballcvt.equilibrium import residual as rs
from ballcvt.equilibrium.problem import CarrierFrame, OperatingInputs, build_problem, make_problem
from ballcvt.params.drive import Drive
from ballcvt.solvers.newton import solve_batch
from ballcvt.solvers.options import SolverOptions

OPTIONS = SolverOptions()


def _variator(case):
    design, fluid = load_builtin("table1")
    return {
        "table1": lambda: Variator(),
        "single": lambda: Variator(design, fluid, "single"),
        "viscoelastic": lambda: Variator(traction_law="viscoelastic"),
        "thermal": lambda: Variator(traction_law="thermal"),
        "mixed": lambda: Variator(design.with_lubrication("mixed"), fluid),
        "hub": lambda: Variator(*load_builtin("hub")),  # shaft drags, mixed lubrication
    }[case]()


def _problem(v, n=5):
    ratio, torque = np.linspace(0.6, 1.6, n), np.linspace(0.0, 40.0, n)
    speed = 209.4 * np.linspace(0.2, 1.0, n)
    return build_problem(v.design, v.fluid, v.architecture, ratio, torque, 1500.0, speed).flat()


def _numpy_path(monkeypatch):
    monkeypatch.setattr(compiled, "covers", lambda problem, constants: False)


def _relative(a, b):
    return float(np.max(np.abs(a - b)) / (np.max(np.abs(b)) + 1e-300)) if b.size else 0.0


@pytest.mark.parametrize("case", ["table1", "single", "viscoelastic", "thermal", "mixed", "hub"])
def test_the_same_states_and_jacobians_as_numpy(case, monkeypatch):
    v = _variator(case)
    p = _problem(v)
    assert compiled.covers(p, rs._constants(p))
    x = solve_batch(p, OPTIONS).state.creep * 1.2  # off the solution: residuals not small
    got = rs.evaluate_with_jacobian(p, x, OPTIONS.quadrature)
    plain = rs.evaluate(p, x, OPTIONS.quadrature)
    with monkeypatch.context() as m:
        _numpy_path(m)
        want = rs.evaluate_with_jacobian(p, x, OPTIONS.quadrature)
        want_plain = rs.evaluate(p, x, OPTIONS.quadrature)
    for name in vars(want[0]):  # measured: 4e-16 at most (NumPy's vector pow: an ulp)
        assert _relative(getattr(got[0], name), getattr(want[0], name)) < 1e-14, name
        assert _relative(getattr(plain, name), getattr(want_plain, name)) < 1e-14, name
        assert getattr(got[0], name).shape == getattr(want[0], name).shape, name
    # forward differences of step 1e-7: an ulp of the residual is 1e-9 of an entry
    assert _relative(got[1], want[1]) < 1e-7


def test_the_same_solutions(monkeypatch):
    v = _variator("table1")
    p = _problem(v, 8)
    got = solve_batch(p, OPTIONS)
    _numpy_path(monkeypatch)
    want = solve_batch(p, OPTIONS)
    assert got.converged.all() and want.converged.all()
    assert np.allclose(got.state.creep, want.state.creep, rtol=1e-9, atol=1e-15)


def test_what_it_leaves_to_numpy():
    v = _variator("table1")
    flat = _problem(v)
    assert compiled.covers(flat, rs._constants(flat))
    one = build_problem(v.design, v.fluid, v.architecture, 1.0, 10.0, 1500.0, 209.4)
    assert not compiled.covers(one, rs._constants(one))  # not a 1-D batch


def _mode_problems(v):
    """A planetary mode's carrier-frame problems: a turning carrier (tilted: a gyroscopic
    moment on the axle bearings) and torque conditions other than the output's."""
    drive = Drive(v.design, v.fluid, v.architecture)
    ratio = np.linspace(0.6, 1.6, 4)
    yield make_problem(drive, OperatingInputs(ratio, 10.0, 1500.0, 209.4),
                       CarrierFrame(carrier_speed=50.0))
    for weights in ((1.0, 0.0), (-1.0, 1.0), (1.0, 1.0)):
        yield make_problem(drive, OperatingInputs(ratio, -15.0, 1500.0, 209.4),
                           CarrierFrame(carrier_speed=-30.0, torque_weights=weights,
                                        signed_torque=True))


@pytest.mark.parametrize("case", ["table1", "single", "mixed"])  # (no drags: refused there)
def test_planetary_modes_the_same_as_numpy(case, monkeypatch):
    """Since session 38 the kernels take the modes' torque condition and gyroscopic
    moment: the same states and Jacobians as the NumPy path, and the same solutions."""
    v = _variator(case)
    for p in _mode_problems(v):
        assert compiled.covers(p, rs._constants(p))
        assert np.any(p.gyro_factor) or p.torque_weights != (0.0, 1.0)
        sol = solve_batch(p, OPTIONS)
        x = sol.state.creep * 1.2
        got = rs.evaluate_with_jacobian(p, x, OPTIONS.quadrature)
        with monkeypatch.context() as m:
            _numpy_path(m)
            want = rs.evaluate_with_jacobian(p, x, OPTIONS.quadrature)
            again = solve_batch(p, OPTIONS)
        for name in vars(want[0]):
            assert _relative(getattr(got[0], name), getattr(want[0], name)) < 1e-14, name
        assert _relative(got[1], want[1]) < 1e-7
        # (a made-up torque condition can have no equilibrium: the same verdict both ways)
        assert (sol.converged == again.converged).all() and sol.converged.sum() >= 3
        ok = sol.converged
        assert np.allclose(sol.state.creep[ok], again.state.creep[ok], rtol=1e-9, atol=1e-15)


def test_no_warning_from_a_problem_of_broadcast_inputs():
    """A problem's scalar inputs are broadcast views (read-only, warning on write): the
    kernels get writeable copies, so that numba's typing raises no FutureWarning."""
    import warnings

    for v in (_variator("table1"), _variator("hub")):
        p = build_problem(v.design, v.fluid, v.architecture, np.ones(1), 40.0, 2000.0,
                          209.4).flat()
        x = solve_batch(p, OPTIONS).state.creep
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            rs.evaluate_with_jacobian(p, x, OPTIONS.quadrature)
            rs.evaluate(p, x, OPTIONS.quadrature)
        assert [str(w.message) for w in caught] == []
        # numba warns once a process, on the first call that types such a view (reading
        # its flags warns): none of the kernels' inputs is one
        geometry, speed, unit, constants, _ = p.__dict__["_memo_compiled"]
        per_point = [speed, unit, *geometry[:2], *constants[0], *constants[1]]
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            assert all(a.flags.writeable for a in per_point)
        assert [str(w.message) for w in caught] == []
