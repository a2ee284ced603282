"""The equilibrium layer: the problem and its residual (docs/model.md §5)."""

from .problem import EquilibriumProblem, build_problem
from .residual import EquilibriumState, evaluate

__all__ = ["EquilibriumProblem", "build_problem", "EquilibriumState", "evaluate"]
