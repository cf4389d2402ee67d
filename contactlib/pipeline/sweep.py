"""Fan a pure point function out over a parameter grid and combine the points into one labelled Dataset.

The library knows nothing of Snakemake: :func:`run_grid` takes a function, a grid of parameter
values and (optionally) a ``distributed.Client``; every point is one task. A point that fails with
:class:`contactlib.ConvergenceError` or ``ValueError`` is recorded with a ``status`` code, its
``residual`` and NaN values; the rest of the sweep goes on. Finished points are checkpointed one
small file each (temporary name, then ``os.replace``), so an interrupted sweep resumes where it
stopped and gives the same Dataset as an uninterrupted one (``wall_time`` aside).

Every task imports the parent's FFTW wisdom and runs single-threaded FFTs, so a point computes the
same bits whichever worker (or the parent itself) runs it.
"""

from __future__ import annotations

import contextlib
import datetime
import hashlib
import json
import logging
import math
import os
import pickle
import subprocess
import sys
import time
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path

import numpy as np
import xarray as xr

from ..core import fft
from .. import resolution
from .._version import __version__
from ..errors import ConvergenceError
from ..core.labels import VARIABLES

log = logging.getLogger(__name__)

STATUS_OK, STATUS_NOT_CONVERGED, STATUS_BAD_INPUT = 0, 1, 2

SWEEP_VARIABLES: dict[str, dict[str, str]] = {
    "status": {"units": "1", "long_name": "point status: 0 ok, 1 not converged, 2 bad input"},
    "wall_time": {"units": "s", "long_name": "wall-clock time of the point"},
    "residual": VARIABLES["residual"],
    "seed": {"units": "1", "long_name": "random seed of the surface"},
    "n": {"units": "1", "long_name": "grid points per side"},
    "predicted_resolution_error": {"units": "1", "long_name": "largest contact-area or pressure error the measured "
                                   "resolution rules predict for the point's solves (contactlib.resolution)"},
}

_worker_wisdom: dict[str, str] = {}


def point_key(params: Mapping, fingerprint: str = "") -> str:
    """Stable hex digest of one point's parameters (and the study ``fingerprint``)."""
    text = json.dumps({"fingerprint": fingerprint, "params": {k: _plain(v) for k, v in params.items()}},
                      sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:24]


def _plain(v):
    return v.item() if isinstance(v, np.generic) else v


def _prepare_worker(wisdom, threads: int) -> None:
    """Single-threaded FFTs and the parent's plans, once per process."""
    fft.set_fft_options(threads=threads)
    if wisdom is None:
        return
    digest = hashlib.sha256(b"".join(wisdom)).hexdigest()
    if _worker_wisdom.get("digest") != digest:
        fft.import_wisdom(wisdom)  # over the on-disk cache: the parent's plans are the last word
        _worker_wisdom["digest"] = digest


def evaluate_point(point_fn: Callable, params: dict, wisdom=None, threads: int = 1, **extra) -> dict:
    """Run one point, turning the expected failures into a status code (runs on a worker).

    Outputs whose names start with ``_`` (e.g. ``_warm_start``) are returned apart, under ``"private"``. The
    resolution guard's warnings of the point's solves are recorded, not printed: the largest prediction is the
    output ``predicted_resolution_error`` (:func:`contactlib.resolution.recording`; :func:`run_grid` sums them up
    in one line).
    """
    _prepare_worker(wisdom, threads)
    start = time.perf_counter()
    values, message = {}, ""
    try:
        with resolution.recording() as seen:
            values = dict(point_fn(**params, **extra))
        if seen:
            values["predicted_resolution_error"] = max(r.predicted_error for r in seen)
        status = STATUS_OK
        residual = float(values.pop("residual", math.nan))
    except ConvergenceError as err:
        status, residual, message = STATUS_NOT_CONVERGED, float(err.residual), str(err)
    except ValueError as err:
        status, residual, message = STATUS_BAD_INPUT, math.nan, str(err)
    private = {k: values.pop(k) for k in [k for k in values if k.startswith("_")]}
    return {"params": dict(params), "values": values, "status": status, "residual": residual,
            "wall_time": time.perf_counter() - start, "message": message, "private": private}


def evaluate_task(point_fn: Callable, points: list[dict], wisdom=None, threads: int = 1,
                  warm_start: bool = False) -> list[dict]:
    """Run the points of one task in order; along a load path each point starts from the last converged
    ``_warm_start`` output (passed as ``initial_pressure``)."""
    results, state = [], None
    for params in points:
        extra = {"initial_pressure": state} if warm_start and state is not None else {}
        result = evaluate_point(point_fn, params, wisdom, threads, **extra)
        if result["status"] == STATUS_OK:
            state = result["private"].get("_warm_start", state)
        result.pop("private")
        results.append(result)
    return results


