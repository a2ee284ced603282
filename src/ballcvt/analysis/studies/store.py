"""The study's store: an xarray Dataset in Zarr, appended as designs finish (resumable).

Zarr format 2 (its fixed-length text and every dtype here have a published specification,
so any Zarr library reads the store).
"""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from .evaluate import DESIGN_CODES, METRICS

__all__ = ["STORE", "chunk_dataset", "append", "load", "evaluated"]

STORE = "designs.zarr"


def chunk_dataset(spec, ctx, x, result: dict) -> xr.Dataset:
    """A Dataset of one evaluated chunk: dimension ``design`` (and ``point``)."""
    design = result["design"]
    data: dict[str, Any] = {
        name: ("design", x[:, j], {"long_name": f"varied parameter {name}"})
        for j, name in enumerate(spec.names)
    }
    data["status"] = (
        "design",
        result["status"],
        {
            "flag_values": [int(k) for k in DESIGN_CODES],
            "flag_meanings": " ".join(w.replace(" ", "_") for w in DESIGN_CODES.values()),
        },
    )
    data["reason"] = ("design", result["reason"])
    for m in METRICS:
        data[m] = ("design", result[m])
    data["eta"] = (("design", "point"), result["eta"])
    data["point_status"] = (("design", "point"), result["point_status"])
    return xr.Dataset(data, coords={"design": design, "point": np.arange(ctx.n_points)})


def append(path: Path, ds: xr.Dataset, attrs: dict) -> None:
    """Append ``ds`` to the store at ``path`` (created with ``attrs`` if new)."""
    store = Path(path)
    if not (store / ".zgroup").exists():
        if store.exists():
            shutil.rmtree(store)
        ds.attrs.update(attrs)
        ds.to_zarr(store, mode="w", consolidated=False, zarr_format=2)
    else:
        ds.to_zarr(store, append_dim="design", consolidated=False, zarr_format=2)


def load(path: Path) -> xr.Dataset:
    """The whole store, sorted by design index (tasks finish in any order)."""
    ds = xr.open_zarr(path, consolidated=False).load()
    return ds.sortby("design")


def evaluated(path: Path) -> set[int]:
    """Indices of the designs already in the store (empty if there is none)."""
    store = Path(path)
    if not store.exists():
        return set()
    try:
        return set(int(i) for i in xr.open_zarr(store, consolidated=False)["design"].values)
    except (FileNotFoundError, KeyError, ValueError):
        return set()
