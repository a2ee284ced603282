"""Write the mixed-lubrication validation page: docs/validation/mixed-lubrication.md.

The mixed-lubrication model (docs/model.md §16, `ballcvt.model.lubrication`) swept over the
entrainment speed at one contact of the built-in ``hub``, as a Stribeck curve would be
measured on a ball-on-disc machine: the traction coefficient, the asperity load share and
the friction of the asperity share against the smooth film parameter ``h_s / sigma``, at
a small creep (a traction drive's) and in sliding (slide-to-roll ratio 0.5, a Stribeck
test's), for Greenwood and Williamson's middle and extreme asperity parameters. No
measured curve is drawn: none was found in a citable, tabulated form (the page says what
was searched). Nothing here is fitted.

Run from the repository's root (about half a minute)::

    python docs/scripts/mixed_lubrication.py             # writes docs/validation/
    python docs/scripts/mixed_lubrication.py --out /tmp/page
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402
from scipy.special import gamma  # noqa: E402

import ballcvt  # noqa: E402
from ballcvt import load_builtin  # noqa: E402
from ballcvt.model.film import SPEED_EXPONENT  # noqa: E402
from ballcvt.model.lubrication import (  # noqa: E402
    Asperities,
    boundary_coefficients,
    load_sharing,
    lubricated_coefficients,
)
from ballcvt.model.traction.contact import ContactState, contact_coefficients  # noqa: E402
from ballcvt.model.traction.quadrature import Quadrature  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
NAME = "mixed-lubrication"
#: The hub's input contact at 114 rpm, ratio 1, 200 W (``ballcvt point --design hub
#: --ratio 1 --torque 4.19 --speed 114``; as tests/test_lubrication.py): creep term,
#: spin, a_x, a_y [m], p_max [Pa], load [N], r_c [m], u_ref [m/s], central film [m].
HUB_INPUT = ContactState(0.0175, -2.64, 4.04e-4, 4.87e-4, 7.55e8, 311.0, 0.07, 0.24, 8.28e-8)
#: Entrainment speeds of the sweep [m/s] (the film follows Eq. 56, ``h ~ u^0.67``).
SPEEDS = np.geomspace(1e-3, 10.0, 25)
#: Creep terms (sliding over rolling speed): a traction drive's, and a Stribeck test's.
CREEPS = (0.02, 0.5)
#: ``(label, eta beta sigma, sigma / beta)``: Greenwood and Williamson (1966)'s middle
#: (ballcvt's defaults) and the two ends of their ranges.
SURFACES = (
    ("defaults 0.04, 1e-3", 0.04, 1e-3),
    ("smooth end 0.03, 1e-4", 0.03, 1e-4),
    ("rough end 0.05, 1e-2", 0.05, 1e-2),
)


def f52_at_zero() -> float:
    """Greenwood-Tripp's ``F_5/2(0) = (2 pi)^-1/2 int_0^inf s^5/2 exp(-s^2/2) ds``, the
    Gaussian moment ``2^(3/4) Gamma(7/4) / sqrt(2 pi)`` [-]."""
    return 2.0**0.75 * float(gamma(1.75)) / math.sqrt(2.0 * math.pi)


def ceiling(asp: Asperities, state: ContactState) -> float:
    """The largest asperity share the model gives (``lambda -> 0``):
    ``K E' F_5/2(0) / p_mean``, by hand from Greenwood and Tripp's prefactor [-]."""
    k = 16.0 * math.sqrt(2.0) / 15.0 * math.pi * asp.density_product**2 * math.sqrt(asp.slope)
    p_mean = state.load / (math.pi * state.ax * state.ay)
    return k * asp.modulus * f52_at_zero() / p_mean


def sweep(fluid, asp: Asperities, creep: float) -> dict:
    """Film parameter, asperity share and coefficients over `SPEEDS` at ``creep``."""
    film = HUB_INPUT.film * (SPEEDS / HUB_INPUT.u_ref) ** SPEED_EXPONENT
    state = HUB_INPUT.replace(creep_term=creep, spin=0.0, u_ref=SPEEDS, film=film)
    share, lam_share = load_sharing(film, state.load, state.ax, state.ay, asp)
    mu, _ = lubricated_coefficients(state, fluid, asp)
    # the asperity shear as the model takes it: at the film of the film's share
    at_share = state.replace(film=lam_share * asp.roughness)
    boundary, _ = boundary_coefficients(
        at_share, fluid, asp.boundary_friction, Quadrature(), False
    )
    return {
        "lam": film / asp.roughness,
        "share": share,
        "mu": mu,
        "film_mu": contact_coefficients(state, fluid)[0],
        "asperity_mu": boundary,
    }


def at_hub_point(fluid, asp: Asperities) -> tuple[float, float]:
    """The asperity share's friction coefficient and the film's at the hub's own contact."""
    _, lam_share = load_sharing(HUB_INPUT.film, HUB_INPUT.load, HUB_INPUT.ax, HUB_INPUT.ay, asp)
    at_share = HUB_INPUT.replace(film=float(lam_share) * asp.roughness)
    boundary, _ = boundary_coefficients(
        at_share, fluid, asp.boundary_friction, Quadrature(), False
    )
    return float(boundary), float(contact_coefficients(HUB_INPUT, fluid)[0])


