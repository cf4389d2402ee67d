"""The parametric studies: one module per study, each a pure point function plus its variable labels.

A point function takes the swept parameters and the study's constants as keywords (bind the
constants with ``functools.partial``), calls only the public API and returns scalars (and, on
request, small labelled fields). :data:`STUDIES` maps a study name to its point function, the FFT
shapes it plans, and optionally ``path_dim`` (a load path walked with warm starts) or ``group_dims``
(names whose points share one task and its in-process caches, e.g. the rough reference of
``speed_vs_error``), ``ladder_dim``: a swept name whose values are also passed whole as
``<name>_ladder`` (``speed_vs_error`` solves once for every ``tol``), ``surface_keys`` (the
parameters of the seeded surfaces the workflow writes beside the study), ``dataset_attrs`` (a function of
the constants giving attrs the dataset carries and the checkpoints depend on, e.g. a measured file's
checksum) and ``per_surface`` (one dataset per measured surface file listed in the study's config).

Adding a study: write ``contactlib/studies/<name>.py`` exposing ``STUDY`` (its entry of
:data:`STUDIES`: at least ``point`` and ``fft_shapes``) and ``VARIABLES`` (labels of the names only
it takes or returns; the shared ones are in :data:`contactlib.studies._common.COMMON_VARIABLES`), and add ``<name>``
to :data:`STUDY_MODULES`. The module's name is the study's name, as in ``workflow/config.yaml``.

The names re-exported here (``area_load_point``, ``REFERENCE_MAX_ITER``, ...) are the modules' own
objects; a module reads its constants from its own namespace, so patch them there
(``contactlib.studies.speed_vs_error.REFERENCE_MAX_ITER``), not here.
"""

from __future__ import annotations

import importlib
import inspect
import itertools

import numpy as np
import xarray as xr

from .. import accuracy
from ..pipeline.sweep import SWEEP_VARIABLES
from ._common import COMMON_VARIABLES, rough_surface
from .anisotropy import anisotropy_point
from .area_load import PERSSON_KAPPA, PUBLISHED_KAPPA_RANGE, area_load_point
from .fig5_friction_area import friction_area_point
from .fig6a_interlocking import interlocking_point
from .measured_area_load import measured_area_load_point
from .speed_vs_error import (REFERENCE_FLOOR, REFERENCE_MAX_ITER, SCENES, rough_master, rough_reference,
    speed_error_point, speed_error_shapes)
from .two_scale import two_scale_point
from .validation import validation_point

STUDY_MODULES = ("validation", "area_load", "anisotropy", "speed_vs_error", "fig5_friction_area",
                 "fig6a_interlocking", "measured_area_load", "fig2_viscoelastic_map", "fig3_anisotropy_polar",
                 "fig6b_viscoelastic_layer", "friction_speed", "two_scale", "fig4_adhesive_layers", "adhesive_rough",
                 "viscoelastic_transient", "reciprocating", "two_scale_transient")
"""The study modules of this package, in registry order; each module's name is its study's name."""


def _registry(names) -> tuple[dict[str, dict], dict[str, dict[str, str]]]:
    """:data:`STUDIES` and :data:`STUDY_VARIABLES` from the ``STUDY`` and ``VARIABLES`` of each module.

    A name labelled twice must be labelled alike: the labels are one table for every study.
    """
    studies, variables = {}, dict(COMMON_VARIABLES)
    for name in names:
        module = importlib.import_module(f"{__name__}.{name}")
        studies[name] = module.STUDY
        for key, label in module.VARIABLES.items():
            if variables.setdefault(key, label) != label:
                raise ValueError(f"study {name!r} labels {key!r} as {label}, another as {variables[key]}")
    return studies, variables


# study name -> its entry (point, fft_shapes, ...); variable name -> units, long_name, for every study
STUDIES, STUDY_VARIABLES = _registry(STUDY_MODULES)

__all__ = ["STUDIES", "STUDY_VARIABLES", "STUDY_MODULES", "add_error_estimate", "study_surfaces", "rough_surface",
           "validation_point", "area_load_point", "anisotropy_point", "speed_error_point", "speed_error_shapes",
           "friction_area_point", "interlocking_point", "measured_area_load_point", "two_scale_point",
           "rough_master", "rough_reference", "SCENES", "REFERENCE_FLOOR", "REFERENCE_MAX_ITER", "PERSSON_KAPPA",
           "PUBLISHED_KAPPA_RANGE"]


def add_error_estimate(ds: xr.Dataset, name: str, constants: dict) -> xr.Dataset:
    """State the contact-area error a rough-surface study's resolution gives: ``area_error_estimate``
    (over ``n`` if swept) from :func:`contactlib.accuracy.expected_error` at ``n / q_cutoff`` points per
    shortest wavelength (the fit, not the bound). Other studies are returned unchanged."""
    if "surface_keys" not in STUDIES[name]:
        return ds
    n = ds["n"] if "n" in ds.dims else constants["n"]
    estimate = xr.DataArray(accuracy.expected_error(np.asarray(n) / constants["q_cutoff"]),
                            dims=("n",) if "n" in ds.dims else (), attrs=STUDY_VARIABLES["area_error_estimate"])
    return ds.assign(area_error_estimate=estimate)


def study_surfaces(name: str, constants: dict, grid: dict) -> xr.Dataset:
    """The seeded surfaces of a study (at its smallest resolution) as one labelled Dataset.

    Dims are the study's surface parameters (e.g. ``hurst``, ``seed``) then ``x``, ``y``; the
    points regenerate the same surfaces bit for bit from these parameters.
    """
    keys = STUDIES[name]["surface_keys"]
    n = min(grid["n"]) if "n" in grid else constants["n"]
    accepted = set(inspect.signature(rough_surface).parameters)
    fixed = {k: v for k, v in constants.items() if k in accepted and k not in keys}
    values = [sorted(grid[k]) for k in keys]
    rows = []
    for combo in itertools.product(*values):
        rows.append(rough_surface(**{**fixed, "n": n, **dict(zip(keys, combo))}))
    first = rows[0]
    stacked = np.stack([r.values for r in rows]).reshape(tuple(len(v) for v in values) + first.shape)
    table = {**SWEEP_VARIABLES, **STUDY_VARIABLES}
    coords = {k: (k, np.asarray(v), dict(table[k])) for k, v in zip(keys, values)}
    coords.update({d: first[d] for d in first.dims})
    height = xr.DataArray(stacked, dims=keys + first.dims, coords=coords,
                          attrs={"units": "m", "long_name": "rigid surface height"})
    ds = xr.Dataset({"height": height})
    ds.attrs.update({k: v for k, v in fixed.items()})
    ds.attrs["n"] = n
    return ds
