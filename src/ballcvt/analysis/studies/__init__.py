"""Design studies: sampled sweeps and optimisation over designs, on Dask (docs/studies.md)."""

from .evaluate import STATUS, envelope_diameter, evaluate_chunk, make_context
from .pareto import choose, pareto_mask
from .run import StudyResult, design_vectors, local_client, run_study
from .spec import CONSTRAINTS, OBJECTIVES, StudySpec, parse_study, read_study

__all__ = [
    "STATUS",
    "envelope_diameter",
    "evaluate_chunk",
    "make_context",
    "choose",
    "pareto_mask",
    "StudyResult",
    "design_vectors",
    "local_client",
    "run_study",
    "CONSTRAINTS",
    "OBJECTIVES",
    "StudySpec",
    "parse_study",
    "read_study",
]
