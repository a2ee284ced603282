"""A drive's operating context and its loading cam: checks and sizing (docs/drive-files.md).

`check_operating` refuses an ``[operating]`` ratio range outside the drive's usable range
(the tilt limits live in the model layer, so the params layer cannot check it).
`drive_warnings` lists what fits the geometry but looks meant for another design, among
them a cam whose capacity collapses over the usable ratio range. `size_cam` sizes the
cam's preload and ramp angle for the drive's rated torque (`rated_torque`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import BallCVTError, InputError
from ..model.kinematics import ratio_range as usable_ratio_range
from ..params.drive import PAPER_POINT
from ..params.feasibility import design_warnings
from ..params.models import CamModel, Design
from ..solvers.capacity import Capacity
from .oil import with_oil_temperature

__all__ = [
    "CamSizing",
    "check_operating",
    "drive_warnings",
    "operating_ratio_range",
    "operating_speed_rpm",
    "rated_torque",
    "size_cam",
]

#: Ratios checked over the ratio range (geometrically spaced, both ends included).
N_RATIOS = 5
#: Smallest and largest ramp angle `size_cam` considers [deg].
RAMP_BOUNDS = (0.5, 45.0)


def check_operating(design: Design) -> None:
    """Refuse an ``[operating] ratio_range`` outside the usable range of the design.

    Raises
    ------
    InputError
        Naming ``operating.ratio_range``, its value and the usable range.
    """
    op = design.operating
    if op is None or op.ratio_range is None:
        return
    lo, hi = usable_ratio_range(design)
    a, b = op.ratio_range
    if a < lo * (1 - 1e-9) or b > hi * (1 + 1e-9):
        raise InputError(
            "operating.ratio_range",
            [a, b],
            f"within the usable range {lo:.4g} to {hi:.4g} (tilt within "
            f"{design.tilt_safety_factor:g} x the Eq. 6 limits)",
        )


def operating_ratio_range(design: Design) -> tuple[float, float]:
    """The ratio range the drive is run over: ``[operating] ratio_range``, else the usable
    range (`ballcvt.model.kinematics.ratio_range`) [-]."""
    op = design.operating
    if op is not None and op.ratio_range is not None:
        return (float(op.ratio_range[0]), float(op.ratio_range[1]))
    return usable_ratio_range(design)


def operating_speed_rpm(design: Design) -> float:
    """The drive's input speed: ``[operating] input_speed_rpm``, else the paper's [rpm]."""
    op = design.operating
    if op is not None and op.input_speed_rpm is not None:
        return float(op.input_speed_rpm)
    return PAPER_POINT.input_speed_rpm


def _ratios(design: Design, n: int = N_RATIOS) -> np.ndarray:
    lo, hi = operating_ratio_range(design)
    return np.geomspace(lo, hi, n)


def rated_torque(drive, creep_limit: float | None = None) -> float:
    """The output torque a drive is rated for [N m].

    ``[operating] rated_torque`` when the file gives it; else the constant-clamp capacity:
    the smallest limiting torque over the ratio range (`operating_ratio_range`) at the
    ``[operating] clamp_force`` (the paper's 2000 N without it), the input speed and
    ``creep_limit`` (the design's by default), with the fluid as given (docs/model.md §15).
    """
    d = drive.design
    op = d.operating
    if op is not None and op.rated_torque is not None:
        return float(op.rated_torque)
    drive = with_oil_temperature(drive, "fixed")  # as `size_cam` sizes (docs/model.md §15)
    force = op.clamp_force if op is not None and op.clamp_force is not None else None
    force = PAPER_POINT.clamp_force if force is None else force
    speed = operating_speed_rpm(d)
    return min(
        drive.limit_torque(
            float(r), clamp_force=force, input_speed_rpm=speed, creep_limit=creep_limit
        )
        for r in _ratios(d)
    )


def _scan(drive, creep_limit: float) -> list[tuple[float, Capacity]]:
    """``(ratio, capacity under the cam)`` over the ratio range at the input speed, with
    the fluid as given (as `size_cam` sizes it, docs/model.md §15)."""
    drive = with_oil_temperature(drive, "fixed")
    speed = operating_speed_rpm(drive.design)
    return [
        (
            float(r),
            drive.capacity(
                float(r), clamp_law="cam", input_speed_rpm=speed, creep_limit=creep_limit
            ),
        )
        for r in _ratios(drive.design)
    ]


def _covers(cap: Capacity, torque: float) -> bool:
    """Whether the first interval runs from zero to ``torque``."""
    return bool(cap.intervals) and cap.intervals[0][0] == 0.0 and cap.intervals[0][1] >= torque


def drive_warnings(drive, *, cam: bool = True) -> list[str]:
    """What fits the geometry but looks meant for another design, one line each naming
    the field and the fix (empty for a consistent drive).

    Parameters
    ----------
    drive : Variator
        The drive.
    cam : bool
        Also check the loading cam over the ratio range (a few capacity solutions) of a
        drive with an ``[operating]`` table (one that says where it runs; the paper's
        Table I drive has none, and its cam is not part of the paper's rig): under the cam
        every ratio of `operating_ratio_range` must admit every torque from zero to
        `rated_torque` within the design's creep limit.
    """
    out = design_warnings(drive.design)
    if not cam or drive.design.cam is None or drive.design.operating is None:
        return out
    try:
        rated = rated_torque(drive)
        scan = _scan(drive, drive.design.creep_limit)
    except (BallCVTError, ValueError) as exc:  # advisory: say so, do not stop the command
        return [*out, f"[design.cam] could not be checked over the ratio range: {exc}"]
    short = [(r, c) for r, c in scan if not _covers(c, rated)]
    if short:
        ratio, cap = min(short, key=lambda rc: rc[1].largest if rc[1].intervals else -1.0)
        lo, hi = operating_ratio_range(drive.design)
        out.append(
            f"[design.cam] does not fit this drive: at ratio {ratio:.3g} the cam admits "
            f"{cap.describe()} (needed: 0 to {rated:.4g} N m over ratios {lo:.3g}-{hi:.3g}); "
            "size it for this geometry: ballcvt design size-cam --design FILE"
        )
    return out


@dataclass(frozen=True)
class CamSizing:
    """A sized cam and what it was sized for.

    Attributes
    ----------
    cam : CamModel
        The cam, ``preload`` and ``ramp_angle_deg`` sized, the rest as the design's.
    design : Design
        The design with that cam.
    rated_torque : float
        Output torque it carries [N m].
    creep_limit : float
        Creep limit it was sized to: the design's divided by the margin [-].
    ratios : tuple of float
        Ratios checked [-].
    """

    cam: CamModel
    design: Design
    rated_torque: float
    creep_limit: float
    ratios: tuple[float, ...]


def size_cam(drive, margin: float = 1.2) -> CamSizing:
    """Size the cam's preload and ramp angle for the drive's rated torque.

    Over the ratio range (`operating_ratio_range`, `N_RATIOS` ratios) at the input speed
    (`operating_speed_rpm`), the cam's clamp must keep every creep within
    ``creep_limit / margin`` (and every pressure within ``max_pressure``) for every output
    torque from zero to `rated_torque`. The preload is the smallest that holds the no-load
    drag at every ratio (the capacity starts at zero); the ramp angle is then the largest
    (least clamping, least loss) that carries the rated torque. The limits are those of
    the fluid as given, whatever the drive's oil model (docs/model.md §15: a heat balance
    per trial limit would cost some ten times more).

    Parameters
    ----------
    drive : Variator
        A drive with a ``[design.cam]`` table (its disc, mean radius and friction are kept).
    margin : float
        Safety factor on the creep limit (> 1 is a margin) [-].

    Returns
    -------
    CamSizing

    Raises
    ------
    InputError
        Without a cam, or when no cam within the bounds carries the rated torque.
    """
    d = drive.design
    if d.cam is None:
        raise InputError("design.cam", None, "a [design.cam] table to size")
    if not 1.0 <= margin < 10.0:
        raise InputError("margin", margin, "1 <= margin < 10")
    c_lim = d.creep_limit / margin
    fixed = with_oil_temperature(drive, "fixed")  # sized with the fluid as given (§15)
    rated = rated_torque(fixed, c_lim)
    per_force = d.n_rollers * math.sin(d.theta0)  # thrust per unit F_N0 (the cam law)
    preload, gain = _thrust_line(fixed, c_lim, rated)
    preload, gain = preload * per_force, gain * per_force
    for _ in range(MAX_BUMPS):
        cam = _cam(d.cam, preload, gain)
        sized = drive.__class__(d.replace(cam=cam), drive.fluid, drive.architecture)
        if all(_covers(c, rated) for _, c in _scan(sized, c_lim)):
            return CamSizing(cam, sized.design, rated, c_lim, tuple(_ratios(d)))
        preload, gain = preload * 1.1, gain * 1.1
    raise InputError(
        "cam",
        None,
        f"a cam that carries 0 to {rated:.4g} N m within creep {c_lim:.3g} and max_pressure: "
        "none found (lower [operating] rated_torque or the margin, or raise max_pressure)",
    )


#: Times `size_cam` raises the thrust line by 10 % when the check over the ratios fails.
MAX_BUMPS = 8
#: First constant force of `_thrust_line` [N] and how many it tries per ratio.
FIRST_FORCE = 10.0
MAX_FORCES = 25


def _cam(cam: CamModel, preload: float, gain: float) -> CamModel:
    """``cam`` with the preload [N] rounded up to 10 N and the ramp angle [deg] of the
    thrust ``gain`` [1/m], ``phi = atan(1 / (gain r_m)) - atan(mu_r)``, rounded down."""
    lead = math.atan(1.0 / (gain * cam.mean_radius)) if gain > 0.0 else math.pi / 2
    angle = math.degrees(lead - math.atan(cam.friction))
    angle = min(math.floor(angle * 10.0) / 10.0, RAMP_BOUNDS[1])
    if not angle >= RAMP_BOUNDS[0]:
        raise InputError(
            "cam.mean_radius",
            cam.mean_radius,
            f"a larger radius: the thrust needed per torque ({gain:.4g} 1/m) asks for a "
            f"ramp angle below {RAMP_BOUNDS[0]:g} deg",
        )
    return cam.replace(preload=math.ceil(preload / 10.0) * 10.0, ramp_angle_deg=angle)


def _thrust_line(drive, c_lim: float, rated: float) -> tuple[float, float]:
    """``(F0, g)``: the line ``F_N0 = F0 + g T_2`` [N, N/(N m)] above the constant clamp
    force each torque up to ``rated`` needs at every ratio (`limit_torque` at forces 1.5
    times apart) and above the force that holds the no-load drag (`_lowest_line`)."""
    speed = operating_speed_rpm(drive.design)
    points, floor = [], 0.0
    for r in _ratios(drive.design):
        force = FIRST_FORCE
        for _ in range(MAX_FORCES):
            try:
                torque = drive.limit_torque(
                    float(r), clamp_force=force, input_speed_rpm=speed, creep_limit=c_lim
                )
            except BallCVTError:  # not even the no-load drag is held
                torque = math.nan
            if not torque >= 0.0:
                floor = max(floor, force * 1.5)
            else:
                points.append((torque, force))
                if torque >= rated:
                    break
            force *= 1.5
        else:
            raise InputError(
                "rated_torque",
                rated,
                f"what a clamp force up to {force / 1.5:.3g} N carries at ratio {r:.3g} "
                "within the creep limit (narrow [operating] ratio_range or lower the rating)",
            )
    return _lowest_line([(0.0, floor), *points], 0.5 * rated)


def _lowest_line(points, at: float) -> tuple[float, float]:
    """``(F0, g)``, ``g >= 0``: the line above every ``(torque, force)`` point that is
    lowest at the torque ``at`` (for ``at = rated / 2``, the least mean clamp force over
    the torques up to the rating, hence the least loss on average)."""
    t, f = np.array(points, dtype=float).T
    slopes = np.concatenate(([0.0], np.geomspace(1e-3, 1e5, 4000)))
    intercepts = np.max(f[None, :] - slopes[:, None] * t[None, :], axis=1)
    best = int(np.argmin(intercepts + slopes * at))
    return float(intercepts[best]), float(slopes[best])
