"""Write the "real hub" validation page: docs/validation/real-hub.md and its figures.

The built-in ``hub`` drive (or ``--design FILE``) at 114 rpm input, 50 / 100 / 200 W of
input power, ratios 0.5 / 1 / 1.8 (issue 27): efficiency, loss breakdown, film parameter
lambda at each contact (and the oil temperature when the drive's models compute one), its
uncertainty band and ranking (docs/uncertainty.md), the models the drive file names, and
every assumption it rests on (its ASSUMED comments and its [uncertainty] table).

Run from the repository's root. The points are solved under the drive file's own models
(the hub's oil at its heat balance, docs/model.md §15) and again with the other oil model
(fixed, or balanced where the file fixes it); the uncertainty band follows the drive file's
own models (under a ``[models] oil_temperature = "balance"`` each drawn drive's points and
capacities are balanced too). On 2 processes (``--workers``;
the same samples either way)::

    python docs/scripts/real_hub.py                 # writes docs/validation/real-hub.md
    python docs/scripts/real_hub.py --samples 64 --out /tmp/page   # a quick look

Only the public API is used. Models a drive file names (its clamping law, traction law,
and any key ending in ``_law`` or ``_model``, or a ``[models]`` table) are listed on the
page as they are read; the ``Variator`` built from the file runs them.
"""

from __future__ import annotations

import argparse
import re
import time
import tomllib
from pathlib import Path

import matplotlib
import numpy as np

matplotlib.use("Agg")
from matplotlib.figure import Figure  # noqa: E402

import ballcvt  # noqa: E402
from ballcvt import BallCVTError, Variator  # noqa: E402
from ballcvt.api import (  # noqa: E402
    BUILTIN_DRIVES,
    builtin_text,
    drive_clamp,
    resolve_drive,
    uncertainty,
    with_oil_temperature,  # noqa: E402
)
from ballcvt.plotting import uncertainty_figure  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
SPEED_RPM = 114.0
POWERS = (50.0, 100.0, 200.0)
RATIOS = (0.5, 1.0, 1.8)
#: Secant passes on the output torque that draws the input power.
PASSES = 12


def drive_text(design: str) -> str:
    """The drive file's text (a built-in drive's name or a path)."""
    if design in BUILTIN_DRIVES and not Path(design).exists():
        return builtin_text(design)
    return Path(design).read_text(encoding="utf-8")


def named_models(text: str) -> list[tuple[str, str]]:
    """``(dotted key, value)`` of every model the file names: keys ending in ``_law`` or
    ``_model``, and every key of a table named ``models``."""
    found = []

    def walk(node, prefix, in_models):
        for key, value in node.items():
            path = f"{prefix}{key}"
            if isinstance(value, dict):
                walk(value, path + ".", in_models or key == "models")
            elif in_models or key.endswith(("_law", "_model")):
                found.append((path, str(value)))

    data = tomllib.loads(text)
    data.pop("uncertainty", None)
    walk(data, "", False)
    return found


def assumptions(text: str) -> list[tuple[str, str, str]]:
    """``(table.key, value, comment)`` of every line marked ASSUMED in the file (outside
    its [uncertainty] table)."""
    out, table = [], ""
    for line in text.split("\n[uncertainty]")[0].splitlines():
        head = re.match(r"\s*\[([^\]]+)\]", line)
        if head:
            table = head.group(1)
            continue
        m = re.match(r"\s*([A-Za-z_0-9]+)\s*=\s*([^#]+?)\s*#\s*(.*ASSUMED.*)$", line)
        if m:
            comment = re.sub(r"\s+", " ", m.group(3)).strip()
            out.append((f"{table}.{m.group(1)}", m.group(2), comment))
    return out


def at_power(v: Variator, ratio: float, power: float, law: dict):
    """The solved point whose input power is ``power`` [W] (secant on the output torque;
    the input torque is nearly affine in it)."""
    w0 = SPEED_RPM * np.pi / 30.0
    t_in = power / w0
    t2, prev = 0.9 * t_in * ratio, None
    for _ in range(PASSES):
        r = v.solve(ratio=ratio, output_torque=t2, input_speed_rpm=SPEED_RPM, **law)
        if abs(r.input_torque - t_in) <= 1e-7 * t_in:
            return r
        slope = ratio if prev is None else (r.input_torque - prev[1]) / (t2 - prev[0])
        prev = (t2, r.input_torque)
        t2 = max(t2 + (t_in - r.input_torque) / (slope if slope > 0 else ratio), 0.0)
    return r


