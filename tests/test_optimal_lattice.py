"""The optimal clamp's lattice climb (session 32): one optimum per point whatever the
search starts from, even where the efficiency has a saw tooth in the force."""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from types import SimpleNamespace

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from ballcvt import Variator, load_builtin
from ballcvt.analysis.cycle_files import cycle_from_arrays
from ballcvt.api import CycleSettings, with_oil_temperature
from ballcvt.model.clamping import OptimalClamp
from ballcvt.params.io import load_builtin_fluid
from ballcvt.solvers.optimal_batch import optimal_forces
from ballcvt.solvers.optimal_clamp import ClampCase, point_problem
from ballcvt.solvers.optimal_lattice import LATTICE, lattice_search
from ballcvt.units import rpm_to_rad_s


@dataclass(frozen=True)
class _Options:
    predictor: None = None
    predictor_min_points: int = 1


#: What the climb reads of a problem: the contacts (for a cold start's creeps).
_POINTS = SimpleNamespace(  # the scorer's problem: its shape, layout and (its law) fluid
    shape=(64,),
    layout=SimpleNamespace(is_idler=np.array([0, 1, 1, 0]) > 0),
    fluid=load_builtin_fluid(),
)


@dataclass(frozen=True)
class _Synthetic:
    """A scorer of an efficiency ``eta(u)`` given as a function (no solves); creeps 0."""

    eta: object
    bound: float = -np.inf  # forces below exp(bound) have no admissible equilibrium
    options: _Options = _Options()
    problem: object = field(default_factory=lambda: _POINTS)

    def __call__(self, index, u, x0=None):
        e = np.where(u >= self.bound, self.eta(u), -np.inf)
        return e, np.zeros((np.size(u), 4))


def _climb(score, start, lo=np.log(100.0), hi=np.log(2e4)):
    n = np.size(start)
    bounds = (np.full(n, lo), np.full(n, hi))
    return lattice_search(score, np.arange(n), bounds, np.asarray(start, float))


U0 = np.log(1500.0)


def _saw(u, phase=0.0, height=1.6e-5, q=0.18):
    """A parabola in ``ln F`` with the saw tooth of harden task 30999:56 (teeth 1 % of the
    force apart, 1.6e-5 high)."""
    tooth = (u / 0.01 + phase) % 1.0
    return 0.42 - q * (u - U0) ** 2 + height * tooth


@settings(max_examples=60, deadline=None)
@given(st.floats(-0.6, 0.6), st.floats(0.0, 1.0))
def test_every_start_ends_on_the_same_lattice_stencil(offset, phase):
    """From any start within a factor 1.8 of the optimum, the climb certifies the same
    vertex: the one of the start at the optimum itself."""
    score = _Synthetic(lambda u: _saw(u, phase))
    ref = _climb(score, [U0])
    got = _climb(score, [U0 + offset])
    assert ref[1][0] and got[1][0]
    assert got[0][0] == ref[0][0]


def test_a_cubic_efficiency_gives_its_optimum_exactly():
    """The answer is the maximum of the cubic through the certified stencil and the lattice
    force two steps out on the vertex's side: exact on a cubic efficiency (a parabola's
    vertex on the 2 % lattice would miss it by about ``2 LATTICE^2`` in ``ln F_N0``), from
    every start, on either side."""
    q = 0.25
    for c in (0.3, -0.3):
        score = _Synthetic(lambda u, c=c: 0.9 - q * (u - U0) ** 2 + c * (u - U0) ** 3)
        got = _climb(score, U0 + np.linspace(-0.3, 0.3, 13))
        assert got[1].all()
        np.testing.assert_allclose(got[0], U0, rtol=0, atol=1e-9)


def test_climbs_from_below_the_creep_bound_and_stops_at_it():
    """A start far below the creep bound climbs (no admissible force in its stencil) to the
    optimum above it; an optimum within a lattice step of the bound is left uncertified,
    with the best lattice force as the start of the search that follows."""
    score = _Synthetic(lambda u: _saw(u, height=0.0), bound=U0 - 0.5)
    got = _climb(score, [np.log(200.0)])
    assert got[1][0] and abs(got[0][0] - U0) <= 1e-9
    near = _Synthetic(lambda u: _saw(u, height=0.0), bound=U0 + 0.001)
    got = _climb(near, [U0 + 0.2])
    assert not got[1][0]
    assert U0 + 0.001 <= got[0][0] <= U0 + 0.001 + 2 * LATTICE  # the lowest admissible
    assert np.isclose(got[0][0] / LATTICE, np.rint(got[0][0] / LATTICE))  # a lattice point