def _write_atomic(path: Path, write: Callable[[Path], None]) -> None:
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        write(tmp)
        os.replace(tmp, path)
    finally:
        with contextlib.suppress(FileNotFoundError):
            tmp.unlink()


def _save_checkpoint(directory: Path, key: str, result: dict) -> None:
    def write(tmp):
        with open(tmp, "wb") as f:
            pickle.dump(result, f, protocol=pickle.HIGHEST_PROTOCOL)
    _write_atomic(directory / f"{key}.pkl", write)


def _load_checkpoint(directory: Path, key: str):
    path = directory / f"{key}.pkl"
    try:
        with open(path, "rb") as f:
            return pickle.load(f)
    except (OSError, EOFError, pickle.UnpicklingError):
        return None


def grid_points(grid: Mapping[str, Iterable]) -> tuple[dict[str, np.ndarray], list[dict]]:
    """Sorted unique coordinate values per swept name, and every point of their product (C order)."""
    coords = {}
    for name, values in grid.items():
        values = np.unique(np.asarray(list(values)))
        if values.size == 0:
            raise ValueError(f"grid: {name!r} has no values")
        coords[name] = values
    names = list(coords)
    points = [dict(zip(names, (_plain(v) for v in combo)))
              for combo in np.array(np.meshgrid(*coords.values(), indexing="ij"), dtype=object)
              .reshape(len(names), -1).T]
    return coords, points


class Progress:
    """Per-point log line with elapsed time and ETA, written to ``stream`` (or passed to a callable)."""

    def __init__(self, total: int, sink=True):
        self.total, self.done, self.start = total, 0, time.perf_counter()
        self.sink = sink

    def __call__(self, result: dict, cached: bool = False) -> None:
        self.done += 1
        elapsed = time.perf_counter() - self.start
        eta = elapsed / self.done * (self.total - self.done)
        params = " ".join(f"{k}={v:g}" if isinstance(v, float) else f"{k}={v}" for k, v in result["params"].items())
        state = ("cached" if cached else ("ok", "not converged", "bad input")[result["status"]])
        if result["status"] and result.get("message"):
            state += f" ({result['message'][:120]})"
        line = (f"[{self.done}/{self.total}] {params} {state} {result['wall_time']:.2f} s | "
                f"elapsed {elapsed:.1f} s, ETA {eta:.1f} s")
        if callable(self.sink):
            self.sink(line)
        elif self.sink:
            print(line, file=sys.stderr, flush=True)


