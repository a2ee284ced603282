"""Following the branch from zero torque to next to its fold, in a moving held creep.

With a contact's creep held, the drive's balances other than the output disc's fix the
other creeps (`ballcvt.solvers.newton.solve_pinned`): they define a curve in the space of
the creeps, on which the output torque is a function. The branch of equilibria from zero
torque is that curve, and where the traction can fall with the creep (the thermal law,
docs/model.md §14) the torque along it rises to a largest value, the fold, and falls past
it. `follow_branch` walks the curve from zero torque towards the fold by a
predictor-corrector continuation with local parametrisation (Rheinboldt 1986, *Numerical
analysis of parametrized nonlinear equations*, ch. 4; Allgower and Georg 1990,
*Numerical continuation methods*, §10.2): each step predicts along the secant of the
last two points (the curve's tangent at the first step, the null vector of the balances'
Jacobian), holds the creep that moves most along it at its predicted value, and corrects
with one held-creep Newton solve. The held creep is chosen afresh at every step, so the
walk goes on where a disc creep stops growing along the curve (harden task 2028:592),
and the step doubles while the solves converge, so a few steps reach the fold where a
torque continuation took a dozen (most of them failed Newton runs next to the fold).

The walk stops at the first step whose torque does not rise (the fold lies beyond the
point before it) or that takes a creep past the limit; its result, the last two points on
the rising side, starts the climb in a disc's held creep that locates the fold
(`ballcvt.solvers.fold.climb_to_fold`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..equilibrium.residual import evaluate_with_jacobian
from ..model.traction.quadrature import Quadrature
from .held_creep import Pinned, held_of, pinned_step

__all__ = [
    "follow_branch",
    "walks",
    "Walk",
    "FIRST_ARC_STEP",
    "LARGEST_ARC_STEP",
    "LEAST_ARC_STEP",
]

#: First step along the curve, as a share of the creep limit [-].
FIRST_ARC_STEP = 0.05
#: Largest step along the curve, as a share of the creep limit [-].
LARGEST_ARC_STEP = 0.4
#: Step, as a share of the creep limit, below which a walk whose solves fail gives up
#: (the torque continuation then follows that point) [-].
LEAST_ARC_STEP = 1e-3
#: Largest distance of a corrected point from its prediction, as a share of the step [-]
#: (Allgower and Georg 1990, §6.1: the corrector's contraction bounds the step).
CORRECTOR_SHARE = 0.5
#: Largest angle between a step's chord and its predictor [rad] (45 degrees).
BEND = np.pi / 4
#: Most steps of a walk.
MAX_ARC_STEPS = 40


@dataclass
class Walk:
    """The result of `follow_branch` for a 1-D batch ``(n,)``.

    Attributes
    ----------
    torque : ndarray
        The torque at the last point on the rising side [N m] (NaN where zero torque
        failed or was inadmissible).
    creep : ndarray
        The creeps there ``(n, n_c)`` [-].
    before : tuple of ndarray
        ``(torque (n,), creeps (n, n_c))`` of the point before it (zero torque's at the
        first step).
    after : tuple of ndarray
        ``(torque (n,), creeps (n, n_c))`` of the step that stopped the walk: a torque
        not above ``torque``, or -inf where it took a creep past the limit (NaN where the
        walk did not stop).
    direction : ndarray
        The unit chord of its last step ``(n, n_c)`` (the first tangent before any): the
        creep that moves most along it parametrises the branch best next to the fold.
    stopped : ndarray of bool
        Whether the walk stopped next to the fold or the creep bound (its last step fell
        in torque or took a creep past the bound), or past its target; False where its
        solves failed (the caller follows those points otherwise).
    passed : ndarray of bool
        Whether it stopped at a step whose torque reached the target (``after``, the
        target between ``torque`` and it).
    path : tuple of ndarray
        Every point of the walk on the rising side, the start's first: torques ``(n, S)``
        [N m] in increasing order, ``+inf`` after a point's last, and creeps ``(n, S,
        n_c)`` [-] (NaN there): warm starts for solves between them
        (`ballcvt.solvers.limit.LimitSearch.start_between`).
    """

    torque: np.ndarray
    creep: np.ndarray
    before: tuple
    after: tuple
    direction: np.ndarray
    stopped: np.ndarray
    passed: np.ndarray
    path: tuple = ()

    @classmethod
    def start(cls, t0, x0, direction) -> Walk:
        """A walk at its start ``(t0, x0)``, its predictor ``direction`` (filled in place)."""
        n, nan = t0.size, np.full_like(x0, np.nan)
        false = np.zeros(n, dtype=bool)
        return cls(t0.copy(), x0.copy(), (t0.copy(), x0.copy()), (np.full(n, np.nan), nan),
                   direction, false, false.copy())  # fmt: skip


def walks(flat) -> bool:
    """Whether the walk applies to ``flat``: its torque condition is on ``T_2``, the
    torque a held-creep solve gives (not a planetary mode's ``a T_0 + b T_2``)."""
    return tuple(flat.torque_weights) == (0.0, 1.0)


def follow_branch(flat, pinned, quadrature, bounds, start, target=None) -> Walk:
    """Walk each point's branch from the equilibria ``start`` up to its fold, its creep
    bound or its target torque (module docstring).

    Parameters
    ----------
    flat : EquilibriumProblem
        Operating points, 1-D batch ``(n,)``, under the torque condition on ``T_2``.
    pinned : tuple
        `ballcvt.solvers.held_creep.Pinned` and the solver tolerance [-].
    quadrature : Quadrature or None
        The rule of the first tangent's Jacobian (None: the default rule).
    bounds : tuple of float
        The creep scale of the steps (the creep limit) and the bound no creep may pass
        (the creep limit a hair below, or ``inf``) [-].
    start : tuple of ndarray
        Equilibria on the branch: torques ``(n,)`` [N m] (NaN where none) and creeps
        ``(n, n_c)`` [-].
    target : ndarray, optional
        Torques ``(n,)`` [N m] at which a walk stops (`Walk.passed`); None: none.

    Returns
    -------
    Walk
    """
    (pinned, tol), (scale, bound) = pinned, bounds
    t0, x0 = (np.array(v, dtype=float) for v in start)
    n = flat.size
    goal = np.full(n, np.inf) if target is None else np.asarray(target, dtype=float)
    direction = np.zeros_like(x0)
    walk = Walk.start(t0, x0, direction)
    ok = np.flatnonzero(np.isfinite(t0))
    if ok.size:
        direction[ok] = _tangent(flat.take(ok), x0[ok], quadrature)
    step = np.full(n, FIRST_ARC_STEP * scale)
    active = ok[np.all(np.isfinite(direction[ok]), axis=-1)]
    points = [(ok, t0[ok], x0[ok])]  # the walk's points on the rising side, step by step
    for _ in range(MAX_ARC_STEPS):
        active = active[step[active] >= LEAST_ARC_STEP * scale]
        if active.size == 0:
            break
        got, xs = _steps(flat, pinned, (walk.creep, direction, step), active, tol)
        got = np.where(
            _close(xs, walk.creep[active], direction[active], step[active]), got, np.nan
        )
        inside = np.max(np.abs(xs), axis=-1) <= bound * (1.0 + 1e-9)
        up = np.isfinite(got) & (got > walk.torque[active]) & inside  # a step on the way
        walk.passed[active] = up & (got >= goal[active])
        go = up & ~walk.passed[active]
        stop = np.isfinite(got) & ~go
        walk.stopped[active[stop]] = True
        walk.after[0][active[stop]] = np.where(inside, got, -np.inf)[stop]
        walk.after[1][active[stop]] = xs[stop]
        i = active[go]
        points.append((i, got[go], xs[go]))
        chord = xs[go] - walk.creep[i]
        direction[i] = chord / np.linalg.norm(chord, axis=-1, keepdims=True)
        walk.before[0][i], walk.before[1][i] = walk.torque[i], walk.creep[i]
        walk.torque[i], walk.creep[i] = got[go], xs[go]
        step[i] = np.minimum(2.0 * step[i], LARGEST_ARC_STEP * scale)
        step[active[~np.isfinite(got)]] *= 0.5
        active = active[~walk.stopped[active]]
    walk.path = _path(points, x0)
    return walk


def _path(points, x0):
    """`Walk.path` from the walk's points, step by step ``(indices, torques, creeps)``:
    each point's in increasing torque (along the rising side), ``+inf`` and NaN after."""
    n, nc = x0.shape
    torque, creep = np.full((n, len(points)), np.inf), np.full((n, len(points), nc), np.nan)
    for j, (i, t, x) in enumerate(points):
        torque[i, j], creep[i, j] = t, x
    return by_torque(torque, creep)


def by_torque(torque, creep):
    """Each row's points ``torque`` ``(n, S)``, ``creep`` ``(n, S, n_c)`` in increasing
    torque (``+inf`` last)."""
    order = np.argsort(torque, axis=1, kind="stable")
    return (np.take_along_axis(torque, order, axis=1),
            np.take_along_axis(creep, order[..., None], axis=1))  # fmt: skip


def _close(xs, x, direction, step) -> np.ndarray:
    """Whether the corrected points ``xs`` lie near their predictions: within
    `CORRECTOR_SHARE` of the step from them, and in a direction from ``x`` within
    `BEND` of the predictor's. A longer corrector can land on another branch of the held
    creep's equations (a creep past its largest value on this branch): such a step is
    halved, like a failed one."""
    chord = xs - x
    length = np.linalg.norm(chord, axis=-1)
    off = np.linalg.norm(xs - (x + step[:, None] * direction), axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        cos = np.einsum("ij,ij->i", chord, direction) / length
    return (off <= CORRECTOR_SHARE * step) & (cos >= np.cos(BEND))


def _steps(flat, pinned: Pinned, path, active, tol):
    """One predictor-corrector step of the points ``active``: the creep that moves most
    along the predictor ``direction`` held at its predicted value, the rest solved.
    Returns the torques (NaN where the solve failed) and creeps of the corrected points."""
    x, direction, step = path
    guess = x[active] + step[active, None] * direction[active]
    held = np.argmax(np.abs(direction[active]), axis=-1)  # one batch, whichever it is
    return pinned_step(pinned, flat.take(active), held, guess, held_of(guess, held), tol)


def _tangent(flat, x, quadrature) -> np.ndarray:
    """The unit tangent ``(m, n_c)`` of each point's curve at the creeps ``x``, oriented
    the way the output torque rises: the null vector of the Jacobian of the balances
    other than the output disc's (NaN where the torque does not move along it)."""
    _, jac = evaluate_with_jacobian(flat, x, Quadrature() if quadrature is None else quadrature)
    _, _, vt = np.linalg.svd(jac[:, :-1, :])
    t = vt[:, -1, :]
    rise = np.einsum("ij,ij->i", jac[:, -1, :], t)  # d res_T2 / ds: T_2 rises with it
    sign = np.where(rise > 0.0, 1.0, np.where(rise < 0.0, -1.0, np.nan))
    return t * sign[:, None]
