"""Save and load sweep datasets: NetCDF4 (CF conventions, lossless) and CSV (flat table).

Both are written atomically (a temporary file renamed when complete). CSV column names
carry their units, e.g. ``output_torque [N m]``, so ``pandas.read_csv(path)`` reads them
as they are; dimensionless quantities have unit ``1`` (CF/UDUNITS), as in the NetCDF file.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ...files import atomic_path
from .variables import VARIABLES

__all__ = ["to_netcdf", "to_csv", "load_dataset", "to_frame", "write_table", "parameters"]

#: The NetCDF engine: netCDF4 (NetCDF-4/HDF5 files, the format CF tools expect).
ENGINE = "netcdf4"
#: HDF5 chunk cache per variable while `to_netcdf` writes [bytes].
CHUNK_CACHE = 4 * 2**20


def to_netcdf(ds: xr.Dataset, path) -> Path:
    """Write ``ds`` to a NetCDF-4 file (CF-1.10 attributes, compressed, atomic).

    Parameters
    ----------
    ds : xarray.Dataset
        A sweep (`ballcvt.analysis.sweeps.grid.sweep`).
    path : path-like
        Output file.

    Returns
    -------
    pathlib.Path
    """
    import netCDF4

    path = Path(path)
    encoding: dict[Any, Any] = {name: {"zlib": True, "complevel": 4} for name in ds.data_vars}
    # HDF5 keeps a chunk cache per variable (64 MB by default) until the file closes: for a
    # 1000 x 1000 map that is about 0.4 GB; a small one writes the same file in less memory
    cache = netCDF4.get_chunk_cache()
    netCDF4.set_chunk_cache(CHUNK_CACHE, *cache[1:])
    try:
        with atomic_path(path) as tmp:
            ds.to_netcdf(tmp, engine=ENGINE, format="NETCDF4", encoding=encoding)  # type: ignore[call-overload]
    finally:
        netCDF4.set_chunk_cache(*cache)
    return path


def load_dataset(path) -> xr.Dataset:
    """Read a dataset written by `to_netcdf` (loaded into memory, file closed)."""
    with xr.open_dataset(path, engine=ENGINE) as ds:
        return ds.load()


def parameters(ds: xr.Dataset, prefix: str) -> dict:
    """The nested parameter set stored as ``<prefix>_<key>`` attributes of a sweep.

    ``Design(**parameters(ds, "design"))`` and ``Fluid(**parameters(ds, "fluid"))`` rebuild
    the parameter sets a sweep was computed with.
    """
    nested = {"design": ("material", "bearings", "cam", "parasitic", "thermal")}.get(prefix, ())
    out: dict = {}
    for key, value in ds.attrs.items():
        if not key.startswith(prefix + "_"):
            continue
        name = key[len(prefix) + 1 :]
        if name == "viscosity_data":  # rows of (C, mm^2/s), written row after row
            value = [list(map(float, row)) for row in list(value.reshape(-1, 2))]
        value = value.item() if hasattr(value, "item") else value
        group = next((g for g in nested if name.startswith(g + "_")), None)
        if group:
            out.setdefault(group, {})[name[len(group) + 1 :]] = value
        else:
            out[name] = value
    return out


def to_frame(ds: xr.Dataset):
    """One row per operating point; per-contact and per-loss variables become
    ``<name>_<contact>`` and ``loss_<kind>`` columns."""
    flat = _flat(ds)
    return _with_units(flat.to_dataframe().reset_index(), flat)


def _flat(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with its contact and loss axes spread into variables (views, no copies)."""
    flat = ds.copy()
    for dim, name_of in (
        ("contact", lambda n, c: f"{n}_{c}"),
        ("loss", lambda n, c: f"loss_{c}"),
        ("subtotal", lambda n, c: f"loss_{c}"),
    ):
        if dim not in ds.dims:
            continue
        for name in [n for n in flat.data_vars if dim in flat[n].dims]:
            for c in ds[dim].values:
                flat[name_of(name, c)] = (
                    flat[name].sel({dim: c}, drop=True).assign_attrs(flat[name].attrs)
                )
            flat = flat.drop_vars([name])
        flat = flat.drop_dims(dim, errors="ignore")
    return flat


