"""Trial states of a solver are judged, not warned about.

A Newton or hybrid step far from the solution (a force that runs away, a creep past the
traction peak) can evaluate the model where it overflows or goes NaN. The solver judges
every such trial by its residual and flags a point it cannot converge (never returns it
as an answer), so numpy's RuntimeWarnings about those trials say nothing a user can act
on; the solver entry points run under `quiet_trials`.
"""

from __future__ import annotations

import functools

import numpy as np

__all__ = ["quiet_trials"]


def quiet_trials(solver):
    """Run ``solver`` with numpy's floating-point warnings off (`numpy.errstate`)."""

    @functools.wraps(solver)
    def run(*args, **kwargs):
        with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
            return solver(*args, **kwargs)

    return run
