"""The smooth search rule of the optimal clamp's coarse passes (session 24, issue 26)."""

import numpy as np
import pytest

from ballcvt import Variator
from ballcvt.model.traction.contact import ContactState, contact_coefficients
from ballcvt.model.traction.isothermal import pole_position
from ballcvt.model.traction.quadrature import Quadrature
from ballcvt.solvers.options import SolverOptions, coarse_options

#: An input-disc contact of the Table I drive at 620 N, 2000 rpm, ratio 1 (the middle force
#: of the optimal clamp's first stencil at 30 N m), as the residual builds it.
CONTACT = ContactState(0.012603, -2.657059, 5.089025e-4, 6.123083e-4, 9.500103e8, 620.0,
                       0.1022132, 21.40748, 5.402098e-7)
POLES = np.array([0.05, 0.2, 0.4, 0.6, 0.7, 0.75, 0.8, 0.85, 0.9, 0.95, 1.0, 1.1, 1.5])


def _slopes(rule: Quadrature) -> np.ndarray:
    """``d mu / d c`` by central differences of the rule's own ``mu``, the contact's creep
    term set to put its pole at each of `POLES` (``|Y_p|``)."""
    fluid = Variator().fluid
    y0 = abs(float(pole_position(CONTACT.creep_term, CONTACT.spin, CONTACT.ay, CONTACT.radius)))
    c = CONTACT.creep_term * POLES / y0
    h = 1e-6 * c
    up = contact_coefficients(CONTACT._replace(creep_term=c + h), fluid, rule)[0]
    down = contact_coefficients(CONTACT._replace(creep_term=c - h), fluid, rule)[0]
    return (up - down) / (2 * h)


def test_the_search_rule_follows_the_full_rules_traction_slope_where_the_predictor_wiggles():
    """On 12 x 8 nodes the pole-centred rule's nodes move with the pole, and its traction
    slope in the creep swings from 0.3x to 2.3x the full rule's as the pole nears the edge
    (the optimal clamp's efficiency then wiggles in the force, and Newton converges
    linearly there); the centred search rule, on as many nodes, stays within 3 %."""
    options = SolverOptions()
    full = _slopes(options.quadrature)
    search = _slopes(options.search_rule) / full
    predictor = _slopes(options.predictor) / full
    assert np.all(np.abs(search - 1) < 0.03), search
    assert predictor.min() < 0.5 and predictor.max() > 1.5, predictor  # the reason


def test_coarse_options_take_the_search_rule_only_when_asked_and_a_predictor_is_set():
    fine = SolverOptions()
    assert coarse_options(fine).quadrature == fine.predictor
    searched = coarse_options(fine, search=True)
    assert searched.quadrature == fine.search_rule and searched.predictor is None
    assert searched.tol == fine.predictor_tol
    no_rule = SolverOptions(search_rule=None)
    assert coarse_options(no_rule, search=True).quadrature == no_rule.predictor
    bare = SolverOptions(predictor=None)  # no coarse rule at all: the options' own
    assert coarse_options(bare, search=True).quadrature == bare.quadrature


@pytest.mark.parametrize("clamp", [{"clamp_law": "optimal"}, {"clamp_force": 1500.0}])
def test_a_cycles_first_pass_searches_on_the_search_rule_under_the_optimal_clamp(
    monkeypatch, clamp
):
    """The optimal clamp's first pass compares efficiencies across forces: on the search
    rule; other clamps keep the predictor's rule (their first pass compares none)."""
    import ballcvt.analysis.cycles as cycles
    from ballcvt.analysis.cycle_files import cycle_from_arrays

    rules, real = [], cycles.evaluate_points

    def spy(points, *args, **kwargs):
        rules.append(points.options.quadrature)
        return real(points, *args, **kwargs)

    monkeypatch.setattr(cycles, "evaluate_points", spy)
    v = Variator()
    cycle = cycle_from_arrays(time=[0.0, 1.0, 2.0], output_speed=[20.0, 25.0, 30.0],
                              output_torque=[10.0, 20.0, 30.0])
    cycles.run_cycle(v, cycle, target_input_speed=180 * np.pi / 30, progress=False, **clamp)
    first = v.options.search_rule if "clamp_law" in clamp else v.options.predictor
    assert rules == [first, v.options.quadrature]
