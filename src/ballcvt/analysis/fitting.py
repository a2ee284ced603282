"""Fit a fluid's traction parameters to measured traction curves (docs/model.md §14).

Measured curves come as one CSV file (`read_curves`), one row per measured point, each
column's unit in brackets in its header (``load [kN]``: converted to SI on reading; an
unknown unit is refused; a header without brackets is in the unit below):

=============  =====  =======================================================
column         unit   meaning
=============  =====  =======================================================
``condition``  --     label of the curve the point belongs to (any text)
``rx``         m      equivalent radius along the rolling direction ``R_x``
``ry``         m      equivalent radius across it ``R_y``
``load``       N      normal load
``speed``      m/s    rolling (entrainment) speed ``U``
``spin``       --     spin-to-roll ratio ``omega_spin R_x / U``
``creep``      --     slide-to-roll ratio ``Delta U / U``
``mu``         --     measured traction coefficient
=============  =====  =======================================================

The model of each point is `ballcvt.model.traction.curve` (Hertz, film, the fluid's law). The
chosen parameters are found by nonlinear least squares on their logarithms
(`scipy.optimize.least_squares`, trust-region reflective, within the fields' bounds).
Standard errors and correlations come from the Jacobian at the optimum,
``cov = s^2 (J^T J)^-1`` with ``s^2 = SSR / (m - p)`` (the Gauss-Newton linearisation,
e.g. Bates and Watts 1988, §2.3); a parameter whose relative standard error exceeds 50 %
or whose correlation with another exceeds 0.995 in magnitude is reported as not
identifiable from the data given.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..model.traction.contact import contact_coefficients
from ..model.traction.curve import MachineContact, machine_state
from ..model.traction.quadrature import Quadrature
from ..params.models import Fluid
from ..registry import TRACTION_LAWS
from ..units import parse_header, unit_factor

__all__ = [
    "COLUMNS",
    "DEFAULT_PARAMETERS",
    "FITTABLE",
    "Curves",
    "FluidFit",
    "read_curves",
    "fit_fluid",
    "model_mu",
]

#: Columns of a curves file, in order, and their units.
COLUMNS = {
    "condition": "-",
    "rx": "m",
    "ry": "m",
    "load": "N",
    "speed": "m/s",
    "spin": "-",
    "creep": "-",
    "mu": "-",
}
#: Fluid fields a fit may adjust.
FITTABLE = (
    "viscosity",
    "roelands_index",
    "limiting_shear_stress",
    "limiting_shear_slope",
    "temperature_viscosity_coefficient",
    "limiting_shear_temperature_coefficient",
    "thermal_conductivity",
    "shear_modulus",
)


class _DefaultParameters(Mapping):
    """Law name -> the fields fitted by default under it (its registry entry's
    ``fit_parameters``; a law registered later is in it)."""

    def __getitem__(self, name: str) -> tuple[str, ...]:
        return tuple(TRACTION_LAWS.get(name).fit_parameters)

    def __iter__(self):
        return iter(TRACTION_LAWS)

    def __len__(self) -> int:
        return len(TRACTION_LAWS)


#: Parameters fitted by default under each law (`TractionLaw.fit_parameters`).
DEFAULT_PARAMETERS: Mapping[str, tuple[str, ...]] = _DefaultParameters()
#: Identifiability thresholds: relative standard error and |correlation|.
MAX_RELATIVE_ERROR = 0.5
MAX_CORRELATION = 0.995


@dataclass(frozen=True)
class Curves:
    """Measured traction points (arrays of one length ``m``, SI units, see module)."""

    condition: np.ndarray
    rx: np.ndarray
    ry: np.ndarray
    load: np.ndarray
    speed: np.ndarray
    spin: np.ndarray
    creep: np.ndarray
    mu: np.ndarray

    @property
    def size(self) -> int:
        return int(self.mu.size)


def read_curves(path) -> Curves:
    """Read and check a curves CSV file (columns in `COLUMNS`, a header row).

    Raises
    ------
    InputError
        One line naming the file, the row or column and what is wrong.
    """
    import pandas as pd

    try:
        frame = pd.read_csv(path, skipinitialspace=True, comment="#")
    except FileNotFoundError:
        raise InputError(
            "curves file",
            str(path),
            "an existing CSV file",
            message=f"curves file {path}: not found",
        ) from None
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        raise InputError(
            "curves file",
            str(path),
            "CSV",
            message=f"curves file {path}: not a CSV table ({str(exc).splitlines()[0]})",
        ) from None
    frame, factors = _to_si(frame, f"curves file {path}")
    missing = [c for c in COLUMNS if c not in frame.columns]
    if missing:
        raise InputError(
            missing[0],
            None,
            "a column",
            message=(
                f"curves file {path}: column '{missing[0]}' is missing (columns: "
                + ", ".join(f"{c} [{u}]" for c, u in COLUMNS.items())
                + ")"
            ),
        )
    if len(frame) == 0:
        raise InputError(
            "curves file",
            str(path),
            "at least one row",
            message=f"curves file {path}: no data rows",
        )
    data = {"condition": frame["condition"].astype(str).to_numpy()}
    for name in list(COLUMNS)[1:]:
        values = pd.to_numeric(frame[name], errors="coerce").to_numpy(dtype=float)
        bad = np.flatnonzero(~np.isfinite(values))
        if bad.size:
            raise InputError(
                name,
                frame[name].iloc[bad[0]],
                "a finite number",
                message=(
                    f"curves file {path}, row {bad[0] + 2}: {name} = {frame[name].iloc[bad[0]]!r} "
                    "is not a finite number"
                ),
            )
        data[name] = values * factors[name]
    for name in ("rx", "ry", "load", "speed"):
        bad = np.flatnonzero(data[name] <= 0)
        if bad.size:
            raise InputError(
                name,
                data[name][bad[0]],
                "> 0",
                message=(
                    f"curves file {path}, row {bad[0] + 2}: {name} = {data[name][bad[0]]:g} "
                    f"[{COLUMNS[name]}] is out of range: allowed > 0"
                ),
            )
    bad = np.flatnonzero(np.abs(data["creep"]) >= 2)
    if bad.size:
        raise InputError(
            "creep",
            data["creep"][bad[0]],
            "|creep| < 2",
            message=(
                f"curves file {path}, row {bad[0] + 2}: creep = {data['creep'][bad[0]]:g} is out "
                "of range: allowed |creep| < 2"
            ),
        )
    return Curves(**data)


#: The quantity of each curves column (its accepted units: `ballcvt.units.QUANTITY_UNITS`).
QUANTITIES = {
    "rx": "length",
    "ry": "length",
    "load": "force",
    "speed": "speed",
    "spin": "dimensionless",
    "creep": "dimensionless",
    "mu": "dimensionless",
}


def _to_si(frame, source: str) -> tuple:
    """``(frame, factors)``: the curves table with plain column names, and the factor that
    converts each numeric column to SI: a header's unit in brackets is read (``load [kN]``),
    a header without one is in the unit of `COLUMNS`, an unknown unit is an `InputError`."""
    names, factors = [], {}
    for header in frame.columns:
        name, unit = parse_header(header)
        names.append(name)
        if name in QUANTITIES:
            factors[name] = (
                1.0 if unit is None else unit_factor(unit, QUANTITIES[name], str(header), source)
            )
    return frame.set_axis(names, axis=1), factors


def model_mu(
    fluid: Fluid, curves: Curves, reduced_modulus: float, quadrature: Quadrature = Quadrature()
) -> np.ndarray:
    """Modelled traction coefficient at every point of ``curves`` [-] (one batched call)."""
    machine = MachineContact(
        curves.rx, curves.ry, curves.speed, curves.load, None, curves.spin, reduced_modulus
    )
    mu, _ = contact_coefficients(machine_state(fluid, machine, curves.creep), fluid, quadrature)
    return np.asarray(mu)


@dataclass(frozen=True)
class FluidFit:
    """Result of `fit_fluid`.

    Attributes
    ----------
    fluid : Fluid
        The fitted fluid (the start fluid with the fitted values).
    parameters : tuple of str
        Fitted fields.
    estimates, standard_errors : dict
        Value and standard error of each fitted field [its unit].
    correlation : ndarray
        Correlation matrix of the estimates, ``(p, p)``.
    rms : float
        Root-mean-square residual of ``mu`` [-].
    model, residuals : ndarray
        Modelled ``mu`` and ``model - measured`` at every point [-].
    warnings : tuple of str
        Parameters not identifiable from the data, and why.
    converged : bool
        Whether the least-squares solver met its tolerance.
    """

    fluid: Fluid
    parameters: tuple
    estimates: dict
    standard_errors: dict
    correlation: np.ndarray
    rms: float
    model: np.ndarray
    residuals: np.ndarray
    warnings: tuple = field(default_factory=tuple)
    converged: bool = True

    def to_toml(self, source: str = "curves") -> str:
        """TOML text of the fitted fluid (``[fluid]``), with the estimates, their standard
        errors and the warnings as comments; any command loads it with ``--fluid``.

        Parameters
        ----------
        source : str
            The measured curves' file (as given), named in the header and the fluid's name.
        """
        from .._version import __version__
        from ..params.io import fluid_to_toml

        start = self.fluid.name
        header = (
            f"ballcvt {__version__} fit-fluid: {self.fluid.traction_law} law fitted to "
            f"{source} ({self.model.size} points, rms residual {self.rms:.3e})\n"
            + "\n".join(
                f"{n} = {self.estimates[n]:.6g} +/- {self.standard_errors[n]:.3g} "
                f"[{Fluid.unit(n)}] (one standard error)"
                for n in self.parameters
            )
            + "".join(f"\nWARNING: {w}" for w in self.warnings)
            + f"\nthe other values are those of the start fluid '{start}'"
        )
        named = Fluid(
            **{**self.fluid.model_dump(), "name": f"{start} (fitted to {Path(source).name})"}
        )
        return fluid_to_toml(named, header)

    def save(self, out, curves: Curves, source: str = "curves") -> list[Path]:
        """Write ``fluid.toml`` (`to_toml`), ``fit.json`` (`as_dict`) and ``fit.csv`` (each
        point's creep, measured and modelled ``mu`` and residual [-]) in the folder ``out``.

        Parameters
        ----------
        out : path
            An existing folder.
        curves : Curves
            The measured points the fit was made to.
        source : str
            The curves' file, for `to_toml`.

        Returns
        -------
        list of Path
            The files written.
        """
        import pandas as pd

        from ..files import atomic_write_text, write_json

        out = Path(out)
        frame = pd.DataFrame(
            {
                "condition": curves.condition,
                "creep": curves.creep,
                "mu": curves.mu,
                "mu_model": self.model,
                "residual": self.residuals,
            }
        )
        files = [out / "fluid.toml", out / "fit.json", out / "fit.csv"]
        atomic_write_text(files[0], self.to_toml(source))
        write_json(files[1], self.as_dict())
        atomic_write_text(files[2], frame.to_csv(index=False))
        return files

    def as_dict(self) -> dict:
        """JSON-ready summary (no arrays of points)."""
        return {
            "fluid": self.fluid.name,
            "traction_law": self.fluid.traction_law,
            "parameters": list(self.parameters),
            "estimates": self.estimates,
            "standard_errors": self.standard_errors,
            "units": {p: Fluid.unit(p) for p in self.parameters},
            "correlation": np.round(self.correlation, 6).tolist(),
            "rms": self.rms,
            "points": int(self.model.size),
            "converged": self.converged,
            "warnings": list(self.warnings),
        }


def _bounds(name: str) -> tuple[float, float]:
    """Log bounds of a field from its validation constraints."""
    lo, hi = 1e-300, math.inf
    for meta in Fluid.model_fields[name].metadata:
        for attr in ("gt", "ge"):
            if getattr(meta, attr, None) is not None:
                lo = max(lo, float(getattr(meta, attr)))
        for attr in ("lt", "le"):
            if getattr(meta, attr, None) is not None:
                hi = min(hi, float(getattr(meta, attr)))
    return math.log(max(lo, 1e-300)), (math.log(hi) - 1e-9 if math.isfinite(hi) else math.inf)


def fit_fluid(
    curves: Curves,
    fluid: Fluid,
    parameters=None,
    *,
    reduced_modulus: float,
    quadrature: Quadrature = Quadrature(),
) -> FluidFit:
    """Least-squares fit of ``fluid``'s parameters to measured traction curves.

    Parameters
    ----------
    curves : Curves
        Measured points (`read_curves`).
    fluid : Fluid
        Start values, the law (``fluid.traction_law``) and the fields not fitted.
    parameters : sequence of str, optional
        Fields to fit (`FITTABLE`); default `DEFAULT_PARAMETERS` of the law.
    reduced_modulus : float
        ``E'`` of the test pair [Pa].
    quadrature : Quadrature
        Rule for the traction integrals.

    Returns
    -------
    FluidFit
    """
    from scipy.optimize import least_squares

    names = tuple(parameters or DEFAULT_PARAMETERS[fluid.traction_law])
    for name in names:
        if name not in FITTABLE:
            raise InputError("parameters", name, "one of " + ", ".join(FITTABLE))
        if getattr(fluid, name) is None or getattr(fluid, name) <= 0:
            raise InputError(
                name,
                getattr(fluid, name),
                "a start value > 0",
                message=(f"{name} needs a start value > 0 in the fluid to be fitted"),
            )
    if curves.size <= len(names):
        raise InputError("curves", curves.size, f"more points than parameters ({len(names)})")
    base = fluid.model_dump()
    lo, hi = np.array([_bounds(n) for n in names]).T
    x0 = np.clip(np.log([getattr(fluid, n) for n in names]), lo + 1e-12, hi - 1e-12)

    def make(x) -> Fluid:
        return Fluid(**{**base, **{n: float(math.exp(v)) for n, v in zip(names, x)}})

    def residual(x):
        return model_mu(make(x), curves, reduced_modulus, quadrature) - curves.mu

    sol = least_squares(
        residual,
        x0,
        bounds=(lo, hi),
        x_scale="jac",
        diff_step=1e-6,
        xtol=1e-10,
        ftol=1e-12,
        gtol=1e-12,
    )
    fitted = make(sol.x)
    res = sol.fun
    m, p = res.size, len(names)
    s2 = float(res @ res) / max(m - p, 1)
    jtj = sol.jac.T @ sol.jac
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cov_log = s2 * np.linalg.pinv(jtj, rcond=1e-13)
    se_log = np.sqrt(np.maximum(np.diag(cov_log), 0.0))
    values = np.exp(sol.x)
    scale = np.where(se_log > 0, se_log, 1.0)
    corr = cov_log / np.outer(scale, scale)
    notes = []
    rank = np.linalg.matrix_rank(jtj, tol=1e-12 * np.max(np.abs(jtj)) if jtj.size else 0)
    for i, name in enumerate(names):
        rel = float(np.expm1(se_log[i])) if se_log[i] < 50 else math.inf
        others = [(abs(corr[i, j]), names[j]) for j in range(p) if j != i]
        worst = max(others) if others else (0.0, "")
        if rank < p and se_log[i] == 0:
            notes.append(
                f"{name} is not identifiable from these data: the curves do not depend on it"
            )
        elif rel > MAX_RELATIVE_ERROR:
            notes.append(
                f"{name} is not identifiable from these data: relative standard error {rel:.0%}"
            )
        elif worst[0] > MAX_CORRELATION:
            notes.append(
                f"{name} is not identifiable from these data: correlation "
                f"{worst[0]:.3f} with {worst[1]}"
            )
    return FluidFit(
        fluid=fitted,
        parameters=names,
        estimates={n: float(v) for n, v in zip(names, values)},
        standard_errors={n: float(v * s) for n, v, s in zip(names, values, se_log)},
        correlation=corr,
        rms=float(np.sqrt(np.mean(res**2))),
        model=res + curves.mu,
        residuals=res,
        warnings=tuple(notes),
        converged=bool(sol.success),
    )
