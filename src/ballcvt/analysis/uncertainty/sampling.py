"""Draw the uncertain parameters: a seeded (quasi-)random design mapped through each
parameter's distribution (inverse-transform sampling).

``sobol`` (scrambled Sobol points, Owen 1998) and ``lhs`` (Latin hypercube, McKay,
Beckman and Conover 1979) cover the parameter space more evenly than ``random`` (plain
Monte Carlo), so a band's sampling error falls faster with the number of samples (Saltelli
et al. 2008, "Global Sensitivity Analysis: The Primer", Wiley, §1.2.3 and §4.3);
`scipy.stats.qmc` draws them.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from ...errors import InputError
from ...params.uncertainty import UncertaintyTable, UncertainValue

__all__ = ["METHODS", "unit_samples", "scale", "draw"]

#: Sampling designs: name -> what it is.
METHODS = {
    "sobol": "scrambled Sobol sequence (quasi-random, scipy.stats.qmc.Sobol)",
    "lhs": "Latin hypercube (scipy.stats.qmc.LatinHypercube)",
    "random": "plain Monte Carlo (numpy.random.default_rng)",
}
#: Unit-cube coordinates are kept this far inside (0, 1): the normal's tails are finite.
_EDGE = 1e-9


def unit_samples(method: str, n: int, d: int, seed: int) -> np.ndarray:
    """``(n, d)`` points in the open unit cube drawn by ``method`` (`METHODS`) from
    ``seed``: the same seed, the same points."""
    from scipy.stats import qmc

    if method not in METHODS:
        raise InputError("method", method, "one of " + ", ".join(METHODS))
    if method == "sobol":
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # balance warning off powers of two
            u = qmc.Sobol(d, scramble=True, seed=seed).random(n)
    elif method == "lhs":
        u = qmc.LatinHypercube(d, seed=seed).random(n)
    else:
        u = np.random.default_rng(seed).random((n, d))
    return np.clip(u, _EDGE, 1.0 - _EDGE)


def scale(value: UncertainValue, u) -> np.ndarray:
    """Values of ``value``'s distribution at the quantiles ``u`` in (0, 1) (the inverse
    of its cumulative distribution); whole numbers for an integer value."""
    from scipy import stats

    u = np.asarray(u, dtype=float)
    lo, hi = value.lo, value.hi
    d = value.distribution
    if d == "uniform":
        x = lo + u * (hi - lo)
    elif d == "loguniform":
        x = np.exp(math.log(lo) + u * (math.log(hi) - math.log(lo)))
    elif d == "triangular":
        c = (value.mode - lo) / (hi - lo)
        x = stats.triang(c, loc=lo, scale=hi - lo).ppf(u)
    else:  # normal, truncated to its range when it has one
        a, b = (lo - value.mean) / value.std, (hi - value.mean) / value.std
        x = stats.truncnorm(a, b, loc=value.mean, scale=value.std).ppf(u)
    return np.round(x) if value.integer else x


def draw(table: UncertaintyTable, n: int, method: str, seed: int) -> np.ndarray:
    """``(n, len(table))`` parameter values, one column per uncertain value."""
    u = unit_samples(method, n, len(table), seed)
    return np.column_stack([scale(v, u[:, j]) for j, v in enumerate(table.values)])
