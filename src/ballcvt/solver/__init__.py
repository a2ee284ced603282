"""Layer 5: solvers of the equilibrium and the limiting torque (MODEL.md sections 5, 7)."""

from .point import PointSolution, SolverOptions, initial_creep, solve_point

__all__ = ["PointSolution", "SolverOptions", "initial_creep", "solve_point"]
