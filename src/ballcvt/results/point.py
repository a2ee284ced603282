"""Immutable results of one operating point, with their inputs, version and convergence.

`OperatingResult.to_dict` gives plain JSON-able data (the CLI's ``--json`` output);
`OperatingResult.save` / `OperatingResult.load` round-trip it through a JSON file.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, fields
from pathlib import Path
from types import MappingProxyType
from typing import Any, Mapping

import numpy as np

from .._version import __version__
from ..contact.quadrature import Quadrature
from ..equilibrium.problem import EquilibriumProblem
from ..performance.efficiency import efficiency, power_losses
from ..params.models import Design, Fluid
from ..solver.point import PointSolution

__all__ = ["ContactResult", "OperatingResult", "make_result"]


@dataclass(frozen=True)
class ContactResult:
    """One contact of one ball (loss figures are for all ``n`` balls).

    Attributes
    ----------
    creep, spin, mu, chi : float
        Creep (Eq. 7), spin (Eqs. 11-14), traction and spin-moment coefficients [-].
    normal_load : float
        ``F_N`` [N].
    p_max : float
        Hertz peak pressure [Pa].
    semi_axis_x, semi_axis_y : float
        Contact semi-axes, rolling and transverse [m].
    film_thickness : float
        Hamrock-Dowson central film thickness [m].
    tangential_force : float
        Traction force on the ball along ``+i`` [N].
    spin_moment : float
        Spin moment on the ball about the contact normal [N m].
    body_speed : float
        Signed speed of the disc or idler about the main axis [rad/s].
    creep_loss, spin_loss : float
        Power dissipated by creep and by spin [W].
    """

    creep: float
    spin: float
    mu: float
    chi: float
    normal_load: float
    p_max: float
    semi_axis_x: float
    semi_axis_y: float
    film_thickness: float
    tangential_force: float
    spin_moment: float
    body_speed: float
    creep_loss: float
    spin_loss: float


@dataclass(frozen=True)
class OperatingResult:
    """Solved operating point of a variator (SI units; names say where not).

    Attributes
    ----------
    architecture : str
        ``"double"`` or ``"single"`` idler.
    design, fluid : Design, Fluid
        The parameter sets used.
    ratio, output_torque, clamp_force, input_speed : float
        The inputs: ideal ratio [-], ``T_2`` [N m], ``F_N0`` [N], ``omega_0`` [rad/s].
    tilt : float
        Ball-axis tilt [rad].
    actual_ratio : float
        ``tau_R = omega_2 / omega_0`` (Eq. 8) [-].
    input_torque : float
        ``T_0`` [N m].
    output_speed, roller_speed : float
        ``omega_2`` and the ball speed ``omega_S`` [rad/s].
    contacts : Mapping[str, ContactResult]
        Per contact, keyed ``input``, ``idler_a``, ``idler_b``/``idler``, ``output``.
    axle_reactions : tuple of float
        ``(F_Ra, F_Rb)`` on each ball axle [N].
    losses : Mapping[str, float]
        ``creep``, ``spin``, ``roller_bearings``, ``idler_bearings``, ``bearing``, ``total`` [W].
    eta, eta_loss, eta_speed, eta_torque : float
        Overall efficiency by Eq. 38 and by Eq. 39, speed (Eq. 9) and torque (Eq. 37) [-].
    converged : bool
        Whether the residual met the tolerance.
    residual_norm : float
        ``max |residual|`` (dimensionless torques) [-].
    iterations : int
        Residual evaluations of the solver.
    quadrature : str
        The traction-integral rule, e.g. ``"pole 32x12 (centred part 32x32)"``.
    version : str
        ballcvt version that computed the result.
    """

    architecture: str
    design: Design
    fluid: Fluid
    ratio: float
    output_torque: float
    clamp_force: float
    input_speed: float
    tilt: float
    actual_ratio: float
    input_torque: float
    output_speed: float
    roller_speed: float
    contacts: Mapping[str, ContactResult]
    axle_reactions: tuple[float, float]
    losses: Mapping[str, float]
    eta: float
    eta_loss: float
    eta_speed: float
    eta_torque: float
    converged: bool
    residual_norm: float
    iterations: int
    quadrature: str
    version: str = __version__

    @property
    def tilt_deg(self) -> float:
        """Tilt [deg]."""
        return math.degrees(self.tilt)

    @property
    def input_speed_rpm(self) -> float:
        """Input speed [rpm]."""
        return self.input_speed * 30.0 / math.pi

    @property
    def input_power(self) -> float:
        """``T_0 omega_0`` [W]."""
        return self.input_torque * self.input_speed

    @property
    def output_power(self) -> float:
        """``T_2 omega_2`` [W]."""
        return self.output_torque * self.output_speed

    def to_dict(self) -> dict[str, Any]:
        """Plain, JSON-able data, including the CLI keys (``tilt_deg``, per-contact maps)."""
        out: dict[str, Any] = {}
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name in ("design", "fluid"):
                value = value.model_dump()
            elif f.name == "contacts":
                value = {k: asdict(v) for k, v in value.items()}
            elif f.name in ("losses",):
                value = dict(value)
            elif f.name == "axle_reactions":
                value = list(value)
            out[f.name] = value
        out["tilt_deg"] = self.tilt_deg
        out["input_speed_rpm"] = self.input_speed_rpm
        names = list(self.contacts)
        for key in ("creep", "spin", "mu", "chi", "p_max", "film_thickness"):
            out[key] = {n: getattr(self.contacts[n], key) for n in names}
        return out

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> "OperatingResult":
        """Inverse of `to_dict`."""
        kw = {f.name: data[f.name] for f in fields(cls)}
        kw["design"] = Design(**kw["design"])
        kw["fluid"] = Fluid(**kw["fluid"])
        kw["contacts"] = MappingProxyType({k: ContactResult(**v) for k, v in kw["contacts"].items()})
        kw["losses"] = MappingProxyType(dict(kw["losses"]))
        kw["axle_reactions"] = tuple(kw["axle_reactions"])
        return cls(**kw)

    def to_json(self, **kwargs: Any) -> str:
        """JSON text of `to_dict` (non-finite numbers are written as ``null``)."""
        return json.dumps(_finite(self.to_dict()), **kwargs)

    def save(self, path: str | Path) -> None:
        """Write the result as JSON."""
        Path(path).write_text(self.to_json(indent=2))

    @classmethod
    def load(cls, path: str | Path) -> "OperatingResult":
        """Read a result written by `save`."""
        return cls.from_dict(json.loads(Path(path).read_text(), parse_constant=float))


def _finite(obj: Any) -> Any:
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else (str(obj) if math.isinf(obj) else None)
    if isinstance(obj, dict):
        return {k: _finite(v) for k, v in obj.items()}
    if isinstance(obj, list):
        return [_finite(v) for v in obj]
    return obj


def make_result(problem: EquilibriumProblem, solution: PointSolution,
                quadrature: Quadrature) -> OperatingResult:
    """Collect a solved single point into an `OperatingResult`."""
    st, lay = solution.state, problem.layout
    loss = power_losses(problem, st)
    eff = efficiency(problem, st, loss)
    f = lambda a: float(np.asarray(a))  # noqa: E731
    contacts = {
        name: ContactResult(
            creep=f(st.creep[i]), spin=f(st.spin[i]), mu=f(st.mu[i]), chi=f(st.chi[i]),
            normal_load=f(problem.load[i]), p_max=f(problem.p_max[i]),
            semi_axis_x=f(problem.ax[i]), semi_axis_y=f(problem.ay[i]),
            film_thickness=f(st.film[i]), tangential_force=f(st.force[i]),
            spin_moment=f(st.moment[i]), body_speed=f(st.omega[i]),
            creep_loss=f(loss.creep[i]), spin_loss=f(loss.spin[i]))
        for i, name in enumerate(lay.names)}
    losses = {"creep": f(np.sum(loss.creep)), "spin": f(np.sum(loss.spin)),
              "roller_bearings": f(loss.roller_bearings),
              "idler_bearings": f(np.sum(loss.idler_bearings)), "bearing": f(loss.bearing),
              "total": f(loss.total)}
    return OperatingResult(
        architecture=lay.architecture, design=problem.design, fluid=problem.fluid,
        ratio=f(problem.ratio), output_torque=f(problem.output_torque),
        clamp_force=f(problem.clamp_force), input_speed=f(problem.input_speed),
        tilt=f(problem.tilt), actual_ratio=f(st.omega[-1] / st.omega[0]),
        input_torque=f(st.input_torque), output_speed=f(st.omega[-1]),
        roller_speed=f(st.omega_s), contacts=MappingProxyType(contacts),
        axle_reactions=(f(st.axle_reactions[0]), f(st.axle_reactions[1])),
        losses=MappingProxyType(losses), eta=f(eff.overall), eta_loss=f(eff.from_losses),
        eta_speed=f(eff.speed), eta_torque=f(eff.torque), converged=solution.converged,
        residual_norm=solution.residual_norm, iterations=solution.evaluations,
        quadrature=_label(quadrature))


def _label(q: Quadrature) -> str:
    if q.method == "centred":
        return f"centred {q.n_radial}x{q.n_angular}"
    return f"pole {q.n_radial}x{q.n_angular} (centred part {q.n_radial}x{q.n_centred})"