# Harden task 30999:56: the hub-derived drive, isothermal, double idler, 8,637 rpm, whose
# efficiency has a saw tooth of 1.6e-5 every 1 % of the force near its optimum (the pole
# quadrature of a hard-spinning contact); a duty cycle's steps were up to 6.7e-5 in
# efficiency from `solve`.
TASK_56 = (
    '{"aspect_ratio": 1.9469019603282602, "roller_radius": 0.009932012360856397, '
    '"theta0_deg": 57.57590481268453, "theta2_deg": 51.58644962662076, '
    '"alpha_deg": 11.624557403163575, "n_rollers": 4, '
    '"roller_bearing_diameter": 0.003768908517337822, '
    '"idler_bearing_diameter": 0.006827851916582512, "disc_groove_ratio": 1.6547081943502548, '
    '"idler_groove_ratio": 1.9520133015176553, "single_idler_groove_ratio": 6.351937805402365, '
    '"tilt_safety_factor": 0.6384163866681013, "creep_limit": 0.08873814905800856, '
    '"min_roller_gap": 0.0018062313986054546, "cam": {"disc": "output", '
    '"preload": 356.5032894524011, "ramp_angle_deg": 2.3024519077669297, '
    '"mean_radius": 0.02304749661235582, "friction": 0.01161194509523263}}'
)
RPM = 8636.557827829702


def _task_56() -> Variator:
    d, f = load_builtin("hub")
    d = d.replace(name="random", **json.loads(TASK_56))
    return with_oil_temperature(Variator(d, f, "double", traction_law="isothermal"), "fixed")


def test_task_30999_56_one_optimum_from_every_start():
    """The point of the largest gap (step 10): the batched search gives one force from the
    cold start and from guesses 0.7 to 1.4 times it, with or without creeps."""
    v = _task_56()
    case = ClampCase(v.design, v.fluid, v.architecture, 0.9957691664961302,
                     10.898082791847969, rpm_to_rad_s(RPM))
    pb = point_problem(case)
    cold = optimal_forces(pb, OptimalClamp(), v.options)
    assert cold.fast[0]
    for factor in (0.7, 0.97, 0.99, 1.01, 1.03, 1.4):
        got = optimal_forces(pb, OptimalClamp(), v.options, guess=cold.force * factor)
        assert got.fast[0]
        np.testing.assert_allclose(got.force, cold.force, rtol=1e-6)


def test_task_30999_56_cycle_steps_are_solve():
    """Four steps of the task's cycle (three were 1.4e-6 to 6.7e-5 from `solve`): every
    step's efficiency and force are `solve`'s at its ratio."""
    v = _task_56()
    speed = [804.558345871757, 800.9393571090171, 800.7312003261584, 793.3257185241704]
    torque = [7.154324515820529, 12.42321408109607, 10.898082791847969, 12.370942344864867]
    cycle = cycle_from_arrays(time=np.arange(4.0), output_speed=speed, output_torque=torque)
    steps = v.run_cycle(cycle, clamp_law="optimal",
                        settings=CycleSettings(target_input_speed_rpm=RPM, progress=False)).steps
    assert (steps["status"] == 0).all()
    for _, s in steps.iterrows():
        p = v.solve(s.ratio, s.output_torque, clamp_law="optimal",
                    input_speed_rpm=s.input_speed_rpm)
        assert abs(p.eta - s.eta) <= 1e-8
        assert abs(p.clamp_force - s.clamp_force) <= 1e-5 * p.clamp_force


# Harden task 3102:3101: Table I's drive reshaped (three rollers, creep limit 0.157), whose
# search rule's optimum lies on its creep bound, so `solve`'s climb starts from the guess
# 317 N, four times too low, climbs past the optimum and jumps back below the bound; it
# ran out of rounds and the stencil search certified another tooth (6.5e-5 in efficiency
# from the cycle's step).
TASK_3101 = (
    '{"aspect_ratio": 1.0356828857404266, "roller_radius": 0.010041496978746872, '
    '"theta0_deg": 56.99543423568752, "theta2_deg": 56.09525460404558, '
    '"alpha_deg": 10.641409046180861, "n_rollers": 3, '
    '"roller_bearing_diameter": 0.005279114069910914, '
    '"idler_bearing_diameter": 0.0014409167031526286, "disc_groove_ratio": 2.224034072150393, '
    '"idler_groove_ratio": 1.4440563383528333, "single_idler_groove_ratio": Infinity, '
    '"tilt_safety_factor": 0.6974828276091194, "creep_limit": 0.15746856060131892, '
    '"min_roller_gap": 0.0020676206365585594}'
)


