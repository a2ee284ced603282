"""Every numeric claim of the paper (docs/model.md §9) against the reproduced model.

Each `Claim` carries the paper's value, ours, the difference and a verdict from a stated
tolerance: "agrees" or "differs". Qualitative claims are checked by a stated criterion.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Claim", "paper_claims"]


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


def _num(figure, claim, paper, ours, tol, unit="", fmt="{:.3g}", rel=False):
    diff = ours - paper
    ok = abs(diff) <= (tol * abs(paper) if rel else tol)
    crit = f"|diff| <= {tol * 100:g} %" if rel else f"|diff| <= {tol:g}{unit}"
    d = f"{diff / paper * 100:+.1f} %" if rel else (fmt.format(diff) + unit)
    return Claim(
        figure,
        claim,
        fmt.format(paper) + unit,
        fmt.format(ours) + unit,
        d,
        "agrees" if ok else "differs",
        crit,
    )


def _bool(figure, claim, paper, holds, ours, criterion):
    return Claim(
        figure,
        claim,
        paper,
        ours,
        "-" if holds else "opposite",
        "agrees" if holds else "differs",
        criterion,
    )


def _sign_change(x, y):
    """First ``x`` where ``y`` changes sign (linear interpolation), or NaN."""
    s = np.sign(y)
    idx = np.flatnonzero(s[:-1] * s[1:] < 0)
    if idx.size == 0:
        return float("nan")
    i = idx[0]
    return float(x[i] - y[i] * (x[i + 1] - x[i]) / (y[i + 1] - y[i]))


def paper_claims(data, fig11_peak) -> list[Claim]:
    """Build the claim table.

    Parameters
    ----------
    data : FigureData
        The reproduction's sweeps.
    fig11_peak : tuple of float
        ``(ratio, eta)`` of the refined efficiency maximum at T_2 = 40 N m.
    """
    rows = []
    rc = data.ratio_curves
    sq = lambda a: a.squeeze(drop=True)  # noqa: E731
    p_double = float(sq(rc.p_max.sel(architecture="double", contact="idler_a")).max())
    p_single = float(sq(rc.p_max.sel(architecture="single", contact="idler")).max())
    rows.append(
        _num(
            "Sec. III",
            "p_max roller-idler, double idler, 2 kN",
            1.63,
            p_double / 1e9,
            0.02,
            " GPa",
            rel=True,
        )
    )
    rows.append(
        _num(
            "Sec. III",
            "p_max roller-idler, single idler, 2 kN",
            2.61,
            p_single / 1e9,
            0.02,
            " GPa",
            rel=True,
        )
    )
    tc = sq(data.torque_curves.sel(architecture="double"))
    lim = {float(r): float(tc.limit_torque.sel(ratio=r)) for r in tc.ratio.values}
    for r, paper in ((0.5, 120.0), (1.0, 120.0), (2.0, 60.0)):
        rows.append(
            _num(
                "Fig. 7",
                f"limiting T_2 at tau_ID = {r:g} (|C| <= 0.1)",
                paper,
                lim[r],
                0.10,
                " N m",
                fmt="{:.1f}",
                rel=True,
            )
        )
    rows.append(
        _num(
            "Fig. 7", "T_lim(1) / T_lim(2)", 2.0, lim[1.0] / lim[2.0], 0.10, fmt="{:.2f}", rel=True
        )
    )
    peak = float(tc.eta.max())
    rows.append(_num("Fig. 7", "peak overall efficiency", 0.90, peak, 0.01, fmt="{:.3f}"))
    spreads = []
    for r in tc.ratio.values:
        c = tc.sel(ratio=r)
        band = (c.output_torque >= 0.5 * lim[float(r)]) & (c.output_torque <= 0.9 * lim[float(r)])
        e = c.eta.where(band)
        spreads.append(float(e.max() - e.min()))
    rows.append(
        _bool(
            "Fig. 7",
            "efficiency flat between 50 and 90 % of T_lim",
            "flat",
            max(spreads) <= 0.03,
            f"spread <= {max(spreads):.3f}",
            "max - min of eta over the band <= 0.03 at every ratio",
        )
    )
    first = tc.eta.isel(output_torque=slice(0, 3))
    falls = bool(
        (first.isel(output_torque=0) == 0).all() and (first.diff("output_torque") > 0).all()
    )
    rows.append(
        _bool(
            "Fig. 7",
            "efficiency falls to zero at small torque",
            "-> 0",
            falls,
            "eta = "
            + " / ".join(f"{float(e):.2f}" for e in first.isel(ratio=1))
            + " at T_2 = "
            + " / ".join(f"{float(t):g}" for t in first.output_torque)
            + " N m (tau_ID = 1)",
            "eta = 0 at T_2 = 0 and rising over the first torques, every ratio",
        )
    )
    cc = sq(data.clamp_curves.sel(architecture="double"))
    lims = cc.limit_torque.values
    rows.append(
        _bool(
            "Fig. 8",
            "raising F_N0 raises the limiting torque",
            "rises",
            bool(np.all(np.diff(lims) > 0)),
            " / ".join(f"{v:.0f}" for v in lims) + " N m",
            "T_lim strictly increasing in F_N0",
        )
    )
    both = (cc.status.max("clamp_force") == 0) & (cc.output_torque > 0)
    d_speed = cc.eta_speed.where(both).diff("clamp_force")
    d_torque = cc.eta_torque.where(both).diff("clamp_force")
    worst = d_speed.where(d_speed == d_speed.min(), drop=True)
    rows.append(
        _bool(
            "Fig. 8",
            "raising F_N0 raises the speed efficiency",
            "rises",
            bool((d_speed.fillna(1) > 0).all()),
            f"min step {float(d_speed.min()):+.2e} (at T_2 = "
            f"{float(worst.output_torque[0]):g} N m)",
            "at every T_2 > 0 where all clamps converge",
        )
    )
    rows.append(
        _bool(
            "Fig. 8",
            "raising F_N0 lowers the torque efficiency",
            "falls",
            bool((d_torque.fillna(-1) < 0).all()),
            f"max step {float(d_torque.max()):+.2e}",
            "at every T_2 > 0 where all clamps converge",
        )
    )
    env = data.envelope
    band = env[env.output_torque >= 10.0]
    rows.append(
        _bool(
            "Fig. 8c",
            "envelope over F_N0 above 0.92 over the torque range",
            "> 0.92",
            bool((band.eta > 0.92).all()),
            f"min {band.eta.min():.3f} for T_2 >= 10 N m",
            "optimal-clamp eta > 0.92 at every plotted T_2 >= 10 N m",
        )
    )
    d40 = sq(rc.sel(architecture="double", output_torque=40.0))
    r = d40.ratio.values
    r_creep = _sign_change(r, sq(d40.creep.sel(contact="idler_a")).values)
    r_spin = _sign_change(r, sq(d40.spin.sel(contact="idler_a")).values)
    rows.append(
        _bool(
            "Fig. 10",
            "idler creep and spin change sign near the same ratio",
            "same ratio",
            abs(r_creep - r_spin) <= 0.1,
            f"creep at {r_creep:.3f}, spin at {r_spin:.3f}",
            "within 0.1 in tau_ID",
        )
    )
    eta05 = float(d40.eta.sel(ratio=0.5))
    rows.append(
        _num("Fig. 11", "eta at tau_ID = 0.5, T_2 = 40 N m", 0.82, eta05, 0.01, fmt="{:.3f}")
    )
    rows.append(
        _num("Fig. 11", "maximum eta, T_2 = 40 N m", 0.89, fig11_peak[1], 0.01, fmt="{:.3f}")
    )
    rows.append(_num("Fig. 11", "ratio of the maximum", 1.76, fig11_peak[0], 0.1, fmt="{:.2f}"))
    gap = float(np.nanmax(np.abs(d40.eta - d40.eta_loss)))
    rows.append(
        _bool(
            "Fig. 11",
            "Eq. 38 = Eq. 39",
            "equal",
            gap <= 1e-6,
            f"max |diff| {gap:.1e}",
            "max |eta_38 - eta_39| <= 1e-6",
        )
    )
    s40 = sq(rc.sel(architecture="single", output_torque=40.0))
    c_s = np.abs(sq(s40.creep.sel(contact="idler")).values)
    c_d = np.abs(sq(d40.creep.sel(contact=["idler_a", "idler_b"])).values).max(axis=-1)
    orders = float(np.log10(np.nanmax(c_d) / np.nanmax(c_s)))
    rows.append(
        _num(
            "Fig. 12",
            "single idler creep below double's (orders of magnitude, max over ratio)",
            2.0,
            orders,
            0.5,
            fmt="{:.2f}",
        )
    )
    better = all(
        bool(
            (
                sq(rc.eta.sel(architecture="single", output_torque=t))
                > sq(rc.eta.sel(architecture="double", output_torque=t))
            ).all()
        )
        for t in rc.output_torque.values
    )
    rows.append(
        _bool(
            "Fig. 13",
            "single idler more efficient at every ratio",
            "better",
            better,
            "yes" if better else "no",
            "at T_2 = 20, 40, 60 N m, all ratios",
        )
    )
    e_s1 = float(s40.eta.sel(ratio=1.0))
    e_d1 = float(d40.eta.sel(ratio=1.0))
    rows.append(
        _num(
            "Fig. 13",
            "single idler eta at tau_ID = 1, T_2 = 40 N m",
            0.90,
            e_s1,
            0.01,
            fmt="{:.3f}",
        )
    )
    rows.append(
        _num(
            "Fig. 13",
            "single minus double at tau_ID = 1 (points)",
            3.0,
            100 * (e_s1 - e_d1),
            1.0,
            fmt="{:.1f}",
        )
    )
    return rows