def figure(curves: dict, path: Path) -> None:
    """Traction, asperity share and the asperity share's friction against ``h_s/sigma``."""
    fig = Figure(figsize=(11.0, 3.8), layout="constrained")
    ax_mu, ax_share, ax_asp = fig.subplots(1, 3)
    colours = {label: f"C{i}" for i, (label, _, _) in enumerate(SURFACES)}
    for (label, creep), c in curves.items():
        kw = {"color": colours[label], "ls": "-" if creep == CREEPS[1] else "--"}
        ax_mu.loglog(c["lam"], c["mu"], label=f"mixed, {label}, creep {creep}", **kw)
        ax_asp.semilogx(c["lam"], c["asperity_mu"], label=f"{label}, creep {creep}", **kw)
        if creep == CREEPS[1]:  # the share depends on the film alone
            ax_share.semilogx(c["lam"], 100 * c["share"], label=label, **kw)
    for creep in CREEPS:
        first = curves[(SURFACES[0][0], creep)]
        ax_mu.loglog(first["lam"], first["film_mu"], "k:", label=f"full film, creep {creep}")
    ax_asp.axhline(0.1, color="k", lw=0.8, label="mu_b = 0.1 (what it should reach)")
    ax_mu.set(xlabel="h_s / sigma", ylabel="traction coefficient mu", title="Stribeck sweep")
    ax_share.set(xlabel="h_s / sigma", ylabel="asperity load share f_a [%]", title="load share")
    ax_asp.set(
        xlabel="h_s / sigma", ylabel="friction of the asperity share", title="asperity friction"
    )
    for ax in (ax_mu, ax_share, ax_asp):
        ax.grid(True, which="both", alpha=0.3)
        ax.axvline(4.0, color="grey", lw=0.6)
    ax_mu.legend(fontsize=6)
    ax_share.legend(fontsize=7)
    ax_asp.legend(fontsize=6)
    fig.savefig(path, dpi=110)


def table(head: list[str], rows: list[list[str]]) -> str:
    """A markdown table."""
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    return "\n".join(lines + ["| " + " | ".join(r) + " |" for r in rows])


def findings(fluid, design) -> tuple[str, dict]:
    """The numbers of the page: ceilings, the sweep's ends, and the hub point."""
    curves, rows = {}, []
    e = design.material.reduced_modulus
    for label, dens, slope in SURFACES:
        asp = Asperities("mixed", design.surface_roughness, e, 0.1, dens, slope)
        for creep in CREEPS:
            curves[(label, creep)] = c = sweep(fluid, asp, creep)
            rows.append(
                [
                    label,
                    f"{creep:g}",
                    f"{100 * ceiling(asp, HUB_INPUT):.1f}",
                    f"{100 * c['share'][0]:.1f}",
                    f"{c['mu'][0]:.4f}",
                    f"{c['film_mu'][0]:.4f}",
                    f"{c['asperity_mu'][0]:.4f}",
                    f"{c['mu'][-1]:.4f}",
                ]
            )
    head = [
        "asperities (eta beta sigma, sigma/beta)",
        "creep",
        "ceiling f_a [%] (hand)",
        f"f_a at {SPEEDS[0] * 1e3:g} mm/s [%]",
        "mu there",
        "full-film mu there",
        "asperity-share mu there",
        f"mu at {SPEEDS[-1]:g} m/s",
    ]
    return table(head, rows), curves


