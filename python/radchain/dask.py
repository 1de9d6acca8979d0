"""radchain on a dask.distributed cluster: a sweep grid or a catalogue split into shards, one task per shard, joined
by the batch path's merge (docs/python.md, "Dask"; docs/batch.md, "How a job is split").

    from distributed import Client
    import radchain.dask
    client = Client("tcp://scheduler:8786")            # or Client(LocalCluster(...))
    df = radchain.dask.sweep(client, "sensors/msx-sbv.toml", {"optics.aperture": "15 cm:30 cm:100000"},
                             results=["target.magnitude"])
    cat = radchain.dask.catalogue(client, ["sensors/"])

Each task runs `radchain sweep … --shard k/n` (or `catalogue`) in the worker through the module and returns the
shard file's bytes; the client merges them (`radchain merge`) into exactly what the unsharded job writes, rows in
point order. The workers need the module and the sensor files (and their spectra) at the same absolute paths as the
client: a shared filesystem or the same container image.
"""
from __future__ import annotations

import io as _io
import os as _os
import tempfile as _tempfile
import warnings as _warnings

import numpy as _np

from . import _catalogue_frame, _name, _names, _no_nul, _pandas, _path, _radchain, _split_sets

__all__ = ["sweep", "catalogue"]


def _catalogue_shard(inputs, sets, results, no_solve, shard, order):
    table, _errors, _code = _radchain.catalogue(inputs, sets, results, no_solve, shard, order)
    return table.encode(), ""


def _sweep_shard(path, sets, axes, results, no_solve, allow_large, shard, order):
    table, failure, _code, _method, units = _radchain.sweep_table(path, sets, axes, results, no_solve, "npy", shard,
                                                                   order, allow_large, True)
    return table, failure, units


def _texts_only(set, call):
    texts, numbers = _split_sets(set)
    if numbers:
        raise TypeError(f"{call}(set=...) takes TOML value text, as --set does")
    return texts


def _run_sharded(client, task, args, shards, order, format):
    """One task per shard k/n (1 <= k <= n) of the same job; the shard files merged in point order.
    Returns (merged bytes, exit code, the failure messages of the shards in shard order, the first shard's answer)."""
    if shards is None:
        shards = max(1, len(client.scheduler_info()["workers"]))
    shards = int(shards)
    if shards < 1:
        raise ValueError(f"shards = {shards}: give at least 1")
    futures = [client.submit(task, *args, f"{k}/{shards}", order, pure=False) for k in range(1, shards + 1)]
    parts = client.gather(futures)
    with _tempfile.TemporaryDirectory(prefix="radchain-shards-") as folder:
        files = []
        for k, (table, *_rest) in enumerate(parts, start=1):
            files.append(_os.path.join(folder, f"part-{k}-of-{shards}.csv"))
            with open(files[-1], "wb") as f:
                f.write(table)
        merged, code = _radchain.merge(files, format)
    return merged, code, [part[1] for part in parts if part[1]], parts[0]


def sweep(client, path, axes: dict, set: dict | None = None, results=None, solve: bool = True, shards: int | None = None,
          order: str = "block", allow_large: bool = False):
    """`radchain sweep path --set key=from:to:steps …` over the cluster: radchain.grid's DataFrame, bit for bit (the
    grid points in point order, the last axis varying fastest; columns in SI under their bare names, their units in
    df.attrs["units"]).

    axes: {"<section>.<key>": "from:to:steps"} (e.g. "15 cm:30 cm:1000"), the first outermost. set: fixed values,
    TOML text. shards: how many tasks (default: one per worker); order: "block" or "round-robin" (--shard-order).
    A grid of more than 10^8 points is refused unless allow_large=True (--allow-large), more than 10^10 always.
    df.attrs["exit_code"] is the command's (1: a solve failed at some point, NaN there; a RuntimeWarning says where).
    """
    if not axes:
        raise ValueError("sweep: give at least one axis, e.g. {\"optics.aperture\": \"15 cm:30 cm:16\"}")
    if isinstance(results, str):
        results = [results]
    args = (_os.path.abspath(_path(path)), _texts_only(set, "sweep"),
            [(_name(k, "an axis key"), _no_nul(str(v), "an axis")) for k, v in axes.items()], _names(results), not solve,
            bool(allow_large))
    merged, code, failures, (_table, _failure, units) = _run_sharded(client, _sweep_shard, args, shards, order, "npy")
    if failures:
        _warnings.warn(f"radchain sweep: {failures[0]}", RuntimeWarning, stacklevel=2)
    # (radchain's own bytes: a wide table's header may exceed np.load's default 10000-byte guard against hostile files)
    df = _pandas().DataFrame(_np.load(_io.BytesIO(merged), max_header_size=len(merged)))
    df.attrs["units"] = dict(zip(df.columns, units))
    df.attrs["exit_code"] = code
    return df


def catalogue(client, inputs, set: dict | None = None, results=None, solve: bool = True, shards: int | None = None,
              order: str = "block"):
    """radchain.catalogue(inputs, …) over the cluster, one task per shard of the sensor files: the same DataFrame
    (sensor, instrument, result, kind, computed, reference, tolerance, unit, delta, delta_pct, check, note; attrs exit_code, errors, summary).
    shards: how many tasks (default: one per worker); order: "block" or "round-robin"."""
    if isinstance(inputs, str):
        inputs = [inputs]
    args = ([_os.path.abspath(_path(i)) for i in inputs], _texts_only(set, "catalogue"), _names(results), not solve)
    merged, code, _failures, _first = _run_sharded(client, _catalogue_shard, args, shards, order, "json")
    return _catalogue_frame(merged.decode(), None, code)