def _with_units(frame, flat: xr.Dataset):
    """``frame`` with the units of ``flat``'s variables in its column names."""
    units = {c: flat[c].attrs.get("units") for c in frame.columns if c in flat.variables}
    return frame.rename(columns={c: f"{c} [{u}]" for c, u in units.items() if u})


#: Rows of a CSV table built and written at a time (`to_csv` streams: its memory is that
#: of the dataset plus one block of rows, whatever the dataset's size).
CSV_ROWS = 20_000


def _blocks(flat: xr.Dataset, dims: list, rows: int):
    """Pieces of ``flat`` whose tables have at most about ``rows`` rows and which,
    concatenated in turn, make its table (C order of ``dims``, the table's order)."""
    size = int(np.prod([flat.sizes[d] for d in dims]))
    if size <= rows or not dims:
        yield flat
        return
    n = flat.sizes[dims[0]]
    step = rows // (size // n)
    if step < 1:  # one slice of the outer axis is still too long: split inside it
        for a in range(n):
            yield from _blocks(flat.isel({dims[0]: slice(a, a + 1)}), dims[1:], rows)
        return
    for a in range(0, n, step):
        yield flat.isel({dims[0]: slice(a, a + step)})


def write_table(frame, path, units: dict | None = None) -> Path:
    """Write a DataFrame as CSV, atomically, with the units in the column names.

    Columns named after a sweep variable get its unit (``output_torque [N m]``); ``units``
    adds or overrides units of other columns; columns without a unit keep their name.
    """
    path = Path(path)
    units = {
        **{
            c: VARIABLES[c][0]
            for c in frame.columns
            if c in VARIABLES and c not in ("status", "warnings")
        },
        **(units or {}),
    }
    frame = frame.rename(columns={c: f"{c} [{units[c]}]" for c in frame.columns if units.get(c)})
    with atomic_path(path) as tmp:
        frame.to_csv(tmp, index=False)
    return path


def to_csv(ds: xr.Dataset, path) -> Path:
    """Write ``ds`` as a CSV table (see `to_frame`), units in the column names.

    The table is built and written `CSV_ROWS` rows at a time, in bounded memory, by
    polars' writer (about 20 times faster than pandas' on a map: 0.3 s instead of 5.3 s
    for 90,000 rows of 72 columns, issue 26). It holds the values of
    ``to_frame(ds).to_csv(path, index=False)`` to the bit: every float is written in the
    shortest form that reads back to the same double, but exponents are not padded
    (``3.5e-8``, ``3.3e-5`` written ``0.000033``); a NaN is an empty field, as in pandas,
    and a boolean ``True``/``False``."""
    path = Path(path)
    flat = _flat(ds)
    with atomic_path(path) as tmp, open(tmp, "wb") as fh:
        for k, block in enumerate(_blocks(flat, list(flat.dims), CSV_ROWS)):
            frame = _with_units(block.to_dataframe().reset_index(), flat)
            _write_csv(frame, fh, k == 0)
    return path


def _write_csv(frame, fh, header: bool) -> None:
    """Append the DataFrame ``frame`` to the binary file ``fh`` as CSV rows (polars)."""
    import polars as pl

    columns = []
    for name in frame.columns:
        values = frame[name].to_numpy()
        if values.dtype == bool:  # pandas' spelling, not polars' true/false
            values = np.where(values, "True", "False")
        elif values.dtype.kind not in "fiu":
            values = values.astype(str)
        columns.append(pl.Series(name, values, nan_to_null=values.dtype.kind == "f"))
    pl.DataFrame(columns).write_csv(fh, include_header=header)
