"""Old module paths keep working: each warns once with its new name.

The package was rearranged into layers (docs/architecture.md): `ballcvt.contact.traction`
is now `ballcvt.model.traction.isothermal`, `ballcvt.solver` is `ballcvt.solvers`, and so
on. An import of an old path is answered with the module at its new path (the same module
object, so ``isinstance`` and monkeypatching keep working) and one `BallCVTDeprecationWarning`
naming the new path. An old package that was dissolved (`ballcvt.geometry`, ...) answers
each of its former names from the module that now holds it.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import sys
import types
import warnings

from .errors import BallCVTDeprecationWarning

__all__ = ["MOVED_MODULES", "MOVED_PACKAGES", "install", "warn_renamed", "moved_names"]

MOVED_MODULES = {
    "ballcvt.geometry.kinematics": "ballcvt.model.kinematics",
    "ballcvt.geometry.layout": "ballcvt.model.architectures",
    "ballcvt.contact.film": "ballcvt.model.film",
    "ballcvt.contact.hertz": "ballcvt.model.hertz",
    "ballcvt.contact.rheology": "ballcvt.model.rheology",
    "ballcvt.contact.laws": "ballcvt.model.traction.base",
    "ballcvt.contact.traction": "ballcvt.model.traction.isothermal",
    "ballcvt.contact.thermal": "ballcvt.model.traction.thermal",
    "ballcvt.contact.kernels": "ballcvt.model.traction.kernels",
    "ballcvt.contact.quadrature": "ballcvt.model.traction.quadrature",
    "ballcvt.contact.reference": "ballcvt.model.traction.reference",
    "ballcvt.contact.curve": "ballcvt.model.traction.curve",
    "ballcvt.bearings.friction": "ballcvt.model.bearings",
    "ballcvt.bearings.parasitic": "ballcvt.model.losses",
    "ballcvt.modes.members": "ballcvt.model.modes",
    "ballcvt.clamping.laws": "ballcvt.model.clamping",
    "ballcvt.solver.batch": "ballcvt.solvers.newton",
    "ballcvt.solver.point": "ballcvt.solvers.point",
    "ballcvt.solver.nested": "ballcvt.solvers.bracketing",
    "ballcvt.solver.clamped": "ballcvt.solvers.clamped",
    "ballcvt.solver.limit": "ballcvt.solvers.limit",
    "ballcvt.solver.planetary": "ballcvt.solvers.planetary",
    "ballcvt.sweeps.planetary": "ballcvt.solvers.planetary_batch",
    "ballcvt.optimize.clamp": "ballcvt.solvers.optimal_clamp",
    "ballcvt.fitting.fluid": "ballcvt.analysis.fitting",
    "ballcvt.sweeps.grid": "ballcvt.analysis.sweeps.grid",
    "ballcvt.sweeps.curves": "ballcvt.analysis.sweeps.curves",
    "ballcvt.sweeps.points": "ballcvt.analysis.sweeps.points",
    "ballcvt.sweeps.variables": "ballcvt.analysis.sweeps.variables",
    "ballcvt.sweeps.export": "ballcvt.analysis.sweeps.export",
    "ballcvt.sweeps.tables": "ballcvt.analysis.tables",
    "ballcvt.cycles.run": "ballcvt.analysis.cycles",
    "ballcvt.cycles.io": "ballcvt.analysis.cycle_files",
    "ballcvt.studies.spec": "ballcvt.analysis.studies.spec",
    "ballcvt.studies.evaluate": "ballcvt.analysis.studies.evaluate",
    "ballcvt.studies.run": "ballcvt.analysis.studies.run",
    "ballcvt.studies.pareto": "ballcvt.analysis.studies.pareto",
    "ballcvt.studies.store": "ballcvt.analysis.studies.store",
    "ballcvt.variator": "ballcvt.api",
    "ballcvt.cli.main": "ballcvt.interfaces.cli.main",
    "ballcvt.cli.format": "ballcvt.interfaces.cli.format",
    "ballcvt.ui.app": "ballcvt.interfaces.ui.app",
    "ballcvt._fileio": "ballcvt.files",
}
MOVED_PACKAGES = {
    "ballcvt.contact": {
        **dict.fromkeys(("central_film_thickness",), "ballcvt.model.film"),
        **dict.fromkeys(
            ("hertz_contact", "rolling_curvature_ratio", "transverse_curvature_ratio"),
            "ballcvt.model.hertz",
        ),
        **dict.fromkeys(("LAWS", "law_coefficients"), "ballcvt.model.traction.base"),
        **dict.fromkeys(
            ("METHODS", "Quadrature", "REFERENCE", "centred_rule", "inner_pole_rule"),
            "ballcvt.model.traction.quadrature",
        ),
        **dict.fromkeys(
            ("limiting_shear_stress", "roelands_viscosity", "saturation_factor"),
            "ballcvt.model.rheology",
        ),
        **dict.fromkeys(
            ("film_temperature_rise", "thermal_coefficients"), "ballcvt.model.traction.thermal"
        ),
        **dict.fromkeys(
            ("pole_position", "traction_coefficients"), "ballcvt.model.traction.isothermal"
        ),
    },
    "ballcvt.geometry": {
        **dict.fromkeys(
            (
                "body_speeds",
                "check_ratio",
                "creep_term",
                "entrainment_factor",
                "ideal_ratio",
                "ratio_range",
                "rolling_radius",
                "spin",
                "spin_axis_projection",
                "tilt_from_ratio",
                "tilt_limits",
            ),
            "ballcvt.model.kinematics",
        ),
        **dict.fromkeys(
            ("CONTACT_NAMES", "ContactLayout", "contact_layout"), "ballcvt.model.architectures"
        ),
    },
    "ballcvt.bearings": {
        **dict.fromkeys(
            ("load_dependent_torque", "speed_dependent_torque"), "ballcvt.model.bearings"
        ),
    },
    "ballcvt.modes": {
        **dict.fromkeys(
            ("MEMBERS", "OperatingMode", "member_torques", "relative_ratio_coefficients"),
            "ballcvt.model.modes",
        ),
    },
    "ballcvt.clamping": {
        **dict.fromkeys(
            (
                "CLAMP_LAWS",
                "CamClamp",
                "ConstantClamp",
                "OptimalClamp",
                "axial_force",
                "clamp_law",
            ),
            "ballcvt.model.clamping",
        ),
    },
    "ballcvt.optimize": {
        **dict.fromkeys(("ClampOptimum", "optimal_clamp_force"), "ballcvt.solvers.optimal_clamp"),
    },
    "ballcvt.fitting": {
        **dict.fromkeys(
            (
                "COLUMNS",
                "Curves",
                "DEFAULT_PARAMETERS",
                "FITTABLE",
                "FluidFit",
                "fit_fluid",
                "model_mu",
                "read_curves",
            ),
            "ballcvt.analysis.fitting",
        ),
    },
    "ballcvt.cycles": {
        **dict.fromkeys(
            ("Cycle", "KINDS", "STRATEGIES", "UNITS", "cycle_from_arrays", "read_cycle"),
            "ballcvt.analysis.cycle_files",
        ),
        **dict.fromkeys(("CycleResult", "FLAGS", "run_cycle"), "ballcvt.analysis.cycles"),
    },
    "ballcvt.solver": {
        **dict.fromkeys(("BatchSolution", "solve_batch"), "ballcvt.solvers.newton"),
        **dict.fromkeys(
            ("limit_torque", "limit_torque_batch", "traction_ceiling_torque"),
            "ballcvt.solvers.limit",
        ),
        **dict.fromkeys(
            ("PointSolution", "SolverOptions", "initial_creep", "solve_point"),
            "ballcvt.solvers.point",
        ),
    },
    "ballcvt.sweeps": {
        **dict.fromkeys(("solve_curves",), "ballcvt.analysis.sweeps.curves"),
        **dict.fromkeys(
            ("load_dataset", "parameters", "to_csv", "to_frame", "to_netcdf"),
            "ballcvt.analysis.sweeps.export",
        ),
        **dict.fromkeys(("sweep",), "ballcvt.analysis.sweeps.grid"),
        "STATUS": "ballcvt.analysis.sweeps",
        **dict.fromkeys(("LOSS_KINDS", "VARIABLES"), "ballcvt.analysis.sweeps.variables"),
    },
    "ballcvt.studies": {
        "STATUS": "ballcvt.analysis.studies",
        **dict.fromkeys(
            ("envelope_diameter", "evaluate_chunk", "make_context"),
            "ballcvt.analysis.studies.evaluate",
        ),
        **dict.fromkeys(("choose", "pareto_mask"), "ballcvt.analysis.studies.pareto"),
        **dict.fromkeys(
            ("StudyResult", "design_vectors", "local_client", "run_study"),
            "ballcvt.analysis.studies.run",
        ),
        **dict.fromkeys(
            ("CONSTRAINTS", "OBJECTIVES", "StudySpec", "parse_study", "read_study"),
            "ballcvt.analysis.studies.spec",
        ),
    },
    "ballcvt.cli": {},
    "ballcvt.ui": {
        **dict.fromkeys(
            ("MAP_GRID", "SLIDERS", "make_document", "serve"), "ballcvt.interfaces.ui.app"
        ),
    },
}

_warned: set[str] = set()


def warn_renamed(old: str, new: str, stacklevel: int = 3) -> None:
    """Warn once per process that ``old`` is now called ``new``."""
    if old in _warned:
        return
    _warned.add(old)
    warnings.warn(
        f"{old} was renamed {new}; the old name will be removed in a future release",
        BallCVTDeprecationWarning,
        stacklevel=stacklevel,
    )


def moved_names(module: str, names: dict[str, str]):
    """A module-level ``__getattr__`` for ``module``: each of ``names`` (name -> the module
    that now holds it, or ``"module:new_name"`` if it was renamed too) is answered from
    there, with one warning."""

    def __getattr__(name: str):
        if name not in names:
            raise AttributeError(f"module {module!r} has no attribute {name!r}")
        where, _, new = names[name].partition(":")  # "module" or "module:new_name"
        warn_renamed(f"{module}.{name}", f"{where}.{new or name}")
        return getattr(importlib.import_module(where), new or name)

    return __getattr__


class _OldPackage(types.ModuleType):
    """A dissolved package: each former name is looked up where it lives now."""

    def __getattr__(self, name: str):
        names = MOVED_PACKAGES[self.__name__]
        if name not in names:
            raise AttributeError(f"module {self.__name__!r} has no attribute {name!r}")
        warn_renamed(f"{self.__name__}.{name}", f"{names[name]}.{name}")
        return getattr(importlib.import_module(names[name]), name)

    def __dir__(self):
        return sorted(MOVED_PACKAGES[self.__name__])


class _Loader(importlib.abc.Loader):
    def create_module(self, spec):
        if spec.name in MOVED_MODULES:
            new = MOVED_MODULES[spec.name]
            warn_renamed(spec.name, new, stacklevel=8)
            return importlib.import_module(new)
        module = _OldPackage(spec.name)
        module.__path__ = []
        module.__all__ = sorted(MOVED_PACKAGES[spec.name])
        return module

    def exec_module(self, module):
        return None


class _Finder(importlib.abc.MetaPathFinder):
    def find_spec(self, fullname, path=None, target=None):
        if fullname in MOVED_MODULES or fullname in MOVED_PACKAGES:
            return importlib.machinery.ModuleSpec(
                fullname, _Loader(), is_package=fullname in MOVED_PACKAGES
            )
        return None


def install() -> None:
    """Answer the old module paths (idempotent; called when `ballcvt` is imported)."""
    if not any(isinstance(f, _Finder) for f in sys.meta_path):
        sys.meta_path.append(_Finder())
