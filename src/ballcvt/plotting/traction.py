"""Figures of traction curves and of a fluid fit (docs/model.md §14)."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

__all__ = ["plot_traction_curve", "traction_curve_figure", "fit_figure"]


def plot_traction_curve(curve, ax, label: str | None = None, **style):
    """Draw ``mu`` against the slide-to-roll ratio of a `TractionCurve` on ``ax``.

    Returns the list of matplotlib artists drawn.
    """
    return ax.plot(curve.creep, curve.mu, label=label or f"{curve.law} law", **style)


def traction_curve_figure(curves, title: str = "Traction curve") -> Figure:
    """Traction coefficient (left) and spin-moment coefficient (right) against the
    slide-to-roll ratio, one line per `TractionCurve`; the film temperature rise on a
    right axis of the left panel where a curve is thermal."""
    fig = Figure(figsize=(10.0, 4.2), layout="constrained")
    ax1, ax2 = fig.subplots(1, 2)
    for curve in curves:
        (line,) = plot_traction_curve(curve, ax1)
        ax2.plot(curve.creep, curve.chi, color=line.get_color(), label=f"{curve.law} law")
        if np.any(curve.temperature_rise):
            twin = ax1.twinx()
            twin.plot(curve.creep, curve.temperature_rise, ls="--", color=line.get_color())
            twin.set_ylabel("film temperature rise [K] (dashed)")
    ax1.set_xlabel(r"slide-to-roll ratio $\Delta U / U$ [-]")
    ax1.set_ylabel(r"traction coefficient $\mu$ [-]")
    ax2.set_xlabel(r"slide-to-roll ratio $\Delta U / U$ [-]")
    ax2.set_ylabel(r"spin-moment coefficient $\chi$ [-]")
    ax1.legend(loc="lower right")
    fig.suptitle(title)
    return fig


def fit_figure(curves, fit, title: str = "Fluid fit") -> Figure:
    """Measured points and fitted curves per condition (left), residuals (right)."""
    fig = Figure(figsize=(10.0, 4.2), layout="constrained")
    ax1, ax2 = fig.subplots(1, 2)
    for label in dict.fromkeys(curves.condition):
        sel = curves.condition == label
        order = np.argsort(curves.creep[sel])
        pts = ax1.plot(curves.creep[sel], curves.mu[sel], "o", ms=3, label=str(label))
        ax1.plot(curves.creep[sel][order], fit.model[sel][order], "-", color=pts[0].get_color())
        ax2.plot(curves.creep[sel], fit.residuals[sel], "o", ms=3, color=pts[0].get_color())
    ax2.axhline(0.0, color="black", lw=0.8)
    for ax in (ax1, ax2):
        ax.set_xlabel(r"slide-to-roll ratio $\Delta U / U$ [-]")
    ax1.set_ylabel(r"traction coefficient $\mu$ [-] (points: measured, lines: fit)")
    ax2.set_ylabel(r"residual $\mu_{model} - \mu_{measured}$ [-]")
    ax1.legend(title="condition", fontsize="small")
    fig.suptitle(f"{title}: rms residual {fit.rms:.2e}")
    return fig
