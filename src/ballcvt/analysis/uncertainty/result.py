"""`UncertaintyResult`: the samples of a propagation, its bands and its sensitivity ranking."""

from __future__ import annotations

import json
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..._display import html_summary, text_summary
from ...errors import InputError
from ...files import atomic_write_text, strict_json
from ...status import Status
from .sensitivity import spearman, srrc

__all__ = ["UncertaintyResult", "QUANTILES"]

#: Quantiles of a band.
QUANTILES = (0.05, 0.5, 0.95)
#: Arrays saved with a result, with their leading axis ``sample``.
_ARRAYS = ("values", "built", "reason", "eta", "status", "output_torque", "capacity")


@dataclass(frozen=True)
class UncertaintyResult:
    """Outcome of `ballcvt.analysis.uncertainty.run_uncertainty` (frozen; `save`, `load`).

    Attributes
    ----------
    inputs : dict
        What was propagated: ``drive``, ``parameters`` (path, nominal, distribution,
        source), ``method``, ``samples``, ``seed``, ``points`` (ratio, input speed [rpm],
        output torque [N m] or input power [W]), ``capacity_points``, ``clamp_law``.
    values : ndarray
        Drawn parameter values ``(n, d)``, columns in ``inputs["parameters"]`` order.
    built : ndarray
        Whether each drawn drive could be built ``(n,)``; ``reason`` says why not.
    reason : ndarray
        Why a sample was not built or not solved ("" otherwise) ``(n,)``.
    eta, status, output_torque : ndarray
        Efficiency [-], `ballcvt.status.Status` and output torque [N m] per sample and
        operating point ``(n, m)`` (NaN where not converged within the capacity).
    capacity : ndarray
        Limiting output torque [N m] per sample and capacity point ``(n, c)``.
    nominal : dict
        ``eta`` ``(m,)`` and ``capacity`` ``(c,)`` of the drive file's own values.
    version : str
        ballcvt version that computed it.
    run_time : float
        Seconds.
    execution : str
        Where the samples were evaluated.
    """

    inputs: dict
    values: np.ndarray
    built: np.ndarray
    reason: np.ndarray
    eta: np.ndarray
    status: np.ndarray
    output_torque: np.ndarray
    capacity: np.ndarray
    nominal: dict = field(default_factory=dict)
    version: str = ""
    run_time: float = 0.0
    execution: str = ""

    @property
    def paths(self) -> list[str]:
        """Dotted paths of the uncertain parameters."""
        return [p["path"] for p in self.inputs["parameters"]]

    def outputs(self) -> list[tuple[str, str, np.ndarray, float]]:
        """``(label, unit, samples (n,), nominal)`` of every output: the efficiency at each
        operating point, then the capacity at each capacity point."""
        rows = []
        for j, p in enumerate(self.inputs["points"]):
            load = (
                f"P {p['input_power']:g} W"
                if "input_power" in p
                else f"T2 {p['output_torque']:g} N m"
            )
            label = f"eta at ratio {p['ratio']:g}, {load}, {p['input_speed_rpm']:g} rpm"
            rows.append((label, "-", self.eta[:, j], self.nominal["eta"][j]))
        for j, p in enumerate(self.inputs["capacity_points"]):
            label = f"capacity at ratio {p['ratio']:g}, {p['input_speed_rpm']:g} rpm"
            rows.append((label, "N m", self.capacity[:, j], self.nominal["capacity"][j]))
        return rows

    def band(self):
        """Each output's band over the samples solved: nominal, mean, std, the 5/50/95 %
        quantiles, and how many samples were solved and not (a pandas DataFrame)."""
        import pandas as pd

        rows = []
        for label, unit, y, nom in self.outputs():
            ok = np.isfinite(y)
            q = np.quantile(y[ok], QUANTILES) if ok.any() else np.full(3, np.nan)
            rows.append(
                {
                    "output": label,
                    "unit": unit,
                    "nominal": nom,
                    "mean": float(np.mean(y[ok])) if ok.any() else np.nan,
                    "std": float(np.std(y[ok], ddof=1)) if ok.sum() > 1 else np.nan,
                    "q05": q[0],
                    "q50": q[1],
                    "q95": q[2],
                    "solved": int(ok.sum()),
                    "not_solved": int(self.built.sum() - ok.sum()),
                }
            )
        return pd.DataFrame(rows)

    def sensitivity(self, measure: str = "spearman"):
        """Rank correlation (``"spearman"``) or standardised rank regression coefficient
        (``"srrc"``) of every parameter (rows) with every output (columns), and for
        ``srrc`` a last row ``R^2`` (`ballcvt.analysis.uncertainty.sensitivity`)."""
        import pandas as pd

        if measure not in ("spearman", "srrc"):
            raise InputError("measure", measure, "spearman or srrc")
        cols, r2 = {}, {}
        x = self.values[self.built]
        for label, _, y, _ in self.outputs():
            if measure == "spearman":
                cols[label] = spearman(x, y[self.built])
            else:
                cols[label], r2[label] = srrc(x, y[self.built])
        frame = pd.DataFrame(cols, index=self.paths)
        if measure == "srrc":
            frame.loc["R^2"] = pd.Series(r2)
        return frame

    def ranking(self):
        """The parameters ranked by their mean absolute rank correlation with the
        efficiencies (``score_eta``), with the same for the capacities (``score_capacity``)
        and the signed correlation at each output: a pandas DataFrame, most influential
        first."""
        rho = self.sensitivity()
        m = len(self.inputs["points"])
        frame = rho.copy()
        frame.insert(0, "score_capacity", rho.iloc[:, m:].abs().mean(axis=1))
        frame.insert(0, "score_eta", rho.iloc[:, :m].abs().mean(axis=1))
        frame = frame.sort_values("score_eta", ascending=False, na_position="last")
        frame.insert(0, "rank", np.arange(1, len(frame) + 1))
        frame.index.name = "parameter"
        return frame

    def counts(self) -> dict:
        """Samples drawn, built and not (by reason, numbers left out), and per operating
        point how many were solved within the capacity, beyond it, and not solved."""
        reasons: dict[str, int] = {}
        for r in self.reason[~self.built]:
            key = re.sub(r"[-+]?\d[\d.]*(e[-+]?\d+)?", "#", str(r).split(": allowed")[0])[:90]
            reasons[key] = reasons.get(key, 0) + 1
        st = self.status[self.built]
        return {
            "samples": int(self.built.size),
            "built": int(self.built.sum()),
            "cannot_be_built": int((~self.built).sum()),
            "reasons": reasons,
            "solved": [int(v) for v in np.sum(st == Status.CONVERGED, axis=0)],
            "beyond_capacity": [int(v) for v in np.sum(st == Status.BEYOND_LIMIT, axis=0)],
            "not_solved": [int(v) for v in np.sum(st == Status.NOT_CONVERGED, axis=0)],
        }

    def summary(self) -> dict:
        """Inputs, counts, bands and ranking as plain data (what ``to_json`` writes
        besides the samples)."""
        rank = self.ranking()
        return {
            "inputs": self.inputs,
            "counts": self.counts(),
            "band": self.band().to_dict(orient="records"),
            "ranking": [
                {
                    "parameter": p,
                    "rank": int(r["rank"]),
                    "score_eta": r["score_eta"],
                    "score_capacity": r["score_capacity"],
                }
                for p, r in rank.iterrows()
            ],
            "run_time_s": self.run_time,
            "execution": self.execution,
            "ballcvt_version": self.version,
        }

    def to_csv(self, path=None) -> str:
        """The bands as CSV text (written to ``path`` too, atomically, when given)."""
        text = self.band().to_csv(index=False, float_format="%.6g")
        if path is not None:
            atomic_write_text(path, text)
        return text

    def to_json(self, samples: bool = True) -> str:
        """Strict JSON of `summary`, with every sample's arrays when ``samples``."""
        data: dict[str, Any] = self.summary()
        data["nominal"] = self.nominal
        if samples:
            data["samples"] = {k: getattr(self, k) for k in _ARRAYS}
        clean, _ = strict_json(data)
        return json.dumps(clean, indent=1, allow_nan=False) + "\n"

    def save(self, path) -> Path:
        """Write the whole result as JSON (atomically); `load` reads it back."""
        return atomic_write_text(path, self.to_json())

    @classmethod
    def load(cls, path) -> UncertaintyResult:
        """A result written by `save`."""
        data = json.loads(Path(path).read_text(encoding="utf-8"))
        s = data["samples"]

        def arr(key):  # null (a non-finite value) reads back as NaN
            return np.array(s[key], dtype=float)

        return cls(
            inputs=data["inputs"],
            values=arr("values"),
            built=np.array(s["built"], dtype=bool),
            reason=np.array(s["reason"], dtype="<U200"),
            eta=arr("eta"),
            status=np.array(s["status"], dtype=np.int8),
            output_torque=arr("output_torque"),
            capacity=arr("capacity"),
            nominal={k: np.array(v, dtype=float) for k, v in data["nominal"].items()},
            version=data["ballcvt_version"],
            run_time=data["run_time_s"],
            execution=data["execution"],
        )

    def _summary(self) -> tuple[str, list]:
        c = self.counts()
        band = self.band()
        rows: list = [
            (
                "samples",
                f"{c['samples']} ({self.inputs['method']}, seed {self.inputs['seed']})",
                "",
            ),
            ("cannot be built", c["cannot_be_built"], ""),
        ]
        for _, b in band.iterrows():
            rows.append(
                (
                    b["output"],
                    f"{b['q05']:.4g} / {b['q50']:.4g} / {b['q95']:.4g}",
                    f"{b['unit']} (5/50/95 %)",
                )
            )
        top = list(self.ranking().index[:3])
        rows.append(("most influential", ", ".join(top), ""))
        rows.append(("run time", self.run_time, "s"))
        return "UncertaintyResult", rows

    def __repr__(self) -> str:
        return text_summary(*self._summary())

    def _repr_html_(self) -> str:
        return html_summary(*self._summary())
