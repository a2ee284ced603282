"""Study files: which designs to explore, at which duty, for which objectives (docs/studies.md).

A study is a TOML file with the tables below; every key is checked, and a wrong one gets one
line naming it (`read_study`).

``[study]``
    ``name``; ``drive`` (a built-in drive's name or a drive TOML file: the base design and
    the fluid); ``architecture``; ``method`` (``sobol``, ``lhs`` or ``nsga2``);
    ``samples`` (designs drawn by a sampling method), or ``population`` and
    ``generations`` (NSGA-II); ``seed``; ``chunk`` (designs per task); ``choose`` (the
    objective that picks the chosen design on the Pareto front; by default the design
    nearest the ideal point, objectives scaled to [0, 1]); ``oil_temperature``
    (``"fixed"``, ``"balance"`` or a temperature [K]; by default the drive file's
    ``[models]``: the built-in ``hub``'s oil balance, some 25 s of CPU a design).
``[parameters]``
    Design fields to vary: ``{min = .., max = ..}`` (continuous; ``integer = true`` for a
    whole-number range) or ``{values = [..]}`` (a list). ``clamp_force`` [N] may be varied
    too (the constant clamping force of the operating points).
``[fixed]``
    Design fields set for every design (on top of the base drive's).
``[operating]``
    The duty: ``ratio``, ``output_torque`` [N m], ``input_speed_rpm`` (lists; their grid
    is evaluated) with ``weights`` (optional, one per grid point, else equal), and
    ``clamp_force`` [N] or ``clamp_law`` (``cam``, ``optimal``); or ``cycle`` (a duty-cycle
    CSV, run with ``strategy`` and ``target_input_speed_rpm``).
``[objectives]``
    ``name = "max"`` or ``"min"`` for names in `OBJECTIVES`.
``[constraints]``
    Any of `CONSTRAINTS`. Every operating point within the traction capacity is always
    required.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, Literal

from pydantic import Field, model_validator

from ...errors import InputError
from ...model.clamping.base import names_fixed_force
from ...model.oil import MAX_OIL_TEMPERATURE
from ...params.io import parse_toml, read_text
from ...params.models import ARCHITECTURES, Design, ParameterModel
from ...registry import TRACTION_LAWS

__all__ = [
    "StudySpec",
    "Parameter",
    "Operating",
    "Constraints",
    "read_study",
    "parse_study",
    "OBJECTIVES",
    "CONSTRAINTS",
    "METHODS",
]

METHODS = ("sobol", "lhs", "nsga2")
#: Objectives a study can ask for, with their units and meaning.
OBJECTIVES = {
    "eta_mean": ("-", "duty-weighted mean efficiency over the operating points (Eq. 38)"),
    "eta_min": ("-", "lowest efficiency over the operating points"),
    "cycle_efficiency": ("-", "energy out over energy in over the duty cycle"),
    "capacity": ("N m", "lowest limiting torque over the capacity ratios"),
    "torque_per_volume": ("N m/m^3", "capacity over the ball envelope volume"),
    "torque_per_mass": ("N m/kg", "capacity over the mass of the balls"),
    "min_lambda": ("-", "lowest film thickness ratio over points (or cycle steps) and contacts"),
    "max_pressure": (
        "Pa",
        "highest Hertz peak pressure over points (or cycle steps) and contacts",
    ),
    "outer_diameter": ("m", "ball envelope diameter 2 (k + 2) r_S"),
    "l10_hours": (
        "h",
        "system fatigue life L10 (Lundberg-Palmgren, docs/life.md): the shortest over the "
        "operating points, or by Miner's rule over the duty cycle",
    ),
}
#: Constraints a study can set (name -> unit, meaning).
CONSTRAINTS = {
    "outer_diameter_max": ("m", "ball envelope diameter at most"),
    "max_pressure_max": ("Pa", "highest peak pressure at most"),
    "min_lambda_min": ("-", "lowest film thickness ratio at least"),
    "eta_min_min": ("-", "lowest efficiency at least"),
    "ratio_range": ("-", "[lo, hi]: the usable ratio range covers it"),
    "min_capacity": ("N m", "[{ratio, torque}]: limiting torque at the ratio at least"),
    "min_l10_hours": ("h", "system fatigue life L10 at least"),
}
#: Fields a study may vary besides the design's own.
EXTRA_PARAMETERS = ("clamp_force",)


class Parameter(ParameterModel):
    """One varied parameter: a range (``min``, ``max``, ``integer``) or ``values``."""

    min: float | None = None
    max: float | None = None
    integer: bool = False
    values: list[float] | None = None

    @model_validator(mode="after")
    def _one_kind(self) -> Parameter:
        if self.values is not None:
            if self.min is not None or self.max is not None or not self.values:
                raise InputError("values", self.values, "a non-empty list, without min/max")
            if not all(math.isfinite(v) for v in self.values):
                raise InputError("values", self.values, "finite numbers")
        else:
            if self.min is None or self.max is None:
                raise InputError(
                    "min",
                    self.min,
                    "min and max (or values)",
                    message="a parameter needs min and max, or values",
                )
            if not (math.isfinite(self.min) and math.isfinite(self.max) and self.min < self.max):
                raise InputError("max", self.max, f"finite and > min = {self.min:g}")
        return self

    def scale(self, u):
        """Map unit-cube coordinates ``u`` in [0, 1) to values of this parameter."""
        import numpy as np

        u = np.asarray(u, dtype=float)
        if self.values is not None:
            idx = np.minimum((u * len(self.values)).astype(int), len(self.values) - 1)
            return np.asarray(self.values, dtype=float)[idx]
        if self.integer:
            lo, hi = math.ceil(self.min), math.floor(self.max)
            return np.minimum(np.floor(lo + u * (hi - lo + 1)), hi)
        return self.min + u * (self.max - self.min)


class Operating(ParameterModel):
    """The duty: a grid of operating points, or a duty cycle."""

    ratio: list[float] | None = None
    output_torque: list[float] | None = None
    input_speed_rpm: list[float] | None = None
    weights: list[float] | None = None
    clamp_force: float | None = Field(None, gt=0, lt=math.inf)
    clamp_law: str = Field("constant", description="a name in ballcvt.registry.CLAMP_LAWS")
    cycle: str | None = None
    strategy: Literal["target-input-speed", "max-efficiency"] = "target-input-speed"
    target_input_speed_rpm: float | None = Field(None, gt=0, lt=math.inf)

    @model_validator(mode="after")
    def _complete(self) -> Operating:
        grid = (self.ratio, self.output_torque, self.input_speed_rpm)
        if self.cycle is None:
            if any(g is None or not g for g in grid):
                raise InputError(
                    "operating",
                    None,
                    "ratio, output_torque, input_speed_rpm",
                    message="[operating] needs ratio, output_torque and "
                    "input_speed_rpm (lists), or a cycle",
                )
            for name, g, ok in (
                ("ratio", self.ratio, lambda v: v > 0),
                ("output_torque", self.output_torque, lambda v: v >= 0),
                ("input_speed_rpm", self.input_speed_rpm, lambda v: v > 0),
            ):
                bad = [v for v in g or () if not (math.isfinite(v) and ok(v))]
                if bad:
                    raise InputError(
                        f"operating.{name}", bad[0], ">= 0" if name == "output_torque" else "> 0"
                    )
            n = (
                len(self.ratio or ())
                * len(self.output_torque or ())
                * len(self.input_speed_rpm or ())
            )
            if self.weights is not None and (
                len(self.weights) != n or min(self.weights) < 0 or sum(self.weights) <= 0
            ):
                raise InputError(
                    "operating.weights",
                    len(self.weights),
                    f"{n} non-negative weights (one per grid point), not all 0",
                )
        elif any(g is not None for g in grid):
            raise InputError("operating.cycle", self.cycle, "a cycle or a grid, not both")
        elif self.strategy == "target-input-speed" and self.target_input_speed_rpm is None:
            raise InputError(
                "operating.target_input_speed_rpm",
                None,
                "a speed [rpm]",
                message="[operating] cycle with target-input-speed needs target_input_speed_rpm",
            )
        return self


class MinCapacity(ParameterModel):
    """A capacity requirement: limiting torque at ``ratio`` at least ``torque``."""

    ratio: float = Field(..., gt=0, lt=math.inf)
    torque: float = Field(..., ge=0, lt=math.inf)


class Constraints(ParameterModel):
    """Limits a design must meet (`CONSTRAINTS`); none by default."""

    outer_diameter_max: float | None = Field(None, gt=0, lt=math.inf)
    max_pressure_max: float | None = Field(None, gt=0, lt=math.inf)
    min_lambda_min: float | None = Field(None, ge=0, lt=math.inf)
    eta_min_min: float | None = Field(None, ge=0, le=1)
    ratio_range: list[float] | None = None
    min_capacity: list[MinCapacity] = []
    min_l10_hours: float | None = Field(None, gt=0, lt=math.inf)

    @model_validator(mode="after")
    def _range(self) -> Constraints:
        r = self.ratio_range
        if r is not None and not (len(r) == 2 and 0 < r[0] < r[1] < math.inf):
            raise InputError("constraints.ratio_range", r, "[lo, hi] with 0 < lo < hi")
        return self


class StudySettings(ParameterModel):
    """The ``[study]`` table."""

    name: str
    drive: str = "table1"
    architecture: str = Field("double", description="a name in ballcvt.registry.ARCHITECTURES")
    method: Literal["sobol", "lhs", "nsga2"] = "sobol"
    samples: int = Field(64, ge=1, le=10_000_000)
    population: int = Field(16, ge=4, le=100_000)
    generations: int = Field(5, ge=1, le=10_000)
    seed: int = Field(0, ge=0)
    chunk: int = Field(8, ge=1, le=100_000)
    choose: str | None = None
    capacity_ratios: list[float] | None = None
    traction_law: str | None = Field(
        None, description="a name in ballcvt.registry.TRACTION_LAWS (None: the fluid's)"
    )
    oil_temperature: Literal["fixed", "balance"] | float | None = Field(
        None,
        description=(
            "the oil's model: 'fixed', 'balance' or a temperature [K] (None: the drive "
            "file's [models])"
        ),
    )

    @model_validator(mode="after")
    def _oil(self) -> StudySettings:
        t = self.oil_temperature
        if isinstance(t, float) and not 150.0 < t < MAX_OIL_TEMPERATURE:
            raise InputError(
                "study.oil_temperature",
                t,
                f"'fixed', 'balance' or 150 to {MAX_OIL_TEMPERATURE:g} K",
            )
        return self


class StudySpec(ParameterModel):
    """A validated study (see module docstring)."""

    study: StudySettings
    parameters: dict[str, Parameter]
    fixed: dict[str, Any] = {}
    operating: Operating
    objectives: dict[str, Literal["max", "min"]]
    constraints: Constraints = Constraints()

    @model_validator(mode="after")
    def _consistent(self) -> StudySpec:
        fields = set(Design.model_fields) - {"name"}
        if not self.parameters:
            raise InputError("parameters", None, "at least one parameter to vary")
        for name in self.parameters:
            if name not in fields and name not in EXTRA_PARAMETERS:
                raise InputError(
                    f"parameters.{name}",
                    name,
                    "a design field or clamp_force",
                    message=f"[parameters] {name}: not a design field (known: "
                    + ", ".join(sorted(fields | set(EXTRA_PARAMETERS)))
                    + ")",
                )
        for name in self.fixed:
            if name not in fields:
                raise InputError(
                    f"fixed.{name}",
                    name,
                    "a design field",
                    message=f"[fixed] {name}: not a design field",
                )
            if name in self.parameters:
                raise InputError(f"fixed.{name}", name, "not also varied")
            _check_fixed(name, self.fixed[name])
        if not self.objectives:
            raise InputError("objectives", None, "at least one objective")
        for name in self.objectives:
            if name not in OBJECTIVES:
                raise InputError(f"objectives.{name}", name, "one of " + ", ".join(OBJECTIVES))
        cycle = self.operating.cycle is not None
        for name in self.objectives:
            if (name == "cycle_efficiency") != cycle and name in (
                "cycle_efficiency",
                "eta_mean",
                "eta_min",
            ):
                raise InputError(
                    f"objectives.{name}",
                    name,
                    "cycle_efficiency with a cycle, eta_mean/eta_min with a grid",
                )
        if cycle and self.constraints.eta_min_min is not None:
            raise InputError(
                "constraints.eta_min_min", self.constraints.eta_min_min, "with a grid, not a cycle"
            )
        if self.study.choose is not None and self.study.choose not in self.objectives:
            raise InputError(
                "study.choose",
                self.study.choose,
                "one of the objectives: " + ", ".join(self.objectives),
            )
        if self.study.architecture not in ARCHITECTURES:
            raise InputError(
                "study.architecture",
                self.study.architecture,
                "one of: " + ", ".join(ARCHITECTURES),
            )
        if self.study.traction_law is not None:
            TRACTION_LAWS.get(self.study.traction_law)  # InputError listing the laws
        fixed = names_fixed_force(self.operating.clamp_law)  # unknown: InputError too
        if fixed and self.operating.clamp_force is None and "clamp_force" not in self.parameters:
            raise InputError(
                "operating.clamp_force",
                None,
                "a force [N]",
                message="[operating] needs clamp_force [N] (or clamp_law cam or "
                "optimal, or clamp_force in [parameters])",
            )
        if ("clamp_force" in self.parameters) and not fixed:
            raise InputError("parameters.clamp_force", None, "clamp_law constant")
        return self

    @property
    def names(self) -> tuple[str, ...]:
        """Varied parameters, in file order."""
        return tuple(self.parameters)


def _check_fixed(name: str, value: Any) -> None:
    """A ``[fixed]`` value within its design field's own type and range, checked up front
    (not discovered at the end of a study in which no design could be built)."""
    try:
        Design.check_field(name, value)
    except InputError as exc:
        raise InputError(
            f"fixed.{exc.quantity}",
            exc.value,
            exc.allowed,
            message=f"[fixed] {str(exc)}",
        ) from None


def parse_study(text: str, source: str = "study file", base: Path | None = None) -> StudySpec:
    """Parse and validate the TOML text of a study; ``base`` resolves relative paths."""
    data = parse_toml(text, source)
    try:
        spec = StudySpec(**data)
    except InputError as exc:
        raise InputError(
            exc.quantity, exc.value, exc.allowed, message=f"{source}: {exc}"
        ) from None
    if base is not None:
        updates: dict[str, Any] = {}
        drive = spec.study.drive
        if (base / drive).exists():
            updates["study"] = spec.study.model_copy(update={"drive": str(base / drive)})
        if spec.operating.cycle is not None and not Path(spec.operating.cycle).is_absolute():
            updates["operating"] = spec.operating.model_copy(
                update={"cycle": str(base / spec.operating.cycle)}
            )
        spec = spec.model_copy(update=updates)
    return spec


def read_study(path) -> StudySpec:
    """Read and validate a study file (relative paths in it are relative to the file)."""
    path = Path(path)
    text = read_text(path, "study file")
    return parse_study(text, f"study file {path}", path.parent)
