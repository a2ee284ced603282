"""Figure of the traction capacity over a ratio range, marked by its active constraint."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

__all__ = ["capacity_figure"]

_MARKERS = ("o", "s", "^", "D", "v", "P", "X")


def capacity_figure(frame, title: str = "Traction capacity") -> Figure:
    """The largest admissible output torque against the ratio, one marker per active
    constraint (creep at a named contact, pressure, no equilibrium); the lowest admissible
    torque where it is above zero.

    Parameters
    ----------
    frame : pandas.DataFrame
        `ballcvt.api.CapacityCurve.to_frame`: ``ratio`` [-], ``limit_torque`` [N m],
        ``lowest_torque`` [N m], ``active_constraint``.
    title : str
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
    """
    ratio = frame["ratio"].to_numpy(dtype=float)
    top = frame["limit_torque"].to_numpy(dtype=float)
    low = frame["lowest_torque"].to_numpy(dtype=float)
    active = frame["active_constraint"].fillna("not determined").to_numpy(dtype=str)
    fig = Figure(figsize=(7.0, 4.5), layout="constrained")
    ax = fig.subplots()
    ax.plot(ratio, top, color="0.6", lw=1.0, zorder=1)
    for k, name in enumerate(dict.fromkeys(active)):
        m = active == name
        ax.plot(
            ratio[m],
            np.where(np.isfinite(top[m]), top[m], 0.0),
            _MARKERS[k % 7],
            ls="none",
            label=f"set by {name}",
        )
    if np.nanmax(np.append(low, 0.0)) > 0.0:
        ax.plot(ratio, low, "--", color="tab:gray", lw=1.0, label="lowest admissible torque")
    ax.set_xlabel(r"ideal ratio $\tau_{ID}$ [-]")
    ax.set_ylabel("largest admissible output torque [N m]")
    ax.set_ylim(bottom=0.0)
    ax.set_title(title)
    ax.legend(fontsize=8)
    return fig
