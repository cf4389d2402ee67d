"""The ``fig4_adhesive_layers`` study: seed 1, Figure 4. Adhesive contact of a rigid 1D wavy profile
(amplitude ``Lambda``, ``q0 Lambda = 2``) on a thin layer, confined or loaded by a remote pressure, by the
energy balance (eqs 9-11, the ``"jkr"`` model): the dimensionless mean pressure ``p~ = 2 (1 - nu^2) p /
(E q0 Lambda)`` against ``Delta / Lambda`` along a loading-unloading path under penetration control, for
several ``q0 h``, with the pull-off of each path and ``(1 - nu^2) q0 w / (pi E) = 0.05``.

Two pull-offs are reported. ``scaled_pull_off_pressure`` is :func:`contactlib.adhesion_curve`'s: the least load
of the equilibrium curve G = w where it rises (the pull-off of load control, whatever the path's sampling; NaN where
the curve never rises, as on thin remote-pressure layers). Under load control only states whose mean pressure grows
with the approach are stable; a thin remote-pressure layer's path grows more tensile as it nears full contact, so
its most tensile state is one load control never holds. ``scaled_load_pull_off_pressure`` is the most
tensile of the states that load control holds (:func:`load_control_pull_off`): the paper's pull-off, NaN
where the path holds none or does not reach the pull-off. ``jump_to_full_contact`` flags a path with no
stable partially closed state under a compressive load (the paper's threshold thickness).

One task per (base, thickness): its points (``scaled_penetration`` x ``branch``) share the path, solved
once (:func:`contactlib.adhesion_curve`) and cached.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from .. import surfaces
from ..model.adhesion import Adhesion
from ..problems.adhesion_curve import adhesion_curve
from ..model.bodies import Layer

VARIABLES: dict[str, dict[str, str]] = {
    "layer_base": {"units": "1", "long_name": "layer back face (confined, remote_pressure)"},
    "scaled_layer_thickness": {"units": "1", "long_name": "layer thickness q0 h"},
    "scaled_penetration": {"units": "1", "long_name": "penetration Delta / Lambda"},
    "branch": {"units": "1", "long_name": "path branch (loading, unloading)"},
    "scaled_mean_pressure": {"units": "1", "long_name": "mean pressure 2 (1 - nu^2) p / (E q0 Lambda)"},
    "scaled_pull_off_pressure": {"units": "1", "long_name": "pull-off pressure 2 (1 - nu^2) p / (E q0 Lambda)"},
    "scaled_pull_off_penetration": {"units": "1", "long_name": "pull-off penetration Delta / Lambda"},
    "scaled_load_pull_off_pressure": {"units": "1", "long_name": "load-control pull-off pressure "
                                      "2 (1 - nu^2) p / (E q0 Lambda)"},
    "scaled_load_pull_off_penetration": {"units": "1", "long_name": "load-control pull-off penetration Delta / Lambda"},
    "jump_to_full_contact": {"units": "1", "long_name": "1 where no partial contact carries a compressive load "
                             "stably (load control jumps to full contact)"},
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
    pull, pull_at, full = load_control_pull_off(ds.penetration.values, ds.mean_pressure.values,
                                                ds.contact_area.values, ds.jump.values)
    return {
        "scaled_mean_pressure": float(ds.mean_pressure[k]) * scale,
        "contact_area": float(ds.contact_area[k]),
        "jump": float(ds.jump[k]),
        "residual": float(ds.residual[k]),
        "full_contact": float(float(ds.contact_area[k]) >= 1 - 1.5 / n),
        "scaled_pull_off_pressure": float(ds.pull_off_pressure) * scale,
        "scaled_pull_off_penetration": float(ds.pull_off_penetration) / amplitude,
        "scaled_load_pull_off_pressure": pull * scale,
        "scaled_load_pull_off_penetration": pull_at / amplitude,
        "jump_to_full_contact": float(full),
    }


def load_control_pull_off(penetration: np.ndarray, mean_pressure: np.ndarray, area: np.ndarray,
                          jump: np.ndarray) -> tuple[float, float, int]:
    """``(pressure, penetration, jump_to_full_contact)`` of a path's loading-then-unloading rows.

    A state is held under load control where the mean pressure grows with the approach: on the unloading
    branch, a closed state whose pressure rises to its next closed state at larger approach (no jump
    between them). The pull-off is the most tensile such state; it counts only where load control lets
    go right below it (the next state at smaller approach is open, or not held), else NaN: the path stops
    before the pull-off. Resolved to the path's step.
    ``jump_to_full_contact`` is 1 where no state of the loading branch with a compressive load is held.
    """
    k = (penetration.size + 1) // 2  # loading rows 0 .. k-1, unloading k-1 .. 2k-2 (the turn shared)
    d = penetration[k - 1:][::-1]
    p, a, j = mean_pressure[k - 1:][::-1], area[k - 1:][::-1], jump[k - 1:][::-1]
    held = np.zeros(d.size, dtype=bool)
    held[:-1] = (a[:-1] > 0) & (a[1:] > 0) & (j[:-1] == 0) & (np.diff(p) > 0)  # j[i] = 0: i not reached by a jump
    pressure, at = math.nan, math.nan
    if held.any():
        i = int(np.flatnonzero(held)[np.argmin(p[held])])
        if i > 0 and (a[i - 1] == 0 or not held[i - 1]):  # below it the path opens, or load control lets go
            pressure, at = float(p[i]), float(d[i])
    dl, pl, al = penetration[:k], mean_pressure[:k], area[:k]
    loaded = (al[:-1] > 0) & (al[1:] > 0) & (np.diff(pl) > 0) & (pl[:-1] > 0)
    return pressure, at, int(not loaded.any())


def _shapes(grid, constants):
    return [(int(constants["n"]),)]


STUDY = {"point": adhesive_layer_point, "fft_shapes": _shapes, "ladder_dim": "scaled_penetration",
         "group_dims": ("scaled_penetration", "branch")}
"""This study's entry of :data:`contactlib.studies.STUDIES`."""
