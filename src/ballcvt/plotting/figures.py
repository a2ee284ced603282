"""Matplotlib figures of the paper's results (and the efficiency map) from sweep data.

Nothing here computes physics, and nothing here changes matplotlib's backend: figures for
files are `matplotlib.figure.Figure` objects that never touch pyplot (so they work
headless and leave a notebook's own plotting alone), and the helpers for interactive use
(`plot_efficiency_map`, `plot_curves`) draw on an ``ax`` you pass, or on pyplot's current
axes, and return the artists. Labels use mathtext (``$\\tau_{ID}$``, ``$T_2$``, ``$\\eta$``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from ..errors import InputError
from ..files import atomic_path

__all__ = [
    "save",
    "line_panels",
    "efficiency_map",
    "ratio_vs_tilt",
    "draw_efficiency_map",
    "plot_efficiency_map",
    "plot_curves",
    "map_title",
    "LABELS",
]

#: Axis labels of the common quantities (mathtext).
LABELS = {
    "ratio": r"ideal speed ratio $\tau_{ID}$ [-]",
    "output_torque": r"output torque $T_2$ [N m]",
    "clamp_force": r"clamping force $F_{N0}$ [N]",
    "input_speed": r"input speed $\omega_0$ [rad/s]",
    "input_speed_rpm": r"input speed $\omega_0$ [rpm]",
    "eta": r"overall efficiency $\eta$ [-]",
    "eta_loss": r"overall efficiency $\eta$ (Eq. 39) [-]",
    "eta_speed": r"speed efficiency $\eta_\omega$ [-]",
    "eta_torque": r"torque efficiency $\eta_T$ [-]",
    "creep": r"creep $C$ [-]",
    "spin": r"spin coefficient $\sigma$ [-]",
    "tilt_deg": r"tilt $\gamma$ [deg]",
    "input_torque": r"input torque $T_0$ [N m]",
    "limit_torque": r"limiting torque $T_{2,lim}$ [N m]",
}


def save(fig: Figure, directory, name) -> list[Path]:
    """Write ``fig`` as ``name.png`` and ``name.svg`` in ``directory`` (atomically)."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    paths = [directory / f"{name}.png", directory / f"{name}.svg"]
    for path, dpi in zip(paths, (130, "figure")):
        with atomic_path(path) as tmp:
            fig.savefig(tmp, bbox_inches="tight", dpi=dpi)
    return paths


def line_panels(panels, xlabel, title=None, ncols=None) -> Figure:
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
    fig = Figure(figsize=(4.2 * ncols, 3.4 * nrows), layout="constrained")
    axes = fig.subplots(nrows, ncols, squeeze=False)
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
    return fig


def _levels(eta):
    finite = eta[np.isfinite(eta)]
    lo = float(np.min(finite)) if finite.size else 0.0
    top = float(np.max(finite)) if finite.size else 1.0
    coarse = np.arange(np.floor(lo * 10) / 10, 0.9, 0.1)
    fine = np.arange(0.9, top + 0.01, 0.01)
    levels = np.unique(np.round(np.concatenate([coarse, [0.85], fine, [top + 1e-9]]), 3))
    return levels[levels >= np.floor(lo * 10) / 10]


