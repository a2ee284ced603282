"""`Variator`: the one obvious entry point of the Python API."""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ._display import html_summary, text_summary
from .equilibrium.problem import build_problem
from .errors import ConvergenceError, InputError, TractionLimitError
from .model.clamping import ConstantClamp, OptimalClamp
from .model.clamping import clamp_law as _clamp_law
from .model.kinematics import ratio_range
from .model.modes import OperatingMode
from .model.traction.quadrature import Quadrature
from .params.feasibility import check_architecture
from .params.io import load_builtin
from .params.models import ARCHITECTURES, Design, Fluid
from .results.planetary import PlanetaryResult, make_planetary_result
from .results.point import OperatingResult, make_result
from .solvers.clamped import capacity_basis, pressure_bound_force, solve_clamped
from .solvers.limit import limit_torque
from .solvers.optimal_clamp import ClampCase, ClampOptimum, clamp_optimum
from .solvers.planetary import solve_mode
from .solvers.point import SolverOptions, solve_point

__all__ = ["Variator"]


def _default_drive():
    return load_builtin("table1")


@dataclass(frozen=True)
class Variator:
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
        Shear law of the film (docs/model.md §14); default: the fluid's own
        (``Fluid.traction_law``, the paper's isothermal law for Table I). The fluid must
        carry the law's parameters.

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
        object.__setattr__(self, "fluid", self.fluid.with_traction_law(self.traction_law))
        object.__setattr__(self, "traction_law", self.fluid.traction_law)
        if self.architecture not in ARCHITECTURES:
            raise InputError(
                "architecture", self.architecture, "one of: " + ", ".join(ARCHITECTURES)
            )
        check_architecture(self.design, self.architecture)

    def _summary(self) -> tuple[str, list]:
        lo, hi = self.ratio_range
        d = self.design
        rows = [
            ("design", d.name, ""),
            ("fluid", self.fluid.name, ""),
            ("architecture", f"{self.architecture} idler", ""),
            ("balls", f"{d.n_rollers} x r_S {d.roller_radius * 1e3:.4g}", "mm"),
            ("aspect ratio k", d.aspect_ratio, "-"),
            ("contact angles", f"{d.theta0_deg:g} / {d.theta2_deg:g}", "deg"),
            ("ratio range", f"{lo:.3f} - {hi:.3f}", "-"),
            ("traction law", self.fluid.traction_law, ""),
            (
                "quadrature",
                str(self.options.quadrature.n_radial)
                + " x "
                + str(self.options.quadrature.n_angular),
                "nodes",
            ),
        ]
        return "Variator", rows

    def __repr__(self) -> str:
        return text_summary(*self._summary())

    def _repr_html_(self) -> str:
        return html_summary(*self._summary())

    @property
    def ratio_range(self) -> tuple[float, float]:
        """Usable ideal-ratio range ``(min, max)`` [-]."""
        return ratio_range(self.design)

    def clamp_law(self, clamp_law=None, clamp_force=None):
        """The clamping law named by ``clamp_law`` (see `ballcvt.model.clamping.clamp_law`)."""
        return _clamp_law(clamp_law, self.design, clamp_force)

    def _problem(self, ratio, output_torque, law, input_speed, input_speed_rpm):
        """The operating point, at the law's force for the given torque (a start value for
        a law that senses the input torque)."""
        speed = _speed(input_speed, input_speed_rpm)
        t2 = float(output_torque)
        force = law.clamp_force(self.design, t2 * float(ratio), t2)
        return build_problem(
            self.design, self.fluid, self.architecture, float(ratio), t2, force, speed
        )

    def _resolve(self, ratio, output_torque, clamp_force, clamp_law, input_speed, input_speed_rpm):
        """(force law, law name): the optimal law becomes the constant law at its optimum."""
        law = self.clamp_law(clamp_law, clamp_force)
        if not law.optimises:
            return law, law.name
        opt = self.optimal_clamp_force(
            ratio,
            output_torque,
            input_speed=input_speed,
            input_speed_rpm=input_speed_rpm,
            creep_limit=law.creep_limit,
            max_pressure=law.max_pressure,
        )
        return ConstantClamp(opt.clamp_force), law.name

    def solve(
        self,
        ratio: float,
        output_torque: float,
        *,
        clamp_force: float | None = None,
        clamp_law=None,
        input_speed: float | None = None,
        input_speed_rpm: float | None = None,
        check_capacity: bool = True,
        mode: OperatingMode | None = None,
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
        check_capacity : bool
            If True (default), a torque whose equilibrium has a creep above
            ``design.creep_limit``, or has none, raises `TractionLimitError` with the limit;
            so does, under a torque-following law, a force whose peak pressure exceeds
            ``design.max_pressure``.
        mode : OperatingMode, optional
            The variator as a planetary (`ballcvt.model.modes.OperatingMode`, docs/model.md
            §13): which member is held and which drives. Then ``output_torque`` is the
            driven member's load torque [N m], ``input_speed`` (or ``input_speed_rpm``) the
            driver's speed (signed), ``ratio`` still ``tau_ID`` relative to the carrier,
            and a `PlanetaryResult` is returned. The default (carrier held, disc 0
            drives) is the paper's drive.

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
        if mode is not None and not mode.is_default:
            return self._solve_mode(
                mode,
                ratio,
                output_torque,
                clamp_force,
                clamp_law,
                _speed(input_speed, input_speed_rpm),
                check_capacity,
            )
        law, name = self._resolve(
            ratio, output_torque, clamp_force, clamp_law, input_speed, input_speed_rpm
        )
        problem = self._problem(ratio, output_torque, law, input_speed, input_speed_rpm)
        follows = not isinstance(law, ConstantClamp)
        if follows:
            problem, sol = solve_clamped(
                problem, law, lambda p, x: solve_point(p, self.options, x)
            )
        else:
            sol = solve_point(problem, self.options)
        over = sol.converged and float(np.abs(sol.state.creep).max()) > self.design.creep_limit
        if follows:
            over = over or float(problem.clamp_force) > float(
                pressure_bound_force(problem, self.design.max_pressure)
            ) * (1 + 1e-12)
        if check_capacity and (over or not sol.converged):
            lim = limit_torque(problem, self.design.creep_limit, self.options, law=law)
            if output_torque > lim:
                where = (
                    f"clamp {float(problem.clamp_force):g} N"
                    if not follows
                    else f"{name} clamping law"
                )
                raise TractionLimitError(
                    float(output_torque), lim, f" at ratio {ratio:g}, {where}"
                )
        if not sol.converged:
            raise ConvergenceError(sol.message)
        return make_result(problem, sol, self.options.quadrature, clamp_law=name)

    def _solve_mode(
        self, mode, ratio, load_torque, clamp_force, clamp_law, driver_speed, check_capacity
    ) -> PlanetaryResult:
        """`solve` in a planetary mode (docs/model.md §13)."""
        law = self.clamp_law(clamp_law, clamp_force)
        if not law.fixed_force:
            raise InputError(
                "clamp_law",
                law.name,
                "constant in a planetary mode (the cam "
                "and optimal laws are not yet defined with the carrier turning)",
            )
        got = solve_mode(
            self.design,
            self.fluid,
            self.architecture,
            mode,
            float(ratio),
            float(load_torque),
            driver_speed,
            law.force,
            self.options,
        )
        creep = max(abs(c) for c in got.solution.state.creep)
        if check_capacity and creep > self.design.creep_limit:
            raise InputError(
                "output_torque",
                float(load_torque),
                f"within the traction capacity: the largest creep {creep:.3g} "
                f"exceeds creep_limit {self.design.creep_limit:g} ({mode.label})",
            )
        rel = make_result(got.problem, got.solution, self.options.quadrature)
        return make_planetary_result(
            mode, rel, got.sign, got.speeds, float(load_torque), driver_speed, got.passes
        )

    def limit_torque(
        self,
        ratio: float,
        *,
        clamp_force: float | None = None,
        clamp_law=None,
        input_speed: float | None = None,
        input_speed_rpm: float | None = None,
        creep_limit: float | None = None,
    ) -> float:
        """Largest admissible output torque (docs/model.md §8, §11) [N m].

        Parameters
        ----------
        ratio, clamp_force, clamp_law, input_speed, input_speed_rpm
            As in `solve`. Under a torque-following law (``cam``) the capacity is also
            bounded by ``design.max_pressure``; under ``optimal`` it is the limit at the
            largest force within ``max_pressure`` (the optimiser may pick any force up to
            it).
        creep_limit : float, optional
            Largest admissible ``|C|``; ``design.creep_limit`` by default.
        """
        c_lim = self.design.creep_limit if creep_limit is None else float(creep_limit)
        if not 0.0 < c_lim < 1.0:
            raise InputError("creep_limit", c_lim, "0 < creep_limit < 1")
        law = self.clamp_law(clamp_law, clamp_force)
        start = ConstantClamp(1.0) if law.optimises else law
        problem, law, c_lim = capacity_basis(
            self._problem(ratio, 0.0, start, input_speed, input_speed_rpm), law, c_lim
        )
        return limit_torque(problem, c_lim, self.options, law=law)

    def sweep(
        self,
        *,
        ratio,
        output_torque,
        clamp_force=None,
        clamp_law=None,
        input_speed=None,
        input_speed_rpm=None,
        architecture=None,
        creep_limit: float | None = None,
        limit_torque=None,
        workers: int = 1,
        progress: bool | None = None,
        label: str | None = None,
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
        architecture : str or sequence of str, optional
            This variator's architecture by default; e.g. ``("double", "single")``.
        creep_limit : float, optional
            ``C_lim`` of the limiting torque [-].
        limit_torque : array_like, optional
            Limiting torques already known at these conditions [N m] (see
            `ballcvt.analysis.sweeps.grid.sweep`).
        workers : int
            Processes to use.
        progress : bool, optional
            Progress bar (default: when stderr is a terminal).
        label : str, optional
            What the progress bar says it computes.

        Returns
        -------
        xarray.Dataset
        """
        if (input_speed is None) == (input_speed_rpm is None):
            raise InputError(
                "input_speed",
                input_speed,
                "exactly one of input_speed [rad/s] or input_speed_rpm [rpm]",
            )
        from .analysis.sweeps.grid import sweep

        rpm = (
            None if input_speed_rpm is None else np.atleast_1d(np.asarray(input_speed_rpm, float))
        )
        speed = np.asarray(input_speed, float) if rpm is None else rpm * math.pi / 30.0
        ds = sweep(
            self.design,
            self.fluid,
            ratio=ratio,
            output_torque=output_torque,
            clamp_force=clamp_force,
            clamp_law=clamp_law,
            input_speed=speed,
            architecture=architecture or self.architecture,
            options=self.options,
            creep_limit=creep_limit,
            limit_torque=limit_torque,
            workers=workers,
            progress=progress,
            label=label,
            input_speed_rpm=rpm,
        )
        return ds

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
        case = ClampCase(
            self.design,
            self.fluid,
            self.architecture,
            float(ratio),
            float(output_torque),
            _speed(input_speed, input_speed_rpm),
        )
        return clamp_optimum(case, OptimalClamp(creep_limit, max_pressure), self.options)

    def run_cycle(
        self,
        cycle,
        *,
        strategy: str = "target-input-speed",
        target_input_speed: float | None = None,
        target_input_speed_rpm: float | None = None,
        clamp_force: float | None = None,
        clamp_law=None,
        candidates: int = 9,
        ratio_range=None,
        progress: bool | None = None,
        workers: int = 1,
    ):
        """Run this drive over a duty cycle (see `ballcvt.analysis.cycles.run_cycle`).

        Parameters
        ----------
        cycle : Cycle or path
            A `ballcvt.analysis.cycles.Cycle`, or a cycle CSV file (docs/cycles.md).
        strategy : {"target-input-speed", "max-efficiency"}
            How the ratio is chosen.
        target_input_speed, target_input_speed_rpm : float, optional
            Input speed held by ``target-input-speed`` [rad/s] or [rpm].
        clamp_force, clamp_law
            As in `solve`.
        candidates : int
            Ratios tried per step by ``max-efficiency``.
        ratio_range : (float, float), optional
            Ratios ``max-efficiency`` may use [-].
        progress : bool, optional
            Progress bar (default: when stderr is a terminal).
        workers : int
            Processes to solve the steps on.

        Returns
        -------
        CycleResult
        """
        from .analysis.cycle_files import Cycle, read_cycle
        from .analysis.cycles import run_cycle

        if not isinstance(cycle, Cycle):
            cycle = read_cycle(cycle)
        if target_input_speed is not None and target_input_speed_rpm is not None:
            raise InputError(
                "target_input_speed",
                target_input_speed,
                "at most one of target_input_speed [rad/s] or target_input_speed_rpm [rpm]",
            )
        target = (
            target_input_speed_rpm * math.pi / 30.0
            if target_input_speed_rpm is not None
            else target_input_speed
        )
        return run_cycle(
            self,
            cycle,
            strategy=strategy,
            target_input_speed=target,
            clamp_force=clamp_force,
            clamp_law=clamp_law,
            candidates=candidates,
            ratio_range=ratio_range,
            progress=progress,
            workers=workers,
        )

    def with_quadrature(self, quadrature: Quadrature) -> Variator:
        """A copy using another traction-integral rule."""
        return replace(self, options=replace(self.options, quadrature=quadrature))


def _speed(input_speed, input_speed_rpm) -> float:
    if (input_speed is None) == (input_speed_rpm is None):
        raise InputError(
            "input_speed",
            input_speed,
            "exactly one of input_speed [rad/s] or input_speed_rpm [rpm]",
        )
    return float(input_speed) if input_speed is not None else float(input_speed_rpm) * math.pi / 30
