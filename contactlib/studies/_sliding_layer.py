"""What ``fig5_friction_area`` and ``fig6a_interlocking`` share: the scene of seed 2, section 4.3 (a
rigid 1D self-affine profile sliding with Coulomb friction on an elastic layer on a rigid base) and
the labels of the names both studies take or return.

The scene is dimensionless. The window is ``L = 1`` (``q0 = 2 pi / L``), the layer thickness is given
as ``scaled_layer_thickness = q0 h`` and the load as the seed's ``scaled_pressure = 2 (1 - nu^2) p /
(E q0 Lambda)``, with ``Lambda = max(h) - mean(h)`` the roughness peak of the profile (the amplitude
of a sinusoid), measured on every seed. The profile is normalised by its rms slope; its rms height
follows from the spectrum and is recorded per seed.
"""

from __future__ import annotations

import math

import xarray as xr

from .. import analysis, surfaces
from ..model.bodies import Layer
from ..core.labels import attrs_for
from ..model.materials import contact_modulus

SCENE_VARIABLES: dict[str, dict[str, str]] = {
    "friction": {"units": "1", "long_name": "Coulomb friction coefficient mu_c"},
    "scaled_layer_thickness": {"units": "1", "long_name": "layer thickness q0 h"},
    "scaled_pressure": {"units": "1", "long_name": "mean pressure 2 (1 - nu^2) p / (E q0 Lambda)"},
    "nu": {"units": "1", "long_name": "Poisson ratio of the layer"},
    "peak_height": {"units": "m", "long_name": "roughness peak Lambda = max(h) - mean(h) of the profile"},
    "rms_height": {"units": "m", "long_name": "rms height of the discretised profile"},
    "coupled": {"units": "1", "long_name": "normal-tangential coupling modelled (1) or reduced away (0)"},
    "friction_coefficient_interlocking": attrs_for("friction_coefficient_interlocking"),
    "outer_iterations": attrs_for("outer_iterations"),
}
"""Labels of the names both studies of the scene have (each module's ``VARIABLES`` includes them)."""


def sliding_layer_scene(*, n: int, hurst: float, seed: int, q_low: float, q_roll: float, q_cutoff: float,
                        rms_slope: float, scaled_layer_thickness: float, scaled_pressure: float, layer_base: str,
                        E: float, nu: float) -> tuple[xr.DataArray, Layer, float, dict]:
    """The seeded profile, the layer, the mean pressure [Pa] and the profile's measures.

    Returns ``(heights, layer, mean_pressure, measures)`` with ``measures`` the scalars every point
    records: ``peak_height`` (Lambda), ``rms_height``, ``rms_slope`` (measured, g).
    """
    h = surfaces.self_affine(n, length=1.0, hurst=hurst, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff,
                             rms_slope=rms_slope, seed=seed, dim=1)
    q0 = 2 * math.pi / 1.0
    peak = float(h.max() - h.mean())
    layer = Layer(scaled_layer_thickness / q0, base=layer_base)
    mean_pressure = scaled_pressure * contact_modulus(E, nu) * q0 * peak / 2
    measures = {"peak_height": peak, "rms_height": analysis.rms_height(h), "rms_slope": analysis.rms_slope(h)}
    return h, layer, mean_pressure, measures


def coupling_flag(out: xr.Dataset) -> float:
    """1.0 where the solve modelled the normal-tangential coupling, 0.0 where it was reduced away."""
    return float(out.attrs["coupling"] == "normal-tangential")


def profile_shapes(grid: dict, constants: dict) -> list[tuple[int, ...]]:
    """FFT shapes of a study of this scene: one periodic profile of ``n`` points."""
    return [(n,) for n in grid.get("n", [constants.get("n")])]