def points(v: Variator, law: dict) -> dict:
    """(power, ratio) -> solved result, or the one-line reason it is not."""
    out = {}
    for p in POWERS:
        for ratio in RATIOS:
            try:
                out[p, ratio] = at_power(v, ratio, p, law)
            except BallCVTError as exc:
                out[p, ratio] = str(exc).split(": allowed")[0]
    return out


def table(head: list[str], rows: list[list[str]]) -> str:
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    return "\n".join(lines + ["| " + " | ".join(r) + " |" for r in rows])


def efficiency_section(solved: dict, band) -> str:
    """Efficiency with its 5-95 % band, per power and ratio."""
    rows = []
    q = {(row["output"]): row for _, row in band.iterrows()}
    for (p, ratio), r in solved.items():
        key = f"eta at ratio {ratio:g}, P {p:g} W, {SPEED_RPM:g} rpm"
        b = q.get(key)
        span = (
            f"{b['q05']:.3f} - {b['q95']:.3f} ({b['solved']} solved)"
            if b is not None and np.isfinite(b["q05"])
            else "-"
        )
        if isinstance(r, str):
            rows.append([f"{p:g}", f"{ratio:g}", "not solved", "", span, r])
            continue
        temp = getattr(r, "oil_temperature", None)
        note = f"oil {temp - 273.15:.1f} C" if temp is not None else ""
        rows.append([f"{p:g}", f"{ratio:g}", f"{r.eta:.4f}", f"{r.output_torque:.2f}", span, note])
    return table(
        ["input power [W]", "ratio", "efficiency", "T2 [N m]", "band 5-95 %", "note"], rows
    )


def oil_model(v: Variator) -> str:
    """The oil model the drive file names (``fixed`` without one)."""
    models = v.design.models
    return (models.oil_temperature if models is not None else None) or "fixed"


def balance_text(own: str) -> str:
    """What the oil section compares, by the drive file's own oil model."""
    how = (
        "the oil where the shell (`[design.thermal]`) rejects the point's losses "
        "(docs/model.md §15), its viscosity by Walther's law"
    )
    if own == "balance":
        return (
            f'The drive file names `oil_temperature = "balance"`: the tables above have {how}. '
            "Here the same points with the fluid fixed at its own temperature as well "
            '(`--oil-temperature fixed`, `ballcvt.api.with_oil_temperature(v, "fixed")`).'
        )
    return (
        "The same points with `--oil-temperature balance` (`ballcvt.api.with_oil_temperature"
        f'(v, "balance")`): {how}. The drive file does not name the balance (§15).'
    )


def balance_section(solved: dict, balanced: dict) -> str:
    """Efficiency at the fluid's fixed temperature and with the oil's heat balance."""
    rows = []
    for key, r in balanced.items():
        p, ratio = key
        fixed = solved[key]
        eta0 = f"{fixed.eta:.4f}" if not isinstance(fixed, str) else "-"
        if isinstance(r, str):
            rows.append([f"{p:g}", f"{ratio:g}", eta0, "not solved", "", r])
            continue
        temp = f"{r.oil_temperature - 273.15:.1f}"
        rows.append(
            [f"{p:g}", f"{ratio:g}", eta0, f"{r.eta:.4f}", temp, f"{r.losses['total']:.2f} W"]
        )
    return table(
        [
            "input power [W]",
            "ratio",
            "efficiency (fixed)",
            "efficiency (balance)",
            "oil [C]",
            "losses (balance)",
        ],
        rows,
    )


def loss_section(solved: dict) -> str:
    names = []
    for r in solved.values():
        if not isinstance(r, str):
            names += [k for k in r.losses if k not in names and k != "total"]
    rows = [
        [f"{p:g}", f"{ratio:g}"]
        + (
            [f"{r.losses[n]:.3f}" if n in r.losses else "" for n in names]
            + [f"{r.losses['total']:.3f}"]
            if not isinstance(r, str)
            else ["-"] * (len(names) + 1)
        )
        for (p, ratio), r in solved.items()
    ]
    return table(["P [W]", "ratio", *names, "total"], rows)


