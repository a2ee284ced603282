"""Lookup tables for system simulation: efficiency and losses over ratio x speed x torque.

`lookup_table` evaluates the model on a grid (a sweep, under any clamping law) and
`write_tables` writes it in three layouts (docs/cycles.md, "Lookup tables"):

* ``table.csv``: one row per grid point, units in the column names (pandas, Excel);
* ``table.mat``: MATLAB arrays for Simscape's table-based blocks (e.g. *PS Lookup Table
  (n-D)*): breakpoint vectors ``ratio``, ``input_speed_rpm``, ``output_torque`` and the
  tables ``eta``, ``input_torque``, ``loss_<kind>`` of shape ``(n_ratio, n_speed,
  n_torque)``, the capacity ``limit_torque`` ``(n_ratio, n_speed)`` and ``status``;
* ``table_modelica.txt``: Modelica Standard Library text tables (``#1`` format) for
  ``Modelica.Blocks.Tables.CombiTable2Ds``: ``eta_w<k>`` and ``loss_total_w<k>`` per input
  speed ``k`` (first row: output torque [N m], first column: ratio), and
  ``limit_torque`` (first row: input speed [rpm], first column: ratio).

A point beyond the traction capacity (``status`` 1) has no efficiency or losses: the
drive cannot carry its torque. Its cells hold no number, so that a system model that
ignores ``status`` cannot take them for a real drive: empty in the CSV, NaN in the
``.mat`` file, and the sentinel `MODELICA_BEYOND` (-1, which no efficiency or loss can
be) in the Modelica tables, whose interpolation needs finite values. So do the points
outside the converged range of their ratio and speed (a ratio and speed where nothing is
admissible). ``status`` (0 converged, 1 beyond the capacity, 2 not converged) is written
beside the tables in every layout but the Modelica one, and ``limit_torque`` gives the
capacity (0 where none): a system model should saturate the torque there. An isolated
unconverged point (``status`` 2) between admissible ones is interpolated along the
torque. Under a loading cam with a small preload the admissible torques may start above
zero or leave a gap (`ballcvt.analysis.torque_capacity`): the points below the first
interval and in the gap have ``status`` 1 and hold no number either.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..files import atomic_path, atomic_write_text
from ..performance.efficiency import LOSS_KINDS
from .sweeps.export import write_table

__all__ = [
    "TABLE_VARIABLES",
    "table_arrays",
    "write_tables",
    "read_modelica_tables",
    "MODELICA_BEYOND",
]

#: The quantities tabulated (with ``loss_<kind>`` for every kind of `LOSS_KINDS`).
TABLE_VARIABLES = ("eta", "input_torque", "clamp_force")
#: The value of a Modelica table cell beyond the traction capacity (no efficiency, loss,
#: torque or force is negative; CombiTable2Ds needs finite values).
MODELICA_BEYOND = -1.0


def table_arrays(ds) -> dict:
    """The grid of a single-architecture sweep over ratio, input speed and torque as
    arrays ``(n_ratio, n_speed, n_torque)``, NaN beyond the capacity.

    Parameters
    ----------
    ds : xarray.Dataset
        From `Variator.sweep` with one architecture, ``input_speed_rpm`` and, under the
        constant law, one clamping force.

    Returns
    -------
    dict of ndarray
        Breakpoints ``ratio``, ``input_speed_rpm``, ``output_torque``; tables ``eta``,
        ``input_torque``, ``clamp_force``, ``loss_<kind>``, ``status``; ``limit_torque``.
    """
    one = ds.squeeze([d for d in ("architecture", "clamp_force") if d in ds.dims], drop=False)
    one = one.transpose("ratio", "input_speed_rpm", "output_torque", ...)
    out = {
        "ratio": one.ratio.values,
        "input_speed_rpm": one.input_speed_rpm.values,
        "output_torque": one.output_torque.values,
        "status": one.status.values.astype(np.int8),
        "limit_torque": one.limit_torque.transpose("ratio", "input_speed_rpm").values,
    }
    for name in TABLE_VARIABLES:
        if name in one:
            out[name] = np.broadcast_to(one[name].values, out["status"].shape).copy()
    for kind in LOSS_KINDS:  # the components and total, then the subtotals
        source = (
            one.losses.sel(loss=kind)
            if kind in one.loss
            else one.loss_subtotals.sel(subtotal=kind)
        )
        out[f"loss_{kind}"] = source.values
    return out


def _filled(table: np.ndarray, status: np.ndarray) -> np.ndarray:
    """NaN at the points beyond the capacity and outside the converged range of their
    ratio and speed; isolated unconverged points between converged ones interpolated."""
    out = np.array(table, dtype=float)
    ok = status == 0
    for i, j in np.ndindex(out.shape[:2]):
        good = np.flatnonzero(ok[i, j])
        if good.size == 0:
            out[i, j] = np.nan
            continue
        inside = np.zeros(ok.shape[2], dtype=bool)
        inside[good[0] : good[-1] + 1] = True
        bad = ~ok[i, j] & inside & (status[i, j] != 1)
        if bad.any():  # isolated unconverged points: interpolate
            out[i, j, bad] = np.interp(np.flatnonzero(bad), good, out[i, j, good])
        out[i, j, ~ok[i, j] & ~bad] = np.nan
    return out


def write_tables(ds, out, formats=("csv", "mat", "modelica")) -> list[Path]:
    """Write the lookup tables of a sweep (see the module docstring).

    Parameters
    ----------
    ds : xarray.Dataset
        A single-architecture sweep over ``ratio``, ``input_speed_rpm``,
        ``output_torque``.
    out : path
        Output folder (created).
    formats : sequence of {"csv", "mat", "modelica"}
        Layouts to write.

    Returns
    -------
    list of Path
    """
    from scipy.io import savemat

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    arr = table_arrays(ds)
    names = [
        n
        for n in arr
        if n not in ("ratio", "input_speed_rpm", "output_torque", "status", "limit_torque")
    ]
    files = []
    if "csv" in formats:
        r, w, t = np.meshgrid(
            arr["ratio"], arr["input_speed_rpm"], arr["output_torque"], indexing="ij"
        )
        import pandas as pd

        frame = pd.DataFrame(
            {
                "ratio": r.ravel(),
                "input_speed_rpm": w.ravel(),
                "output_torque": t.ravel(),
                **{n: arr[n].ravel() for n in names},
                "status": arr["status"].ravel(),
            }
        )
        files.append(write_table(frame, out / "table.csv", {f"loss_{k}": "W" for k in LOSS_KINDS}))
    filled = {n: _filled(arr[n], arr["status"]) for n in names}
    if "mat" in formats:
        data = {
            "ratio": arr["ratio"],
            "input_speed_rpm": arr["input_speed_rpm"],
            "output_torque": arr["output_torque"],
            "status": arr["status"],
            "limit_torque": np.nan_to_num(arr["limit_torque"], nan=0.0),
            **filled,
            "description": "ballcvt lookup table: tables (ratio, input_speed_rpm, "
            "output_torque); NaN beyond the capacity (status 1) and where nothing "
            "converged; see docs/cycles.md",
        }
        path = out / "table.mat"
        with atomic_path(path) as tmp:
            with open(tmp, "wb") as f:
                savemat(f, data, do_compression=True, oned_as="column")
        files.append(path)
    if "modelica" in formats:
        text = [
            "#1",
            "// ballcvt lookup tables for Modelica.Blocks.Tables.CombiTable2Ds",
            "// eta_w<k>, loss_total_w<k>: u1 = ratio [1], u2 = output torque [N m], at "
            "input speed k:",
            f"// {MODELICA_BEYOND:g} in eta and loss_total: beyond the traction capacity "
            "(no drive: saturate the torque at limit_torque)",
        ]
        for k, w in enumerate(arr["input_speed_rpm"], start=1):
            text.append(f"//   w{k} = {w:.10g} rpm")
        text.append("// limit_torque [N m]: u1 = ratio [1], u2 = input speed [rpm]")
        for k in range(arr["input_speed_rpm"].size):
            for name in ("eta", "loss_total"):
                cells = np.nan_to_num(filled[name][:, k, :], nan=MODELICA_BEYOND)
                text += _modelica(f"{name}_w{k + 1}", arr["ratio"], arr["output_torque"], cells)
        text += _modelica(
            "limit_torque",
            arr["ratio"],
            arr["input_speed_rpm"],
            np.nan_to_num(arr["limit_torque"], nan=0.0),
        )
        files.append(atomic_write_text(out / "table_modelica.txt", "\n".join(text) + "\n"))
    return files


def _modelica(name, u1, u2, table) -> list[str]:
    rows = [
        f"double {name}({u1.size + 1},{u2.size + 1})",
        " ".join(["0"] + [f"{x:.17g}" for x in u2]),
    ]
    for x, row in zip(u1, table):
        rows.append(" ".join([f"{x:.17g}"] + [f"{v:.17g}" for v in row]))
    return rows


def read_modelica_tables(path) -> dict:
    """Read a Modelica ``#1`` text-table file into ``{name: (u1, u2, table)}``."""
    lines = [ln.strip() for ln in Path(path).read_text().splitlines()]
    out, i = {}, 0
    while i < len(lines):
        line = lines[i]
        if line.startswith("double "):
            name, dims = line[7:].split("(")
            rows, cols = (int(v) for v in dims.rstrip(")").split(","))
            block = np.array([[float(v) for v in lines[i + 1 + r].split()] for r in range(rows)])
            if block.shape != (rows, cols):
                raise ValueError(f"table {name}: {block.shape} is not ({rows}, {cols})")
            out[name] = (block[1:, 0], block[0, 1:], block[1:, 1:])
            i += rows + 1
        else:
            i += 1
    return out