def run_grid(
    point_fn: Callable[..., Mapping],
    grid: Mapping[str, Iterable],
    *,
    client=None,
    checkpoint_dir: str | os.PathLike | None = None,
    fingerprint: str = "",
    fft_shapes: Iterable[tuple[int, ...]] = (),
    labels: Mapping[str, Mapping[str, str]] | None = None,
    attrs: Mapping | None = None,
    progress: bool | Callable[[str], None] = True,
    path_dim: str | None = None,
    group_dims: Iterable[str] = (),
) -> xr.Dataset:
    """Evaluate ``point_fn(**point)`` at every point of ``grid`` and combine into one Dataset.

    Parameters
    ----------
    point_fn : callable
        Pure function of the swept parameters (bind constants with ``functools.partial``), returning
        a mapping of scalars and, optionally, small ``xarray.DataArray`` fields. Must be importable
        (or picklable) where the tasks run.
    grid : mapping name -> values
        Swept parameters; each becomes a sorted 1-D coordinate and a dimension, in this order.
    client : distributed.Client, optional
        Run one task per point on this client; ``None`` runs the points here, one after another.
    checkpoint_dir : path, optional
        One file per finished task (point or path); tasks found there are loaded, not recomputed.
    fingerprint : str
        Anything that changes what a point computes (the study's config); part of each point's key.
    fft_shapes : iterable of shapes
        FFT shapes the points use: planned here once, and the wisdom shipped with every task.
    labels : mapping name -> {"units", "long_name"}
        Labels of the point's outputs and swept names; together with :data:`SWEEP_VARIABLES`
        they must cover every variable and coordinate, or ``KeyError`` is raised.
    attrs : mapping
        Global attributes (``title``, ``source``, ``config``, ...); provenance is added.
    progress : bool or callable
        Per-point log line with ETA on stderr (``True``), to a callable, or none.
    path_dim : str, optional
        A swept name (e.g. a load) to walk as a path: one task per combination of the other names,
        its points in increasing ``path_dim``, each warm-started from the previous converged point
        (``point_fn`` must accept ``initial_pressure`` and return ``_warm_start``). Checkpoints are
        then per path. Without it, one task and one checkpoint per point.
    group_dims : iterable of str, optional
        Swept names whose points share one task (run in order, no warm start): the points that differ
        only in these names run in one process, one after another, so an in-process cache (e.g. a
        reference solution shared by every tolerance and kernel) is computed once per task.
        Checkpoints are then per group. Not together with ``path_dim``.

    Returns
    -------
    xarray.Dataset with dims = the swept names (+ the fields' own dims), ``status``, ``residual``,
    ``wall_time`` and the point outputs; where the points called the library's entry points,
    ``predicted_resolution_error`` (the resolution guard's prediction, recorded instead of warned,
    :func:`evaluate_point`) and, where some point's exceeds 1 %, ``attrs['resolution_summary']``, the one line
    also logged (logger ``contactlib.pipeline.sweep``, WARNING).

    Examples
    --------
    >>> import contactlib.pipeline.sweep as sw
    >>> ds = sw.run_grid(lambda a, b: {"c": a * b}, {"a": [1.0, 2.0], "b": [3.0]}, progress=False,
    ...                  labels={"a": {"units": "1", "long_name": "a"}, "b": {"units": "1", "long_name": "b"},
    ...                          "c": {"units": "1", "long_name": "a b"}})
    >>> ds.c.values.tolist()
    [[3.0], [6.0]]
    """
    coords, points = grid_points(grid)
    keys = [point_key(p, fingerprint) for p in points]
    if len(set(keys)) != len(keys):
        raise ValueError("grid: duplicate points")
    group_dims = tuple(group_dims)
    if path_dim is not None and group_dims:
        raise ValueError("give path_dim or group_dims, not both")
    tasks = _tasks(points, keys, path_dim, fingerprint) if not group_dims else _groups(points, keys, group_dims,
                                                                                        fingerprint)
    checkpoint_dir = None if checkpoint_dir is None else Path(checkpoint_dir)
    report = Progress(len(points), progress)
    results: dict[str, dict] = {}
    todo = []
    for task_key, members in tasks.items():
        cached = None if checkpoint_dir is None else _load_checkpoint(checkpoint_dir, task_key)
        if cached is None or len(cached) != len(members):
            todo.append((task_key, members))
            continue
        for (key, _), result in zip(members, cached):
            results[key] = result
            report(result, cached=True)
    threads = fft.fft_options()["threads"]
    for shape in fft_shapes:
        fft.get_fft(tuple(shape))
    wisdom = fft.export_wisdom()
    warm = path_dim is not None

    def finish(task_key, members, task_results):
        if checkpoint_dir is not None:
            _save_checkpoint(checkpoint_dir, task_key, task_results)
        for (key, _), result in zip(members, task_results):
            results[key] = result
            report(result)

    if client is None:
        for task_key, members in todo:
            finish(task_key, members, evaluate_task(point_fn, [p for _, p in members], wisdom, threads, warm))
    elif todo:
        from distributed import as_completed

        futures = {client.submit(evaluate_task, point_fn, [p for _, p in members], wisdom, 1, warm,
                                 key=f"contactlib-task-{task_key}", pure=False): (task_key, members)
                   for task_key, members in todo}
        for future in as_completed(futures):
            finish(*futures[future], future.result())
            future.release()
    ds = combine(coords, [results[k] for k in keys], labels=labels, attrs=attrs)
    summary = resolution_summary(ds)
    if summary:  # one line for the sweep, where each point's solves would have warned
        ds.attrs["resolution_summary"] = summary
        log.warning("%s%s", f"{ds.attrs['study']}: " if "study" in ds.attrs else "", summary)
    return ds


def resolution_summary(ds: xr.Dataset) -> str:
    """One line on the points whose predicted resolution error exceeds :data:`contactlib.resolution.THRESHOLD`
    (empty where none does, or none was measured)."""
    if "predicted_resolution_error" not in ds:
        return ""
    error = ds["predicted_resolution_error"].values
    measured = np.isfinite(error)
    over = measured & (error > resolution.THRESHOLD)
    if not over.any():
        return ""
    return (f"resolution: {int(over.sum())} of {int(measured.sum())} points predict more than "
            f"{resolution.THRESHOLD:.0%} error in the contact area or pressure (up to {float(np.nanmax(error)):.1%}, "
            "variable predicted_resolution_error; contactlib.resolution)")


def _tasks(points: list[dict], keys: list[str], path_dim: str | None, fingerprint: str) -> dict:
    """Task key -> [(point key, params)], one point per task or one load path per task."""
    if path_dim is None:
        return {key: [(key, params)] for key, params in zip(keys, points)}
    if path_dim not in points[0]:
        raise ValueError(f"path_dim {path_dim!r} is not a swept name")
    paths: dict[str, list] = {}
    for key, params in zip(keys, points):
        rest = {k: v for k, v in params.items() if k != path_dim}
        paths.setdefault(point_key(rest, f"{fingerprint}|path:{path_dim}"), []).append((key, params))
    return {k: sorted(v, key=lambda kp: kp[1][path_dim]) for k, v in paths.items()}


