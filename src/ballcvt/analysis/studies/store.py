"""The study's store: an xarray Dataset in Zarr, appended as designs finish (resumable).

Zarr format 2 (its fixed-length text and every dtype here have a published specification,
so any Zarr library reads the store).

**Commits.** An append writes the chunk's arrays (Zarr replaces every file it writes by
renaming a complete temporary file) and then commits: the manifest ``designs.commit.json``
beside the store names how many design rows are committed, the study and its content
hash, and is itself replaced atomically (temporary file, ``os.replace``). A process killed at any
instant leaves either the old or the new manifest; rows beyond the manifest (an append cut
short, arrays of different lengths) are cut off when the store is opened again, so a kill
loses at most the designs being evaluated. A store written before manifests existed is
adopted when its arrays agree in length.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import shutil
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ...errors import InputError
from .evaluate import DESIGN_CODES, METRICS

__all__ = [
    "STORE",
    "MANIFEST",
    "DesignStore",
    "chunk_dataset",
    "study_record",
    "study_hash",
    "study_changes",
]

STORE = "designs.zarr"
#: The commit record beside the store: committed design rows, the study and its hash.
MANIFEST = "designs.commit.json"
#: Keys of the study that do not change its designs (left out of its hash).
_NOT_HASHED = (("study", "chunk"),)


def study_record(spec) -> dict:
    """The study as plain JSON data (what the store keeps in its ``spec`` attribute)."""
    return spec.model_dump(mode="json")


def _hashed(record: dict) -> dict:
    rec = json.loads(json.dumps(record))
    for table, key in _NOT_HASHED:
        if isinstance(rec.get(table), dict):
            rec[table].pop(key, None)
    return rec


def study_hash(record: dict) -> str:
    """SHA-256 of the study's canonical JSON (sorted keys; ``study.chunk`` left out)."""
    text = json.dumps(_hashed(record), sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()


def study_changes(old: dict, new: dict, prefix: str = "") -> list[str]:
    """Dotted keys whose values differ between two study records (``operating.ratio``)."""
    out = []
    for key in sorted(set(old) | set(new)):
        name = f"{prefix}{key}"
        a, b = old.get(key), new.get(key)
        if isinstance(a, dict) and isinstance(b, dict):
            out += study_changes(a, b, name + ".")
        elif a != b:
            out.append(name)
    return out


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


def _open_group(path: Path):
    import zarr

    if int(zarr.__version__.split(".")[0]) >= 3:
        return zarr.open_group(str(path), mode="r+", zarr_format=2)
    return zarr.open_group(str(path), mode="r+")  # pragma: no cover (zarr 2)


@dataclass
class DesignStore:
    """The Zarr store of a study's designs, committed append by append.

    Attributes
    ----------
    path : Path
        The store (``designs.zarr``).
    rows : int
        Committed design rows.
    record : dict or None
        The stored study (`study_record`), None for a new store.
    """

    path: Path
    rows: int = 0
    record: dict | None = field(default=None, repr=False)

    @property
    def manifest(self) -> Path:
        """The commit record beside the store (``designs.commit.json``)."""
        return self.path.with_name(MANIFEST)

    def open(self) -> set[int]:
        """Read the committed designs, repairing what an interrupted append left.

        Returns the indices of the committed designs (empty for a new store).

        Raises
        ------
        InputError
            If the store was torn by an older ballcvt (no manifest, arrays of different
            lengths) or is not a study store.
        """
        self.rows, self.record = 0, None
        if not self.path.exists():
            return set()
        try:
            commit = json.loads(self.manifest.read_text())
            rows, record = int(commit["designs"]), commit["spec"]
        except FileNotFoundError:
            return self._adopt()
        except (ValueError, KeyError, TypeError):
            raise self._refuse("its commit record cannot be read") from None
        for tmp in self.path.parent.glob(f".{MANIFEST}.*.partial"):
            tmp.unlink(missing_ok=True)  # a commit killed before its rename
        if rows == 0:  # the first chunk was killed before its commit
            return set()
        self.rows, self.record = rows, record
        self._repair(rows)
        return set(int(i) for i in self._dataset()["design"].values)

    def _adopt(self) -> set[int]:
        """A store of an older ballcvt (no manifest): adopted if its arrays agree in length.

        Its study is known only if it was written in one chunk (appends dropped the
        attributes); unknown, it is not checked on resume."""
        try:
            ds = xr.open_zarr(self.path, consolidated=False)
            self.rows = int(ds.sizes["design"])
        except (OSError, ValueError, KeyError):
            raise self._refuse("its arrays differ in length: torn by an interrupted run") from None
        self.record = json.loads(ds.attrs["spec"]) if "spec" in ds.attrs else None
        self._commit()
        return set(int(i) for i in ds["design"].values)

    def _refuse(self, why: str) -> InputError:
        return InputError(
            "out",
            str(self.path.parent),
            "a folder without a study, or a study store ballcvt can read",
            message=f"{self.path}: not a readable study store ({why}); choose another --out",
        )

    def _repair(self, rows: int) -> None:
        """Cut every design array to the committed ``rows``; remove partial files."""
        for tmp in self.path.rglob("*.partial"):
            with contextlib.suppress(OSError):
                tmp.unlink()
        group = _open_group(self.path)
        for _, arr in group.arrays():
            dims = arr.attrs.get("_ARRAY_DIMENSIONS", [])
            if dims[:1] == ["design"] and arr.shape[0] < rows:
                raise self._refuse(f"{arr.name} holds fewer designs than committed")
            if dims[:1] == ["design"] and arr.shape[0] > rows:
                arr.resize((rows,) + tuple(arr.shape[1:]))

    def _dataset(self) -> xr.Dataset:
        ds = xr.open_zarr(self.path, consolidated=False)
        return ds.isel(design=slice(0, self.rows)) if self.rows else ds

    def _commit(self) -> None:
        """Replace the manifest atomically: it names the committed rows and the study."""
        record = self.record
        text = json.dumps(
            {
                "format": 1,
                "designs": self.rows,
                "study_hash": study_hash(record) if record is not None else None,
                "spec": record,
            }
        )
        tmp = self.manifest.with_name(f".{MANIFEST}.{os.getpid()}.partial")
        tmp.write_text(text)
        os.replace(tmp, self.manifest)

    def append(self, ds: xr.Dataset, attrs: dict) -> None:
        """Append ``ds`` (the store created with ``attrs`` if new), then commit its rows."""
        record = json.loads(attrs["spec"])
        ds.attrs.update(attrs, study_hash=study_hash(record))  # an append replaces them
        if self.record is None:  # a new store, or an adopted one of an older ballcvt
            self.record = record
        if self.rows == 0:
            self._commit()  # zero rows: whatever the store holds is not committed
            if self.path.exists():
                shutil.rmtree(self.path)
            ds.to_zarr(self.path, mode="w", consolidated=False, zarr_format=2)
        else:
            ds.to_zarr(self.path, append_dim="design", consolidated=False, zarr_format=2)
        self.rows += int(ds.sizes["design"])
        self._commit()

    def load(self) -> xr.Dataset:
        """The committed designs, sorted by design index (tasks finish in any order)."""
        return self._dataset().load().sortby("design")
