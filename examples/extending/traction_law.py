"""A traction law defined outside the package, registered and used by the solver.

The law: the "circular" limiting-shear model of Lee and Hamrock (R.-T. Lee and B. J.
Hamrock, "A circular non-Newtonian fluid model: Part I - Used in elastohydrodynamic
lubrication", ASME Journal of Tribology 112 (1990) 486-495), a linear-then-saturating
shear law: Newtonian at low shear rate, tending to the limiting shear stress tau_L,

    tau = eta gamma / (1 + (eta gamma / tau_L)^n)^(1/n),   gamma = |V| / h,

with n = 2 in the paper; here n is the law's own parameter (``sharpness``, kept in
``Fluid.law_parameters``). Written with ``a = eta |V| / (h tau_L)`` the stress is
``(eta / h) S(a) V`` with ``S(a) = (1 + a^n)^(-1/n)``: a `ShearLaw`, integrated over each
contact ellipse by the package's quadrature (`shear_law_coefficients`).

Run: ``python examples/extending/traction_law.py``.
"""

from __future__ import annotations

import numpy as np

from ballcvt import Fluid, Variator, load_builtin
from ballcvt.model.traction import ShearLaw, TractionLaw, shear_law_coefficients
from ballcvt.registry import TRACTION_LAWS


def circular_coefficients(state, fluid, quadrature, derivatives):
    """``mu, chi`` (and derivatives) of the contacts ``state`` under the circular law."""
    n = fluid.law_parameters["sharpness"]

    def factor(a):  # S(a) = (1 + a^n)^(-1/n)
        return (1.0 + a**n) ** (-1.0 / n)

    def slope(a, s):  # dS/da = -a^(n-1) (1 + a^n)^(-1/n - 1) = -a^(n-1) S^(n+1)
        return -(a ** (n - 1.0)) * s ** (n + 1.0)

    return shear_law_coefficients(state, fluid, ShearLaw(factor, slope), quadrature, derivatives)


TRACTION_LAWS.register(
    TractionLaw(
        "circular",
        circular_coefficients,
        description="Lee and Hamrock's circular limiting-shear model (J. Tribol. 1990)",
        parameters=("sharpness",),
    )
)

if __name__ == "__main__":
    design, table1 = load_builtin()
    fluid = Fluid(
        **{
            **table1.model_dump(),
            "traction_law": "circular",
            "law_parameters": {"sharpness": 2.0},
        }
    )
    paper = Variator(design=design, fluid=table1)
    circular = Variator(design=design, fluid=fluid)
    for name, v in (("isothermal (Eq. 53)", paper), ("circular (Lee-Hamrock)", circular)):
        r = v.solve(1.0, 40.0, clamp_force=2000.0, input_speed_rpm=2000.0)
        limit = v.limit_torque(1.0, clamp_force=2000.0, input_speed_rpm=2000.0)
        print(f"{name}: eta = {r.eta:.4f} at 40 N m, limiting torque {limit:.1f} N m")
    ds = circular.sweep(
        ratio=[0.7, 1.0, 1.4],
        output_torque=[20.0, 40.0],
        clamp_force=2000.0,
        input_speed_rpm=2000.0,
        progress=False,
    )
    eta = np.asarray(ds["eta"]).ravel()
    print(f"circular law sweep: {eta.size} points, eta from {eta.min():.4f} to {eta.max():.4f}")
