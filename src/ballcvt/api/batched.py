"""Batched methods of `Variator`: limit curves, efficiency maps, lookup tables, the
planetary modes, and a cam of other values (``ballcvt map``, ``table``, ``--cam-*``)."""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from ..errors import InputError
from ..model.clamping.base import names_fixed_force
from ..model.modes import resolve_mode
from ..params.drive_models import drive_clamp, effective_models
from ..params.models import Design, Fluid
from ..solvers.options import SolverOptions
from ..units import rpm_to_rad_s
from . import grids, planetary
from .settings import MapGrid, TableGrid

__all__ = ["BatchMethods", "CAM_KEYS"]


class BatchMethods:
    """The batched methods `Variator` inherits (its fields are declared here for typing)."""

    design: Design
    fluid: Fluid
    architecture: str
    options: SolverOptions

    @property
    def models(self) -> dict[str, str]:
        """The models this drive is computed with when a call names none: clamping law,
        traction law, lubrication and oil temperature (a drive file's ``[models]``, else
        the package's defaults; `ballcvt.params.drive_models.effective_models`)."""
        return effective_models(self.design, self.fluid, traction_law=self.fluid.traction_law)

    def limit_curve(
        self,
        ratio,
        *,
        input_speed=None,
        input_speed_rpm=None,
        clamp_force: float | None = None,
        clamp_law=None,
        creep_limit: float | None = None,
        progress: bool | None = None,
    ) -> grids.LimitCurve:
        """Limiting output torques of many (ratio, input speed) curves in one batched search.

        Parameters
        ----------
        ratio : array_like
            Ideal ratios [-].
        input_speed, input_speed_rpm : float or array_like
            Input speeds [rad/s] or [rpm] (exactly one); broadcast with ``ratio`` (for a
            ratio x speed grid pass ``numpy.meshgrid`` outputs).
        clamp_force, clamp_law
            As in `limit_torque` (one clamping force [N] for every curve).
        creep_limit : float, optional
            Largest admissible ``|C|``; ``design.creep_limit`` by default.
        progress : bool, optional
            Progress bar (default: when stderr is a terminal).

        Returns
        -------
        LimitCurve
            ``.torque`` [N m] per curve (NaN where none); pass it to `sweep` as
            ``limit_torque`` to reuse the search.
        """
        speed = _speeds(input_speed, input_speed_rpm)
        clamp = _clamp(self.design, clamp_force, clamp_law)
        return grids.limit_curve(self, ratio, speed, clamp, creep_limit, progress)

    def efficiency_map(
        self,
        grid: MapGrid | None = None,
        *,
        input_speed_rpm: float = 2000.0,
        clamp_force: float | None = None,
        clamp_law=None,
        workers: int = 1,
        progress: bool | None = None,
        mode=None,
    ):
        """Efficiency over ideal ratio x output torque, with the limiting-torque curve.

        Parameters
        ----------
        grid : MapGrid, optional
            Ratios [-] and torques [N m]; by default 31 ratios in 0.5-2 and 35 torques up to
            1.02 x the largest limiting torque (``grid.torque_max`` otherwise).
        input_speed_rpm : float
            Input speed [rpm].
        clamp_force, clamp_law
            As in `solve`.
        workers : int
            Processes to use.
        progress : bool, optional
            Progress bars (default: when stderr is a terminal).
        mode : OperatingMode or str, optional
            As in `solve`: in a planetary mode, the map over ratio x load torque of the
            driven member at ``input_speed_rpm`` of the driver, batched
            (`ballcvt.analysis.planetary.mode_map`; constant clamping only, one process).

        Returns
        -------
        xarray.Dataset
            As `sweep`; ``limit_torque`` [N m] is the limit curve, points beyond it have
            status 1.
        """
        if not resolve_mode(mode).is_default:
            return planetary.map_in_mode(
                self,
                resolve_mode(mode),
                grid or MapGrid(),
                rpm_to_rad_s(input_speed_rpm),
                {"clamp_force": clamp_force, "clamp_law": clamp_law},
            )
        run = {"workers": workers, "progress": progress}
        clamp = _clamp(self.design, clamp_force, clamp_law)
        return grids.efficiency_map(self, grid or MapGrid(), input_speed_rpm, clamp, run)

    def lookup_table(
        self,
        grid: TableGrid | None = None,
        *,
        clamp_force: float | None = None,
        clamp_law=None,
        workers: int = 1,
        progress: bool | None = None,
    ):
        """Efficiency, input torque and losses over ratio x input speed x output torque.

        The dataset `ballcvt.api.write_tables` writes as CSV, MATLAB and Modelica tables
        (docs/cycles.md).

        Parameters
        ----------
        grid : TableGrid, optional
            Ratios [-], input speeds [rpm] and torques [N m]; by default 16 ratios in 0.5-2,
            5 speeds in 500-4000 rpm and 20 torques from 0 to the largest limiting torque.
        clamp_force, clamp_law
            As in `solve`.
        workers : int
            Processes to use.
        progress : bool, optional
            Progress bars (default: when stderr is a terminal).

        Returns
        -------
        xarray.Dataset
        """
        run = {"workers": workers, "progress": progress}
        clamp = _clamp(self.design, clamp_force, clamp_law)
        return grids.lookup_table(self, grid or TableGrid(), clamp, run)

    def planetary_map(
        self,
        mode,
        ratio,
        load_torque,
        *,
        driver_speed=None,
        driver_speed_rpm=None,
        clamp_force: float | None = None,
    ):
        """A batch of points in a planetary mode (docs/model.md §13).

        Parameters
        ----------
        mode : OperatingMode
            Which member is held and which drives.
        ratio, load_torque : float or array_like
            Ideal ratios ``tau_ID`` [-] and load torques on the driven member [N m],
            broadcast together (with the speed).
        driver_speed, driver_speed_rpm : float or array_like
            Driver speed [rad/s] or [rpm] (exactly one).
        clamp_force : float
            ``F_N0`` [N] of the constant law (the only one defined with the carrier turning).

        Returns
        -------
        ModeBatch
            Status (0 converged, 1 beyond the creep limit, 2 no equilibrium, 3 speeds out
            of range), member speeds [rad/s] and torques [N m], losses [W], efficiency.
        """
        speed = _speeds(driver_speed, driver_speed_rpm, "driver_speed")
        return planetary.planetary_map(self, mode, ratio, load_torque, speed, clamp_force)

    def planetary_capacity(
        self,
        mode,
        ratio,
        *,
        driver_speed=None,
        driver_speed_rpm=None,
        clamp_force: float | None = None,
    ):
        """Largest load torque of the driven member in a planetary mode, at each ratio.

        Parameters
        ----------
        mode, driver_speed, driver_speed_rpm, clamp_force
            As in `planetary_map`.
        ratio : array_like
            Ideal ratios ``tau_ID`` [-].

        Returns
        -------
        ndarray
            ``|L|`` at the creep limit [N m]; NaN where even zero load is not admissible.
        """
        speed = _speeds(driver_speed, driver_speed_rpm, "driver_speed")
        return planetary.planetary_capacity(self, mode, ratio, speed, clamp_force)

    def with_cam(self, cam: dict, names: dict | None = None) -> Any:
        """A copy whose design's loading cam (``[design.cam]``) has ``cam``'s values.

        Parameters
        ----------
        cam : dict
            ``[design.cam]`` keys (``disc``, ``preload`` [N], ``ramp_angle_deg`` [deg],
            ``mean_radius`` [m], ``friction`` [-]) and their new values.
        names : dict, optional
            What to call each key in the message when the design has no cam and a key is
            missing (e.g. the command line's option names); the keys by default.

        Raises
        ------
        InputError
            The design has no ``[design.cam]`` and ``cam`` does not give every key.
        """
        base = self.design.cam.model_dump() if self.design.cam is not None else {}
        missing = [k for k in CAM_KEYS if k not in {**base, **cam}]
        if missing:
            said = names or {}
            raise InputError(
                "design.cam",
                None,
                "every cam key",
                message="the design has no [design.cam] table: give every cam option "
                "(missing: " + ", ".join(said.get(k, k) for k in missing) + ")",
            )
        return replace(self, design=self.design.replace(cam={**base, **cam}))  # type: ignore[type-var]


#: The keys of ``[design.cam]`` (`Variator.with_cam`).
CAM_KEYS = ("disc", "preload", "ramp_angle_deg", "mean_radius", "friction")


def _clamp(design, clamp_force, clamp_law) -> dict:
    """The clamping keywords of `solve` that were given (with neither, the drive file's,
    `ballcvt.params.drive_models.drive_clamp`)."""
    clamp_law, clamp_force = drive_clamp(design, clamp_law, clamp_force)
    if names_fixed_force(clamp_law):
        return {"clamp_force": clamp_force}
    return {
        "clamp_law": clamp_law,
        **({} if clamp_force is None else {"clamp_force": clamp_force}),
    }


def _speeds(speed, rpm, name: str = "input_speed"):
    """Speeds [rad/s] from exactly one of ``speed`` [rad/s] or ``rpm`` [rpm] (arrays)."""
    if (speed is None) == (rpm is None):
        raise InputError(name, speed, f"exactly one of {name} [rad/s] or {name}_rpm [rpm]")
    return np.asarray(speed, float) if rpm is None else rpm_to_rad_s(np.asarray(rpm, float))
