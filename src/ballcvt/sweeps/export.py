"""Save and load sweep datasets: NetCDF (lossless, with attributes) and CSV (flat table)."""

from __future__ import annotations

from pathlib import Path

import xarray as xr

__all__ = ["to_netcdf", "to_csv", "load_dataset", "to_frame", "write_table"]


def to_netcdf(ds: xr.Dataset, path) -> Path:
    """Write ``ds`` to a NetCDF file (SciPy engine, no compiled NetCDF library needed)."""
    path = Path(path)
    ds.to_netcdf(path, engine="scipy")
    return path


def load_dataset(path) -> xr.Dataset:
    """Read a dataset written by `to_netcdf` (loaded into memory, file closed)."""
    with xr.open_dataset(path, engine="scipy") as ds:
        return ds.load()


def to_frame(ds: xr.Dataset):
    """One row per operating point; per-contact variables become ``<name>_<contact>``."""
    flat = ds.copy()
    if "contact" in ds.dims:
        for name in [n for n in ds.data_vars if "contact" in ds[n].dims]:
            for c in ds["contact"].values:
                flat[f"{name}_{c}"] = ds[name].sel(contact=c, drop=True)
            flat = flat.drop_vars(name)
        flat = flat.drop_dims("contact", errors="ignore")
    return flat.to_dataframe().reset_index()


def write_table(frame, path, units: dict) -> Path:
    """Write a DataFrame as CSV after a ``# units: col [unit], ...`` line (``-`` if unknown)."""
    path = Path(path)
    with path.open("w") as fh:
        fh.write("# units: " + ", ".join(f"{c} [{units.get(c, '-')}]" for c in frame.columns)
                 + "\n")
        frame.to_csv(fh, index=False)
    return path


def to_csv(ds: xr.Dataset, path) -> Path:
    """Write ``ds`` as a CSV table (see `to_frame`), units in a commented header line."""
    frame = to_frame(ds)
    units = {}
    for col in frame.columns:
        base = col if col in ds.variables else next(
            (n for n in ds.variables if col.startswith(n + "_")), None)
        if base is not None:
            units[col] = ds[base].attrs.get("units", "-")
    return write_table(frame, path, units)
