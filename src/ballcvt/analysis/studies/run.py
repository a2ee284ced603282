"""Run a study: sample or optimise designs, evaluate them on Dask, keep every result.

Designs are evaluated in tasks of `task_size` designs (at least `StudySettings.chunk`;
about a quarter of a worker's share on Dask, a sixteenth of the designs in process, at most
`MAX_TASK`): few tasks, so few round trips to the workers and few appends. Each finished
task is appended to the Zarr store and committed at once (`store.DesignStore`), so an
interrupted study, even one killed in the middle of an append, resumes where it stopped
(``resume=True``): designs already in the store are never evaluated again, and a
different study is refused. A run holds its folder (`lock.folder_lock`): a second run into
it is refused. Sampled
designs are numbered by their position in the (seeded) sequence; the optimiser's designs
are looked up by their parameter vector, so a resumed NSGA-II run (same seed, the same
populations) finds its earlier designs in the store.

Without a Dask client the chunks run in this process, in order; with one (a
``LocalCluster`` of ``workers`` processes, or any cluster's scheduler address) they run on
its workers. Either way a design gives the same numbers (tests/test_studies.py).
"""

from __future__ import annotations

import json
import re
import sys
import time
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ..._display import html_summary, text_summary
from ..._version import __version__
from ...errors import InputError
from ...files import atomic_write_text, check_output_dir, write_json
from ...params.io import drive_to_toml
from ...params.models import Design
from .cluster import local_client
from .evaluate import DESIGN_CODES, Context, _design, evaluate_chunk, make_context
from .lock import folder_lock
from .pareto import choose, pareto_mask
from .spec import OBJECTIVES, StudySpec
from .store import STORE, DesignStore, chunk_dataset, study_changes, study_hash, study_record

__all__ = [
    "StudyResult",
    "Compute",
    "run_study",
    "design_vectors",
    "local_client",
    "task_size",
    "MAX_TASK",
]

#: Tasks a study aims at per worker: enough for the workers to share the tail evenly.
TASKS_PER_WORKER = 4
#: Processes the in-process path pretends to have (n / 16 designs per append).
_IN_PROCESS_SHARE = 4
#: The most designs in one task (one append; a kill loses at most a task per worker).
MAX_TASK = 500


@dataclass(frozen=True)
class StudyResult:
    """Outcome of `run_study`.

    Attributes
    ----------
    dataset : xarray.Dataset
        Every evaluated design (dimension ``design``): varied parameters, ``status``,
        ``reason``, the metrics, ``eta`` and ``point_status`` per operating point, and
        ``pareto`` (on the front) and ``chosen``.
    chosen : int
        Index of the chosen design (-1 if no design is feasible).
    chosen_design : Design or None
        The chosen design.
    evaluated_now : int
        Designs evaluated in this run (the rest came from the store).
    files : list of Path
        Files written.
    run_time : float
        Seconds.
    """

    dataset: xr.Dataset
    chosen: int
    chosen_design: Design | None
    evaluated_now: int
    files: list = field(default_factory=list)
    run_time: float = 0.0

    def _summary(self) -> tuple[str, list]:
        c = self.counts()
        ds = self.dataset
        rows = [
            ("designs", int(ds.sizes["design"]), ""),
            ("evaluated now", self.evaluated_now, ""),
            ("feasible", c["evaluated"], ""),
            ("cannot be built", c["cannot be built"], ""),
            ("violate a constraint", c["constraint violated"], ""),
            ("on the Pareto front", int(ds["pareto"].sum()), ""),
            (
                "chosen design",
                int(ds["design"].values[self.chosen]) if self.chosen >= 0 else "none",
                "",
            ),
            ("run time", self.run_time, "s"),
        ]
        return f"StudyResult: {ds.attrs.get('study', '')}", rows

    def __repr__(self) -> str:
        return text_summary(*self._summary())

    def _repr_html_(self) -> str:
        return html_summary(*self._summary())

    def to_dataframe(self):
        """Every design as a row: parameters, status, reason, objectives, front, chosen."""
        names = [v for v in self.dataset.data_vars if self.dataset[v].dims == ("design",)]
        return self.dataset[names].to_dataframe()

    @property
    def front(self) -> np.ndarray:
        """Indices of the designs on the Pareto front."""
        return self.dataset["design"].values[self.dataset["pareto"].values]

    def counts(self) -> dict:
        """Designs by status, and the infeasible ones by reason (first words)."""
        st = self.dataset["status"].values
        out: dict[str, Any] = {w: int(np.sum(st == k)) for k, w in DESIGN_CODES.items()}
        reasons: dict[str, int] = {}
        for s, r in zip(st, self.dataset["reason"].values):
            if s != 0:  # the reason with its numbers left out
                key = re.sub(r"[-+]?\d[\d.]*(e[-+]?\d+)?", "#", str(r).split(": allowed")[0])[:90]
                reasons[key] = reasons.get(key, 0) + 1
        out["reasons"] = dict(sorted(reasons.items(), key=lambda kv: -kv[1]))
        return out


