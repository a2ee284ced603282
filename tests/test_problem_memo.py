"""A problem's sub-batches (`take`, `flat`, `expand`) carry its per-point constants
(session 25): the values they would build again, bit for bit."""

from dataclasses import fields, replace

import numpy as np
import pytest

from ballcvt import Variator, load_builtin
from ballcvt.equilibrium.problem import build_problem
from ballcvt.equilibrium.residual import (
    _balance_constants,
    _constants,
    _film_unit,
    evaluate_with_jacobian,
)
from ballcvt.solvers.newton import solve_batch


def _problem(which, n=5):
    design, fluid = load_builtin("hub") if which == "hub" else (None, None)
    v = Variator(design, fluid) if design is not None else Variator()
    ratio, torque = np.linspace(0.6, 1.5, n), np.linspace(0.0, 30.0, n)
    return build_problem(v.design, v.fluid, v.architecture, ratio, torque, 2000.0, 209.4)


def _equal(a, b):
    if isinstance(a, dict):
        assert a.keys() == b.keys()
        for k in a:
            _equal(a[k], b[k])
    elif isinstance(a, np.ndarray):
        assert a.shape == np.shape(b) and np.array_equal(a, b)
    else:
        assert a == b or (a is None and b is None)


@pytest.mark.parametrize("which", ["table1", "hub"])
def test_a_sub_batch_carries_what_it_would_build(which):
    p = _problem(which)
    _film_unit(p), _constants(p)
    index = np.array([0, 3, 4])
    sub = p.take(index)
    # the hub's shaft drags (a `DragMagnitudes`) are not carried: built again
    assert ("_memo_balances" in sub.__dict__) == (which == "table1")
    assert "_memo_film_unit_speed" in sub.__dict__
    fresh = replace(sub)  # the same fields, no memos: everything built again
    _equal(_film_unit(sub), _film_unit(fresh))
    _equal(_constants(sub), _balance_constants(fresh))
    wide = sub.expand()
    _equal(_constants(wide), _balance_constants(replace(wide)))
    _equal(_film_unit(wide), _film_unit(replace(wide)))


def test_the_sub_batch_is_the_problem_of_its_points():
    p = _problem("table1")
    sub = p.take(np.array([1, 2]))
    again = _problem("table1", 5).take(np.array([1, 2]))
    for f in fields(sub):
        _equal(getattr(sub, f.name), getattr(again, f.name))
    one = build_problem(p.design, p.fluid, p.layout.architecture, 1.0, 20.0, 2000.0, 209.4)
    _film_unit(one), _constants(one)
    flat = one.flat()
    assert flat.shape == (1,)
    _equal(_film_unit(flat), _film_unit(replace(flat)))
    _equal(_constants(flat), _balance_constants(replace(flat)))


def test_a_newton_iteration_on_a_sub_batch_gives_the_same_numbers():
    p = _problem("table1", 4).flat()
    x = solve_batch(p).state.creep
    evaluate_with_jacobian(p, x)  # the constants now on p, carried to its sub-batches
    index = np.array([0, 2])
    carried = evaluate_with_jacobian(p.take(index), x[index])
    built = evaluate_with_jacobian(replace(p.take(index)), x[index])
    _equal(carried[1], built[1])
    for name in vars(carried[0]):
        _equal(getattr(carried[0], name), getattr(built[0], name))
