"""``ballcvt uncertainty``: a drive file's uncertain parameters propagated to bands of
efficiency and capacity, with the parameters ranked by influence (docs/uncertainty.md)."""

from __future__ import annotations

from pathlib import Path

from ... import api
from ...files import atomic_write_text, check_output_dir
from . import options as o
from .network import check_scheduler
from .oil_option import add_oil_option, oil_setting


def add_parser(subparsers) -> None:
    """Add ``uncertainty`` and its options."""
    p = o.sub(
        subparsers,
        "uncertainty",
        "efficiency and capacity bands from a drive file's uncertain parameters, ranked",
        "Draw --samples drives from the [uncertainty] table of --design (a seeded "
        "quasi-random design), solve each at the operating points (the grid of --ratio, "
        "--power or --torque, --speed) and search its capacity at each ratio; report the "
        "5/50/95 % band of efficiency and capacity and the parameters ranked by Spearman "
        "rank correlation. Writes band.csv, ranking.csv, uncertainty.json (every sample; "
        "api.UncertaintyResult.load reads it) and uncertainty.png, uncertainty.svg in --out.",
        "ballcvt uncertainty --design hub --samples 256 --ratio 0.5 1 1.8 --power 100 --speed 114",
    )
    p.add_argument(
        "--design",
        default="hub",
        metavar="FILE.toml",
        help="drive with an [uncertainty] table: a TOML file or a built-in drive's name "
        "(default: hub)",
    )
    p.add_argument(
        "--samples",
        type=o.count(1, 100_000),
        default=256,
        help="drives drawn, 1-100000 (default: 256)",
    )
    p.add_argument(
        "--seed",
        type=o.count(0, 2**32 - 1),
        default=0,
        help="seed of the sampling design (default: 0)",
    )
    p.add_argument(
        "--method",
        choices=("sobol", "lhs", "random"),
        default="sobol",
        help="sampling design: scrambled Sobol, Latin hypercube or plain Monte "
        "Carlo (default: sobol)",
    )
    p.add_argument(
        "--ratio",
        type=o.quantity("ratio", "-", above=0.0),
        nargs="+",
        default=[1.0],
        metavar="R",
        help="ideal ratios tau_ID (default: 1)",
    )
    _points(p)
    o.add(p, "arch")
    add_oil_option(p, "balance")
    where = p.add_mutually_exclusive_group()
    where.add_argument(
        "--workers",
        type=o.count(1, 256),
        default=None,
        help="evaluate on a local Dask cluster of this many processes (default: in this process)",
    )
    where.add_argument(
        "--scheduler",
        default=None,
        metavar="ADDRESS",
        help="address of a running Dask scheduler, e.g. tcp://10.0.0.1:8786",
    )
    o.out(p, "ballcvt-uncertainty")
    p.add_argument("--quiet", action="store_true", help="no progress bar and no summary")
    o.add(p, "json")


def _points(p) -> None:
    """``--power`` or ``--torque``, and ``--speed``."""
    load = p.add_mutually_exclusive_group()
    load.add_argument(
        "--power",
        type=o.quantity("input_power", "W", above=0.0, most=1e7),
        nargs="+",
        default=None,
        metavar="W",
        help="input powers [W]",
    )
    load.add_argument(
        "--torque",
        type=o.quantity("output_torque", "N m", most=o.MOST_TORQUE),
        nargs="+",
        default=None,
        metavar="N_M",
        help="output torques T2 [N m] (default: 40, the paper's)",
    )
    p.add_argument(
        "--speed",
        type=o.quantity("speed", "rpm", above=0.0, most=o.MOST_RPM),
        nargs="+",
        default=None,
        dest="speeds",
        metavar="RPM",
        help="input speeds [rpm] (default: the drive's [operating] input_speed_rpm, else 2000)",
    )


def run(args) -> int:
    """Propagate; write the band, the ranking, the samples and the figure."""
    if args.scheduler is not None:
        check_scheduler(args.scheduler)  # one line within seconds, before --out is made
    if not Path(args.design).exists() and args.design not in api.BUILTIN_DRIVES:
        o.input_file(Path(args.design), "design file")
    out = check_output_dir(args.out)
    result = api.uncertainty(
        args.design,
        samples=args.samples,
        seed=args.seed,
        method=args.method,
        ratio=tuple(args.ratio),
        input_power=None if args.power is None else tuple(args.power),
        output_torque=None if args.torque is None else tuple(args.torque),
        input_speed_rpm=None if args.speeds is None else tuple(args.speeds),
        architecture=args.arch,
        oil_temperature=oil_setting(args)["oil_temperature"],
        workers=args.workers,
        scheduler=args.scheduler,
        progress=o.show(args),
    )
    files = _write(result, out, args)
    if args.json:
        data = result.summary()
        data["files"] = [str(f) for f in files]
        o.emit_json(data)
    elif not args.quiet:
        o.emit(_summary(result, files, out))
    return 0


def _write(result, out: Path, args) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")  # the CLI writes files only
    from ...plotting import save, uncertainty_figure

    files = [result.save(out / "uncertainty.json"), out / "band.csv", out / "ranking.csv"]
    result.to_csv(out / "band.csv")
    atomic_write_text(out / "ranking.csv", result.ranking().to_csv(float_format="%.4g"))
    title = (
        f"Uncertainty of {args.design}: {result.inputs['samples']} samples "
        f"({result.inputs['method']}, seed {result.inputs['seed']})"
    )
    return files + save(
        uncertainty_figure(result.band(), result.ranking(), title), out, "uncertainty"
    )


def _summary(result, files, out: Path) -> str:
    """The bands and the three most influential parameters, one line each."""
    c = result.counts()
    lines = [
        f"wrote {len(files)} files to {out}: {c['samples']} samples, "
        f"{c['cannot_be_built']} cannot be built; {result.run_time:.1f} s"
    ]
    for _, b in result.band().iterrows():
        unit = "" if b["unit"] == "-" else f" {b['unit']}"
        lines.append(
            f"  {b['output']}: {b['q05']:.4g} / {b['q50']:.4g} / {b['q95']:.4g}{unit} "
            f"(5/50/95 %; nominal {b['nominal']:.4g}; {b['solved']} solved)"
        )
    rank = result.ranking()
    top = ", ".join(f"{p} ({r['score_eta']:.2f})" for p, r in rank.head(3).iterrows())
    lines.append(f"  most influential on efficiency: {top}")
    return "\n".join(lines)
