"""Which uncertain parameter matters most: rank-based global sensitivity measures.

Two measures over the same samples, both robust to monotonic non-linearity (Saltelli et
al. 2008, "Global Sensitivity Analysis: The Primer", Wiley, §1.2.5; Helton and Davis,
Reliab. Eng. Syst. Saf. 81 (2003) 23-69, §6):

- the Spearman rank correlation ``rho`` between a parameter and an output (how
  monotonically the output follows it, -1 to 1);
- the standardised rank regression coefficients ``SRRC`` (the least-squares fit of the
  output's ranks on every parameter's ranks, each in units of its standard deviation),
  with the fit's ``R^2``: when ``R^2`` is near 1 the SRRC^2 share the output's rank
  variance among the parameters; a low ``R^2`` says the output is not monotonic in the
  parameters (or they interact) and the ranking is to be read with care.
"""

from __future__ import annotations

import numpy as np

__all__ = ["ranks", "spearman", "srrc"]


def ranks(a: np.ndarray) -> np.ndarray:
    """Ranks of each column of ``a`` (ties averaged), centred and scaled to unit
    standard deviation (zeros for a constant column)."""
    from scipy.stats import rankdata

    r = rankdata(a, axis=0)
    r = r - r.mean(axis=0)
    sd = r.std(axis=0)
    return np.divide(r, sd, out=np.zeros_like(r), where=sd > 0)


def spearman(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Spearman rank correlation of each column of ``x`` ``(n, d)`` with ``y`` ``(n,)``
    over the rows where ``y`` is finite [-]; NaN with fewer than three such rows, 0 for a
    constant column."""
    ok = np.isfinite(y)
    if ok.sum() < 3:
        return np.full(x.shape[1], np.nan)
    rx, ry = ranks(x[ok]), ranks(y[ok][:, None])[:, 0]
    return (rx * ry[:, None]).mean(axis=0)


def srrc(x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, float]:
    """``(SRRC per column of x, R^2)`` of the rank regression of ``y`` on ``x`` [-],
    over the rows where ``y`` is finite (NaN with too few rows to fit)."""
    ok = np.isfinite(y)
    d = x.shape[1]
    if ok.sum() < d + 2:
        return np.full(d, np.nan), float("nan")
    rx, ry = ranks(x[ok]), ranks(y[ok][:, None])[:, 0]
    coef, *_ = np.linalg.lstsq(rx, ry, rcond=None)
    fit = rx @ coef
    total = float(np.sum(ry**2))
    r2 = 1.0 - float(np.sum((ry - fit) ** 2)) / total if total > 0 else float("nan")
    return coef, r2
