"""Shift-effort map: the moment to tilt the balls over ratio x output torque
(``ballcvt map --shift-effort``, docs/model.md §17)."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from .figures import LABELS

__all__ = ["shift_effort_map"]


def shift_effort_map(ratio, torque, moment, limit, title="Shift effort") -> Figure:
    """Filled contours of the moment per ball to tilt at the map's rate, with the
    limiting-torque curve.

    Parameters
    ----------
    ratio, torque : array_like
        The grid's ratios [-] and output torques [N m].
    moment : array_like
        Shift moment per ball [N m], ``(n_ratio, n_torque)`` (NaN, or a torque above the
        limit: blank).
    limit : array_like
        Limiting torque at each ratio [N m] (``(n_ratio,)``).
    title : str
        Figure title.
    """
    fig = Figure(figsize=(6.6, 4.8), layout="constrained")
    ax = fig.add_subplot()
    z = np.abs(np.asarray(moment, dtype=float)).T  # (n_torque, n_ratio)
    beyond = np.asarray(torque, dtype=float)[:, None] > np.asarray(limit, dtype=float)[None, :]
    z = np.ma.masked_where(beyond | ~np.isfinite(z), z)  # nothing above the limit
    if z.count() >= 4:
        filled = ax.contourf(ratio, torque, z, levels=12, cmap="viridis")
        fig.colorbar(filled, ax=ax, label="shift moment per ball [N m]")
    ax.plot(ratio, limit, "k-", lw=1.2, label="limiting torque")
    ax.set_xlabel(LABELS["ratio"])
    ax.set_ylabel(LABELS["output_torque"])
    ax.set_ylim(0.0, float(np.max(torque)))
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title(title, fontsize=10)
    return fig