def design_vectors(spec: StudySpec, n: int | None = None) -> np.ndarray:
    """The first ``n`` (default ``samples``) designs of a sampling study, ``(n, p)``:
    scrambled Sobol or Latin hypercube points (`scipy.stats.qmc`, seeded) scaled to the
    parameters' ranges, integers rounded, lists indexed."""
    from scipy.stats import qmc

    n = spec.study.samples if n is None else n
    d = len(spec.names)
    if spec.study.method == "lhs":
        u = qmc.LatinHypercube(d, seed=spec.study.seed).random(n)
    else:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # balance warning off powers of two
            u = qmc.Sobol(d, scramble=True, seed=spec.study.seed).random(n)
    return np.column_stack(
        [spec.parameters[name].scale(u[:, j]) for j, name in enumerate(spec.names)]
    )


def task_size(n: int, chunk: int, workers: int) -> int:
    """Designs per task for ``n`` designs on ``workers`` processes.

    At least ``chunk`` (the study's ``chunk``), else ``n / (4 workers)`` designs, at most
    `MAX_TASK`: each task is one submission and one append to the store (about 0.1 s each),
    so a few large tasks per worker cost next to nothing against the designs' solves
    (about 15-60 ms each), and a kill loses at most the tasks being evaluated. The rows
    stored do not depend on it (each design is evaluated alone).
    """
    return max(chunk, min(MAX_TASK, n // (TASKS_PER_WORKER * max(workers, 1))))


class _Evaluator:
    """Evaluates chunks in process or on a Dask client; appends each to the store."""

    def __init__(self, ctx: Context, store: DesignStore, client, attrs, progress):
        self.ctx, self.store, self.client, self.attrs = ctx, store, client, attrs
        self.progress = progress
        self.count = 0
        self.remote_ctx = client.scatter(ctx, broadcast=True) if client is not None else None
        #: design index -> (status, objective values in `StudySpec.objectives` order)
        self.scores: dict[int, tuple[int, np.ndarray]] = {}

    def remember(self, design, status, values: dict) -> None:
        """Keep the status and objectives of evaluated designs (arrays over ``design``)."""
        objectives = list(self.ctx.spec.objectives)
        for j, i in enumerate(np.asarray(design)):
            self.scores[int(i)] = (int(status[j]), np.array([values[o][j] for o in objectives]))

    def run(self, index: np.ndarray, x: np.ndarray, desc: str) -> None:
        from tqdm.auto import tqdm

        if index.size == 0:
            return
        chunk = self.ctx.spec.study.chunk
        if self.client is None:
            size = task_size(index.size, chunk, _IN_PROCESS_SHARE)
        else:
            size = task_size(index.size, chunk, sum(self.client.nthreads().values()))
        parts = [np.arange(i, min(i + size, index.size)) for i in range(0, index.size, size)]
        show = sys.stderr.isatty() if self.progress is None else self.progress
        with tqdm(total=index.size, desc=desc, unit="design", disable=not show) as bar:
            if self.client is None:
                for p in parts:
                    self._save(index[p], x[p], evaluate_chunk(self.ctx, index[p], x[p]), bar)
            else:
                from distributed import as_completed

                futures = {
                    self.client.submit(
                        evaluate_chunk, self.remote_ctx, index[p], x[p], pure=False
                    ): p
                    for p in parts
                }
                for fut in as_completed(futures):
                    p = futures[fut]
                    self._save(index[p], x[p], fut.result(), bar)

    def _save(self, index, x, result, bar) -> None:
        self.store.append(chunk_dataset(self.ctx.spec, self.ctx, x, result), self.attrs)
        self.remember(result["design"], result["status"], result)
        self.count += index.size
        bar.update(index.size)


@dataclass(frozen=True)
class Compute:
    """Where and how a study's designs are evaluated.

    Attributes
    ----------
    workers : int
        Processes of the local Dask cluster (when neither ``scheduler`` nor ``client``).
    scheduler : str, optional
        Address of a running Dask scheduler (``tcp://host:8786``).
    client : distributed.Client, optional
        A client to use (not closed here).
    in_process : bool
        Evaluate in this process, without Dask.
    progress : bool, optional
        Progress bar and the line naming the Dask dashboard's address (default: when
        stderr is a terminal; ``ballcvt explore --quiet`` gives neither: the dashboard
        closes with the command anyway).
    """

    workers: int = 2
    scheduler: str | None = None
    client: Any = None
    in_process: bool = False
    progress: bool | None = None


def run_study(
    spec: StudySpec,
    out,
    compute: Compute | None = None,
    *,
    resume: bool = False,
    **keywords,
) -> StudyResult:
    """Run ``spec`` and write its store and files into ``out``.

    Parameters
    ----------
    spec : StudySpec
        The study (`ballcvt.analysis.studies.spec.read_study`).
    out : path-like
        Output folder: ``designs.zarr`` (the store), ``designs.csv``, ``pareto.csv``,
        ``chosen_design.toml``, ``summary.json``.
    compute : Compute, optional
        Where the designs are evaluated; or give its fields as keywords
        (``in_process=True``, ``workers=2``, ``scheduler=...``, ``client=...``,
        ``progress=False``).
    resume : bool
        Continue the study in ``out``: designs in its store are not evaluated again.

    Returns
    -------
    StudyResult

    Raises
    ------
    InputError
        If ``out`` holds a study and ``resume`` is false, holds another study (the message
        names the keys that changed), or another running process holds ``out``.
    """
    compute = replace(compute or Compute(), **keywords)
    start = time.perf_counter()
    out = check_output_dir(out)
    with folder_lock(out):
        store = DesignStore(out / STORE)
        done = store.open()
        _check_resume(spec, store, done, resume)
        ctx = make_context(spec)
        attrs = {
            "study": spec.study.name,
            "ballcvt_version": __version__,
            "spec": json.dumps(study_record(spec)),
            "Conventions": "CF-1.10",
            "title": f"ballcvt design study: {spec.study.name}",
        }
        client, own, execution = _connect(compute)
        try:
            ev = _Evaluator(ctx, store, client, attrs, compute.progress)
            if spec.study.method == "nsga2":
                _optimise(spec, ev, done)
            else:
                x = design_vectors(spec)
                todo = np.array([i for i in range(len(x)) if i not in done], dtype=np.int64)
                ev.run(todo, x[todo], f"study {spec.study.name}")
        finally:
            if own is not None:
                cluster = getattr(own, "cluster", None)
                own.close()
                if cluster is not None:
                    cluster.close()
        return _finish(spec, ctx, out, store, ev.count, time.perf_counter() - start, execution)


def _check_resume(spec: StudySpec, store: DesignStore, done: set, resume: bool) -> None:
    """Refuse a folder holding a study unless resuming it, and resuming another study."""
    out = store.path.parent
    if done and not resume:
        raise InputError(
            "out",
            str(out),
            "a folder without a study, or --resume",
            message=f"{out} already holds a study ({len(done)} designs): "
            "resume it with --resume, or choose another --out",
        )
    record = study_record(spec)
    if done and store.record is not None and study_hash(store.record) != study_hash(record):
        changed = study_changes(store.record, record)
        shown = ", ".join(changed[:8]) + (
            f" and {len(changed) - 8} more" if len(changed) > 8 else ""
        )
        raise InputError(
            "study",
            str(out),
            "the study the folder holds",
            message=f"--resume: {out} holds another study ({len(done)} designs); changed: "
            f"{shown}. Resume it with the same study file, or choose another --out",
        )


def _connect(compute: Compute):
    """(client or None, the client this run owns or None, how the designs are evaluated)."""
    if compute.client is not None:
        return compute.client, None, f"Dask client {compute.client.scheduler.address}"
    if compute.in_process:
        return None, None, "in process (no Dask)"
    if compute.scheduler is not None:
        from distributed import Client

        client = Client(compute.scheduler)
        execution = f"Dask scheduler {compute.scheduler}"
    else:
        client = local_client(compute.workers)
        execution = f"local Dask cluster, {compute.workers} worker processes"
    if sys.stderr.isatty() if compute.progress is None else compute.progress:
        print(f"Dask dashboard: {client.dashboard_link}", file=sys.stderr)
    return client, client, execution


def _optimise(spec: StudySpec, ev: _Evaluator, done: set) -> None:
    """NSGA-II (pymoo) over the parameter ranges; each population evaluated as chunks."""
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.core.problem import Problem
    from pymoo.optimize import minimize

    names = spec.names
    lo = np.zeros(len(names))
    hi = np.ones(len(names))
    senses = [spec.objectives[o] for o in spec.objectives]
    known: dict[bytes, int] = {}
    if done:  # the designs of the interrupted run: looked up, never evaluated again
        ds = ev.store.load()
        for i, row in zip(ds["design"].values, np.column_stack([ds[n].values for n in names])):
            known[np.round(row, 12).tobytes()] = int(i)
        ev.remember(
            ds["design"].values, ds["status"].values, {o: ds[o].values for o in spec.objectives}
        )
    next_index = [max(done) + 1 if done else 0]

    class _Study(Problem):
        def __init__(self):
            super().__init__(n_var=len(names), n_obj=len(senses), n_ieq_constr=1, xl=lo, xu=hi)

        def _evaluate(self, u, out, *args, **kwargs):
            x = np.column_stack(
                [
                    spec.parameters[n].scale(np.minimum(u[:, j], 1 - 1e-12))
                    for j, n in enumerate(names)
                ]
            )
            idx = np.empty(len(x), dtype=np.int64)
            new = []  # rows of designs not seen before (each a first occurrence)
            for r, row in enumerate(x):
                key = np.round(row, 12).tobytes()
                if key not in known:
                    known[key] = next_index[0]
                    next_index[0] += 1
                    new.append(r)
                idx[r] = known[key]
            ev.run(idx[new], x[new], f"study {spec.study.name}, NSGA-II")
            status = np.array([ev.scores[int(i)][0] for i in idx])
            f = np.array([ev.scores[int(i)][1] for i in idx]) * np.array(
                [-1.0 if s == "max" else 1.0 for s in senses]
            )
            ok = (status == 0) & np.all(np.isfinite(f), axis=1)
            out["F"] = np.where(np.isfinite(f), f, 1e30)
            out["G"] = np.where(ok, -1.0, 1.0)[:, None]

    minimize(
        _Study(),
        NSGA2(pop_size=spec.study.population),
        ("n_gen", spec.study.generations),
        seed=spec.study.seed,
        verbose=False,
    )


def _finish(
    spec, ctx, out: Path, store: DesignStore, count: int, run_time: float, execution: str
) -> StudyResult:
    ds = store.load()
    objectives = list(spec.objectives)
    senses = [spec.objectives[o] for o in objectives]
    values = np.column_stack([ds[o].values for o in objectives])
    front = pareto_mask(values, senses, ds["status"].values == 0)
    pick = choose(values, senses, front, objectives, spec.study.choose)
    ds["pareto"] = ("design", front, {"long_name": "on the Pareto front"})
    ds["chosen"] = (
        "design",
        np.arange(ds.sizes["design"]) == pick,
        {"long_name": "the chosen design"},
    )
    for o in OBJECTIVES:
        ds[o].attrs.update(units=OBJECTIVES[o][0], long_name=OBJECTIVES[o][1])
    files = []
    cols = list(spec.names) + ["status", "reason"] + list(OBJECTIVES) + ["pareto", "chosen"]
    table = ds[cols].to_dataframe()
    atomic_write_text(out / "designs.csv", table.to_csv())
    atomic_write_text(out / "pareto.csv", table[table["pareto"]].to_csv())
    files += [out / "designs.csv", out / "pareto.csv"]
    chosen_design = None
    if pick >= 0:
        row = {n: float(ds[n].values[pick]) for n in spec.names}
        chosen_design = _design(ctx, row)
        text = drive_to_toml(chosen_design, ctx.fluid)
        head = (
            f"# chosen by ballcvt explore, study '{spec.study.name}', design "
            f"{int(ds['design'].values[pick])}"
            + (
                f" (operating clamp_force {row['clamp_force']:g} N)"
                if "clamp_force" in row
                else ""
            )
            + "\n"
        )
        atomic_write_text(out / "chosen_design.toml", head + text)
        files.append(out / "chosen_design.toml")
    result = StudyResult(ds, pick, chosen_design, count, files, run_time)
    summary = {
        "study": spec.study.name,
        "method": spec.study.method,
        "designs": int(ds.sizes["design"]),
        "evaluated_now": count,
        "counts": result.counts(),
        "pareto": int(front.sum()),
        "chosen": int(ds["design"].values[pick]) if pick >= 0 else None,
        "objectives": {o: s for o, s in zip(objectives, senses)},
        "chosen_objectives": (
            {o: float(ds[o].values[pick]) for o in objectives} if pick >= 0 else None
        ),
        "out": str(out),
        "execution": execution,
        "run_time_s": run_time,
        "ballcvt_version": __version__,
    }
    write_json(out / "summary.json", summary)  # strict JSON: non-finite values as null
    files.append(out / "summary.json")
    return result
