"""Pareto front and the chosen design of a study (docs/studies.md)."""

from __future__ import annotations

import numpy as np

__all__ = ["pareto_mask", "choose"]


def pareto_mask(values, senses, feasible) -> np.ndarray:
    """Non-dominated feasible designs.

    Parameters
    ----------
    values : array_like
        Objective values, ``(n, m)``.
    senses : sequence of {"max", "min"}
        Per objective.
    feasible : array_like of bool
        ``(n,)``; infeasible designs (or any with a NaN objective) are never on the front.

    Returns
    -------
    ndarray of bool
        ``(n,)``: on the Pareto front.
    """
    v = np.asarray(values, dtype=float).reshape(len(feasible), -1)
    sign = np.array([-1.0 if s == "max" else 1.0 for s in senses])
    cost = v * sign  # all minimised
    ok = np.asarray(feasible, bool) & np.all(np.isfinite(cost), axis=1)
    idx = np.flatnonzero(ok)
    front = np.zeros(len(feasible), bool)
    c = cost[idx]
    for j, row in enumerate(c):
        dominated = np.any(np.all(c <= row, axis=1) & np.any(c < row, axis=1))
        front[idx[j]] = not dominated
    return front


def choose(values, senses, front, objectives, by: str | None = None) -> int:
    """Index of the chosen design on the front: the best by objective ``by``, or the one
    nearest the ideal point with every objective scaled to [0, 1] over the front. -1 when
    the front is empty."""
    idx = np.flatnonzero(front)
    if idx.size == 0:
        return -1
    v = np.asarray(values, dtype=float)[idx]
    sign = np.array([-1.0 if s == "max" else 1.0 for s in senses])
    cost = v * sign
    if by is not None:
        return int(idx[np.argmin(cost[:, list(objectives).index(by)])])
    lo, hi = cost.min(axis=0), cost.max(axis=0)
    scaled = (cost - lo) / np.where(hi > lo, hi - lo, 1.0)
    return int(idx[np.argmin(np.linalg.norm(scaled, axis=1))])
