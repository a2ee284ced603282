"""Figure of a duty-cycle run: ratio and speeds, efficiency, and losses against time."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

__all__ = ["cycle_figure"]

_FLAG_STYLE = {
    "ratio_limited": ("tab:orange", "ratio limited"),
    "negative_torque": ("tab:gray", "braking (not modelled)"),
    "power_below_drag": ("tab:brown", "power below the drag"),
    "beyond_capacity": ("tab:red", "beyond capacity"),
    "not_converged": ("black", "not converged"),
}


def cycle_figure(steps, title: str = "Duty cycle") -> Figure:
    """Three panels over time: ratio and speeds, efficiency (flagged steps marked), and the
    power losses by kind (stacked), with the oil temperature on a second axis when the
    steps carry it (``oil_temperature_C``, docs/model.md §15).

    Parameters
    ----------
    steps : pandas.DataFrame
        `ballcvt.analysis.cycles.CycleResult.steps`.
    title : str
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
    """
    t = steps["time"].to_numpy()
    fig = Figure(figsize=(9.0, 8.0), layout="constrained")
    ax1, ax2, ax3 = fig.subplots(3, 1, sharex=True)
    ax1.plot(t, steps["ratio"], color="tab:blue", label=r"ideal ratio $\tau_{ID}$")
    ax1.set_ylabel(r"$\tau_{ID}$ [-]")
    twin = ax1.twinx()
    twin.plot(t, steps["input_speed_rpm"], color="tab:green", lw=0.9, label="input speed")
    twin.plot(t, steps["output_speed_rpm"], color="tab:purple", lw=0.9, label="output speed")
    twin.set_ylabel("speed [rpm]")
    lines = ax1.get_lines() + twin.get_lines()
    ax1.legend(lines, [ln.get_label() for ln in lines], loc="upper right", fontsize=8)
    ax2.plot(t, steps["eta"], color="tab:blue", lw=1.0, label=r"$\eta$")
    lo = np.nanmin(steps["eta"]) if np.isfinite(steps["eta"]).any() else 0.0
    for flag, (color, label) in _FLAG_STYLE.items():
        mask = (steps["flag"] == flag).to_numpy()
        if mask.any():
            ax2.plot(t[mask], np.full(mask.sum(), lo), "|", color=color, ms=10, label=label)
    ax2.set_ylabel(r"overall efficiency $\eta$ [-]")
    ax2.legend(loc="lower right", fontsize=8)
    kinds = [
        ("creep", "creep"),
        ("spin", "spin"),
        ("bearing", "bearings"),
        ("parasitic", "parasitic"),
    ]
    stack = [np.nan_to_num(steps[f"loss_{k}"].to_numpy()) for k, _ in kinds]
    ax3.stackplot(t, *stack, labels=[label for _, label in kinds], alpha=0.85)
    ax3.set_ylabel("power loss [W]")
    ax3.set_xlabel("time [s]")
    ax3.legend(loc="upper right", fontsize=8)
    if "oil_temperature_C" in steps:
        oil = ax3.twinx()
        oil.plot(t, steps["oil_temperature_C"], color="tab:red", lw=1.2, label="oil")
        oil.set_ylabel("oil temperature [C]", color="tab:red")
    fig.suptitle(title)
    return fig
