"""Uncertainty propagation: a drive file's uncertain parameters (its ``[uncertainty]``
table) propagated to efficiency and capacity bands, with a ranked sensitivity
(docs/uncertainty.md)."""

from ..._lazy import lazy_exports

#: Public name -> the submodule that defines it (loaded on first use: `ballcvt._lazy`).
_EXPORTS = {
    "METHODS": ".sampling",
    "draw": ".sampling",
    "spearman": ".sensitivity",
    "srrc": ".sensitivity",
    "Duty": ".evaluate",
    "evaluate_chunk": ".evaluate",
    "UncertaintyResult": ".result",
    "UncertaintyRequest": ".run",
    "UncertainDrive": ".run",
    "run_uncertainty": ".run",
    "duty_of": ".run",
}

__all__ = list(_EXPORTS)

__getattr__, __dir__ = lazy_exports(__name__, _EXPORTS)
