"""Quadrature rules on the unit disc ``X^2 + Y^2 <= 1`` (the normalised contact ellipse).

The traction integrand has a pole at ``(0, Y_p)`` where the sliding speed vanishes and
its direction jumps (docs/model.md §3). Three rules, each with ``n_radial x n_angular``
nodes and weights summing to the disc area ``pi``:

``centred``
    Polar grid about the centre; converges algebraically when the pole is inside.
``pole`` (default)
    Pole inside: polar grid about the pole, on which the sliding direction depends on the
    angle only and the rule converges spectrally in the angle. Pole outside: the centred
    grid (measured better than a fan of chords from the pole, whose chords cut the sharp
    edge ring of the shear law at grazing angles).

On every ray the radial coordinate is mapped, ``r = t (2 - t)``, so that the Hertz factor
``sqrt(1 - X^2 - Y^2)`` becomes smooth at the boundary. The radial direction still carries
the steep viscous-to-limiting-shear transition near the contact edge (the viscosity rises
exponentially with pressure) and needs more nodes than the angle.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

__all__ = [
    "Quadrature",
    "REFERENCE",
    "gauss_legendre",
    "radial_rule",
    "centred_rule",
    "inner_pole_rule",
    "METHODS",
]

METHODS = ("pole", "centred")
#: ``auto``: the compiled kernels of `ballcvt.model.traction.kernels` when numba is installed;
#: ``numpy``: the whole-array NumPy path (the reference implementation).
ENGINES = ("auto", "numpy")


@dataclass(frozen=True)
class Quadrature:
    """Choice of quadrature rule for the traction integrals.

    Attributes
    ----------
    method : {"pole", "centred"}
        Pole-centred (default, spectral) or centred (algebraic) rule.
    n_radial, n_angular : int
        Nodes along the rays and around the pole. The radial direction carries the
        sharp viscous-to-limiting-shear ring near the contact edge and needs more nodes.
    n_centred : int
        Angular nodes of the centred rule when the ``pole`` method uses it (pole outside
        the ellipse); the sliding direction then turns quickly near the edge closest to
        the pole, and needs more angular nodes than the pole-centred rule.
    engine : {"auto", "numpy"}
        Compiled kernels (numba) when available, or the NumPy reference path. Both
        compute the same sums.
    """

    method: str = "pole"
    n_radial: int = 32
    n_angular: int = 24
    n_centred: int = 32
    engine: str = "auto"

    def __post_init__(self):
        if self.method not in METHODS:
            raise ValueError(f"quadrature method must be one of {METHODS}, got {self.method!r}")
        if self.engine not in ENGINES:
            raise ValueError(f"quadrature engine must be one of {ENGINES}, got {self.engine!r}")
        if min(self.n_radial, self.n_angular, self.n_centred) < 2:
            raise ValueError("quadrature needs at least 2 x 2 nodes")


#: Converged high-order reference rule (docs/model.md §3).
REFERENCE = Quadrature("pole", 96, 64, 128)


@lru_cache(maxsize=64)
def gauss_legendre(n: int, a: float = 0.0, b: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and weights on ``[a, b]`` (cached, read-only)."""
    x, w = np.polynomial.legendre.leggauss(n)
    x = 0.5 * (b - a) * x + 0.5 * (b + a)
    w = 0.5 * (b - a) * w
    x.flags.writeable = False
    w.flags.writeable = False
    return x, w


#: Two-panel radial rule: Gauss panels ``[0, RADIAL_SPLIT]`` and ``[RADIAL_SPLIT, 1]`` in
#: ``t`` (``r = 0.84`` at the split), the inner one with ``INNER_SHARE`` of the nodes; used
#: from 16 radial nodes up. It puts more nodes on the edge ring (measured on the 30 x 30
#: benchmark map: max creep error 8.8e-4 -> 6.5e-4, mean 6.7e-5 -> 2.2e-5; on a small,
#: slow, four-ball design the idler creep error fell from 1.0e-3 to 7e-6).
RADIAL_SPLIT = 0.6
INNER_SHARE = 0.4


def radial_rule(n_radial: int) -> tuple[np.ndarray, np.ndarray]:
    """Radial nodes ``r(t) = t (2 - t)`` on [0, 1] and weights ``dr/dt w_t`` (Gauss in t).

    From 16 nodes up, two Gauss panels split at ``t = RADIAL_SPLIT`` (see above).
    """
    if n_radial < 16:
        t, wt = gauss_legendre(n_radial)
    else:
        inner = int(round(INNER_SHARE * n_radial))
        t1, w1 = gauss_legendre(inner, 0.0, RADIAL_SPLIT)
        t2, w2 = gauss_legendre(n_radial - inner, RADIAL_SPLIT, 1.0)
        t, wt = np.concatenate([t1, t2]), np.concatenate([w1, w2])
    return t * (2.0 - t), 2.0 * (1.0 - t) * wt  # r(t), dr/dt * w


def centred_rule(n_radial: int, n_angular: int, shape=()) -> tuple[np.ndarray, ...]:
    """Polar rule about the disc centre.

    Returns
    -------
    X, Y, W : ndarray
        Nodes and weights, shape ``shape + (n_radial * n_angular,)`` [-].
    """
    r, wr = radial_rule(n_radial)
    psi = 2.0 * np.pi * np.arange(n_angular) / n_angular
    x = (r[:, None] * np.cos(psi)).ravel()
    y = (r[:, None] * np.sin(psi)).ravel()
    w = (r * wr)[:, None] * np.full(n_angular, 2.0 * np.pi / n_angular)
    full = shape + (x.size,)
    return (np.broadcast_to(x, full), np.broadcast_to(y, full), np.broadcast_to(w.ravel(), full))


def inner_pole_rule(yp, n_radial, n_angular):
    """Rays from inside poles ``(0, yp)``, ``|yp| < 1`` (1-D array), to the boundary.

    Returns
    -------
    X, Y, W : ndarray
        Shape ``(yp.size, n_radial * n_angular)`` [-].
    """
    r01, wr = radial_rule(n_radial)
    phi = 2.0 * np.pi * np.arange(n_angular) / n_angular
    sp, cp = np.sin(phi), np.cos(phi)
    yp = yp[:, None]
    b = yp * sp
    reach = -b + np.sqrt(b * b + (1.0 - yp * yp))  # (m, n_angular)
    rho = reach[:, None, :] * r01[None, :, None]  # (m, n_r, n_a)
    x = rho * cp
    y = yp[:, None] + rho * sp
    w = rho * reach[:, None, :] * wr[None, :, None] * (2.0 * np.pi / n_angular)
    m = yp.shape[0]
    return x.reshape(m, -1), y.reshape(m, -1), w.reshape(m, -1)