def draw_efficiency_map(ax, ratio, torque, eta, limit, colorbar=True, limit_eta=None):
    """Draw filled efficiency contours and the limiting-torque curve on ``ax``.

    Only the data given is drawn: the contours stay inside the swept torques and below
    the limiting torque. The region above the limit is hatched ("beyond the limiting
    torque") and, where the limit lies above the sweep's largest torque, the band between
    them is dotted ("not computed"); both are named in the legend.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        Target axes.
    ratio : array_like
        Ideal ratios, shape ``(n_r,)`` [-].
    torque : array_like
        Output torques, shape ``(n_T,)`` [N m].
    eta : array_like
        Efficiency, shape ``(n_r, n_T)``, NaN beyond the limit [-].
    limit : array_like
        Limiting torque per ratio, shape ``(n_r,)`` [N m].
    colorbar : bool
        Add a colour bar.
    limit_eta : array_like, optional
        Efficiency at the limiting torque per ratio, shape ``(n_r,)`` [-]. With it the
        contours reach the limit curve where it lies within the swept torques (a
        triangulation of the grid points and those limit points) instead of stopping at
        the last grid row below it.

    Returns
    -------
    dict
        The artists: ``filled`` and ``lines`` (contour sets), ``labels``, ``limit`` (the
        red line), ``outside`` (the hatched regions) and ``colorbar`` (or None).
    """
    ratio, torque = np.asarray(ratio, float), np.asarray(torque, float)
    limit = np.asarray(limit, float)
    eta = np.asarray(eta, dtype=float).T
    levels = _levels(eta)
    line_levels = [v for v in levels if v >= 0.5][::2]
    if limit_eta is None:
        filled = ax.contourf(ratio, torque, eta, levels=levels, cmap="viridis")
        lines = ax.contour(ratio, torque, eta, levels=line_levels, colors="k", linewidths=0.5)
    else:
        swept = np.nanmax(torque)
        inside = np.isfinite(limit) & (limit <= swept)  # limit points within the sweep
        r, t = np.meshgrid(ratio, torque)
        x = np.concatenate([r.ravel(), ratio[inside]])
        y = np.concatenate([t.ravel(), limit[inside]])
        z = np.concatenate([eta.ravel(), np.asarray(limit_eta, float)[inside]])
        keep = np.isfinite(x) & np.isfinite(y) & np.isfinite(z)
        _enough_to_contour(x[keep], y[keep])
        tri = _triangulation(x[keep], y[keep], ratio, np.fmin(limit, swept))
        filled = ax.tricontourf(tri, z[keep], levels=levels, cmap="viridis")
        lines = ax.tricontour(tri, z[keep], levels=line_levels, colors="k", linewidths=0.5)
    labels = ax.clabel(lines, fmt="%.2f", fontsize=7, inline=True)
    (limit_line,) = ax.plot(ratio, limit, "r-", lw=2, label="limiting torque")
    bar = ax.figure.colorbar(filled, ax=ax, label=LABELS["eta"]) if colorbar else None
    ax.set_xlabel(LABELS["ratio"])
    ax.set_ylabel(LABELS["output_torque"])
    top = 1.05 * np.nanmax(np.concatenate([torque, limit]))
    ax.set_ylim(float(np.min(torque)), top)
    ax.set_xlim(float(np.min(ratio)), float(np.max(ratio)))
    outside = _shade_outside(ax, ratio, float(np.nanmax(torque)), limit, top)
    ax.legend(loc="upper right", fontsize=8)
    return {
        "filled": filled,
        "lines": lines,
        "labels": labels,
        "limit": limit_line,
        "outside": outside,
        "colorbar": bar,
    }


def _shade_outside(ax, ratio, swept, limit, top) -> list:
    """Hatch what the map does not show: above the limiting torque, and between the
    sweep's largest torque ``swept`` [N m] and a limit above it (not computed)."""
    known = np.isfinite(limit)
    if not known.any():
        return []
    r = np.linspace(ratio[known].min(), ratio[known].max(), 400)
    lim = np.fmin(np.interp(r, ratio[known], limit[known]), top)
    hatch = {"facecolor": "none", "linewidth": 0}
    shown = [
        ax.fill_between(
            r, lim, top, edgecolor="0.55", hatch="///", label="beyond the limiting torque", **hatch
        )
    ]
    if (lim > swept * (1 + 1e-9)).any():
        label = f"not computed (the sweep ends at {swept:.4g} N m)"
        band = np.maximum(lim, swept)
        shown.append(
            ax.fill_between(r, swept, band, edgecolor="0.7", hatch="..", label=label, **hatch)
        )
    return shown


def _enough_to_contour(x, y) -> None:
    """Refuse, in one line, points that span no triangle (fewer than 3, or all on a line)."""
    pts = np.column_stack([x, y])
    flat = pts.shape[0] < 3 or np.linalg.matrix_rank(pts[1:] - pts[0], tol=1e-12) < 2
    if flat:
        raise InputError(
            "map grid",
            pts.shape[0],
            "at least 3 points, not all on one line",
            message=f"an efficiency map needs at least 3 solved points, not all on one "
            f"line, at or below the limiting torque; this grid has {pts.shape[0]}: use more "
            "ratios or torques, or a lower torque range",
        )