def lambda_section(solved: dict) -> str:
    contacts = []
    for r in solved.values():
        if not isinstance(r, str):
            contacts = list(r.contacts)
            break
    rows = [
        [f"{p:g}", f"{ratio:g}"]
        + (
            [f"{r.contacts[c].lambda_ratio:.2f}" for c in contacts]
            if not isinstance(r, str)
            else ["-"] * len(contacts)
        )
        for (p, ratio), r in solved.items()
    ]
    return table(["P [W]", "ratio", *[f"lambda {c}" for c in contacts]], rows)


def figure(solved: dict, band, path: Path) -> None:
    """Efficiency against input power per ratio (nominal and band), and the losses."""
    fig = Figure(figsize=(10.0, 4.2), layout="constrained")
    ax, bx = fig.subplots(1, 2)
    q = {row["output"]: row for _, row in band.iterrows()}
    for ratio in RATIOS:
        ok = [(p, solved[p, ratio]) for p in POWERS if not isinstance(solved[p, ratio], str)]
        if ok:
            line = ax.plot(
                [p for p, _ in ok], [r.eta for _, r in ok], "o-", label=f"ratio {ratio:g}"
            )[0]
        lo, hi, pw = [], [], []
        for p in POWERS:
            b = q.get(f"eta at ratio {ratio:g}, P {p:g} W, {SPEED_RPM:g} rpm")
            if b is not None and np.isfinite(b["q05"]):
                pw.append(p)
                lo.append(b["q05"])
                hi.append(b["q95"])
        if pw and ok:
            ax.fill_between(pw, lo, hi, alpha=0.2, color=line.get_color())
    ax.set_xlabel("input power [W]")
    ax.set_ylabel("efficiency [-] (band: 5-95 %)")
    ax.set_title(f"hub at {SPEED_RPM:g} rpm input")
    ax.legend(fontsize=8)
    labels, bottoms = [], None
    keys = [k for k, r in solved.items() if not isinstance(r, str)]
    names = [n for n in (keys and solved[keys[0]].losses or {}) if n != "total"]
    x = np.arange(len(keys))
    bottoms = np.zeros(len(keys))
    for n in names:
        vals = np.array([solved[k].losses.get(n, 0.0) for k in keys])
        bx.bar(x, vals, bottom=bottoms, label=n)
        bottoms += vals
    labels = [f"{p:g} W\n{ratio:g}" for p, ratio in keys]
    bx.set_xticks(x, labels, fontsize=7)
    bx.set_ylabel("loss [W]")
    bx.set_title("loss breakdown (power / ratio)")
    bx.legend(fontsize=7)
    fig.savefig(path, dpi=110)


def page(design: str, samples: int, seed: int, out: Path, workers: int = 1) -> Path:
    text = drive_text(design)
    d, f = resolve_drive(design)
    v = Variator(d, f)
    name, force = drive_clamp(d)  # the drive file's ([models], else [operating])
    law = {"clamp_law": name} if name else {}
    if force is not None:
        law["clamp_force"] = force
    solved = points(v, law)  # under the drive file's own models
    own = oil_model(v)
    other = points(with_oil_temperature(v, "fixed" if own == "balance" else "balance"), law)
    fixed, balanced = (other, solved) if own == "balance" else (solved, other)
    run_on = {"workers": workers} if workers > 1 else {}  # the same samples either way
    start = time.perf_counter()
    unc = uncertainty(
        design,
        samples=samples,
        seed=seed,
        ratio=RATIOS,
        input_power=POWERS,
        input_speed_rpm=(SPEED_RPM,),
        progress=False,
        **run_on,
    )
    elapsed = time.perf_counter() - start
    band, rank = unc.band(), unc.ranking()
    out.mkdir(parents=True, exist_ok=True)
    figure(solved, band, out / "real-hub-efficiency.png")
    fig = uncertainty_figure(band, rank, f"{design}: {samples} samples, seed {seed}")
    fig.savefig(out / "real-hub-band.png", dpi=100)
    md = render(design, text, v, (solved, fixed, balanced), unc, (samples, seed, elapsed))
    path = out / "real-hub.md"
    path.write_text(md, encoding="utf-8")
    return path


