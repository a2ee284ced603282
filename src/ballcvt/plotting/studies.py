"""Figures of a design study: Pareto front, the designs' parameters, chosen vs base map."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from .figures import plot_efficiency_map

__all__ = ["pareto_figure", "parameters_figure", "maps_figure"]


def _label(name, units):
    return f"{name} [{units.get(name, '-')}]"


def pareto_figure(ds, objectives, units) -> Figure:
    """Feasible designs (grey), the Pareto front (blue) and the chosen design (star) in the
    plane of the first two objectives (one objective: against the design index)."""
    fig = Figure(figsize=(6.4, 4.8), layout="constrained")
    ax = fig.add_subplot()
    ok = ds["status"].values == 0
    front, pick = ds["pareto"].values, ds["chosen"].values
    if len(objectives) >= 2:
        x, y = ds[objectives[0]].values, ds[objectives[1]].values
        ax.set_xlabel(_label(objectives[0], units))
        ax.set_ylabel(_label(objectives[1], units))
    else:
        x, y = ds["design"].values, ds[objectives[0]].values
        ax.set_xlabel("design")
        ax.set_ylabel(_label(objectives[0], units))
    ax.plot(x[ok & ~front], y[ok & ~front], "o", color="0.7", ms=4, label="feasible")
    order = np.argsort(x[front])
    ax.plot(x[front][order], y[front][order], "o-", color="tab:blue", ms=5, label="Pareto front")
    ax.plot(x[pick], y[pick], "*", color="tab:red", ms=14, label="chosen")
    ax.set_title(
        f"{int(ok.sum())} feasible of {ok.size} designs, {int(front.sum())} on the front",
        fontsize=10,
    )
    ax.legend(fontsize="small")
    return fig


def parameters_figure(ds, names, colour_by) -> Figure:
    """Scatter matrix of the varied parameters: feasible designs coloured by the objective
    ``colour_by``, infeasible ones as grey crosses, the front circled."""
    p = len(names)
    fig = Figure(figsize=(2.3 * p + 1.2, 2.3 * p), layout="constrained")
    axes = np.atleast_2d(fig.subplots(p, p, squeeze=False))
    ok, front = ds["status"].values == 0, ds["pareto"].values
    c = ds[colour_by].values
    art = None
    for i, yi in enumerate(names):
        for j, xj in enumerate(names):
            ax = axes[i, j]
            x, y = ds[xj].values, ds[yi].values
            if i == j:
                ax.hist([x[ok], x[~ok]], bins=10, stacked=True, color=["tab:blue", "0.75"])
            else:
                ax.plot(x[~ok], y[~ok], "x", color="0.75", ms=3)
                art = ax.scatter(x[ok], y[ok], c=c[ok], s=12, cmap="viridis")
                ax.plot(x[front], y[front], "o", mfc="none", mec="tab:red", ms=6)
            if i == p - 1:
                ax.set_xlabel(xj, fontsize=8)
            if j == 0:
                ax.set_ylabel(yi, fontsize=8)
            ax.tick_params(labelsize=7)
    if art is not None:
        fig.colorbar(art, ax=axes, label=colour_by, shrink=0.6)
    return fig


def maps_figure(base, chosen, titles) -> Figure:
    """Efficiency maps of two sweeps side by side (the base design and the chosen one)."""
    fig = Figure(figsize=(12.0, 4.6), layout="constrained")
    for ax, ds, title in zip(fig.subplots(1, 2), (base, chosen), titles):
        plot_efficiency_map(ds, ax=ax)
        ax.set_title(title, fontsize=9)
    return fig
