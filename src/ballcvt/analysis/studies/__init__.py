"""Design studies: sampled sweeps and optimisation over designs, on Dask (docs/studies.md)."""

from .evaluate import DESIGN_CODES, envelope_diameter, evaluate_chunk, make_context
from .pareto import choose, pareto_mask
from .run import Compute, StudyResult, design_vectors, local_client, run_study
from .spec import CONSTRAINTS, OBJECTIVES, StudySpec, parse_study, read_study

__all__ = [
    "DESIGN_CODES",
    "envelope_diameter",
    "evaluate_chunk",
    "make_context",
    "choose",
    "pareto_mask",
    "StudyResult",
    "Compute",
    "design_vectors",
    "local_client",
    "run_study",
    "CONSTRAINTS",
    "OBJECTIVES",
    "StudySpec",
    "parse_study",
    "read_study",
]


def __getattr__(name):
    if name == "STATUS":  # the old code -> words table of a design's status
        from ..._compat import warn_renamed

        warn_renamed("ballcvt.analysis.studies.STATUS", "ballcvt.analysis.studies.DESIGN_CODES")
        return {int(k): w for k, w in DESIGN_CODES.items()}
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
