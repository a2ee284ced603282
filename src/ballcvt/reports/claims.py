"""Every numeric claim of the paper (docs/model.md §9) against the reproduced model.

Each `Claim` carries the paper's value, ours, the difference and a verdict from a stated
tolerance: "agrees" or "differs". Qualitative claims are checked by a stated criterion.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["Claim", "paper_claims", "CLAIMS", "Number", "Check", "Tolerance", "Runs"]


@dataclass(frozen=True)
class Claim:
    """One row of the report table."""

    figure: str
    claim: str
    paper: str
    ours: str
    difference: str
    verdict: str
    criterion: str


@dataclass(frozen=True)
class Tolerance:
    """How a number is compared with the paper's and written.

    ``tol`` is absolute (in the claim's unit) or, with ``rel``, relative to the paper's
    value; ``fmt`` formats the values, ``unit`` follows them.
    """

    tol: float
    unit: str = ""
    fmt: str = "{:.3g}"
    rel: bool = False


@dataclass(frozen=True)
class Number:
    """A numeric claim: the paper's value and how ours is computed from the runs."""

    figure: str
    claim: str
    paper: float
    tolerance: Tolerance
    ours: Callable[[Any], float]

    def evaluate(self, runs) -> Claim:
        """The claim's row, with the difference and the verdict."""
        t, paper, ours = self.tolerance, self.paper, self.ours(runs)
        diff = ours - paper
        ok = abs(diff) <= (t.tol * abs(paper) if t.rel else t.tol)
        crit = f"|diff| <= {t.tol * 100:g} %" if t.rel else f"|diff| <= {t.tol:g}{t.unit}"
        d = f"{diff / paper * 100:+.1f} %" if t.rel else (t.fmt.format(diff) + t.unit)
        return Claim(
            self.figure,
            self.claim,
            t.fmt.format(paper) + t.unit,
            t.fmt.format(ours) + t.unit,
            d,
            "agrees" if ok else "differs",
            crit,
        )


@dataclass(frozen=True)
class Check:
    """A qualitative claim: ``ours`` returns whether the criterion holds and what we see,
    and, where the criterion is a number (a distance within a bound), the number to set
    against it as a third item: the difference column shows it, holding or not."""

    figure: str
    claim: str
    paper: str
    criterion: str
    ours: Callable[[Any], tuple]  # (holds, what we see[, the number against the bound])

    def evaluate(self, runs) -> Claim:
        """The claim's row, with the verdict."""
        holds, ours, *number = self.ours(runs)
        return Claim(
            self.figure,
            self.claim,
            self.paper,
            ours,
            number[0] if number else ("-" if holds else "opposite"),
            "agrees" if holds else "differs",
            self.criterion,
        )


def _sign_change(x, y):
    """First ``x`` where ``y`` changes sign (linear interpolation), or NaN."""
    s = np.sign(y)
    idx = np.flatnonzero(s[:-1] * s[1:] < 0)
    if idx.size == 0:
        return float("nan")
    i = idx[0]
    return float(x[i] - y[i] * (x[i + 1] - x[i]) / (y[i + 1] - y[i]))


def _sq(a):
    return a.squeeze(drop=True)


@dataclass(frozen=True)
class Runs:
    """The reproduction's sweeps as the claims read them.

    Attributes
    ----------
    data : FigureData
        The sweeps.
    peak : tuple of float
        ``(ratio, eta)`` of the refined efficiency maximum at T_2 = 40 N m.
    """

    data: Any
    peak: tuple

    @property
    def rc(self):
        """Both architectures over the ratio at 20 / 40 / 60 N m."""
        return self.data.ratio_curves

    @property
    def tc(self):
        """Double idler over the torque at ratios 0.5 / 1 / 2."""
        return _sq(self.data.torque_curves.sel(architecture="double"))

    @property
    def cc(self):
        """Double idler over the torque at five clamping forces."""
        return _sq(self.data.clamp_curves.sel(architecture="double"))

    @property
    def lim(self) -> dict:
        """Limiting torque [N m] per ratio of the torque curves."""
        tc = self.tc
        return {float(r): float(tc.limit_torque.sel(ratio=r)) for r in tc.ratio.values}

    def at40(self, arch: str):
        """``arch`` over the ratio at T_2 = 40 N m."""
        return _sq(self.rc.sel(architecture=arch, output_torque=40.0))


def _p_max(arch: str, contact: str) -> Callable[[Runs], float]:
    def get(r: Runs) -> float:
        return float(_sq(r.rc.p_max.sel(architecture=arch, contact=contact)).max()) / 1e9

    return get


def _limit(ratio: float) -> Callable[[Runs], float]:
    def get(r: Runs) -> float:
        return r.lim[ratio]

    return get


def _flat(r: Runs) -> tuple[bool, str]:
    spreads = []
    tc, lim = r.tc, r.lim
    for ratio in tc.ratio.values:
        c = tc.sel(ratio=ratio)
        band = (c.output_torque >= 0.5 * lim[float(ratio)]) & (
            c.output_torque <= 0.9 * lim[float(ratio)]
        )
        e = c.eta.where(band)
        spreads.append(float(e.max() - e.min()))
    return max(spreads) <= 0.03, f"spread <= {max(spreads):.3f}"


def _falls(r: Runs) -> tuple[bool, str]:
    first = r.tc.eta.isel(output_torque=slice(0, 3))
    falls = bool(
        (first.isel(output_torque=0) == 0).all() and (first.diff("output_torque") > 0).all()
    )
    return falls, (
        "eta = "
        + " / ".join(f"{float(e):.2f}" for e in first.isel(ratio=1))
        + " at T_2 = "
        + " / ".join(f"{float(t):g}" for t in first.output_torque)
        + " N m (tau_ID = 1)"
    )


def _limit_rises(r: Runs) -> tuple[bool, str]:
    lims = r.cc.limit_torque.values
    return bool(np.all(np.diff(lims) > 0)), " / ".join(f"{v:.0f}" for v in lims) + " N m"


def _clamp_step(r: Runs, var: str):
    """Change of ``var`` from one clamping force to the next where all converge, T_2 > 0."""
    cc = r.cc
    both = (cc.status.max("clamp_force") == 0) & (cc.output_torque > 0)
    return cc[var].where(both).diff("clamp_force")


def _speed_rises(r: Runs) -> tuple[bool, str]:
    d = _clamp_step(r, "eta_speed")
    worst = d.where(d == d.min(), drop=True)
    return bool((d.fillna(1) > 0).all()), (
        f"min step {float(d.min()):+.2e} (at T_2 = {float(worst.output_torque[0]):g} N m)"
    )


def _torque_falls(r: Runs) -> tuple[bool, str]:
    d = _clamp_step(r, "eta_torque")
    return bool((d.fillna(-1) < 0).all()), f"max step {float(d.max()):+.2e}"


def _envelope(r: Runs) -> tuple[bool, str]:
    env = r.data.envelope
    band = env[env.output_torque >= 10.0]
    return bool((band.eta > 0.92).all()), f"min {band.eta.min():.3f} for T_2 >= 10 N m"


def _sign_changes(r: Runs) -> tuple[bool, str, str]:
    d40 = r.at40("double")
    x = d40.ratio.values
    r_creep = _sign_change(x, _sq(d40.creep.sel(contact="idler_a")).values)
    r_spin = _sign_change(x, _sq(d40.spin.sel(contact="idler_a")).values)
    gap = abs(r_creep - r_spin)
    return gap <= 0.1, f"creep at {r_creep:.3f}, spin at {r_spin:.3f}", f"{gap:.3f} in tau_ID"


def _eq38_39(r: Runs) -> tuple[bool, str]:
    d40 = r.at40("double")
    gap = float(np.nanmax(np.abs(d40.eta - d40.eta_loss)))
    return gap <= 1e-6, f"max |diff| {gap:.1e}"


def _creep_orders(r: Runs) -> float:
    c_s = np.abs(_sq(r.at40("single").creep.sel(contact="idler")).values)
    c_d = np.abs(_sq(r.at40("double").creep.sel(contact=["idler_a", "idler_b"])).values)
    return float(np.log10(np.nanmax(c_d.max(axis=-1)) / np.nanmax(c_s)))


def _single_better(r: Runs) -> tuple[bool, str]:
    rc = r.rc
    better = all(
        bool(
            (
                _sq(rc.eta.sel(architecture="single", output_torque=t))
                > _sq(rc.eta.sel(architecture="double", output_torque=t))
            ).all()
        )
        for t in rc.output_torque.values
    )
    return better, "yes" if better else "no"


def _eta1(r: Runs, arch: str) -> float:
    return float(r.at40(arch).eta.sel(ratio=1.0))


GPA = Tolerance(0.02, " GPa", rel=True)
ETA = Tolerance(0.01, fmt="{:.3f}")
#: The paper's claims (docs/model.md §9), in the report's order.
CLAIMS: tuple[Number | Check, ...] = (
    Number(
        "Sec. III",
        "p_max roller-idler, double idler, 2 kN",
        1.63,
        GPA,
        _p_max("double", "idler_a"),
    ),
    Number(
        "Sec. III", "p_max roller-idler, single idler, 2 kN", 2.61, GPA, _p_max("single", "idler")
    ),
    *(
        Number(
            "Fig. 7",
            f"limiting T_2 at tau_ID = {ratio:g} (|C| <= 0.1)",
            paper,
            Tolerance(0.10, " N m", "{:.1f}", rel=True),
            _limit(ratio),
        )
        for ratio, paper in ((0.5, 120.0), (1.0, 120.0), (2.0, 60.0))
    ),
    Number(
        "Fig. 7",
        "T_lim(1) / T_lim(2)",
        2.0,
        Tolerance(0.10, fmt="{:.2f}", rel=True),
        lambda r: r.lim[1.0] / r.lim[2.0],
    ),
    Number("Fig. 7", "peak overall efficiency", 0.90, ETA, lambda r: float(r.tc.eta.max())),
    Check(
        "Fig. 7",
        "efficiency flat between 50 and 90 % of T_lim",
        "flat",
        "max - min of eta over the band <= 0.03 at every ratio",
        _flat,
    ),
    Check(
        "Fig. 7",
        "efficiency falls to zero at small torque",
        "-> 0",
        "eta = 0 at T_2 = 0 and rising over the first torques, every ratio",
        _falls,
    ),
    Check(
        "Fig. 8",
        "raising F_N0 raises the limiting torque",
        "rises",
        "T_lim strictly increasing in F_N0",
        _limit_rises,
    ),
    Check(
        "Fig. 8",
        "raising F_N0 raises the speed efficiency",
        "rises",
        "at every T_2 > 0 where all clamps converge",
        _speed_rises,
    ),
    Check(
        "Fig. 8",
        "raising F_N0 lowers the torque efficiency",
        "falls",
        "at every T_2 > 0 where all clamps converge",
        _torque_falls,
    ),
    Check(
        "Fig. 8c",
        "envelope over F_N0 above 0.92 over the torque range",
        "> 0.92",
        "optimal-clamp eta > 0.92 at every plotted T_2 >= 10 N m",
        _envelope,
    ),
    Check(
        "Fig. 10",
        "idler creep and spin change sign near the same ratio",
        "same ratio",
        "within 0.1 in tau_ID",
        _sign_changes,
    ),
    Number(
        "Fig. 11",
        "eta at tau_ID = 0.5, T_2 = 40 N m",
        0.82,
        ETA,
        lambda r: float(r.at40("double").eta.sel(ratio=0.5)),
    ),
    Number("Fig. 11", "maximum eta, T_2 = 40 N m", 0.89, ETA, lambda r: r.peak[1]),
    Number(
        "Fig. 11", "ratio of the maximum", 1.76, Tolerance(0.1, fmt="{:.2f}"), lambda r: r.peak[0]
    ),
    Check("Fig. 11", "Eq. 38 = Eq. 39", "equal", "max |eta_38 - eta_39| <= 1e-6", _eq38_39),
    Number(
        "Fig. 12",
        "single idler creep below double's (orders of magnitude, max over ratio)",
        2.0,
        Tolerance(0.5, fmt="{:.2f}"),
        _creep_orders,
    ),
    Check(
        "Fig. 13",
        "single idler more efficient at every ratio",
        "better",
        "at T_2 = 20, 40, 60 N m, all ratios",
        _single_better,
    ),
    Number(
        "Fig. 13",
        "single idler eta at tau_ID = 1, T_2 = 40 N m",
        0.90,
        ETA,
        lambda r: _eta1(r, "single"),
    ),
    Number(
        "Fig. 13",
        "single minus double at tau_ID = 1 (points)",
        3.0,
        Tolerance(1.0, fmt="{:.1f}"),
        lambda r: 100 * (_eta1(r, "single") - _eta1(r, "double")),
    ),
)


def paper_claims(data, fig11_peak) -> list[Claim]:
    """Build the claim table: every row of `CLAIMS` evaluated on the runs.

    Parameters
    ----------
    data : FigureData
        The reproduction's sweeps.
    fig11_peak : tuple of float
        ``(ratio, eta)`` of the refined efficiency maximum at T_2 = 40 N m.
    """
    runs = Runs(data, fig11_peak)
    return [row.evaluate(runs) for row in CLAIMS]
