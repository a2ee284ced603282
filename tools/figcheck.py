"""Checks that a matplotlib figure draws what it says (used by the tests and the docs build).

A figure passes when every line it labels (a legend entry) has at least one finite point
(one positive point on a log axis), and every filled contour lies inside the data it was
contoured from and, on an efficiency map (an axes with a line labelled "limiting torque"),
at or below that line. ``problems(fig)`` lists what fails, one line each; the docs build
(docs/conf.py) refuses a gallery figure with any, and tests/test_figures_draw.py runs the
gallery and every figure function of ``ballcvt.plotting`` through it.
"""

from __future__ import annotations

import numpy as np
from matplotlib.contour import ContourSet

LIMIT_LABEL = "limiting torque"


def problems(fig, box=None) -> list[str]:
    """What ``fig`` draws wrongly, one line per problem (empty: nothing).

    ``box``: optional ``(xmin, xmax, ymin, ymax)`` of the data given; every filled contour
    must then lie inside it as well.
    """
    found = []
    for i, ax in enumerate(fig.axes):
        where = f"axes {i} ({ax.get_title() or ax.get_ylabel()!r})"
        found += [f"{where}: {p}" for p in _line_problems(ax)]
        found += [f"{where}: {p}" for p in _contour_problems(ax, box)]
    return found


def _line_problems(ax) -> list[str]:
    out = []
    for line in ax.get_lines():
        label = str(line.get_label())
        if not label or label.startswith("_"):
            continue  # not in the legend
        x = np.asarray(line.get_xdata(), dtype=float)
        y = np.asarray(line.get_ydata(), dtype=float)
        ok = np.isfinite(x) & np.isfinite(y)
        if ax.get_yscale() == "log":
            ok &= y > 0
        if ax.get_xscale() == "log":
            ok &= x > 0
        if not ok.any():
            out.append(f"the line labelled {label!r} has no point that can be drawn")
    return out


def _filled_vertices(ax):
    for artist in ax.collections:
        if isinstance(artist, ContourSet) and artist.filled:
            verts = [p.vertices for p in artist.get_paths() if len(p.vertices)]
            if verts:
                yield artist, np.concatenate(verts)


def _contour_problems(ax, box) -> list[str]:
    out = []
    limit = [ln for ln in ax.get_lines() if ln.get_label() == LIMIT_LABEL]
    for cs, v in _filled_vertices(ax):
        edges = cs.sticky_edges  # the extent of the points contoured
        lo = np.array([min(edges.x), min(edges.y)], float)
        hi = np.array([max(edges.x), max(edges.y)], float)
        tol = 1e-6 * np.maximum(hi - lo, 1.0)
        if (v < lo - tol).any() or (v > hi + tol).any():
            out.append("a filled contour reaches beyond the points it was drawn from")
        if box is not None:
            x0, x1, y0, y1 = box
            span = 1e-6 * max(x1 - x0, y1 - y0, 1.0)
            if (
                (v[:, 0] < x0 - span).any()
                or (v[:, 0] > x1 + span).any()
                or (v[:, 1] < y0 - span).any()
                or (v[:, 1] > y1 + span).any()
            ):
                out.append(f"a filled contour lies outside the data given {box}")
        for line in limit:
            x = np.asarray(line.get_xdata(), float)
            y = np.asarray(line.get_ydata(), float)
            ok = np.isfinite(x) & np.isfinite(y)
            if ok.sum() >= 2:
                cap = np.interp(v[:, 0], x[ok], y[ok])
                if (v[:, 1] > cap * (1 + 1e-6) + 1e-9).any():
                    out.append("a filled contour lies above the limiting torque")
    return out


class CheckedScraper:
    """sphinx-gallery's matplotlib scraper, after `problems` passed every open figure: a
    gallery figure with a labelled line that has nothing to draw, or a contour outside
    its data, fails the docs build (docs/conf.py)."""

    def __repr__(self):  # sphinx-gallery keys its cache on the configuration's repr
        return "figcheck.CheckedScraper"

    def __call__(self, block, block_vars, gallery_conf, **kwargs):
        import matplotlib.pyplot as plt
        from sphinx_gallery.scrapers import matplotlib_scraper

        found = [p for n in plt.get_fignums() for p in problems(plt.figure(n))]
        if found:
            raise RuntimeError(f"{block_vars['src_file']}: " + "; ".join(found))
        return matplotlib_scraper(block, block_vars, gallery_conf, **kwargs)
