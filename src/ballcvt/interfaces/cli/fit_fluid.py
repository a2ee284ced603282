"""``ballcvt fit-fluid``: fit a fluid's traction parameters to measured traction curves."""

from __future__ import annotations

import sys
from pathlib import Path

from ...api import Fluid, contact_fluid, fit_fluid, read_curves
from ...files import check_output_dir
from . import options as o


def add_parser(subparsers) -> None:
    """Add ``fit-fluid`` and its options."""
    p = o.sub(
        subparsers,
        "fit-fluid",
        "fit a fluid's traction parameters to measured traction curves",
        "Least-squares fit of the fluid's traction parameters to measured curves "
        "(CSV columns condition, rx [m], ry [m], load [N], speed [m/s], spin, creep, mu; "
        "docs/model.md section 14): estimates with standard errors and correlations, "
        "warnings for parameters the data do not determine, residual plots, and the "
        "fitted fluid as fluid.toml, which every command loads with --fluid.",
        "ballcvt fit-fluid examples/traction/curves.csv --law thermal --out fit",
    )
    p.add_argument("curves_file", type=Path, metavar="CURVES.csv", help="measured traction curves")
    o.law_option(p, "traction law to fit (default: the start fluid's own)")
    p.add_argument(
        "--params",
        default=None,
        metavar="NAME,NAME",
        help="fluid fields to fit, comma-separated (default: the law's: "
        "limiting shear stress and slope, and the temperature-viscosity "
        "coefficient (thermal) or the shear modulus (viscoelastic))",
    )
    o.add(p, "fluid", "design")
    o.out(p, "ballcvt-fit")
    o.add(p, "json")


def run(args) -> int:
    """Fit; write fluid.toml, fit.json, fit.csv and the residual plots; print a summary."""
    o.input_file(args.curves_file, "curves file")
    fluid, modulus = contact_fluid(args.design, args.fluid, args.traction_law)
    curves = read_curves(args.curves_file)
    params = (
        None if args.params is None else [p.strip() for p in args.params.split(",") if p.strip()]
    )
    out = check_output_dir(args.out)
    fit = fit_fluid(curves, fluid, params, reduced_modulus=modulus)
    fit.save(out, curves, str(args.curves_file))
    import matplotlib

    matplotlib.use("Agg")
    from ...plotting import fit_figure, save

    save(fit_figure(curves, fit, f"{fit.fluid.traction_law} law"), out, "fit_residuals")
    for w in fit.warnings:
        print(f"ballcvt: warning: {w}", file=sys.stderr)
    if args.json:
        o.emit_json(fit.as_dict())
        return 0
    o.emit(
        f"wrote {out}/fluid.toml, fit.json, fit.csv, fit_residuals.png/.svg: rms "
        f"residual {fit.rms:.3e} over {fit.model.size} points"
    )
    for n in fit.parameters:
        o.emit(
            f"  {n} = {fit.estimates[n]:.6g} +/- {fit.standard_errors[n]:.3g} [{Fluid.unit(n)}]"
        )
    return 0
