"""A clamping law defined outside the package, registered and used by the solver.

The law: a preload spring plus a linear torque-sensing term, the simplest model of a
torque-sensing clamp (a loading cam linearised about its operating range, after
Loewenthal and Zaretsky, "Design of traction drives", NASA RP-1154, 1985):

    F_N0 = F_pre + k |T_2|,

with the preload ``F_pre`` [N] and the gain ``k`` [N/(N m)] its own parameters. It senses
the output torque, which is given, so the force is known before the equilibrium is solved
(``implicit`` is False).

Run: ``python examples/extending/clamp_law.py``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ballcvt import Variator
from ballcvt.model.clamping import ClampLaw
from ballcvt.registry import CLAMP_LAWS


@dataclass(frozen=True)
class SpringTorqueClamp(ClampLaw):
    """``F_N0 = preload + gain |T_2|`` [N]."""

    preload: float = 800.0  # [N]
    gain: float = 25.0  # [N/(N m)]
    name: str = "spring_torque"

    def clamp_force(self, design, input_torque, output_torque):
        """``F_N0`` [N] at the disc torques [N m]."""
        shape = np.broadcast_shapes(np.shape(input_torque), np.shape(output_torque))
        t2 = np.broadcast_to(np.abs(np.asarray(output_torque, dtype=float)), shape)
        return self.preload + self.gain * t2

    def output_torque_bound(self, design, clamp_force, ratio):
        """Largest ``T_2`` [N m] whose force stays at or below ``clamp_force`` [N]."""
        torque = np.maximum(np.asarray(clamp_force, dtype=float) - self.preload, 0.0) / self.gain
        return np.broadcast_to(torque, np.shape(ratio))


CLAMP_LAWS.register(SpringTorqueClamp, name="spring_torque")

if __name__ == "__main__":
    v = Variator()
    stiff = SpringTorqueClamp(preload=800.0, gain=40.0)
    for label, law in (("by name (defaults)", "spring_torque"), ("gain 40 N/(N m)", stiff)):
        r = v.solve(1.0, 40.0, clamp_law=law, input_speed_rpm=2000.0)
        limit = v.limit_torque(1.0, clamp_law=law, input_speed_rpm=2000.0)
        print(
            f"spring + torque clamp, {label}: F_N0 = {r.clamp_force:.1f} N, eta = {r.eta:.4f} "
            f"at 40 N m, limiting torque {limit:.1f} N m"
        )
    ds = v.sweep(
        ratio=[0.7, 1.0, 1.4],
        output_torque=[20.0, 40.0],
        clamp_law="spring_torque",
        input_speed_rpm=2000.0,
        progress=False,
    )
    eta = np.asarray(ds["eta"]).ravel()
    force = np.asarray(ds["clamp_force"]).ravel()
    print(
        f"sweep: {eta.size} points, F_N0 from {force.min():.1f} to {force.max():.1f} N, "
        f"eta from {eta.min():.4f} to {eta.max():.4f}"
    )