def _triangulation(x, y, ratio, limit):
    """Delaunay triangles of the points, without those above the curve ``limit`` (the
    limiting torque, capped at the sweep's largest torque) [N m]."""
    from matplotlib.tri import Triangulation

    scale = np.ptp(y) / np.ptp(x) if np.ptp(x) > 0 else 1.0
    tri = Triangulation(x * scale, y)  # triangulate in comparable units
    cx, cy = (x[tri.triangles].mean(axis=1), y[tri.triangles].mean(axis=1))
    ok = np.isfinite(limit)
    above = cy > np.interp(cx, ratio[ok], limit[ok]) * (1 + 1e-9) if ok.any() else False
    return Triangulation(x, y, tri.triangles, mask=above)


def efficiency_map(
    ratio, torque, eta, limit, title="Overall efficiency", limit_eta=None, life=None
) -> Figure:
    """A figure of `draw_efficiency_map` with a title (for files); ``life``, the system L10
    [h] on the same ``(ratio, torque)`` grid, adds its contours (`draw_life_contours`)."""
    fig = Figure(figsize=(6.6, 4.8), layout="constrained")
    ax = fig.add_subplot()
    draw_efficiency_map(ax, ratio, torque, eta, limit, limit_eta=limit_eta)
    if life is not None:
        draw_life_contours(ax, ratio, torque, life)
    ax.set_title(title, fontsize=10)
    return fig


