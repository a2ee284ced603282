"""Figure of a shift transient: ratio and tilt, shift moment and efficiency against time."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

__all__ = ["shift_figure"]


def shift_figure(samples, title: str = "Shift") -> Figure:
    """Three panels over time: ideal ratio (and tilt), the moment about the balls' tilt
    axes (all balls), and the overall efficiency of the quasi-static points.

    Parameters
    ----------
    samples : pandas.DataFrame
        `ballcvt.analysis.shift.ShiftResult.samples`.
    title : str
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
        A moment series without a finite value (no moment model) is not drawn; the panel
        says so.
    """
    t = samples["time_s"].to_numpy()
    fig = Figure(figsize=(8.0, 7.5), layout="constrained")
    ax1, ax2, ax3 = fig.subplots(3, 1, sharex=True)
    ax1.plot(t, samples["ratio"], color="tab:blue", label=r"ideal ratio $\tau_{ID}$")
    ax1.set_ylabel(r"$\tau_{ID}$ [-]")
    twin = ax1.twinx()
    twin.plot(t, samples["tilt_deg"], color="tab:green", lw=0.9, ls="--", label=r"tilt $\gamma$")
    twin.set_ylabel(r"$\gamma$ [deg]")
    lines = ax1.get_lines() + twin.get_lines()
    ax1.legend(lines, [ln.get_label() for ln in lines], loc="best", fontsize=8)
    drawn = False
    for column, label, color in (
        ("shifter_moment_Nm", "at the shifter (all balls)", "tab:red"),
        ("holding_moment_Nm", "holding, per ball", "tab:orange"),
    ):
        y = samples[column].to_numpy()
        if np.isfinite(y).any():
            ax2.plot(t, y, color=color, label=label)
            drawn = True
    if drawn:
        ax2.legend(loc="upper right", fontsize=8)
    else:
        ax2.text(
            0.5,
            0.5,
            "no shift-moment model",
            ha="center",
            va="center",
            transform=ax2.transAxes,
            color="tab:gray",
        )
    ax2.set_ylabel("moment about the\ntilt axes [N m]")
    ax3.plot(t, samples["eta"], color="tab:blue", label=r"$\eta$ (quasi-static)")
    ax3.set_ylabel(r"efficiency $\eta$ [-]")
    ax3.set_xlabel("time [s]")
    ax3.legend(loc="best", fontsize=8)
    fig.suptitle(title)
    return fig
