"""The ``fig4_adhesive_layers`` study: seed 1, Figure 4. Adhesive contact of a rigid 1D wavy profile
(amplitude ``Lambda``, ``q0 Lambda = 2``) on a thin layer, confined or loaded by a remote pressure, by the
energy balance (eqs 9-11, the ``"jkr"`` model): the dimensionless mean pressure ``p~ = 2 (1 - nu^2) p /
(E q0 Lambda)`` against ``Delta / Lambda`` along a loading-unloading path under penetration control, for
several ``q0 h``, with the pull-off of each path and ``(1 - nu^2) q0 w / (pi E) = 0.05``.

One task per (base, thickness): its points (``scaled_penetration`` x ``branch``) share the path, solved
once (:func:`contactlib.adhesion_curve`) and cached.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from .. import surfaces
from ..adhesion import Adhesion
from ..adhesion_curve import adhesion_curve
from ..bodies import Layer

VARIABLES: dict[str, dict[str, str]] = {
    "layer_base": {"units": "1", "long_name": "layer back face (confined, remote_pressure)"},
    "scaled_layer_thickness": {"units": "1", "long_name": "layer thickness q0 h"},
    "scaled_penetration": {"units": "1", "long_name": "penetration Delta / Lambda"},
    "branch": {"units": "1", "long_name": "path branch (loading, unloading)"},
    "scaled_mean_pressure": {"units": "1", "long_name": "mean pressure 2 (1 - nu^2) p / (E q0 Lambda)"},
    "scaled_pull_off_pressure": {"units": "1", "long_name": "pull-off pressure 2 (1 - nu^2) p / (E q0 Lambda)"},
    "scaled_pull_off_penetration": {"units": "1", "long_name": "pull-off penetration Delta / Lambda"},
    "jump": {"units": "1", "long_name": "1 where the state jumped on arriving at this step"},
    "full_contact": {"units": "1", "long_name": "1 in full contact"},
}
"""Labels of the study's own names (the shared ones are in :data:`contactlib.studies._common.COMMON_VARIABLES`)."""


@functools.lru_cache(maxsize=8)
def _path(layer_base: str, scaled_layer_thickness: float, ladder: tuple, n: int, scaled_amplitude: float,
          scaled_work: float, E: float, nu: float):
    q0 = 2 * math.pi  # one wavelength on the unit window
    amplitude = scaled_amplitude / q0
    work = scaled_work * math.pi * E / ((1 - nu**2) * q0)
    h = surfaces.wavy(n, amplitude=amplitude)
    layer = None if scaled_layer_thickness <= 0 else Layer(scaled_layer_thickness / q0, layer_base)
    return adhesion_curve(h, E=E, nu=nu, adhesion=Adhesion(work=work, model="jkr"),
                          penetrations=np.asarray(ladder) * amplitude, layer=layer), amplitude, q0


def adhesive_layer_point(*, layer_base: str, scaled_layer_thickness: float, scaled_penetration: float, branch: str,
                         n: int, scaled_amplitude: float, scaled_work: float, E: float,
                         nu: float, scaled_penetration_ladder=None, **_solver) -> dict:
    """One state of the path of one layer: ``branch`` is ``"loading"`` or ``"unloading"``;
    ``scaled_penetration_ladder``, the whole path (the workflow passes it: ``ladder_dim``), is required, as
    a state depends on the path that led to it."""
    if scaled_penetration_ladder is None or float(scaled_penetration) not in \
            [float(v) for v in scaled_penetration_ladder]:
        raise ValueError("scaled_penetration_ladder: the whole path of penetrations, holding this one, is needed")
    if branch not in ("loading", "unloading"):
        raise ValueError(f"branch must be 'loading' or 'unloading', got {branch!r}")
    ladder = tuple(sorted(float(v) for v in scaled_penetration_ladder))
    ds, amplitude, q0 = _path(layer_base, float(scaled_layer_thickness), ladder, int(n), float(scaled_amplitude),
                              float(scaled_work), float(E), float(nu))
    i = ladder.index(float(scaled_penetration))
    k = i if branch == "loading" else 2 * (len(ladder) - 1) - i
    scale = 2 * (1 - nu**2) / (E * q0 * amplitude)
    return {
        "scaled_mean_pressure": float(ds.mean_pressure[k]) * scale,
        "contact_area": float(ds.contact_area[k]),
        "jump": float(ds.jump[k]),
        "full_contact": float(float(ds.contact_area[k]) >= 1 - 1.5 / n),
        "scaled_pull_off_pressure": float(ds.pull_off_pressure) * scale,
        "scaled_pull_off_penetration": float(ds.pull_off_penetration) / amplitude,
    }


def _shapes(grid, constants):
    return [(int(constants["n"]),)]


STUDY = {"point": adhesive_layer_point, "fft_shapes": _shapes, "ladder_dim": "scaled_penetration",
         "group_dims": ("scaled_penetration", "branch")}
"""This study's entry of :data:`contactlib.studies.STUDIES`."""
