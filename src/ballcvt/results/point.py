"""Immutable results of one operating point, with their inputs, version and convergence.

`OperatingResult.to_dict` gives plain JSON-able data (the CLI's ``--json`` output);
`OperatingResult.save` / `OperatingResult.load` round-trip it through a JSON file.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import asdict, dataclass, fields
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np
from pydantic import TypeAdapter, ValidationError

from .._display import html_summary, text_summary
from .._version import __version__
from ..equilibrium.problem import EquilibriumProblem
from ..errors import InputError
from ..model.clamping import axial_force
from ..model.traction.quadrature import Quadrature
from ..params.models import Design, Fluid
from ..performance.efficiency import efficiency, loss_breakdown, power_losses
from ..performance.validity import validity, warning_messages
from ..solvers.point import PointSolution
from ..units import kelvin_to_celsius, rad_s_to_rpm
from .io import JsonFile, read_result
from .losses import LossBreakdown
from .moments import steady_moments

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
    lambda_ratio : float
        Film thickness ratio ``h_min / sigma`` (docs/model.md §10) [-].
    asperity_fraction : float
        Fraction of the normal load the asperities carry (0 under the full-film
        lubrication model, docs/model.md §16) [-].
    film_parameter : float
        ``h / sigma`` of the lubrication model (central film at the film's share) [-].
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
    lambda_ratio: float
    asperity_fraction: float = 0.0
    film_parameter: float = float("nan")


#: Units of the `ContactResult` fields (`OperatingResult.to_dataframe`).
CONTACT_UNITS = {
    "creep": "-", "spin": "-", "mu": "-", "chi": "-", "normal_load": "N", "p_max": "Pa",
    "semi_axis_x": "m", "semi_axis_y": "m", "film_thickness": "m", "tangential_force": "N",
    "spin_moment": "N m", "body_speed": "rad/s", "creep_loss": "W", "spin_loss": "W",
    "lambda_ratio": "-", "asperity_fraction": "-", "film_parameter": "-",
}  # fmt: skip


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
    losses : LossBreakdown
        Power loss by component [W]: ``creep``, ``spin``, ``roller_bearings``,
        ``idler_bearings``, ``churning``, ``seals``, ``disc_bearings``, ``hub_bearings``
        (zero without ``design.parasitic``, docs/model.md §12), each user loss term's kind, and
        ``total``, their sum (to round-off; `ballcvt.results.losses`). The subtotals are
        ``losses.bearing`` and ``losses.parasitic`` (``losses["bearing"]`` still answers,
        with a deprecation warning).
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
    warnings : tuple of str
        Validity warnings (docs/model.md §10), one line each; empty when the point lies
        within every assumption of the model.
    clamp_law : str
        The clamping law that set ``clamp_force`` (``constant``, ``cam``, ``optimal``;
        docs/model.md §11).
    oil_temperature : float or None
        Bulk oil temperature the fluid was evaluated at [K] (``fluid.inlet_temperature``;
        None for a fluid without one); ``to_dict`` adds ``oil_temperature_C`` [C].
    oil_model : str
        How it was set (docs/model.md §15): ``fixed`` (the fluid as given), ``given`` (a
        temperature asked for) or ``balance`` (the housing's steady heat balance).
    thermal_iterations : int
        Operating points solved to find the balance (0 unless ``balance``).
    holding_moment, skew_moment : float
        Per ball, at the steady point (zero tilt rate): the moment the shifter applies
        about the tilt axis (the direction of increasing tilt) and the contacts' moment
        about the skew axis (radial, outward; the carrier's about the direction of
        increasing skew) [N m] (docs/model.md §17; `ballcvt.results.moments`). NaN in a
        file written before them; ``to_dict`` adds ``skew_moment_Nm``, the CLI's key.
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
    warnings: tuple[str, ...] = ()
    clamp_law: str = "constant"
    oil_temperature: float | None = None
    oil_model: str = "fixed"
    thermal_iterations: int = 0
    holding_moment: float = float("nan")
    skew_moment: float = float("nan")
    version: str = __version__

    @property
    def tilt_deg(self) -> float:
        """Tilt [deg]."""
        return math.degrees(self.tilt)

    @property
    def input_speed_rpm(self) -> float:
        """Input speed [rpm] (rounded to 12 significant digits: no conversion noise)."""
        return float(f"{rad_s_to_rpm(self.input_speed):.12g}")

    @property
    def axial_force(self) -> float:
        """Axial thrust on each disc ``n F_N0 sin(theta_0)`` (docs/model.md §1) [N]."""
        return float(axial_force(self.design, self.clamp_force))

    @property
    def input_power(self) -> float:
        """``T_0 omega_0`` [W]."""
        return self.input_torque * self.input_speed

    @property
    def output_power(self) -> float:
        """``T_2 omega_2`` [W]."""
        return self.output_torque * self.output_speed

    def _summary(self) -> tuple[str, list]:
        c = self.contacts
        rows = [
            ("ideal ratio tau_ID", self.ratio, "-"),
            ("actual ratio", self.actual_ratio, "-"),
            ("tilt", self.tilt_deg, "deg"),
            ("input speed", self.input_speed_rpm, "rpm"),
            ("input torque T_0", self.input_torque, "N m"),
            ("output torque T_2", self.output_torque, "N m"),
            ("input power", self.input_power, "W"),
            ("efficiency (Eq. 38)", self.eta, "-"),
            ("losses", self.losses["total"], "W"),
            ("  creep / spin", f"{self.losses['creep']:.4g} / {self.losses['spin']:.4g}", "W"),
            ("  bearings", self.losses["roller_bearings"] + self.losses["idler_bearings"], "W"),
            ("max |creep|", max(abs(v.creep) for v in c.values()), "-"),
            ("max p_max", max(v.p_max for v in c.values()) / 1e9, "GPa"),
            ("min film", min(v.film_thickness for v in c.values()) * 1e6, "um"),
            ("clamp F_N0", self.clamp_force, f"N ({self.clamp_law} law)"),
            ("traction law", self.traction_law, ""),
            *self._oil_rows(),
            ("converged", f"{self.converged} (residual {self.residual_norm:.1e})", ""),
            ("warnings", len(self.warnings), ""),
        ]
        return f"OperatingResult: {self.architecture} idler, {self.design.name}", rows

    def _oil_rows(self) -> list:
        """The oil temperature's row, when it was not the fluid's own."""
        if self.oil_model == "fixed" or self.oil_temperature is None:
            return []
        return [
            ("oil temperature", kelvin_to_celsius(self.oil_temperature), f"C ({self.oil_model})")
        ]

    def __repr__(self) -> str:
        return text_summary(*self._summary())

    def _repr_html_(self) -> str:
        return html_summary(*self._summary())

    def to_dataframe(self):
        """Per-contact quantities as a `pandas.DataFrame` (one row per contact, units in
        ``df.attrs["units"]``; the point's figures in ``df.attrs["point"]``)."""
        import pandas as pd

        frame = pd.DataFrame({k: asdict(v) for k, v in self.contacts.items()}).T
        frame.index.name = "contact"
        frame.attrs["units"] = dict(CONTACT_UNITS)
        frame.attrs["point"] = {
            k: v for k, v in self.to_dict().items() if isinstance(v, (int, float, str))
        }
        return frame

    @property
    def traction_law(self) -> str:
        """Shear law of the film the point was solved with (``fluid.traction_law``)."""
        return self.fluid.traction_law

    def to_dict(self) -> dict[str, Any]:
        """Plain, JSON-able data, including the CLI keys (``tilt_deg``, per-contact maps,
        ``loss_subtotals``: ``bearing`` and ``parasitic`` [W], which ``losses`` no longer
        holds among its components)."""
        out: dict[str, Any] = {}
        for f in fields(self):
            value = getattr(self, f.name)
            if f.name in ("design", "fluid"):
                value = value.model_dump()
            elif f.name == "contacts":
                value = {k: asdict(v) for k, v in value.items()}
            elif f.name in ("losses",):
                value = dict(value)
            elif f.name in ("axle_reactions", "warnings"):
                value = list(value)
            out[f.name] = value
        out["tilt_deg"] = self.tilt_deg
        out["traction_law"] = self.traction_law
        out["input_speed_rpm"] = self.input_speed_rpm
        out["axial_force"] = self.axial_force
        t_oil = self.oil_temperature
        out["oil_temperature_C"] = None if t_oil is None else kelvin_to_celsius(t_oil)
        ls = LossBreakdown(self.losses)  # subtotals beside the components, not among them
        out["loss_subtotals"] = {"bearing": ls.bearing, "parasitic": ls.parasitic}
        out["skew_moment_Nm"] = self.skew_moment
        names = list(self.contacts)
        for key in ("creep", "spin", "mu", "chi", "p_max", "film_thickness"):
            out[key] = {n: getattr(self.contacts[n], key) for n in names}
        return out

    @classmethod
    def from_dict(cls, data: Mapping[str, Any], source: str = "result") -> OperatingResult:
        """Inverse of `to_dict`, validated.

        Every field is checked for its type (pydantic), the design and fluid are validated
        as parameter sets, and the figures must be consistent with one another
        (Eq. 38 ``eta = eta_speed eta_torque``, Eq. 37, Eq. 39 and the loss total), so an
        edited or corrupted file is refused rather than loaded.

        Raises
        ------
        InputError
            Naming the first missing, wrong-typed or inconsistent field.
        """
        if not isinstance(data, Mapping):
            raise InputError(
                source,
                type(data).__name__,
                "a JSON object",
                message=f"{source}: not a result (a JSON object is expected)",
            )
        # files written before the clamping laws (0.1.0) have no clamp_law (constant), and
        # before the oil's temperature no oil_* keys: the defaults
        # and before the moments (docs/model.md §17) no holding_moment, skew_moment: NaN
        optional: tuple[str, ...] = ("clamp_law", "oil_temperature", "oil_model")
        optional += ("thermal_iterations", "holding_moment", "skew_moment")
        missing = [f.name for f in fields(cls) if f.name not in data and f.name not in optional]
        if missing:
            raise InputError(
                missing[0],
                None,
                "a value",
                message=f"{source}: required key '{missing[0]}' is missing",
            )
        kw = {f.name: data[f.name] for f in fields(cls) if f.name in data}
        try:
            kw["design"] = Design(**kw["design"])
            kw["fluid"] = Fluid(**kw["fluid"])
        except (InputError, TypeError) as exc:
            raise InputError(
                "design", None, "a valid design", message=f"{source}: {exc}"
            ) from None
        try:
            result = _ADAPTER.validate_python(kw)
        except ValidationError as exc:
            err = exc.errors()[0]
            name = ".".join(str(p) for p in err["loc"])
            raise InputError(
                name,
                err.get("input"),
                err["msg"],
                message=f"{source}: {name} = {err.get('input')!r}: {err['msg']}",
            ) from None
        object.__setattr__(result, "contacts", MappingProxyType(dict(result.contacts)))
        object.__setattr__(result, "losses", LossBreakdown(result.losses))
        _check_consistent(result, source)
        return result

    to_json = JsonFile.to_json
    save = JsonFile.save

    @classmethod
    def load(cls, path: str | Path) -> OperatingResult:
        """Read and validate a result written by `save` (see `from_dict`)."""
        return cls.from_dict(*read_result(path))


_ADAPTER = TypeAdapter(OperatingResult)


def _check_consistent(r: OperatingResult, source: str) -> None:
    """Refuse figures that contradict each other (an edited or corrupted file)."""

    def close(a, b, tol):
        return (math.isnan(a) and math.isnan(b)) or abs(a - b) <= tol * max(1.0, abs(b))

    ls = r.losses
    checks = [
        ("eta", r.eta, r.eta_speed * r.eta_torque, 1e-12, "eta_speed * eta_torque (Eq. 38)"),
        (
            "eta_torque",
            r.eta_torque,
            r.ratio * r.output_torque / r.input_torque if r.input_torque else r.eta_torque,
            1e-12,
            "ratio * output_torque / input_torque (Eq. 37)",
        ),
        (
            "eta_loss",
            r.eta_loss,
            1.0 - ls.get("total", math.nan) / r.input_power if r.input_power else r.eta_loss,
            1e-12,
            "1 - losses.total / input power (Eq. 39)",
        ),
        (
            "losses.total",
            ls.get("total", math.nan),
            math.fsum(v for k, v in ls.items() if k != "total"),
            1e-9,
            "the sum of the loss components",
        ),
        ("eta_loss", r.eta_loss, r.eta, 1e-6, "eta (Eq. 38 = Eq. 39)"),
    ]
    for name, value, expected, tol, what in checks:
        if not close(float(value), float(expected), tol):
            raise InputError(
                name,
                value,
                f"{expected:.12g} = {what}",
                message=f"{source}: {name} = {value!r} is inconsistent with "
                f"{what} = {expected:.12g}: the file was edited or is "
                "corrupt",
            )


def make_result(
    problem: EquilibriumProblem,
    solution: PointSolution,
    quadrature: Quadrature,
    clamp_law: str = "constant",
) -> OperatingResult:
    """Collect a solved single point into an `OperatingResult`."""
    st, lay = solution.state, problem.layout
    loss = power_losses(problem, st)
    eff = efficiency(problem, st, loss)
    valid = validity(problem, st)
    f = lambda a: float(np.asarray(a))  # noqa: E731
    per = {  # per-contact values as Python floats (one tolist each, not 60 conversions)
        key: np.asarray(value, dtype=float).tolist()
        for key, value in (
            ("creep", st.creep),
            ("spin", st.spin),
            ("mu", st.mu),
            ("chi", st.chi),
            ("normal_load", problem.load),
            ("p_max", problem.p_max),
            ("semi_axis_x", problem.ax),
            ("semi_axis_y", problem.ay),
            ("film_thickness", st.film),
            ("tangential_force", st.force),
            ("spin_moment", st.moment),
            ("body_speed", st.omega),
            ("creep_loss", loss.creep),
            ("spin_loss", loss.spin),
            ("lambda_ratio", valid.lambda_ratio),
            ("asperity_fraction", valid.asperity_fraction),
            ("film_parameter", valid.film_parameter),
        )
    }
    contacts = {
        name: ContactResult(**{key: values[i] for key, values in per.items()})
        for i, name in enumerate(lay.names)
    }
    losses = {kind: f(value) for kind, value in loss_breakdown(loss).items()}
    holding, skew = steady_moments(problem, st, quadrature)
    return OperatingResult(
        architecture=lay.architecture,
        design=problem.design,
        fluid=problem.fluid,
        ratio=f(problem.ratio),
        output_torque=f(problem.output_torque),
        clamp_force=f(problem.clamp_force),
        input_speed=f(problem.input_speed),
        tilt=f(problem.tilt),
        actual_ratio=f(st.omega[-1] / st.omega[0]),
        input_torque=f(st.input_torque),
        output_speed=f(st.omega[-1]),
        roller_speed=f(st.omega_s),
        contacts=MappingProxyType(contacts),
        axle_reactions=(f(st.axle_reactions[0]), f(st.axle_reactions[1])),
        losses=LossBreakdown(losses),
        eta=f(eff.overall),
        eta_loss=f(eff.from_losses),
        eta_speed=f(eff.speed),
        eta_torque=f(eff.torque),
        converged=solution.converged,
        residual_norm=solution.residual_norm,
        iterations=solution.evaluations,
        quadrature=_label(quadrature),
        warnings=tuple(warning_messages(problem, valid, lay.names)),
        clamp_law=clamp_law,
        oil_temperature=problem.fluid.inlet_temperature,
        holding_moment=f(holding),
        skew_moment=f(skew),
    )


def _label(q: Quadrature) -> str:
    if q.method == "centred":
        return f"centred {q.n_radial}x{q.n_angular}"
    return f"pole {q.n_radial}x{q.n_angular} (centred part {q.n_radial}x{q.n_centred})"
