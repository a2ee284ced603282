"""``ballcvt explore``: a design study on Dask, its Pareto front and the chosen design."""

from __future__ import annotations

from pathlib import Path

from ... import api
from ...errors import InputError
from ...files import check_output_dir
from ...registry import TRACTION_LAWS
from . import options as o
from .network import check_scheduler


def add_parser(subparsers) -> None:
    """Add ``explore`` and its options."""
    p = o.sub(
        subparsers,
        "explore",
        "design study: sample or optimise designs on Dask, Pareto front and the chosen design",
        "Evaluate the designs of a study file (docs/studies.md) on a local Dask cluster "
        "or a running one: every design with its objectives and status in designs.zarr "
        "(written as designs finish; --resume continues an interrupted study), "
        "designs.csv, pareto.csv, chosen_design.toml, summary.json, figures and a "
        "report in --out.",
        "ballcvt explore examples/studies/study_quick.toml --out study --workers 2",
    )
    p.add_argument("study_file", type=Path, metavar="STUDY.toml", help="the study")
    o.out(p, "ballcvt-study")
    p.add_argument(
        "--workers",
        type=o.count(1, 256),
        default=2,
        help="processes of the local Dask cluster, 1-256 (default: 2)",
    )
    p.add_argument(
        "--scheduler",
        default=None,
        metavar="ADDRESS",
        help="address of a running Dask scheduler, e.g. tcp://10.0.0.1:8786 "
        "(default: a local cluster of --workers processes)",
    )
    p.add_argument(
        "--in-process", action="store_true", help="evaluate in this process, without Dask"
    )
    p.add_argument(
        "--traction-law",
        choices=TRACTION_LAWS.names(),
        default=None,
        help="traction law of every design (default: the study's traction_law, else the "
        "fluid's own)",
    )
    p.add_argument(
        "--resume",
        action="store_true",
        help="continue the study in --out: evaluated designs are kept",
    )
    p.add_argument("--quiet", action="store_true", help="no progress bar and no summary")
    o.add(p, "json")


def run(args) -> int:
    """Run the study and its report; print summary.json or a summary line."""
    import matplotlib

    matplotlib.use("Agg")
    from ...reports.study import study_report

    o.input_file(args.study_file, "study file")
    spec = api.read_study(args.study_file, traction_law=args.traction_law)
    if args.scheduler is not None and args.in_process:
        raise InputError("scheduler", args.scheduler, "not with --in-process")
    if args.scheduler is not None:
        check_scheduler(args.scheduler)  # one line within seconds, before --out is made
    check_output_dir(args.out)  # a folder (made if new); anything else is refused
    with api.folder_lock(args.out):  # the run and its report: one run per --out
        result = api.run_study(
            spec,
            args.out,
            workers=args.workers,
            scheduler=args.scheduler,
            in_process=args.in_process,
            resume=args.resume,
            progress=o.show(args),
        )
        files = result.files + study_report(result, spec, args.out)
    if args.json:
        o.emit_json_text((Path(args.out) / "summary.json").read_text())
    elif not args.quiet:
        o.emit(_summary(result, files, Path(args.out)))
    return 0


def _summary(result, files, out: Path) -> str:
    """The one-line summary of a finished study."""
    counts = result.counts()
    chosen = (
        "none feasible"
        if result.chosen < 0
        else f"chosen design {int(result.dataset['design'].values[result.chosen])} -> "
        f"{out / 'chosen_design.toml'}"
    )
    return (
        f"wrote {len(files)} files and {out / 'designs.zarr'} to {out}: "
        f"{result.dataset.sizes['design']} designs ({result.evaluated_now} evaluated "
        f"now), {counts['evaluated']} feasible, {counts['cannot be built']} cannot be "
        f"built, {counts['constraint violated']} violate a constraint; "
        f"{int(result.dataset['pareto'].sum())} on the Pareto front; {chosen}; "
        f"{result.run_time:.1f} s"
    )