INTRO = """\
# Mixed lubrication: what is validated, and what is not

Generated by `python docs/scripts/mixed_lubrication.py` with ballcvt {version}; do not
edit by hand. Issue 27 asks for a published Stribeck (mixed-EHL) traction measurement
reproduced within its scatter, and for the oil's thermal balance against a hand
calculation and a published gearbox heat-rejection figure. **Neither published
measurement could be reproduced here: no citable, tabulated data were found** (what was
searched is listed below). What the page gives instead is the model's own Stribeck sweep,
the hand calculations it rests on, and why its boundary branch stays far below a
measured Stribeck curve's. Nothing is fitted or tuned.

## The model's Stribeck sweep

The hub's input contact (ratio 1, 114 rpm, 200 W: `F_N` = {load:.0f} N, `p_max` =
{pmax:.2f} GPa, `a_x`, `a_y` = {ax:.0f}, {ay:.0f} um, the hub's fluid at 40 C,
`sigma` = {sigma:.2f} um), swept over the entrainment speed {u0:g} mm/s to {u1:g} m/s with
the film of Eq. 56 (`h ~ u^0.67`), no spin, at the creep term 0.02 (a traction drive's) and
0.5 (the slide-to-roll ratio of a ball-on-disc Stribeck test), `mu_b` = 0.1, for Greenwood
and Williamson's middle and extreme asperity parameters (docs/model.md §16):

![Stribeck sweep](mixed-lubrication-stribeck.png)

{table}

The ceiling is `K E' F_5/2(0) / p_mean` computed by hand (`F_5/2(0) = 2^(3/4) Gamma(7/4) /
sqrt(2 pi)` = {f52:.4f}, the Gaussian moment); the sweep's share at the lowest speed tends
to it (`tests/test_validation_mixed.py`).

## What a measured Stribeck curve would show, and what the model shows

A Stribeck curve of lubricated steel rises, as the speed falls, from the film's traction
towards the boundary friction of the asperities (about 0.1: Bowden and Tabor's value, the
model's own `mu_b`); He, Zhu, Wang and Wang ("Experimental and numerical investigations
of the Stribeck curves for lubricated counterformal contacts"; abstract only read) measured
such complete curves, boundary to full film, for counterformal contacts on a
rolling-sliding apparatus from 0.00006 to 60 m/s, and report that in the full film the
friction still falls as the speed rises (flash heating lowers the limiting shear stress):
the isothermal law here rises instead; the thermal law of §14 is the one to compare.

In the model, at a small creep the traction falls with the film's shear as the speed
falls, has a minimum and rises again at the lowest speeds as the asperities take load
with the boundary shear (the table: at creep 0.02 and 1 mm/s, above the full film's); it
stays far below `mu_b`, for two reasons, each checked by a test:

1. **The asperity share is bounded** by the asperity pressure at zero separation: at the
   hub's contact the asperities carry at most {ceil:.1f} % of the load with the defaults
   ({ceil_lo:.1f} % and {ceil_hi:.1f} % at the ends of Greenwood and Williamson's
   ranges), because under Johnson, Greenwood and Poon's scaling the film never thins
   below the smooth film `h_s` (docs/model.md §16, "When not to trust it" (1)). At
   a traction drive's pressures the boundary regime `f_a -> 1` is out of reach.
2. **The asperity share's friction is Coulomb's once the slip passes its elastic
   scale** (docs/model.md §16: `tau = mu_b p (1 - exp(-k s / (mu_b p)))`, `k` from
   Kalker's `C_11`): at the hub's own contact (creep 0.0175, spin, 0.24 m/s) the asperity
   share's friction coefficient is {asp_hub:.4f} against the film's {film_hub:.4f} and
   `mu_b` = 0.1; at the slide-to-roll ratio 0.5 it is {asp_slow:.3f} at {u0:g} mm/s and
   {asp_fast:.3f} at {u1:g} m/s (`test_asperity_share_reaches_boundary_friction_in_sliding`).
   So at a traction drive's creeps (1-2 %) the asperities grip with nearly `mu_b`, but on
   a few percent of the load.

So the mixed model moves a traction drive's traction mostly by what the asperities'
*load* takes from the film (its pressure and viscosity fall), and by their boundary
friction on that small share: this is why it changes the hub's efficiency by a few tenths
of a point only.
"""

