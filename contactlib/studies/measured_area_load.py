"""The ``measured_area_load`` study: contact area against load of a measured topography, read once by
:func:`contactlib.surfaces.read` into a labelled NetCDF surface, each load path walked with warm starts."""

from __future__ import annotations

import functools
import os

import numpy as np
import xarray as xr

from .. import analysis
from ..analysis.friction import directional_slope
from ..core.inputs import in_solver_axes
from ..problems.contact import solve
from ..model.materials import contact_modulus

VARIABLES: dict[str, dict[str, str]] = {
    "penetration": {"units": "m", "long_name": "rigid approach from first contact"},
    "kappa": {"units": "1", "long_name": "area-load coefficient A/A0 / (p/(E* rms slope))"},
}
"""Labels of the study's own names (the shared ones are in :data:`contactlib.studies._common.COMMON_VARIABLES`)."""

PROVENANCE = ("source_file", "source_sha256", "source_format", "source_reader", "height_unit", "length", "periodic",
              "detrend", "fill", "filled_points")
"""The surface's attrs that each dataset of the study carries: what was read and how it was prepared."""


def measured_surface(surface_file: str) -> xr.DataArray:
    """The prepared surface (``height`` [m], NetCDF written from :func:`contactlib.surfaces.read`); read once
    per process and file version, as every load of a path reads it."""
    return _load(str(surface_file), os.stat(surface_file).st_mtime_ns)


@functools.lru_cache(maxsize=4)
def _load(surface_file: str, version: int) -> xr.DataArray:
    return xr.load_dataarray(surface_file)


def rms_gradient(heights: xr.DataArray) -> float:
    """Rms slope [1]: spectral on a periodic window, central differences on a non-periodic one (whose
    spectrum would count the jump across the window's edges as slope)."""
    if heights.attrs["periodic"]:
        return analysis.rms_slope(heights)
    heights = in_solver_axes(heights)  # x and y by name: the angles below are from x
    lengths = tuple(float(heights[d][1] - heights[d][0]) * heights.sizes[d] for d in heights.dims)
    squares = sum(directional_slope(heights.values, lengths=lengths, direction=angle, periodic=False) ** 2
                  for angle in (0.0, np.pi / 2)[: heights.ndim])
    return float(np.sqrt(np.mean(squares)))


def measured_area_load_point(*, surface_file: str, reduced_pressure: float, E: float, nu: float, tol: float,
                             max_iter: int, kernel: str, initial_pressure=None) -> dict:
    """Contact area at mean pressure ``reduced_pressure * E* * rms slope`` on the surface in ``surface_file``,
    periodic or not as its ``attrs['periodic']`` says (a non-periodic window whose contact reaches its edge
    is refused by :func:`contactlib.solve`, a failed point of status 2)."""
    h = measured_surface(surface_file)
    slope = rms_gradient(h)
    out = solve(h, E=E, nu=nu, mean_pressure=reduced_pressure * contact_modulus(E, nu) * slope, tol=tol,
                max_iter=max_iter, kernel=kernel, initial_pressure=initial_pressure)
    area = float(out.contact_area)
    return {"contact_area": area, "mean_pressure": float(out.mean_pressure), "penetration": float(out.penetration),
            "iterations": float(out.iterations), "residual": float(out.residual), "rms_slope": slope,
            "kappa": area / reduced_pressure, "_warm_start": out.pressure}


def measured_area_load_shapes(grid: dict, constants: dict) -> list[tuple[int, ...]]:
    """FFT shapes: the surface's grid, zero-padded to twice its size when it is not periodic."""
    h = measured_surface(constants["surface_file"])
    return [tuple(h.shape) if h.attrs["periodic"] else tuple(2 * n for n in h.shape)]


def measured_area_load_attrs(constants: dict) -> dict:
    """The dataset's provenance: the measured file (name, checksum, format) and its preparation."""
    attrs = measured_surface(constants["surface_file"]).attrs
    return {key: np.asarray(attrs[key]).tolist() for key in PROVENANCE if key in attrs}  # NetCDF's numpy -> plain


STUDY = {"point": measured_area_load_point, "fft_shapes": measured_area_load_shapes, "path_dim": "reduced_pressure",
         "dataset_attrs": measured_area_load_attrs, "per_surface": True}
"""This study's entry of :data:`contactlib.studies.STUDIES` (``per_surface``: one dataset per configured file)."""