def _groups(points: list[dict], keys: list[str], group_dims: tuple[str, ...], fingerprint: str) -> dict:
    """Task key -> [(point key, params)], one task per combination of the names not in ``group_dims``."""
    missing = [d for d in group_dims if d not in points[0]]
    if missing:
        raise ValueError(f"group_dims {missing} are not swept names")
    groups: dict[str, list] = {}
    for key, params in zip(keys, points):
        rest = {k: v for k, v in params.items() if k not in group_dims}
        groups.setdefault(point_key(rest, f"{fingerprint}|group:{','.join(group_dims)}"), []).append((key, params))
    return groups


def combine(coords: Mapping[str, np.ndarray], results: list[dict], *, labels=None, attrs=None) -> xr.Dataset:
    """Stack point results (in C order of ``coords``) into arrays; NaN where a point failed."""
    table = {**SWEEP_VARIABLES, **(labels or {})}
    dims = tuple(coords)
    shape = tuple(len(v) for v in coords.values())
    templates: dict[str, object] = {}
    for r in results:
        for name, value in r["values"].items():
            templates.setdefault(name, value)
    data = {}
    for name, template in templates.items():
        if isinstance(template, xr.DataArray):
            blank = xr.full_like(template, np.nan, dtype=float)
            stacked = xr.concat([r["values"].get(name, blank).astype(float) for r in results], dim="_point")
            values = stacked.values.reshape(shape + template.shape)
            field_coords = {d: template[d] for d in template.dims if d in template.coords}
            data[name] = xr.DataArray(values, dims=dims + template.dims, coords=field_coords)
        else:
            values = np.array([float(r["values"].get(name, np.nan)) for r in results]).reshape(shape)
            data[name] = xr.DataArray(values, dims=dims)
    data["residual"] = xr.DataArray(np.array([r["residual"] for r in results], dtype=float).reshape(shape), dims=dims)
    data["status"] = xr.DataArray(np.array([r["status"] for r in results], dtype=np.int8).reshape(shape), dims=dims)
    data["wall_time"] = xr.DataArray(np.array([r["wall_time"] for r in results]).reshape(shape), dims=dims)
    ds = xr.Dataset(data, coords={name: (name, values) for name, values in coords.items()})
    missing = sorted(n for n in list(ds.data_vars) + list(ds.coords) if n not in table and not ds[n].attrs.get("units"))
    if missing:
        raise KeyError(f"no units/long_name declared for {missing}: add them to labels=")
    for name in list(ds.data_vars) + list(ds.coords):
        if name in table:
            ds[name].attrs.update({"units": table[name]["units"], "long_name": table[name]["long_name"]})
    ds["status"].attrs.update({"flag_values": np.array([0, 1, 2], dtype=np.int8),
                               "flag_meanings": "ok not_converged bad_input"})
    ds.attrs.update(provenance(attrs or {}))
    return ds


def git_revision(path: str | os.PathLike | None = None) -> str:
    """``git describe --always --dirty`` of the source tree, or ``"unknown"``."""
    where = Path(path) if path else Path(__file__).resolve().parent
    try:
        out = subprocess.run(["git", "describe", "--always", "--dirty", "--abbrev=40"], cwd=where,
                             capture_output=True, text=True, timeout=10, check=True)
        return out.stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def provenance(attrs: Mapping) -> dict:
    """Global CF attributes: the caller's plus version, git revision, creation time and history."""
    now = datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds")
    out = {"title": "contactlib parameter sweep", "source": f"contactlib {__version__}", "Conventions": "CF-1.10"}
    out.update({k: (json.dumps(v, sort_keys=True) if isinstance(v, (dict, list)) else v) for k, v in attrs.items()})
    out.update({"contactlib_version": __version__, "git_revision": git_revision(), "date_created": now,
                "history": f"{now} created by contactlib.pipeline.sweep.run_grid"})
    return out


def write_netcdf(ds: xr.Dataset, path: str | os.PathLike, *, sweep_dims: Iterable[str] = ()) -> Path:
    """Write ``ds`` to ``path`` atomically (temporary name, then rename); fields compressed and
    chunked one point per chunk."""
    sweep_dims = set(sweep_dims)
    encoding = {}
    for name, var in ds.data_vars.items():
        if var.ndim > 0 and any(d not in sweep_dims for d in var.dims) and sweep_dims:
            chunks = tuple(1 if d in sweep_dims else var.sizes[d] for d in var.dims)
            encoding[name] = {"zlib": True, "complevel": 4, "chunksizes": chunks}
    path = Path(path)
    _write_atomic(path, lambda tmp: ds.to_netcdf(tmp, encoding=encoding, engine="netcdf4"))
    return path
