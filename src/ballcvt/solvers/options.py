"""Numerical options of the equilibrium solvers (the one place every solver reads them)."""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..model.traction.base import residual_floor
from ..model.traction.quadrature import Quadrature

__all__ = ["SolverOptions", "METHODS", "CREEP_BOUNDS", "at_residual_floor", "coarse_options"]

#: Creeps outside this open interval are unphysical (speeds reverse) [-].
CREEP_BOUNDS = (-0.5, 0.98)
METHODS = ("newton", "hybr")


#: Fewest points of a batch near their solutions that Newton evaluates without the
#: Jacobian apart from the rest (`SolverOptions.split_min`, `ballcvt.solvers.newton_eval`):
#: a second evaluation's fixed cost outweighs fewer.
SPLIT_MIN = 16


@dataclass(frozen=True)
class SolverOptions:
    """Numerical options of the equilibrium solvers.

    Attributes
    ----------
    quadrature : Quadrature
        Traction-integral rule.
    tol : float
        Largest accepted ``max |residual|`` (residuals are torques over ``F_N0 r_S``) [-].
    method : {"newton", "hybr"}
        ``newton``: the batched Newton method with analytic traction derivatives (fast,
        default); ``hybr``: SciPy's hybrid method with a finite-difference Jacobian (the
        straightforward path, kept as a baseline). Both fall back to bracketing.
    max_iterations : int
        Newton iterations allowed (per stage) before the fallback.
    predictor : Quadrature or None
        Coarse rule on which the Newton method first converges to ``predictor_tol``
        (a cheap starting point for the iterations on ``quadrature``); None to skip.
    predictor_tol : float
        Tolerance of the predictor stage [-].
    search_rule : Quadrature or None
        Rule of the coarse passes that compare efficiencies across clamping forces (the
        optimal clamp's coarse search, a duty cycle's first pass under it), to
        ``predictor_tol``; None: the predictor's. The centred rule's nodes stay put as the
        creep moves the pole, so its efficiency is smooth in the force; the predictor's
        pole-centred nodes move with the pole, and on 12 x 8 of them the traction
        coefficient's slope in the creep swung from 0.3 to 2.3 times the full rule's
        (Table I, a disc contact's pole in ``0.6 < |Y_p| < 1``; the centred 12 x 8 rule
        within 2 %, docs/model.md §3).
    predictor_min_points : int
        Smallest batch that runs the predictor stage. On a few points an iteration
        costs the same on either rule (Python, not the integrals, dominates), and Newton
        on the requested rule alone needs 3-5 iterations where the two stages need 7;
        the predictor pays from a few tens of points up (benchmarks/bench_paths.py).
    max_evaluations : int
        Residual evaluations allowed to the hybrid method before the fallback.
    split_min : int
        Fewest points of a batch near their solutions that Newton evaluates without the
        Jacobian, apart from the others (`ballcvt.solvers.newton_eval.evaluate_split`).
        With 1 (and ``predictor_min_points`` above the batch) every point's iterates are
        its own to the bit, whatever its batch: the optimal clamp's capacity search under
        a law with more than one equilibrium (`ballcvt.solvers.optimal_capacity`).
    """

    quadrature: Quadrature = Quadrature()
    tol: float = 1e-11
    method: str = "newton"
    max_iterations: int = 40
    max_evaluations: int = 400
    predictor: Quadrature | None = Quadrature("pole", 12, 8, 12)
    predictor_tol: float = 1e-6
    predictor_min_points: int = 32
    search_rule: Quadrature | None = Quadrature("centred", 12, 8, 8)
    split_min: int = SPLIT_MIN

    def __post_init__(self):
        if self.method not in METHODS:
            raise ValueError(f"solver method must be one of {METHODS}, got {self.method!r}")
        if self.split_min < 1:
            raise ValueError(f"split_min must be at least 1, got {self.split_min!r}")


def at_residual_floor(options: SolverOptions, fluid) -> SolverOptions:
    """``options`` with ``tol`` raised to the residual floor of ``fluid``'s traction law
    (`ballcvt.model.traction.base.TractionLaw.residual_floor`: 1e-9 under the thermal law,
    whose coefficients carry rounding noise; none under the paper's law)."""
    floor = residual_floor(fluid)
    return options if options.tol >= floor else replace(options, tol=floor)


def coarse_options(options: SolverOptions, search: bool = False) -> SolverOptions:
    """``options`` on their predictor's rule, to the predictor's tolerance (never below
    ``tol``), with no predictor stage of their own: the cheap solves whose answers only
    steer the full rule's (a capacity scan's screen, a duty cycle's first pass, the
    optimal clamp's coarse search). ``search``: on the ``search_rule`` instead
    (where there is a predictor), for the passes that compare efficiencies across forces.
    """
    rule = options.predictor or options.quadrature
    if search and options.predictor is not None and options.search_rule is not None:
        rule = options.search_rule
    return replace(
        options,
        quadrature=rule,
        predictor=None,
        tol=max(options.tol, options.predictor_tol),
    )
