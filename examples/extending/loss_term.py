"""A parasitic-loss term defined outside the package: the viscous drag of a lip seal.

Under the lip of a radial shaft seal runs a lubricant film about a micrometre thick
(Müller and Nau, Fluid Sealing Technology, Marcel Dekker, 1998, Ch. 8). Treating it as a
Newtonian film sheared between the shaft and the lip gives Petroff's law (N. P. Petroff,
"Friction in machines and the effect of the lubricant", Inzhenernyi Zhurnal, St. Petersburg,
1883), the torque of a full journal film:

    M = mu omega r^3 2 pi b / h

with ``mu`` the oil's dynamic viscosity [Pa s], ``omega`` the shaft speed [rad/s], ``r`` the
shaft radius [m], ``b`` the lip's contact width [m] and ``h`` the film thickness [m].

The term carries its own numbers (a frozen dataclass), reads the oil's viscosity from the
drive's fluid, is registered in `ballcvt.registry.LOSS_TERMS`, and from then on enters
`Variator.solve`, `.sweep` and `.limit_torque`. Run:  python examples/extending/loss_term.py
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass

import numpy as np

from ballcvt import Variator
from ballcvt.model.losses import DragInputs, LossTerm
from ballcvt.registry import LOSS_TERMS


def petroff_seal_torque(speed, radius, width, film, viscosity):
    """Viscous drag torque of a lip seal's film, Petroff's law [N m].

    ``M = mu |omega| r^3 2 pi b / h`` (Petroff 1883; film under a lip seal: Müller and Nau
    1998, Ch. 8).

    Parameters
    ----------
    speed : array_like
        Shaft speed ``omega`` [rad/s] (sign ignored).
    radius : float
        Shaft radius under the lip ``r`` [m].
    width : float
        Lip contact width ``b`` [m].
    film : float
        Film thickness ``h`` [m].
    viscosity : float
        Dynamic viscosity of the oil ``mu`` [Pa s].

    Returns
    -------
    ndarray
        Torque magnitude [N m].
    """
    w = np.abs(np.asarray(speed, dtype=float))
    return viscosity * w * radius**3 * 2.0 * math.pi * width / film


@dataclass(frozen=True)
class LipSeal:
    """The numbers of one lip seal per shaft: radius, lip width, film thickness [m]."""

    radius: float = 0.015
    width: float = 0.2e-3
    film: float = 1.0e-6

    def __call__(self, at: DragInputs):
        """Torque on one shaft at ``at.speed`` (the term's ``torque`` function) [N m]."""
        return petroff_seal_torque(at.speed, self.radius, self.width, self.film, at.fluid.viscosity)


def main() -> dict:
    term = LOSS_TERMS.register(
        LossTerm(
            "lip_seal",
            "shafts",
            LipSeal(),
            parameters="LipSeal(radius, width, film) in this script; mu from the fluid",
        )
    )
    v = Variator()  # the paper's drive: no built-in parasitic losses
    r = v.solve(1.0, 20.0, clamp_force=2000.0, input_speed_rpm=2000)
    print(f"solve: lip seal loss {r.losses['lip_seal']:.3f} W of {r.losses['total']:.2f} W")
    ds = v.sweep(ratio=[0.6, 1.0, 1.6], output_torque=[20.0], clamp_force=2000.0, input_speed_rpm=2000)
    parasitic = ds.loss_subtotals.sel(subtotal="parasitic").values.ravel()
    print("sweep: parasitic losses (the lip seals) [W]:", np.round(parasitic, 3))
    with_seal = v.limit_torque(1.0, clamp_force=2000.0, input_speed_rpm=2000)
    LOSS_TERMS.unregister(term.name)
    bare = v.limit_torque(1.0, clamp_force=2000.0, input_speed_rpm=2000)
    print(f"limit torque: {with_seal:.3f} N m with the lip seals, {bare:.3f} N m without")
    return {
        "lip_seal_W": float(r.losses["lip_seal"]),
        "breakdown": list(r.losses),
        "sweep_parasitic_W": [float(p) for p in parasitic],
        "limit_with": float(with_seal),
        "limit_without": float(bare),
    }


if __name__ == "__main__":
    print("RESULT " + json.dumps(main()))
