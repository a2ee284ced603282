"""Figure of an uncertainty propagation: the bands of efficiency and capacity, and the
parameters ranked by their influence (a tornado chart)."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

__all__ = ["uncertainty_figure"]


def uncertainty_figure(band, ranking, title: str = "Uncertainty", top: int = 12) -> Figure:
    """Bands (5-95 % range, median, nominal) of the efficiency and capacity at each
    operating point, and a tornado chart of the most influential parameters.

    Parameters
    ----------
    band : pandas.DataFrame
        `UncertaintyResult.band`: ``output``, ``unit`` (``-`` for an efficiency, ``N m``
        for a capacity), ``nominal``, ``q05``, ``q50``, ``q95``.
    ranking : pandas.DataFrame
        `UncertaintyResult.ranking`: parameters as index, ``score_eta``,
        ``score_capacity`` (mean absolute Spearman correlation [-]) and the signed
        correlation with each output (columns named as ``band["output"]``).
    title : str
        Figure title.
    top : int
        Parameters shown in the tornado chart.

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig = Figure(figsize=(11.0, 4.8), layout="constrained")
    axes = fig.subplots(1, 3, width_ratios=[1.0, 0.7, 1.4])
    for ax, unit, what in zip(axes[:2], ("-", "N m"), ("efficiency", "capacity")):
        rows = band[band["unit"] == unit]
        _band(ax, rows, f"{what} [{unit}]" if unit != "-" else "efficiency [-]")
    _tornado(axes[2], band, ranking.head(top))
    fig.suptitle(title)
    return fig


def _label(output: str) -> str:
    """A band's output name without its quantity (``eta at ratio 1, ...`` -> ``ratio 1``,
    ...), one term a line."""
    return output.split(" at ", 1)[-1].replace(", ", "\n")


def _band(ax, rows, ylabel: str) -> None:
    """The 5-95 % range as a bar, the median and the nominal value, per output."""
    x = np.arange(len(rows))
    lo, mid, hi = (rows[c].to_numpy(dtype=float) for c in ("q05", "q50", "q95"))
    ok = np.isfinite(lo) & np.isfinite(hi)
    if ok.any():
        ax.vlines(x[ok], lo[ok], hi[ok], lw=6, color="tab:blue", alpha=0.4, label="5-95 %")
        ax.plot(x[ok], mid[ok], "_", ms=14, mew=2, color="tab:blue", label="median")
    nominal = rows["nominal"].to_numpy(dtype=float)
    shown = np.isfinite(nominal)
    if shown.any():
        ax.plot(x[shown], nominal[shown], "kx", label="nominal (file values)")
    ax.set_xticks(x, [_label(o) for o in rows["output"]], fontsize=7)
    ax.set_xlim(-0.6, max(len(rows), 1) - 0.4)
    ax.set_ylabel(ylabel)
    if ok.any() or shown.any():
        ax.legend(fontsize=7)


def _tornado(ax, band, ranking) -> None:
    """Mean |Spearman rho| with the efficiencies (bar colour: the sign of the mean
    correlation) and with the capacities (outline), most influential on top."""
    names = list(ranking.index)[::-1]
    y = np.arange(len(names))
    eta_cols = [o for o, u in zip(band["output"], band["unit"]) if u == "-" and o in ranking]
    score = ranking["score_eta"].to_numpy(dtype=float)[::-1]
    sign = ranking[eta_cols].mean(axis=1).to_numpy(dtype=float)[::-1] if eta_cols else score
    colours = np.where(sign >= 0, "tab:green", "tab:red")
    ok = np.isfinite(score)
    ax.barh(y[ok] + 0.18, score[ok], height=0.36, color=colours[ok], label="efficiency")
    cap = ranking["score_capacity"].to_numpy(dtype=float)[::-1]
    okc = np.isfinite(cap)
    if okc.any():
        ax.barh(
            y[okc] - 0.18, cap[okc], height=0.36, color="none", edgecolor="0.3", label="capacity"
        )
    ax.set_yticks(y, names, fontsize=7)
    ax.set_xlim(0.0, 1.0)
    ax.set_xlabel("mean |Spearman rank correlation| [-]\n(green: raises efficiency, red: lowers)")
    ax.legend(fontsize=7, loc="lower right")