def draw_life_contours(ax, ratio, torque, hours):
    """Contours of the fatigue life at the decades ``10^k`` hours (dashed white lines).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    ratio, torque : array_like
        The grid's ratios [-] and output torques [N m].
    hours : array_like
        System L10 [h], ``(n_ratio, n_torque)`` (NaN: no solution, left blank).

    Returns
    -------
    ContourSet or None
        None when fewer than two decades are finite (nothing to draw).
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.log10(np.asarray(hours, dtype=float)).T
    finite = z[np.isfinite(z)]
    if finite.size < 4 or np.floor(finite.max()) <= np.ceil(finite.min()) - 1:
        return None
    levels = np.arange(np.ceil(finite.min()), np.floor(finite.max()) + 1)
    lines = ax.contour(
        ratio, torque, np.ma.masked_invalid(z), levels=levels, colors="w", linestyles="--",
        linewidths=0.8,
    )  # fmt: skip
    ax.clabel(lines, fmt=lambda k: f"L10 {10.0**k:g} h", fontsize=7, inline=True)
    return lines


def _axes(ax):
    if ax is None:
        import matplotlib.pyplot as plt  # interactive use: the user's own backend

        ax = plt.gca()
    return ax


def plot_efficiency_map(ds, ax=None, colorbar=True, title=None):
    """Efficiency map of a ratio x torque sweep on ``ax`` (pyplot's current axes if None).

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep with one architecture, clamping force and speed (the other dimensions of
        length 1), e.g. ``Variator().sweep(ratio=..., output_torque=..., ...)``. A sweep
        over several (say two clamping forces) is refused: select one first, e.g.
        ``ds.sel(clamp_force=2000.0)``, and draw each on its own axes.
    ax : matplotlib.axes.Axes, optional
        Target axes.
    colorbar : bool
        Add a colour bar.
    title : str, optional
        Axes title; by default the design's name and the operating point (``""``: none).

    Returns
    -------
    dict
        The artists (see `draw_efficiency_map`).
    """
    _one_map(ds)
    one = ds.squeeze(drop=True)
    ax = _axes(ax)
    artists = draw_efficiency_map(
        ax,
        one.ratio.values,
        one.output_torque.values,
        one.eta.transpose("ratio", "output_torque").values,
        one.limit_torque.values,
        colorbar=colorbar,
        limit_eta=one.eta_at_limit.values,
    )
    ax.set_title(map_title(ds) if title is None else title, fontsize=9)
    return artists


def _one_map(ds) -> None:
    """Refuse, in one line, a sweep with more than one map in it."""
    for dim in ds.eta.dims:
        n = ds.sizes[dim]
        if dim not in ("ratio", "output_torque") and n > 1:
            values = [v.item() for v in ds[dim].values]
            shown = ", ".join(f"{v:g}" if isinstance(v, float) else str(v) for v in values)
            raise InputError(
                dim,
                n,
                "1 value",
                message=f"plot_efficiency_map draws one map, and this sweep has {n} values "
                f"of {dim} ({shown}): select one with sweep.sel({dim}={values[0]!r}) and "
                "draw each on its own axes",
            )


def map_title(ds) -> str:
    """The title of an efficiency map of the sweep ``ds``: the design's name (its
    ``design_name`` attribute) and the architecture, clamping and input speed."""
    parts = []
    if "architecture" in ds.coords and ds["architecture"].size == 1:
        parts.append(f"{ds['architecture'].item()} idler")
    law = ds.attrs.get("clamp_law", "constant")
    if law == "constant" and "clamp_force" in ds.coords and ds["clamp_force"].size == 1:
        parts.append(f"$F_{{N0}}$ = {float(ds['clamp_force'].item()):g} N")
    elif law != "constant":
        parts.append(f"{law} clamping")
    if "input_speed_rpm" in ds.coords and ds["input_speed_rpm"].size == 1:
        parts.append(f"{float(ds['input_speed_rpm'].item()):g} rpm")
    name = ds.attrs.get("design_name", "")
    point = "Efficiency map" + (", " + ", ".join(parts) if parts else "")
    return f"{name}\n{point}" if name else point


def plot_curves(ds, y="eta", x="output_torque", ax=None, **style):
    """Lines of ``ds[y]`` against ``x``, one per value of every other sweep dimension
    (none for a combination without data, such as one architecture's values at the other
    architecture's idler contacts).

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep (or a selection of one).
    y, x : str
        Variable and dimension names.
    ax : matplotlib.axes.Axes, optional
        Target axes (pyplot's current axes if None).
    **style
        Keyword arguments for ``ax.plot``.

    Returns
    -------
    list of matplotlib.lines.Line2D
    """
    ax = _axes(ax)
    da = ds[y].squeeze(drop=True)
    others = [d for d in da.dims if d != x]
    stacked = da.stack(curve=others) if others else da.expand_dims(curve=[""])
    lines = []
    for i in range(stacked.sizes["curve"]):
        curve = stacked.isel(curve=i)
        if not np.isfinite(curve.values).any():
            continue  # e.g. the other architecture's idler contact: nothing to draw
        label = ", ".join(
            f"{d} = {curve[d].item():g}"
            if np.ndim(curve[d]) == 0 and np.issubdtype(curve[d].dtype, np.number)
            else f"{curve[d].item()}"
            for d in others
        )
        lines += ax.plot(curve[x].values, curve.values, label=label or None, **style)
    ax.set_xlabel(LABELS.get(x, x))
    ax.set_ylabel(LABELS.get(y, y))
    if others:
        ax.legend(fontsize=8)
    return lines


def ratio_vs_tilt(curves, title=r"Fig. 3: ideal speed ratio vs tilt ($k$ = 1)") -> Figure:
    """Fig. 3: ``tau_ID(gamma)`` for several contact angles.

    Parameters
    ----------
    curves : list of tuple
        ``(tilt_deg, ratio, label, usable_mask)`` per curve.
        Tilt [deg], ratio [-], legend label, and the part inside the safety factor.
    """
    fig = Figure(figsize=(6.0, 4.2), layout="constrained")
    ax = fig.add_subplot()
    for tilt, ratio, label, usable in curves:
        (line,) = ax.plot(tilt, ratio, ":", lw=1)
        ax.plot(tilt[usable], ratio[usable], "-", color=line.get_color(), label=label)
    ax.set_yscale("log")
    ax.set_xlabel(LABELS["tilt_deg"])
    ax.set_ylabel(LABELS["ratio"])
    ax.set_title(title + "; solid: within the 0.8 safety factor", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    return fig
