"""`Variator`: the one obvious entry point of the Python API."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..equilibrium.problem import build_problem
from ..errors import ConvergenceError, InputError, TractionLimitError
from ..model.architectures import check_architecture
from ..model.clamping import ConstantClamp, OptimalClamp
from ..model.clamping import clamp_law as _clamp_law
from ..model.kinematics import ratio_range
from ..model.modes import resolve_mode
from ..model.traction.quadrature import Quadrature
from ..params.drive_models import drive_clamp
from ..params.io import load_builtin
from ..params.models import ARCHITECTURES, Design, Fluid
from ..results.planetary import PlanetaryResult
from ..results.point import OperatingResult, make_result
from ..solvers.capacity import Capacity
from ..solvers.clamped import solve_clamped
from ..solvers.constraints import with_constraints
from ..solvers.limit import limit_torque
from ..solvers.optimal_capacity import capacity_basis
from ..solvers.optimal_clamp import ClampCase, ClampOptimum, clamp_optimum, optimal_start
from ..solvers.point import SolverOptions, solve_point
from ..solvers.refusal import point_capacity
from ..units import rpm_to_rad_s
from . import grids, oil, planetary
from .batched import BatchMethods
from .cam_sizing import check_operating
from .hints import one_speed as _speed
from .life import LifeMethods
from .refusals import optimal_refusal, refuse_beyond_capacity
from .settings import CycleSettings, SolveSettings, SweepSettings, merge_settings
from .shift import ShiftMethods
from .shift_moments import ShiftMomentMethods
from .summary import SummaryMethods

__all__ = ["Variator"]


def _default_drive():
    return load_builtin("table1")


@dataclass(frozen=True, repr=False)  # the summary is SummaryMethods'
class Variator(SummaryMethods, BatchMethods, LifeMethods, ShiftMethods, ShiftMomentMethods):
    """A ball variator of a given design, fluid and idler architecture.

    Parameters
    ----------
    design : Design, optional
        Geometry; the paper's Table I drive by default.
    fluid : Fluid, optional
        Traction fluid; Table I's by default.
    architecture : {"double", "single"}
        Two idlers (the disassembled drive) or one cylindrical idler (original patent).
    options : SolverOptions
        Solver and quadrature settings.
    traction_law : {"isothermal", "thermal", "viscoelastic"}, optional
        Shear law of the film (docs/model.md §14); default: the drive file's ``[models]
        traction_law``, else the fluid's own (``Fluid.traction_law``, the paper's
        isothermal law for Table I). The fluid must carry the law's parameters.

    Examples
    --------
    >>> from ballcvt import Variator
    >>> v = Variator()
    >>> r = v.solve(ratio=1.76, output_torque=40.0, clamp_force=2000.0, input_speed_rpm=2000)
    >>> round(r.eta, 2)
    0.89
    """

    design: Design = field(default=None)  # type: ignore[assignment]
    fluid: Fluid = field(default=None)  # type: ignore[assignment]
    architecture: str = "double"
    options: SolverOptions = SolverOptions()
    traction_law: str | None = None

    def __post_init__(self):
        if self.design is None or self.fluid is None:
            d, f = _default_drive()
            object.__setattr__(self, "design", self.design or d)
            object.__setattr__(self, "fluid", self.fluid or f)
        named = self.design.models.traction_law if self.design.models is not None else None
        law = self.traction_law or named  # the call's, else the drive file's
        object.__setattr__(self, "fluid", self.fluid.with_traction_law(law))
        object.__setattr__(self, "traction_law", self.fluid.traction_law)
        if self.architecture not in ARCHITECTURES:
            raise InputError(
                "architecture", self.architecture, "one of: " + ", ".join(ARCHITECTURES)
            )
        check_architecture(self.design, self.architecture)
        check_operating(self.design)

    @property
    def ratio_range(self) -> tuple[float, float]:
        """Usable ideal-ratio range ``(min, max)`` [-]."""
        return ratio_range(self.design)

    def clamp_law(self, clamp_law=None, clamp_force=None):
        """The clamping law named by ``clamp_law`` (`ballcvt.model.clamping.clamp_law`);
        with neither argument, the drive file's (`ballcvt.params.drive_models.drive_clamp`)."""
        law, force = drive_clamp(self.design, clamp_law, clamp_force)
        return _clamp_law(law, self.design, force)

    def _problem(self, ratio, output_torque, law, input_speed, input_speed_rpm):
        """The operating point, at the law's force for the given torque (a start value for
        a law that senses the input torque)."""
        speed = _speed(input_speed, input_speed_rpm)
        t2 = float(output_torque)
        force = law.clamp_force(self.design, t2 * float(ratio), t2)
        return build_problem(
            self.design, self.fluid, self.architecture, float(ratio), t2, force, speed
        )

    def _clamp_case(self, ratio, output_torque, input_speed, input_speed_rpm) -> ClampCase:
        """The `ClampCase` of this drive at one point (speed in rad/s or rpm)."""
        speed = _speed(input_speed, input_speed_rpm)
        return ClampCase(
            self.design, self.fluid, self.architecture, float(ratio), float(output_torque), speed
        )

    def _resolve(self, ratio, output_torque, clamp_force, clamp_law, input_speed, input_speed_rpm):
        """(force law, law name, starting creeps or None): the optimal law becomes the
        constant law at its optimum, the solve there started from the search's creeps."""
        law = self.clamp_law(clamp_law, clamp_force)
        if not law.optimises:
            return law, law.name, None
        case = self._clamp_case(ratio, output_torque, input_speed, input_speed_rpm)
        limits = OptimalClamp(law.creep_limit, law.max_pressure)
        force, creep = optimal_start(case, limits, self.options)
        return ConstantClamp(force), law.name, creep

    # many parameters: what is computed, in the user's quantities (ratio, torque, force
    # or law, speed in rad/s or rpm), then one settings object; **legacy: old keywords.
    def solve(
        self,
        ratio: float,
        output_torque: float,
        *,
        clamp_force: float | None = None,
        clamp_law=None,
        input_speed: float | None = None,
        input_speed_rpm: float | None = None,
        settings: SolveSettings | None = None,
        **legacy: Any,
    ) -> OperatingResult | PlanetaryResult:
        """Solve the steady operating point.

        Parameters
        ----------
        ratio : float
            Ideal speed ratio ``tau_ID`` [-].
        output_torque : float
            Output torque ``T_2`` >= 0 [N m].
        clamp_force : float, optional
            Normal load at each input contact ``F_N0`` > 0 [N] of the constant clamping
            law (keyword only, as are the speeds: a unit cannot be guessed wrong).
        clamp_law : str or law object, optional
            ``"constant"`` (the default, with ``clamp_force``), ``"cam"`` (the design's
            loading cam, ``[design.cam]``), ``"optimal"`` (the efficiency-optimal force
            under the creep and pressure limits) or a law object of `ballcvt.model.clamping`
            (docs/model.md §11). The force used is ``result.clamp_force``.
        input_speed : float, optional
            Input speed ``omega_0`` [rad/s]; or give ``input_speed_rpm`` [rpm].
        settings : SolveSettings, optional
            ``check_capacity`` (default True): a torque whose equilibrium has a creep above
            ``design.creep_limit`` raises `TractionLimitError` naming the contact and its
            creep, with the admissible torques (`capacity`); so does, under a
            torque-following law, a force whose peak pressure exceeds
            ``design.max_pressure``, and a torque with no equilibrium outside them.
            ``mode`` (`ballcvt.model.modes.OperatingMode`, or its
            name in `ballcvt.registry.OPERATING_MODES`, e.g.
            ``"disc2_held_carrier_drives"``; docs/model.md §13): which member is held and
            which drives; then
            ``output_torque`` is the driven member's load torque [N m], ``input_speed`` (or
            ``input_speed_rpm``) the driver's speed (signed), ``ratio`` still ``tau_ID``
            relative to the carrier, and a `PlanetaryResult` is returned. The default
            (carrier held, disc 0 drives) is the paper's drive.
            ``oil_temperature``: ``"fixed"`` (default), ``"balance"`` (the housing's heat
            balance, `ballcvt.api.oil`) or a temperature [K] (docs/model.md §15).
        **legacy
            The fields of `SolveSettings` as keywords (``oil_temperature="balance"``).

        Returns
        -------
        OperatingResult
            Or `PlanetaryResult` in a mode other than the default.

        Raises
        ------
        InputError
            Out-of-range input (including a torque beyond the traction capacity).
        ConvergenceError
            If no equilibrium is found and ``check_capacity`` is False.
        """
        how = merge_settings(SolveSettings, settings, legacy, "solve")
        named = oil.drive_choice(self.design, how.oil_temperature, mode=how.mode)
        how = replace(how, oil_temperature=named)
        if how.oil_temperature != "fixed":
            point = {"clamp_force": clamp_force, "clamp_law": clamp_law}
            speeds = {"input_speed": input_speed, "input_speed_rpm": input_speed_rpm}
            return oil.solve_with_oil(self, how, ratio, output_torque, {**point, **speeds})
        mode = resolve_mode(how.mode)
        if not mode.is_default:
            return planetary.solve_in_mode(
                self,
                mode,
                ratio,
                output_torque,
                {"clamp_force": clamp_force, "clamp_law": clamp_law},
                _speed(input_speed, input_speed_rpm),
                how.check_capacity,
            )
        try:
            law, name, x0 = self._resolve(
                ratio, output_torque, clamp_force, clamp_law, input_speed, input_speed_rpm
            )
        except TractionLimitError:  # the optimiser found no force: say the capacity
            speeds = {"input_speed": input_speed, "input_speed_rpm": input_speed_rpm}
            # with the fluid as this solve has it (a trial of the oil's balance runs here
            # at a fixed temperature: the drive file's balance would start another, and
            # that one this trial again, harden task 2720:11)
            given = oil.with_oil_temperature(self, "fixed")
            cap = given.capacity(ratio, clamp_force=clamp_force, clamp_law=clamp_law, **speeds)
            raise optimal_refusal(float(output_torque), ratio, cap) from None
        problem = self._problem(ratio, output_torque, law, input_speed, input_speed_rpm)
        follows = not isinstance(law, ConstantClamp)
        if follows:
            problem, sol = solve_clamped(
                problem, law, lambda p, x: solve_point(p, self.options, x)
            )
        else:
            sol = solve_point(problem, self.options, x0, near=x0 is not None)
        if how.check_capacity:
            refuse_beyond_capacity(problem, sol, law, name, self.options)
        if not sol.converged:
            raise ConvergenceError(sol.message)
        return make_result(problem, sol, self.options.quadrature, clamp_law=name)

    def limit_torque(
        self,
        ratio: float,
        *,
        clamp_force: float | None = None,
        clamp_law=None,
        input_speed: float | None = None,
        input_speed_rpm: float | None = None,
        creep_limit: float | None = None,
        mode=None,
    ) -> float:
        """Largest admissible output torque (docs/model.md §8, §11) [N m].

        Under a loading cam with a small preload the admissible torques need not run from
        zero to it: `capacity` gives them as intervals.

        Parameters
        ----------
        ratio, clamp_force, clamp_law, input_speed, input_speed_rpm
            As in `solve`. Under a torque-following law (``cam``) the capacity is also
            bounded by ``design.max_pressure``; under ``optimal`` it is the limit at the
            largest force within ``max_pressure`` (the optimiser may pick any force up to
            it).
        creep_limit : float, optional
            Largest admissible ``|C|``; ``design.creep_limit`` by default.
        mode : OperatingMode or str, optional
            As in `solve`: in a planetary mode, the largest load torque ``|L|`` of the
            driven member braking it, to 1e-3 relative, the speed that of the driver
            (`ballcvt.api.planetary.limit_in_mode`; where even zero load is not
            admissible, the error of the zero-load point).
        """
        if not resolve_mode(mode).is_default:
            return planetary.limit_in_mode(
                self,
                resolve_mode(mode),
                ratio,
                {"clamp_force": clamp_force, "clamp_law": clamp_law},
                _speed(input_speed, input_speed_rpm),
                self._creep_limit(creep_limit),
            )
        point = {"clamp_force": clamp_force, "clamp_law": clamp_law, "creep_limit": creep_limit}
        point.update(input_speed=input_speed, input_speed_rpm=input_speed_rpm)
        if (choice := oil.path_choice(self)) != "fixed":  # at its own oil temperature, §15
            return oil.limit_with_oil(self, choice, ratio, point, whole=False)[0]
        problem, law, c_lim = self._capacity_basis(
            ratio, clamp_force, clamp_law, (input_speed, input_speed_rpm), creep_limit
        )
        return limit_torque(problem, c_lim, self.options, law=law)

    def capacity(
        self,
        ratio: float,
        *,
        clamp_force: float | None = None,
        clamp_law=None,
        input_speed: float | None = None,
        input_speed_rpm: float | None = None,
        creep_limit: float | None = None,
    ) -> Capacity:
        """The admissible output torques as intervals (docs/model.md §8, §11).

        Parameters as in `limit_torque`. Under a constant force the one interval runs from
        zero to `limit_torque`; under a loading cam with a small preload the admissible
        torques may start above zero, or form two intervals. Empty when none is
        admissible (`limit_torque` then says why).

        Returns
        -------
        Capacity
            ``intervals`` ``((lo, hi), ...)`` [N m]; ``limit`` the limiting torque when the
            only interval starts at zero; ``constraints`` what sets each end and
            ``active_constraint`` what sets the largest (e.g. ``"creep (output contact)"``,
            ``"pressure (max_pressure 3 GPa)"``; `ballcvt.solvers.constraints`).
        """
        point = {"clamp_force": clamp_force, "clamp_law": clamp_law, "creep_limit": creep_limit}
        point.update(input_speed=input_speed, input_speed_rpm=input_speed_rpm)
        if (choice := oil.path_choice(self)) != "fixed":  # at its own oil temperature, §15
            return oil.limit_with_oil(self, choice, ratio, point)[0]
        problem, law, c_lim = self._capacity_basis(
            ratio, clamp_force, clamp_law, (input_speed, input_speed_rpm), creep_limit
        )
        cap = point_capacity(problem, c_lim, self.options, law=law)
        return with_constraints(problem, cap, c_lim, self.options, law)

    def _creep_limit(self, creep_limit: float | None) -> float:
        """The creep limit asked for, else the design's [-]; refused outside (0, 1)."""
        c_lim = self.design.creep_limit if creep_limit is None else float(creep_limit)
        if not 0.0 < c_lim < 1.0:
            raise InputError("creep_limit", c_lim, "0 < creep_limit < 1")
        return c_lim

    def _capacity_basis(self, ratio, clamp_force, clamp_law, speeds, creep_limit):
        """(problem at zero torque, force-following law or None, creep limit) of the
        capacity at a point (`ballcvt.solvers.optimal_capacity.capacity_basis`)."""
        c_lim = self._creep_limit(creep_limit)
        law = self.clamp_law(clamp_law, clamp_force)
        start = ConstantClamp(1.0) if law.optimises else law
        return capacity_basis(self._problem(ratio, 0.0, start, *speeds), law, c_lim, self.options)

    # many parameters: what is computed, in the user's quantities (ratio, torque, force
    # or law, speed in rad/s or rpm), then one settings object; **legacy: old keywords.
    def sweep(
        self,
        *,
        ratio,
        output_torque,
        clamp_force=None,
        clamp_law=None,
        input_speed=None,
        input_speed_rpm=None,
        settings: SweepSettings | None = None,
        **legacy: Any,
    ):
        """Evaluate a grid of operating points (see `ballcvt.analysis.sweeps.grid.sweep`).

        Parameters
        ----------
        ratio, output_torque, clamp_force : float or array_like
            Ideal ratios [-], output torques (increasing) [N m], clamping forces [N] of the
            constant law.
        clamp_law : str or law object, optional
            As in `solve`; under a law other than ``constant`` the sweep has no
            ``clamp_force`` dimension and ``clamp_force`` is the force used at each point.
        input_speed, input_speed_rpm : float or array_like
            Input speeds [rad/s] or [rpm] (exactly one). The speed dimension is named after
            the one given, with the values as given (``ds.sel(input_speed_rpm=2000)``);
            with rpm, ``input_speed`` [rad/s] is a second coordinate on it.
        settings : SweepSettings, optional
            Architecture(s), creep limit [-], known limiting torques [N m] (e.g. a
            `LimitCurve`), workers, progress bar and its label.
        **legacy
            The fields of `SweepSettings` as keywords (``workers=2``), as before it.

        Returns
        -------
        xarray.Dataset
        """
        how = merge_settings(SweepSettings, settings, legacy, "sweep")
        if (input_speed is None) == (input_speed_rpm is None):
            raise InputError(
                "input_speed",
                input_speed,
                "exactly one of input_speed [rad/s] or input_speed_rpm [rpm]",
            )
        from ..analysis.sweeps.grid import SweepRequest

        clamp_law, clamp_force = drive_clamp(self.design, clamp_law, clamp_force)
        rpm = (
            None if input_speed_rpm is None else np.atleast_1d(np.asarray(input_speed_rpm, float))
        )
        speed = np.asarray(input_speed, float) if rpm is None else rpm_to_rad_s(rpm)
        request = SweepRequest(
            ratio=ratio,
            output_torque=output_torque,
            clamp_force=clamp_force,
            clamp_law=clamp_law,
            input_speed=speed,
            architecture=how.architecture or self.architecture,
            options=self.options,
            creep_limit=how.creep_limit,
            limit_torque=grids.sweep_limit(how.limit_torque),
            workers=how.workers,
            progress=how.progress,
            label=how.label,
            input_speed_rpm=rpm,
        )
        return oil.sweep_with_oil(self, oil.path_choice(self, how.oil_temperature), request)

    def optimal_clamp_force(
        self,
        ratio: float,
        output_torque: float,
        *,
        input_speed: float | None = None,
        input_speed_rpm: float | None = None,
        creep_limit: float | None = None,
        max_pressure: float | None = None,
    ) -> ClampOptimum:
        """Clamping force of maximum efficiency under the creep and pressure limits.

        See `ballcvt.solvers.optimal_clamp.optimal_clamp_force`; limits default to the design's
        ``creep_limit`` and ``max_pressure``.
        """
        case = self._clamp_case(ratio, output_torque, input_speed, input_speed_rpm)
        return clamp_optimum(case, OptimalClamp(creep_limit, max_pressure), self.options)

    def run_cycle(
        self,
        cycle,
        *,
        clamp_force: float | None = None,
        clamp_law=None,
        settings: CycleSettings | None = None,
        mode=None,
        **legacy: Any,
    ):
        """Run this drive over a duty cycle (see `ballcvt.analysis.cycles.run_cycle`).

        Parameters
        ----------
        cycle : Cycle or path
            A `ballcvt.analysis.cycles.Cycle`, or a cycle CSV file (docs/cycles.md).
        clamp_force, clamp_law
            As in `solve` (neither: the drive file's law, `drive_clamp`).
        settings : CycleSettings, optional
            Strategy (``"target-input-speed"`` or ``"max-efficiency"``), the target input
            speed [rad/s] or [rpm], candidate ratios per step, the ratio range [-], progress
            bar, workers and the oil's temperature (docs/model.md §15).
        mode : OperatingMode or str, optional
            As in `solve`: in a planetary mode the cycle's output is the driven member
            and the driver turns at the target input speed
            (`ballcvt.api.planetary.cycle_in_mode`; output-side cycles, constant clamping).
        **legacy
            The fields of `CycleSettings` as keywords (``strategy=...``), as before it.

        Returns
        -------
        CycleResult
        """
        from ..analysis.cycle_files import Cycle, read_cycle
        from ..analysis.cycles import run_cycle

        how = merge_settings(CycleSettings, settings, legacy, "run_cycle")
        if not isinstance(cycle, Cycle):
            cycle = read_cycle(cycle)
        # the drive file's law when the call names none, as `solve` and `sweep` take it
        clamp_law, clamp_force = drive_clamp(self.design, clamp_law, clamp_force)
        clamp = {"clamp_force": clamp_force, "clamp_law": clamp_law}
        how = replace(
            how, oil_temperature=oil.drive_choice(self.design, how.oil_temperature, True, mode)
        )
        if how.oil_temperature != "fixed" or how.initial_oil_temperature is not None:
            return oil.cycle_with_oil(self, cycle, how, clamp, resolve_mode(mode))  # §15
        if not resolve_mode(mode).is_default:
            return planetary.cycle_in_mode(self, resolve_mode(mode), cycle, how, clamp)
        return run_cycle(
            self,
            cycle,
            strategy=how.strategy,
            target_input_speed=how.target(),
            clamp_force=clamp_force,
            clamp_law=clamp_law,
            candidates=how.candidates,
            ratio_range=how.ratio_range,
            progress=how.progress,
            workers=how.workers,
        )

    def with_quadrature(self, quadrature: Quadrature) -> Variator:
        """A copy using another traction-integral rule."""
        return replace(self, options=replace(self.options, quadrature=quadrature))