def test_task_3102_3101_the_cold_start_climbs_to_the_same_stencil():
    d, f = load_builtin("table1")
    v = Variator(d.replace(name="random", **json.loads(TASK_3101)), f, "double")
    case = ClampCase(v.design, v.fluid, v.architecture, 0.7984898593422365, 8.3506981820081,
                     rpm_to_rad_s(1835.6054405051689))
    pb = point_problem(case)
    cold = optimal_forces(pb, OptimalClamp(), v.options)
    assert cold.fast[0]
    for guess in (1200.0, 1250.0, 1300.0):
        got = optimal_forces(pb, OptimalClamp(), v.options, guess=guess)
        np.testing.assert_allclose(got.force, cold.force, rtol=1e-5)


def test_far_above_a_convex_tail_the_steps_double():
    """Harden task 3205:1743 (a 25-ball single-idler drive, visco-elastic): from a start
    5.7 times the optimum the efficiency is convex in ``ln F_N0`` (no vertex to jump to),
    and one step a round ran out of rounds 60 steps from the optimum; steps the same way
    now double, so the climb certifies the stencil it reaches from the optimum itself."""
    score = _Synthetic(lambda u: 0.9 / (1.0 + 4.0 * (u - U0) ** 2))
    ref = _climb(score, [U0])
    for offset in (1.74, -1.2, 0.9):
        got = _climb(score, [U0 + offset])
        assert got[1][0] and got[0][0] == ref[0][0]


def test_a_sharp_peak_is_certified_not_jumped_across():
    """Where the efficiency peaks sharply, the parabolas through the stencils on either
    side are concave with vertices beyond each other's centres: the climb jumped back and
    forth for every round and left the point uncertified (three steps of the hub's duty
    cycle, session 33). A neighbour better than the centre now bounds the climb on its
    side, so every start certifies the one stencil around the peak."""
    score = _Synthetic(lambda u: 0.9 - 0.05 * np.sqrt(0.01**2 + (u - U0) ** 2))
    u, done, _ = _climb(score, U0 + np.linspace(-0.5, 0.5, 41))
    assert done.all()
    assert np.ptp(u) == 0.0 and abs(u[0] - U0) <= LATTICE / 2


def test_an_optimum_below_min_force_stays_there():
    """The bound a better lower neighbour sets never lets the climb below ``min_force``:
    harden task 3301:919 (an optimum at 66 N under the 100 N floor, started from 211 N)
    set it one step below the floor, and a duty cycle's steps went on to 70 N (efficiency
    0.889 where `solve`, at 100 N, had 0.828). The point is left uncertified at the
    lowest lattice force within the bounds, for the search that follows."""
    score = _Synthetic(lambda u: 0.9 - 0.25 * (u - np.log(66.0)) ** 2)
    lo = np.log(100.0)
    u, done, _ = _climb(score, np.log([211.0, 150.0, 105.0]), lo=lo)
    assert not done.any()
    assert np.all(u >= lo) and np.all(u <= lo + 2 * LATTICE)


@dataclass(frozen=True)
class _WithCreeps(_Synthetic):
    """`_Synthetic` whose creeps times ``F_N0`` are a cubic in ``ln F_N0``."""

    def __call__(self, index, u, x0=None):
        e, _ = super().__call__(index, u, x0)
        return e, _creeps(np.asarray(u, dtype=float))


def _creeps(u):
    s = u - U0
    scaled = 0.03 + 0.01 * s - 0.02 * s**2 + 0.005 * s**3
    return (scaled * np.exp(-u))[:, None] * np.array([1.0, -0.1, 0.1, -1.0])


def test_the_creeps_at_the_answer_come_from_the_cubic():
    """The creeps returned at a certified answer (the final solve's start) are the cubic
    through the four lattice forces' ``F_N0`` times their creeps: exact when that product
    is a cubic in ``ln F_N0`` (the stencil's parabola missed it by some ``h^3``)."""
    score = _WithCreeps(lambda u: 0.9 - 0.25 * (u - U0) ** 2 + 0.3 * (u - U0) ** 3)
    u, done, creep = _climb(score, U0 + np.array([-0.2, 0.013, 0.3]))
    assert done.all()
    np.testing.assert_allclose(creep, _creeps(u), rtol=1e-12, atol=0)