SEARCH = """\
## What was searched (and not found)

Searched for digitised or tabulated point-contact Stribeck / mixed-EHL traction
measurements (traction coefficient against speed or `lambda`, with load, radii,
roughness, viscosity and pressure-viscosity stated): stored public web pages, package
and project documentation, GitHub code and data files, and GitHub issues, for Lu,
Khonsari and Gelinck (2006, J. Tribol. 128:789), Gelinck and Schipper (2000, Tribol. Int.
33:175), Schipper (1988), Zhu and Hu (2001), Kalin, Velkavrh and Vizintin (2009), Björling,
Larsson and Marklund, Guegan, Kadiric, Gabelli and Spikes, PCS Instruments MTM Stribeck
tests, open-access MDPI *Lubricants* papers, and CSV / WebPlotDigitizer data. Found:
abstracts and reference lists only (Lu, Khonsari and Gelinck's is a journal bearing, a
conformal contact, against a line-contact model; "Stribeck curve for starved line contacts", J.
Tribol. 129:181, which compares with measurements but gives no values in its abstract;
He, Zhu, Wang and Wang's counterformal Stribeck curves; Kalin and
Velkavrh's DLC Stribeck curves, Wear 297:911; Popovici and Schipper's elliptical-contact
model), mixed-EHL solvers without measured data, and no tabulated friction values.
For the housing: ISO/TR 14179-1/-2 (only summaries without their coefficients), the
FZG test gearbox's thermal network (del Valle, KTH thesis 2014; Paschold, Sedlmair, Lohner
and Stahl, Forsch. Ingenieurwes. 2022, open access; the abstracts, not their measured
heat-rejection figures) and Changenet et al. (2006) (cited, not readable here); found:
Jiang's design range of the housing coefficient (used above).

A measured curve would close this: a CSV in `tests/data/validation/` with a header giving
the citation (authors, year, table or figure, how the values were read), the load, radii,
moduli, composite roughness, viscosity and pressure-viscosity coefficient at the test
temperature, the slide-to-roll ratio and the stated scatter; a test running
`lubricated_coefficients` at those conditions and comparing within that scatter.
"""

THERMAL = """\
## The oil's thermal balance

What is checked (tests/test_oil_temperature.py, docs/model.md §15):

* The steady balance against hand calculations: `T - T_amb = P / (h A)` for a constant
  loss, a loss rising and a loss falling with the temperature (to the balance's 0.01 K).
* The hub's solved balance against `P_loss(T) / (h A)` of its own solved losses, and the
  lumped transient against the exact first-order response `1 - exp(-t / tau)`.
* The housing coefficient in still air against AGMA's design value for worm-gear reducers
  without a fan, 0.13 ft lbf/(min in^2 F) = 8.2 W/(m^2 K) (Budynas and Nisbett,
  *Shigley's Mechanical Engineering Design*, 10th ed., Eq. 15-52), within 25 % for
  housings 0.2-0.5 m across and 10-30 K over the ambient.
* The balance against the heat balance of a worm-gear drive, `t_o = t_a + 1000 P (1 -
  eta) / (alpha_s S)`, and the still-air housing coefficient against its range of
  `alpha_s`, 8.15-17.45 W/(m^2 K) (Wei Jiang, *Analysis and Design of Machine Elements*,
  Wiley 2019, §9, Eqs. 9.25-9.26, p. 246; tests/test_validation_mixed.py): inside it, at
  its low end, 8.9-11.7 W/(m^2 K) for housings 0.1-0.5 m across at 20-50 K over the
  ambient; at 10 K 7.9-8.5, the largest housing 3 % under it. The hub's 20 W/(m^2 K)
  (forced convection while riding) lies above the still-air range, as it should.
* Walther's viscosity law and the pressure-viscosity scaling against Stachowiak and
  Batchelor's Table 2.3 (13 mineral oils at 30, 60 and 100 C).

What is not: a measured gearbox's heat rejection (power loss against sump temperature
rise) reproduced by the balance. No such figure was found in a readable form (above).
"""


def page(out: Path) -> Path:
    """Write the page and its figure into ``out``; return the page's path."""
    out.mkdir(parents=True, exist_ok=True)
    design, fluid = load_builtin("hub")[:2]
    rows, curves = findings(fluid, design)
    figure(curves, out / f"{NAME}-stribeck.png")
    e = design.material.reduced_modulus
    asp = [Asperities("mixed", design.surface_roughness, e, 0.1, d, s) for _, d, s in SURFACES]
    asp_hub, film_hub = at_hub_point(fluid, asp[0])
    sliding = curves[(SURFACES[0][0], CREEPS[1])]["asperity_mu"]
    text = INTRO.format(
        version=ballcvt.__version__,
        load=HUB_INPUT.load,
        pmax=HUB_INPUT.p_max / 1e9,
        ax=HUB_INPUT.ax * 1e6,
        ay=HUB_INPUT.ay * 1e6,
        sigma=design.surface_roughness * 1e6,
        u0=SPEEDS[0] * 1e3,
        u1=SPEEDS[-1],
        table=rows,
        f52=f52_at_zero(),
        ceil=100 * ceiling(asp[0], HUB_INPUT),
        ceil_lo=100 * ceiling(asp[1], HUB_INPUT),
        ceil_hi=100 * ceiling(asp[2], HUB_INPUT),
        asp_hub=asp_hub,
        film_hub=film_hub,
        asp_slow=sliding[0],
        asp_fast=sliding[-1],
    )
    path = out / f"{NAME}.md"
    path.write_text(text + "\n" + SEARCH + "\n" + THERMAL, encoding="utf-8")
    return path


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "validation")
    print(page(parser.parse_args().out))


if __name__ == "__main__":
    main()