def render(design, text, v, both, unc, run) -> str:
    samples, seed, elapsed = run
    solved, fixed, balanced = both
    band, rank, counts = unc.band(), unc.ranking(), unc.counts()
    models = named_models(text) or [("(none named)", "the paper's models")]
    cap = band[band["unit"] == "N m"]
    parts = [
        "# A real hub: efficiency, losses, film and how sure we are",
        "",
        f"Generated by `python docs/scripts/real_hub.py --design {design} --samples "
        f"{samples} --seed {seed}` with ballcvt {ballcvt.__version__}; do not edit by hand. "
        f"The drive `{design}` at {SPEED_RPM:g} rpm input (an e-bike hub: cadence about "
        "60 rpm through a chainring/sprocket step-up of about 2), 50 / 100 / 200 W of input "
        "power, ratios 0.5 / 1 / 1.8 (issue 27). No parameter is tuned to a measured "
        "efficiency.",
        "",
        "## Models used",
        "",
        "As named by the drive file (the `Variator` built from it runs them):",
        "",
        *[f"- `{k}` = `{val}`" for k, val in models],
        f"- traction law in use: `{v.fluid.traction_law}`; idler: `{v.architecture}`",
        "",
        "## Efficiency",
        "",
        efficiency_section(solved, band),
        "",
        "![efficiency and losses](real-hub-efficiency.png)",
        "",
        "## The oil: fixed and at its heat balance",
        "",
        balance_text(oil_model(v)),
        "",
        balance_section(fixed, balanced),
        "",
        "## Loss breakdown [W]",
        "",
        "`result.losses` at each point (docs/model.md §7, §12).",
        "",
        loss_section(solved),
        "",
        "## Film parameter lambda = h_min / sigma at each contact",
        "",
        "Below 3 the asperities touch (mixed lubrication; `ballcvt.performance.validity`).",
        "",
        lambda_section(solved),
        "",
        "## Uncertainty band and ranking",
        "",
        f"{samples} drives drawn from the file's `[uncertainty]` table (Sobol, seed {seed}; "
        f"{elapsed:.0f} s; {counts['cannot_be_built']} could not be built). Capacity "
        "(largest admissible output torque) at each ratio:",
        "",
        table(
            ["capacity at", "nominal [N m]", "5 %", "50 %", "95 %"],
            [
                [
                    r["output"].split(" at ", 1)[1],
                    f"{r['nominal']:.1f}",
                    f"{r['q05']:.1f}",
                    f"{r['q50']:.1f}",
                    f"{r['q95']:.1f}",
                ]
                for _, r in cap.iterrows()
            ],
        ),
        "",
        "Parameters ranked by their mean |Spearman rank correlation| with the efficiencies "
        '(docs/uncertainty.md, "How to read it"):',
        "",
        table(
            ["rank", "parameter", "score (efficiency)", "score (capacity)"],
            [
                [
                    str(int(r["rank"])),
                    f"`{p}`",
                    f"{r['score_eta']:.2f}",
                    f"{r['score_capacity']:.2f}",
                ]
                for p, r in rank.iterrows()
            ],
        ),
        "",
        "![band and ranking](real-hub-band.png)",
        "",
        "## Assumptions",
        "",
        "Every value the drive file marks ASSUMED:",
        "",
        *[f"- `{k}` = {val}: {c}" for k, val, c in assumptions(text)],
        "",
        "With the ranges of its `[uncertainty]` table:",
        "",
        *[
            f"- `{p['path']}`: {p['description']} ({p['source'] or 'no source given'})"
            for p in unc.inputs["parameters"]
        ],
        "",
    ]
    return "\n".join(parts)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--design", default="hub")
    parser.add_argument("--samples", type=int, default=256)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--out", type=Path, default=ROOT / "docs" / "validation")
    parser.add_argument("--workers", type=int, default=2, help="processes for the samples")
    args = parser.parse_args()
    print(page(args.design, args.samples, args.seed, args.out, args.workers))


if __name__ == "__main__":
    main()
