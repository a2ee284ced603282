"""The constant clamping law: a fixed ``F_N0``, the paper's test rig (docs/model.md §11)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numpy as np

from ...errors import InputError
from ...params.models import Design
from ...registry import CLAMP_LAWS
from .base import ClampLaw

__all__ = ["ConstantClamp"]


@dataclass(frozen=True)
class ConstantClamp(ClampLaw):
    """The paper's test rig: a fixed ``F_N0`` (the default law).

    Parameters
    ----------
    force : float
        Input-contact normal load ``F_N0`` > 0 [N].
    """

    force: float
    name: str = "constant"
    implicit: bool = False
    fixed_force: ClassVar[bool] = True

    @classmethod
    def resolve(cls, design: Design, clamp_force=None) -> ConstantClamp:
        """The law at ``clamp_force`` [N] (`InputError` naming the other laws if None)."""
        if clamp_force is None:
            others = [n for n, law in CLAMP_LAWS.items() if not law.fixed_force]
            raise InputError(
                "clamp_force",
                None,
                "a value [N] for the constant clamping law "
                "(or choose another clamp_law: " + ", ".join(others) + ")",
            )
        return cls(float(clamp_force))

    def clamp_force(self, design: Design, input_torque, output_torque):
        """``F_N0`` [N], the same at every torque; shape of the torques."""
        shape = np.broadcast_shapes(np.shape(input_torque), np.shape(output_torque))
        return np.full(shape, float(self.force))

    def output_torque_bound(self, design: Design, clamp_force, ratio):
        """Every torque if ``force <= clamp_force``, none otherwise [N m]."""
        return np.where(self.force <= np.asarray(clamp_force, float), np.inf, 0.0)
