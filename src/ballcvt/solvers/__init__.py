"""The solvers layer: the equilibrium, the limiting torque and the clamping force (docs/model.md §5, §8)."""

from .limit import limit_torque, limit_torque_batch, traction_ceiling_torque
from .newton import BatchSolution, solve_batch
from .point import PointSolution, SolverOptions, initial_creep, solve_point

__all__ = [
    "BatchSolution",
    "solve_batch",
    "limit_torque",
    "limit_torque_batch",
    "traction_ceiling_torque",
    "PointSolution",
    "SolverOptions",
    "initial_creep",
    "solve_point",
]
