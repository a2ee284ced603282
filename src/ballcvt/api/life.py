"""Fatigue-life methods of `Variator`: at a point, over a duty cycle, over a map
(``ballcvt life``, ``ballcvt map --life``; docs/life.md)."""

from __future__ import annotations

from typing import Any

from ..params.material import FatigueMaterial
from ..params.models import Design, Fluid
from ..solvers.options import SolverOptions
from .settings import CycleSettings

__all__ = ["LifeMethods", "life_settings"]


def life_settings(life_model: str = "lundberg-palmgren", material=None):
    """A `ballcvt.analysis.life.LifeSettings`: the model by name (``LIFE_MODELS``) and the
    material (a `FatigueMaterial`, or the name of a built-in one; AISI 52100 steel by
    default)."""
    from ..analysis.life import LifeSettings
    from ..params.material import load_material

    if isinstance(material, str):
        material = load_material(material)
    return LifeSettings(life_model, material).check()


class LifeMethods:
    """The life methods `Variator` inherits (its fields are declared here for typing)."""

    design: Design
    fluid: Fluid
    architecture: str
    options: SolverOptions

    def life(
        self,
        ratio: float,
        output_torque: float,
        *,
        life_model: str = "lundberg-palmgren",
        material: FatigueMaterial | str | None = None,
        **point: Any,
    ):
        """Rolling-contact fatigue life at an operating point (docs/life.md).

        Parameters
        ----------
        ratio, output_torque
            As in `solve` [-], [N m].
        life_model : str
            ``"lundberg-palmgren"`` (default), ``"zaretsky"`` or ``"iso-fatigue-limit"``
            (``ballcvt.registry.LIFE_MODELS``).
        material : FatigueMaterial or str, optional
            Fatigue constants of the tracks (AISI 52100 steel by default).
        **point
            The other keywords of `solve`: ``clamp_force`` or ``clamp_law``,
            ``input_speed`` or ``input_speed_rpm``, ``settings`` (a planetary mode's point
            counts its speeds relative to the carrier).

        Returns
        -------
        LifeResult
            Per-element L10 (stress cycles or revolutions, and hours), the system L10 [h]
            and the limiting element.
        """
        from ..analysis.life import point_life

        how = life_settings(life_model, material)
        return point_life(self.solve(ratio, output_torque, **point), how)  # type: ignore[attr-defined]

    def cycle_life(
        self,
        cycle,
        *,
        clamp_force: float | None = None,
        clamp_law=None,
        settings: CycleSettings | None = None,
        life_model: str = "lundberg-palmgren",
        material: FatigueMaterial | str | None = None,
    ):
        """Run a duty cycle (`run_cycle`) and its fatigue life by Miner's rule.

        Returns
        -------
        CycleResult
            The run, with the step columns ``l10_hours``, ``damage``, ``limiting_element``
            and ``summary["life"]`` (`ballcvt.analysis.life.cycle_life`); the life in
            kilometres when the cycle has a ``vehicle_speed`` column.
        """
        from ..analysis.cycle_files import Cycle, read_cycle
        from ..analysis.life import cycle_life

        how = life_settings(life_model, material)
        if not isinstance(cycle, Cycle):
            cycle = read_cycle(cycle)
        run = self.run_cycle(  # type: ignore[attr-defined]
            cycle, clamp_force=clamp_force, clamp_law=clamp_law, settings=settings
        )
        return cycle_life(self, run, how, cycle.distance)

    def map_life(
        self,
        ds,
        *,
        life_model: str = "lundberg-palmgren",
        material: FatigueMaterial | str | None = None,
    ):
        """``ds`` (a sweep or `efficiency_map` of this drive) with the system L10 of each
        converged point, ``l10_hours`` [h] (`ballcvt.analysis.life.sweep_life`)."""
        from ..analysis.life import sweep_life

        how = life_settings(life_model, material)
        return sweep_life(ds, self, how, self.options.quadrature)
