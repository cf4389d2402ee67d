"""Random fields of separate spherical asperities at a chosen density, for studies and benchmarks."""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from scipy.spatial import cKDTree

from .. import surfaces
from ..core.inputs import check_whole

SUMMIT_OVER_FOOTPRINT = 0.1
"""Summit height over footprint radius of the tallest cap: caps of slope about 0.2 at their edge."""
SCATTER_CLIP = 3.0
"""Summit heights are clipped at this many standard deviations from their mean."""


def random_asperity_field(count: int, *, coverage: float, nodes_per_spacing: int, height_scatter: float = 0.1,
                          seed: int = 0, max_attempts: int = 200, n: int | None = None) -> xr.DataArray:
    """``count`` identical spherical caps at random non-overlapping positions (random sequential addition)
    in a periodic unit window, with Gaussian summit scatter (clipped at 3 standard deviations).

    Parameters
    ----------
    count : int
        Number of asperities N.
    coverage : float
        Fraction of the window under the footprints of the tallest possible cap (summit at the mean
        plus :data:`SCATTER_CLIP` deviations), ``N pi r_f^2`` [1]: the exclusion discs of random sequential
        addition, which jams at 0.547, so up to about 0.5 ("nearly touching").
    nodes_per_spacing : int
        Grid nodes per mean spacing ``1 / sqrt(N)``: the grid has ``nodes_per_spacing sqrt(N)`` points
        per side.
    height_scatter : float
        Standard deviation of the summit heights over their mean [1].
    seed : int
        Random seed (positions and heights).
    n : int, optional
        Grid points per side instead (e.g. a fast FFT size at least ``nodes_per_spacing sqrt(N)``); the
        asperities do not depend on it.

    max_attempts : int
        Random placements tried per asperity before the coverage is refused.

    Returns
    -------
    xarray.DataArray
        :func:`contactlib.surfaces.spheres` heights [m], with the asperity table in ``attrs`` and
        ``coverage`` recorded.

    Raises
    ------
    ValueError
        Naming ``coverage`` (outside (0, 0.54), or too dense to place), ``height_scatter``, ``nodes_per_spacing`` or
        ``n``.
    """
    if not 0 < coverage < 0.54:
        raise ValueError(f"coverage must lie in (0, 0.54) (random sequential addition jams at 0.547), got {coverage!r}")
    check_whole(count, "count")
    if not (np.isfinite(height_scatter) and height_scatter >= 0):  # negative: every summit below the base
        raise ValueError(f"height_scatter must be finite and >= 0, got {height_scatter!r}")
    if n is None and not (np.isfinite(nodes_per_spacing) and nodes_per_spacing > 0):
        raise ValueError(f"nodes_per_spacing must be finite and > 0, got {nodes_per_spacing!r}")
    if n is not None:
        check_whole(n, "n", 2)  # grid points per side
    rng = np.random.default_rng(seed)
    footprint = math.sqrt(coverage / (math.pi * count))  # of the tallest possible cap
    tallest = SUMMIT_OVER_FOOTPRINT * footprint
    radius = (footprint**2 + tallest**2) / (2 * tallest)
    summit = tallest / (1 + SCATTER_CLIP * height_scatter)
    heights = summit * (1 + height_scatter * np.clip(rng.standard_normal(int(count)), -SCATTER_CLIP, SCATTER_CLIP))
    heights = np.clip(heights, 0.05 * summit, tallest)
    centers = _sequential_addition(int(count), 2 * footprint * (1 + 1e-9), rng, max_attempts)
    n = int(round(nodes_per_spacing * math.sqrt(count))) if n is None else int(n)
    if n < 2:
        raise ValueError(f"n must be >= 2 grid points per side, got {n!r}")
    field = surfaces.spheres(n, length=1.0, radius=radius, centers=centers, summit_height=heights)
    field.attrs.update(coverage=coverage, footprint_radius=footprint)
    return field


def _sequential_addition(count: int, distance: float, rng: np.random.Generator, max_attempts: int) -> np.ndarray:
    """Positions in the periodic unit square, each at least ``distance`` from the others."""
    accepted = np.empty((0, 2))
    batch = max(64, count)
    for _ in range(max_attempts):
        trial = rng.uniform(0, 1, size=(batch, 2))
        # candidates far from the accepted ones
        if len(accepted):
            near = cKDTree(accepted, boxsize=1.0).query(trial, distance_upper_bound=distance)[0]
            trial = trial[~np.isfinite(near)]
        # then far from each other, greedily in order
        keep = []
        tree = cKDTree(trial, boxsize=1.0) if len(trial) else None
        taken = np.zeros(len(trial), dtype=bool)
        blocked = np.zeros(len(trial), dtype=bool)
        for i in range(len(trial)):
            if blocked[i]:
                continue
            taken[i] = True
            keep.append(i)
            blocked[tree.query_ball_point(trial[i], distance)] = True
            if len(accepted) + len(keep) == count:
                break
        accepted = np.concatenate([accepted, trial[keep]])
        if len(accepted) >= count:
            return accepted[:count]
    raise ValueError(f"coverage: could not place {count} asperities {distance:.3g} apart; lower the coverage")
