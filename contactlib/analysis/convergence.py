"""Speed against error: the analysis of a ``speed_vs_error`` study's dataset
(:func:`contactlib.studies.speed_error_point`) that gave the rules of :mod:`contactlib.accuracy`: measured orders of
convergence, the tolerance's share of the error, Pareto fronts of cost against error and the cheapest settings per
target, as a markdown table."""

from __future__ import annotations

import math

import numpy as np
import xarray as xr

QUANTITIES = ("load_error", "area_error", "pressure_error", "gap_error")
"""Error variables of a ``speed_vs_error`` dataset."""


def fit_order(resolution, error) -> tuple[float, float]:
    """Least-squares fit of ``error = constant * resolution**-order`` in log-log; NaN with < 3 points.

    Parameters
    ----------
    resolution : array_like
        Resolutions (points per wavelength, radius, ...).
    error : array_like
        Relative errors at them.

    Returns
    -------
    order, constant : float
        The fitted ``p`` and ``C`` (NaN with fewer than 3 points).
    """
    r, e = np.asarray(resolution, dtype=float), np.asarray(error, dtype=float)
    ok = np.isfinite(r) & np.isfinite(e) & (e > 0)
    if ok.sum() < 3:
        return math.nan, math.nan
    slope, intercept = np.polyfit(np.log(r[ok]), np.log(e[ok]), 1)
    return float(-slope), float(np.exp(intercept))


def convergence_orders(ds: xr.Dataset, *, floor: float = 1e-12) -> xr.Dataset:
    """Fitted order and constant of every error quantity against ``resolution``, per scene and kernel,
    at the smallest tolerance of the dataset; errors below ``floor`` (round-off) are left out.

    Parameters
    ----------
    ds : xarray.Dataset
        A ``speed_vs_error`` dataset.
    floor : float
        Errors below it are left out.

    Returns
    -------
    xarray.Dataset
        ``order`` and ``constant`` per error quantity, scene and kernel.
    """
    d = ds.where(ds.status == 0).sel(tol=ds.tol.min())
    quantities = [q for q in QUANTITIES if q in ds]
    order = np.full((ds.sizes["scene"], ds.sizes["kernel"], len(quantities)), np.nan)
    constant = order.copy()
    for i, scene in enumerate(ds.scene.values):
        for j, kernel in enumerate(ds.kernel.values):
            p = d.sel(scene=scene, kernel=kernel)
            for k, q in enumerate(quantities):
                err = p[q].where(p[q] > floor)
                order[i, j, k], constant[i, j, k] = fit_order(p.resolution, err)
    coords = {"scene": ds.scene, "kernel": ds.kernel, "quantity": ("quantity", quantities,
                                                                   {"units": "1", "long_name": "error quantity"})}
    return xr.Dataset({
        "order": (("scene", "kernel", "quantity"), order,
                  {"units": "1", "long_name": "convergence order p of error = C resolution^-p"}),
        "constant": (("scene", "kernel", "quantity"), constant,
                     {"units": "1", "long_name": "constant C of error = C resolution^-p"}),
    }, coords=coords)


def tolerance_gain(ds: xr.Dataset) -> float:
    """Largest change of any error quantity caused by the tolerance, per unit tolerance: the maximum
    over points of ``|error(tol) - error(smallest tol)| / tol`` (same scene, grid and kernel).

    Parameters
    ----------
    ds : xarray.Dataset
        A ``speed_vs_error`` dataset.

    Returns
    -------
    float
        The largest change of an error per unit tolerance.
    """
    d = ds.where(ds.status == 0)
    quantities = [q for q in QUANTITIES if q in ds]
    gains = [(abs(d[q] - d[q].sel(tol=d.tol.min())) / d.tol).max() for q in quantities]
    return float(np.nanmax([float(g) for g in gains]))


def pareto_front(cost, error) -> np.ndarray:
    """Mask of the points no other point beats in both cost and error (NaN points are never on it).

    Parameters
    ----------
    cost : array_like
        Cost of each point (e.g. wall time).
    error : array_like
        Error of each point.

    Returns
    -------
    ndarray of bool
        True on the Pareto front.
    """
    c, e = np.asarray(cost, dtype=float).ravel(), np.asarray(error, dtype=float).ravel()
    mask = np.zeros(c.size, dtype=bool)
    best = math.inf
    for i in np.argsort(c, kind="stable"):
        if np.isfinite(c[i]) and np.isfinite(e[i]) and e[i] < best:
            mask[i], best = True, e[i]
    return mask.reshape(np.shape(cost))


def cheapest_settings(ds: xr.Dataset, targets, *, error: str = "max_error") -> list[dict]:
    """For each target relative error and scene, the setting with the smallest ``solve_time`` whose
    ``error`` is within the target (``n``/``tol``/``kernel`` NaN/"" when no setting reaches it).

    Parameters
    ----------
    ds : xarray.Dataset
        A ``speed_vs_error`` dataset.
    targets : sequence of float
        Target relative errors.
    error : str
        The error variable compared with the targets.

    Returns
    -------
    list of dict
        One row per target and scene: ``target``, ``scene``, ``kernel``, ``n``, ``tol``, ``solve_time``, ``error``.
    """
    rows = []
    for target in targets:
        for scene in ds.scene.values:
            d = ds.sel(scene=scene).where(ds.status.sel(scene=scene) == 0)
            s = d[[error, "solve_time"]].to_dataframe().dropna()
            hit = s[s[error] <= target]
            row = {"target": float(target), "scene": str(scene), "kernel": "", "n": math.nan, "tol": math.nan,
                   "solve_time": math.nan, "error": math.nan, "best_error": float(s[error].min())}
            if len(hit):
                best = hit["solve_time"].idxmin()
                idx = dict(zip(hit.index.names, best if isinstance(best, tuple) else (best,)))
                row.update(kernel=str(idx["kernel"]), n=int(idx["n"]), tol=float(idx["tol"]),
                           solve_time=float(hit.loc[best, "solve_time"]), error=float(hit.loc[best, error]))
            rows.append(row)
    return rows


def markdown_table(rows: list[dict]) -> str:
    """The rows of :func:`cheapest_settings` as a Markdown table.

    Parameters
    ----------
    rows : list of dict
        The rows of :func:`cheapest_settings`.

    Returns
    -------
    str
        The Markdown table.
    """
    lines = ["| target error | scene | kernel | N | tol | solve time [s] | error reached |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        if r["kernel"]:
            lines.append(f"| {r['target']:.2%} | {r['scene']} | {r['kernel']} | {r['n']} | {r['tol']:.0e} | "
                         f"{r['solve_time']:.3g} | {r['error']:.2e} |")
        else:
            lines.append(f"| {r['target']:.2%} | {r['scene']} | not reached | | | | best {r['best_error']:.2e} |")
    return "\n".join(lines) + "\n"
