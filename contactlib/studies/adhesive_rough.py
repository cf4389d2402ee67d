"""The ``adhesive_rough`` study: adhesive contact of a 2D periodic self-affine surface on an elastic
half-space with a cohesive (exponential) law, along a loading-unloading path under penetration control,
against the rms slope and the work of adhesion ``w``, over seeds.

Reported per state: the mean pressure over ``E* g`` (``g`` the rms slope), the repulsive contact area and
the interaction area (where the adhesive stress acts): the area-load curves. Per path: the pull-off
pressure over ``E* g`` (:func:`contactlib.adhesion_curve`: the most tensile mean pressure along the path,
the pull-off force of load control) and its penetration, and the hysteresis energy.

The law's range is the shortest the grid resolves: its process zone ``pi E* w / (4 sigma_0^2)`` spans
``process_zone_elements`` elements, so ``sigma_0 = sqrt(pi E* w / (4 zone dx))`` and ``range = w / sigma_0``
(recorded per point). Penetrations are in units of the surface's rms height, from its highest point.

One task per (rms slope, work, seed): its points (``penetration_over_rms`` x ``branch``) share the path,
solved once and cached, as in :mod:`contactlib.studies.fig4_adhesive_layers`.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from ..model.adhesion import Adhesion
from ..problems.adhesion_curve import adhesion_curve
from ..model.materials import contact_modulus
from ._common import rough_surface

VARIABLES: dict[str, dict[str, str]] = {
    "work": {"units": "Pa m", "long_name": "work of adhesion w"},
    "penetration_over_rms": {"units": "1", "long_name": "penetration from the highest point / rms height"},
    "branch": {"units": "1", "long_name": "path branch (loading, unloading)"},
    "reduced_mean_pressure": {"units": "1", "long_name": "mean pressure / (E* rms slope), adhesive part included"},
    "interaction_area": {"units": "1", "long_name": "area fraction where the adhesive stress acts"},
    "reduced_pull_off_pressure": {"units": "1", "long_name": "pull-off pressure / (E* rms slope)"},
    "pull_off_penetration_over_rms": {"units": "1", "long_name": "pull-off penetration / rms height"},
    "hysteresis_energy": {"units": "Pa m", "long_name": "energy lost per unit area over the loading-unloading loop"},
    "adhesion_range": {"units": "m", "long_name": "range of the exponential cohesive law"},
    "converged": {"units": "1", "long_name": "1 where the state's solve converged"},
}
"""Labels of the study's own names (the shared ones are in :data:`contactlib.studies._common.COMMON_VARIABLES`)."""


def cohesive_law(work: float, *, E_star: float, spacing: float, process_zone_elements: float) -> Adhesion:
    """The exponential law of work ``w`` whose process zone spans ``process_zone_elements`` elements."""
    peak = math.sqrt(math.pi * E_star * work / (4 * process_zone_elements * spacing))
    return Adhesion(work=work, range=work / peak, model="exponential")


@functools.lru_cache(maxsize=4)
def _path(rms_slope: float, work: float, seed: int, ladder: tuple, n: int, hurst: float, q_low: float,
          q_roll: float, q_cutoff: float, process_zone_elements: float, E: float, nu: float, tol: float):
    h = rough_surface(n=n, hurst=hurst, seed=seed, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff, rms_slope=rms_slope)
    rms_height = float(h.std())
    law = cohesive_law(work, E_star=contact_modulus(E, nu), spacing=1.0 / n,
                       process_zone_elements=process_zone_elements)
    ds = adhesion_curve(h, E=E, nu=nu, adhesion=law, penetrations=np.asarray(ladder) * rms_height, tol=tol)
    return ds, rms_height, law


def adhesive_rough_point(*, rms_slope: float, work: float, seed: int, penetration_over_rms: float, branch: str,
                         n: int, hurst: float, q_low: float, q_roll: float, q_cutoff: float,
                         process_zone_elements: float, E: float, nu: float, adhesion_tol: float,
                         penetration_over_rms_ladder=None, **_solver) -> dict:
    """One state of the path of one surface and law; ``penetration_over_rms_ladder`` (the whole path, from
    the workflow's ``ladder_dim``) is required, as a state depends on the path that led to it."""
    if penetration_over_rms_ladder is None or float(penetration_over_rms) not in \
            [float(v) for v in penetration_over_rms_ladder]:
        raise ValueError("penetration_over_rms_ladder: the whole path of penetrations, holding this one, is needed")
    if branch not in ("loading", "unloading"):
        raise ValueError(f"branch must be 'loading' or 'unloading', got {branch!r}")
    ladder = tuple(sorted(float(v) for v in penetration_over_rms_ladder))
    ds, rms_height, law = _path(float(rms_slope), float(work), int(seed), ladder, int(n), float(hurst), float(q_low),
                                float(q_roll), float(q_cutoff), float(process_zone_elements), float(E), float(nu),
                                float(adhesion_tol))
    i = ladder.index(float(penetration_over_rms))
    k = i if branch == "loading" else 2 * (len(ladder) - 1) - i
    scale = contact_modulus(E, nu) * float(rms_slope)
    return {
        "reduced_mean_pressure": float(ds.mean_pressure[k]) / scale,
        "contact_area": float(ds.contact_area[k]),
        "interaction_area": float(ds.interaction_area[k]),
        "converged": float(ds.converged[k]),
        "residual": float(ds.residual[k]),  # the state's own (NaN where its step failed)
        "reduced_pull_off_pressure": float(ds.pull_off_pressure) / scale,
        "pull_off_penetration_over_rms": float(ds.pull_off_penetration) / rms_height,
        "hysteresis_energy": float(ds.hysteresis_energy),
        "adhesion_range": float(law.range),
    }


def _shapes(grid, constants):
    return [(int(constants["n"]), int(constants["n"]))]


STUDY = {"point": adhesive_rough_point, "fft_shapes": _shapes, "ladder_dim": "penetration_over_rms",
         "group_dims": ("penetration_over_rms", "branch")}
"""This study's entry of :data:`contactlib.studies.STUDIES`."""
