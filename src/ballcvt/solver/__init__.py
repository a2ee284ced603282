"""Layer 5: solvers of the equilibrium and the limiting torque (MODEL.md sections 5, 7)."""

from .limit import LimitSolution, limit_torque, traction_ceiling_torque
from .point import PointSolution, SolverOptions, initial_creep, solve_point

__all__ = ["LimitSolution", "limit_torque", "traction_ceiling_torque", "PointSolution",
           "SolverOptions", "initial_creep", "solve_point"]
