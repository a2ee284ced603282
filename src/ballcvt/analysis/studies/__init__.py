"""Design studies: sampled sweeps and optimisation over designs, on Dask (docs/studies.md)."""

from ..._lazy import lazy_exports

#: Public name -> the submodule that defines it (loaded on first use: `ballcvt._lazy`).
_EXPORTS = {
    "folder_lock": ".lock",
    "DESIGN_CODES": ".evaluate",
    "envelope_diameter": ".evaluate",
    "evaluate_chunk": ".evaluate",
    "make_context": ".evaluate",
    "choose": ".pareto",
    "pareto_mask": ".pareto",
    "Compute": ".run",
    "StudyResult": ".run",
    "design_vectors": ".run",
    "local_client": ".run",
    "run_study": ".run",
    "CONSTRAINTS": ".spec",
    "OBJECTIVES": ".spec",
    "StudySpec": ".spec",
    "parse_study": ".spec",
    "read_study": ".spec",
}

__all__ = [
    "folder_lock",
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


def _renamed(name):
    if name == "STATUS":  # the old code -> words table of a design's status
        from ..._compat import warn_renamed

        warn_renamed("ballcvt.analysis.studies.STATUS", "ballcvt.analysis.studies.DESIGN_CODES")
        from .evaluate import DESIGN_CODES

        return {int(k): w for k, w in DESIGN_CODES.items()}
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS, _renamed)
