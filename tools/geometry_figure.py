"""The labelled geometry figure of docs/model.md §1, drawn at every docs build (docs/conf.py).

The meridian section through one ball: main axis ``j`` (horizontal), radial direction
``k`` (vertical), the ball of radius ``r_S`` centred at ``(1 + k) r_S`` from the axis, the
input disc touching it at contact angle ``theta_0``, the output disc at ``theta_2``, the
two idlers at ``alpha`` from the radial direction, and the spin axis tilted by ``gamma``.
The proportions are Table I's (``k`` = 1.7, 45 deg contacts, ``alpha`` = 10 deg), the tilt
15 deg for legibility. ``python tools/geometry_figure.py out.png`` draws it by itself.
"""

from __future__ import annotations

import sys

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Arc, Circle, FancyArrowPatch, Polygon

K, THETA0, THETA2, ALPHA, GAMMA = 1.7, 45.0, 45.0, 10.0, 15.0


def _unit(deg_from_k, side):
    """Unit vector at ``deg_from_k`` from +k (side -1: towards -j, +1: towards +j)."""
    a = np.radians(deg_from_k)
    return np.array([side * np.sin(a), np.cos(a)])


def _disc(ax, point, normal, size, style):
    """A body's face tangent to the ball at ``point`` (a slab of half-width and thickness
    ``size``), labelled ``style["label"]`` at ``style["at"]`` times the normal."""
    (w, h), t = size, np.array([normal[1], -normal[0]])
    body = [point + w * t, point - w * t, point - w * t + h * normal, point + w * t + h * normal]
    ax.add_patch(Polygon(body, closed=True, facecolor=style["colour"], edgecolor="k", alpha=0.6))
    ax.text(*(point + style["at"] * normal), style["label"], ha="center", va="center",
            fontsize=9)


def _angle(ax, centre, start, end, radius, text, where):
    """An arc from ``start`` to ``end`` degrees (matplotlib's convention) with a label."""
    lo, hi = sorted((start, end))
    ax.add_patch(Arc(centre, 2 * radius, 2 * radius, theta1=lo, theta2=hi, lw=1))
    ax.text(*(centre + where), text, fontsize=11, ha="center", va="center")


def draw(path) -> None:
    """Write the figure to ``path`` (PNG)."""
    fig = Figure(figsize=(7.0, 5.6), layout="constrained")
    ax = fig.add_subplot()
    c = np.array([0.0, 1.0 + K])  # ball centre, in ball radii
    ax.axhline(0.0, color="k", lw=0.8, ls="-.")
    ax.text(2.45, 0.08, "main axis $j$", fontsize=9, ha="right")
    ax.add_patch(Circle(c, 1.0, facecolor="0.85", edgecolor="k"))
    n0, n2 = _unit(THETA0, -1), _unit(THETA2, +1)
    na, nb = -_unit(ALPHA, +1), -_unit(ALPHA, -1)
    discs = ((n0, "input disc\n$\\omega_0$, $T_0$", "tab:blue"),
             (n2, "output disc\n$\\omega_2$, $T_2$", "tab:green"))
    for n, label, colour in discs:
        _disc(ax, c + n, n, (0.9, 0.35), {"label": label, "colour": colour, "at": 0.62})
    for n, label, at in ((na, "idler a", [-0.55, -0.45]), (nb, "idler b", [0.55, -0.45])):
        _disc(ax, c + n, n, (0.2, 0.3), {"label": "", "colour": "tab:orange", "at": 0.0})
        ax.text(*(c + n + at), label, fontsize=9, ha="center", va="center")
    for n in (n0, n2, na, nb):
        ax.plot(*np.column_stack([c, c + n]), "k:", lw=0.8)
        ax.plot(*(c + n), "ko", ms=3)
    s = np.array([np.cos(np.radians(GAMMA)), -np.sin(np.radians(GAMMA))])
    ax.plot(*np.column_stack([c - 1.5 * s, c + 1.5 * s]), "r-", lw=1.5)
    ax.text(*(c + 1.55 * s + [0.05, -0.05]), "spin axis $s$", color="r", fontsize=9)
    ax.plot([c[0], c[0] + 1.6], [c[1], c[1]], "k--", lw=0.6)
    _angle(ax, c, -GAMMA, 0.0, 1.25, "$\\gamma$", [1.38, -0.15])
    _angle(ax, c, 90.0, 90.0 + THETA0, 0.55, "$\\theta_0$", [-0.2, 0.7])
    _angle(ax, c, 90.0 - THETA2, 90.0, 0.55, "$\\theta_2$", [0.2, 0.7])
    ax.plot([c[0], c[0]], [c[1] - 1.0, c[1] + 0.95], "k--", lw=0.6)
    _angle(ax, c, -90.0 - ALPHA, -90.0, 0.6, "$\\alpha$", [-0.16, -0.78])
    r_end = c + 1.0 * np.array([-np.cos(np.radians(20)), -np.sin(np.radians(20))])
    ax.add_patch(FancyArrowPatch(c, r_end, arrowstyle="->", mutation_scale=10))
    ax.text(*((c + r_end) / 2 + [0.0, 0.12]), "$r_S$", fontsize=11, ha="center")
    ax.add_patch(FancyArrowPatch((-2.3, 0.0), (-2.3, c[1]), arrowstyle="<->", mutation_scale=10))
    ax.plot([-2.4, c[0]], [c[1], c[1]], "k:", lw=0.6)
    ax.text(-2.25, c[1] / 2, "$(1+k)\\,r_S$", fontsize=10, ha="left", va="center")
    ax.add_patch(FancyArrowPatch((2.2, 0.2), (2.2, 0.9), arrowstyle="->", mutation_scale=10))
    ax.text(2.27, 0.55, "$k$ (radial)", fontsize=9, va="center")
    ax.set_xlim(-2.6, 2.6)
    ax.set_ylim(-0.2, c[1] + 1.9)
    ax.set_aspect("equal")
    ax.set_axis_off()
    ax.set_title("One ball in the meridian plane (Table I proportions, tilt exaggerated)",
                 fontsize=10)
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    draw(sys.argv[1] if len(sys.argv) > 1 else "geometry.png")
