"""Shift-effort methods of `Variator`: the moment to hold a ratio and to tilt the balls
(``ballcvt point --tilt-rate``, ``ballcvt map --shift-effort``; docs/model.md §17)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from ..params.models import Design, Fluid
from ..results.point import OperatingResult
from ..solvers.options import SolverOptions

__all__ = ["ShiftMoments", "ShiftMomentMethods"]


@dataclass(frozen=True)
class ShiftMoments:
    """Moments about the balls' tilt axes at a steady point (docs/model.md §17).

    Moments are about the direction of increasing tilt ``gamma`` (towards a higher ratio):
    the moment the shifter applies, whose power is ``moment x tilt_rate``.

    Attributes
    ----------
    holding_moment : float
        Per ball, to hold the ratio at the steady point [N m]. Zero (to round-off) under
        the rigid-plastic laws: every contact force then has no moment about the tilt axis
        (docs/model.md §17); a visco-elastic film's spin gives a small lateral force.
    shift_moment : float
        Per ball, the extra moment to tilt at ``tilt_rate`` (tilt-direct) [N m]; the sign
        of the rate, 0 at rate 0.
    shifter_moment : float
        All the balls: ``n (holding_moment + shift_moment)`` [N m], the moment conjugate to
        the common tilt (a shifter that tilts every ball together, its own friction aside).
    side_slip : tuple of float
        Lateral creep of each contact [-] (``contacts`` order).
    lateral_force : tuple of float
        Lateral force of each contact on the ball [N] (its transverse direction, Eq. 55's
        frame).
    tilt_rate : float
        ``d gamma / dt`` [rad/s].
    saturated : bool
        Whether a contact's lateral force is at its traction limit (below half its
        linear-range extrapolation: the moment no longer grows with the rate).
    contacts : tuple of str
        The contacts' names (``input``, ``idler_a``, ...).
    n_balls : int
        Number of balls ``n``.
    skew_moment : float
        Per ball, the contacts' moment about the ball's skew axis (radial, outward ``k``)
        at ``tilt_rate``: the moment the carrier applies about the direction of
        increasing skew (``ballcvt.model.shift.skew_axis_moment``) [N m]; at rate 0 the
        steady point's, ``OperatingResult.skew_moment``.
    """

    holding_moment: float
    shift_moment: float
    shifter_moment: float
    side_slip: tuple[float, ...]
    lateral_force: tuple[float, ...]
    tilt_rate: float
    saturated: bool
    contacts: tuple[str, ...] = ()
    n_balls: int = 0
    skew_moment: float = float("nan")


class ShiftMomentMethods:
    """The shift-effort methods `Variator` inherits (its fields are declared here for
    typing)."""

    design: Design
    fluid: Fluid
    architecture: str
    options: SolverOptions

    # many parameters: the operating point of `solve` (keywords) and the tilt rate.
    def shift_moments(
        self,
        ratio: float,
        output_torque: float,
        *,
        tilt_rate: float = 0.0,
        clamp_force: float | None = None,
        clamp_law=None,
        input_speed: float | None = None,
        input_speed_rpm: float | None = None,
    ) -> ShiftMoments:
        """Holding and tilt-direct shift moments at a steady point (docs/model.md §17).

        The point is solved (`solve`); its contacts keep their creeps, spins, loads and
        films, and a tilt at ``tilt_rate`` adds the lateral creep
        ``s_c = kappa_c tilt_rate r_S / u_c`` at each (``u_c`` the rolling speed), resisted
        by the film's lateral traction (`ballcvt.model.traction.lateral_coefficients`):
        lever ``r_S`` about the tilt axis (`ballcvt.model.shift`). Quasi-static: the
        longitudinal creeps are not re-solved with the side slip.

        Parameters
        ----------
        ratio, output_torque
            As in `solve` [-], [N m].
        tilt_rate : float
            ``d gamma / dt`` [rad/s]; 0: the holding moment only.
        clamp_force, clamp_law, input_speed, input_speed_rpm
            As in `solve` ([N], law, [rad/s] or [rpm]).

        Returns
        -------
        ShiftMoments
        """
        r = self.solve(  # type: ignore[attr-defined]
            ratio,
            output_torque,
            clamp_force=clamp_force,
            clamp_law=clamp_law,
            input_speed=input_speed,
            input_speed_rpm=input_speed_rpm,
        )
        return self.shift_moments_at(r, tilt_rate=tilt_rate)

    def shift_moments_at(self, result, *, tilt_rate: float = 0.0) -> ShiftMoments:
        """`shift_moments` of a point already solved (an `OperatingResult` of `solve`,
        carrier held), at ``tilt_rate`` [rad/s]."""
        from ..analysis.shift_effort import point_tilt_moments
        from ..model.architectures import CONTACT_NAMES

        if not isinstance(result, OperatingResult):
            raise InputError("result", type(result).__name__, "an OperatingResult (carrier held)")
        got = point_tilt_moments(result, float(tilt_rate), self.options.quadrature)
        n = result.design.n_rollers
        holding, shift = float(got.holding[0]), float(got.shift[0])
        return ShiftMoments(
            holding_moment=holding,
            shift_moment=shift,
            shifter_moment=n * (holding + shift),
            side_slip=tuple(float(v) for v in np.ravel(got.side_slip)),
            lateral_force=tuple(float(v) for v in np.ravel(got.lateral_force)),
            tilt_rate=float(tilt_rate),
            saturated=bool(np.any(got.saturated)),
            contacts=tuple(CONTACT_NAMES[result.architecture]),
            n_balls=n,
            skew_moment=float(got.skew[0]),
        )

    def map_shift_effort(self, ds, *, tilt_rate: float = 0.0):
        """``ds`` (a sweep or `efficiency_map` of this drive) with the moments of each
        converged point: ``holding_moment``, ``shift_moment`` (per ball, at ``tilt_rate``
        [rad/s]), ``shifter_moment`` (all balls), ``skew_moment`` (per ball, about its
        skew axis) [N m] and ``shift_saturated``
        (`ballcvt.analysis.shift_effort.sweep_shift_effort`)."""
        from ..analysis.shift_effort import sweep_shift_effort

        return sweep_shift_effort(ds, self, float(tilt_rate), self.options.quadrature)
