"""Matplotlib figures of the paper's results (and the efficiency map) from sweep data.

Every function takes plain data (an `xarray.Dataset` from `ballcvt.sweeps.sweep` or
arrays) and returns a `matplotlib.figure.Figure`; nothing here computes physics. Axes carry
the quantity and its unit; legends follow the paper's.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only; never needs a display
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

__all__ = ["save", "line_panels", "efficiency_map", "ratio_vs_tilt"]


def save(fig, directory, name) -> list[Path]:
    """Write ``fig`` as ``name.png`` and ``name.svg`` in ``directory``; close it."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    paths = [directory / f"{name}.png", directory / f"{name}.svg"]
    fig.savefig(paths[0], dpi=130, bbox_inches="tight")
    fig.savefig(paths[1], bbox_inches="tight")
    plt.close(fig)
    return paths


def line_panels(panels, xlabel, title=None, ncols=None):
    """A row (or grid) of line plots.

    Parameters
    ----------
    panels : list of dict
        Each with ``ylabel``, ``title`` and ``lines``: a list of
        ``(x, y, label, style)`` (``style`` a dict of matplotlib keyword arguments),
        and optionally ``yscale`` and ``ylim``.
    xlabel : str
        Common x-axis label (quantity [unit]).
    title : str, optional
        Figure title.
    """
    n = len(panels)
    ncols = ncols or min(n, 4)
    nrows = int(np.ceil(n / ncols))
    fig, axes = plt.subplots(nrows, ncols, figsize=(4.2 * ncols, 3.4 * nrows), squeeze=False)
    for ax, panel in zip(axes.flat, panels):
        for x, y, label, style in panel["lines"]:
            ax.plot(x, y, label=label, **(style or {}))
        ax.set_xlabel(xlabel)
        ax.set_ylabel(panel["ylabel"])
        ax.set_title(panel.get("title", ""), fontsize=10)
        if panel.get("yscale"):
            ax.set_yscale(panel["yscale"])
        if panel.get("ylim"):
            ax.set_ylim(*panel["ylim"])
        ax.grid(alpha=0.3)
        if any(line[2] for line in panel["lines"]):
            ax.legend(fontsize=8)
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    if title:
        fig.suptitle(title, fontsize=11)
    fig.tight_layout()
    return fig


def efficiency_map(ratio, torque, eta, limit, title="Overall efficiency"):
    """Filled contours of ``eta(ratio, torque)`` with the limiting-torque curve.

    Parameters
    ----------
    ratio : array_like
        Ideal ratios, shape ``(n_r,)`` [-].
    torque : array_like
        Output torques, shape ``(n_T,)`` [N m].
    eta : array_like
        Efficiency, shape ``(n_r, n_T)``, NaN beyond the limit [-].
    limit : array_like
        Limiting torque per ratio, shape ``(n_r,)`` [N m].
    """
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    eta = np.asarray(eta, dtype=float).T
    finite = eta[np.isfinite(eta)]
    top = float(np.max(finite)) if finite.size else 1.0
    levels = np.unique(np.round(np.concatenate([np.linspace(0.5, 0.9, 9),
                                                np.arange(0.9, top + 0.01, 0.01)]), 3))
    filled = ax.contourf(ratio, torque, np.where(eta >= 0.5, eta, np.nan), levels=levels,
                         cmap="viridis", extend="min")
    lines = ax.contour(ratio, torque, eta, levels=levels[::2], colors="k", linewidths=0.5)
    ax.clabel(lines, fmt="%.2f", fontsize=7)
    ax.plot(ratio, limit, "r-", lw=2, label="limiting torque")
    fig.colorbar(filled, ax=ax, label="overall efficiency eta [-]")
    ax.set_xlabel("ideal speed ratio tau_ID [-]")
    ax.set_ylabel("output torque T_2 [N m]")
    ax.set_title(title, fontsize=10)
    ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    return fig


def ratio_vs_tilt(curves, title="Fig. 3: ideal speed ratio vs tilt (k = 1)"):
    """Fig. 3: ``tau_ID(gamma)`` for several contact angles.

    Parameters
    ----------
    curves : list of (tilt_deg, ratio, label, usable_mask)
        Tilt [deg], ratio [-], legend label, and the part inside the safety factor.
    """
    fig, ax = plt.subplots(figsize=(6.0, 4.2))
    for tilt, ratio, label, usable in curves:
        line, = ax.plot(tilt, ratio, ":", lw=1)
        ax.plot(tilt[usable], ratio[usable], "-", color=line.get_color(), label=label)
    ax.set_yscale("log")
    ax.set_xlabel("tilt angle gamma [deg]")
    ax.set_ylabel("ideal speed ratio tau_ID [-]")
    ax.set_title(title + "; solid: within the 0.8 safety factor", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig
