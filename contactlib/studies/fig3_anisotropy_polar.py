"""The ``fig3_anisotropy_polar`` study: the anisotropy that sliding on a viscoelastic half-space induces
in the deformed surface of an isotropic rough surface (seed 2, Fig. 3; the scene of Fig. 2).

For each seed: the slope tensor ``M`` of the rigid surface (``m2(theta)``) and of the deformed surface,
the normal displacement (``mu2(theta)``), over the band ``zeta1 q0 < |q| < zeta2 q0``
(:func:`contactlib.analysis.anisotropy_tensor`), with ``gamma = lambda_min / lambda_max`` and the
principal direction ``theta_d``. The seed reports ``gamma_s = 1``, ``gamma_d = 0.37``, ``theta_d = pi/2``.
"""

from __future__ import annotations

from .. import surfaces
from ..problems.contact import solve
from ._common import anisotropy_summary
from ._viscoelastic_scene import SCENE_VARIABLES, material

VARIABLES: dict[str, dict[str, str]] = {**SCENE_VARIABLES, "speed_ratio": {"units": "1", "long_name": "V tau / lambda (lambda: the window)"}}
for _name, _what in (("surface", "rigid surface"), ("displacement", "deformed surface (normal displacement)")):
    VARIABLES[f"{_name}_gamma"] = {"units": "1", "long_name": f"anisotropy ratio gamma of the {_what}"}
    VARIABLES[f"{_name}_theta_d"] = {"units": "rad", "long_name": f"principal direction theta_d of the {_what}"}
    for _ij in ("xx", "xy", "yy"):
        VARIABLES[f"{_name}_m_{_ij}"] = {"units": "1", "long_name": f"anisotropy tensor component M_{_ij} of the {_what}"}


def anisotropy_polar_point(*, seed: int, n: int, length: float, hurst: float, scales: int, rms_slope: float,
                           E: float, glassy_ratio: float, tau: float, nu: float, mean_pressure: float,
                           speed_ratio: float, zeta1: float, zeta2: float, tol: float, max_iter: int, kernel: str) -> dict:
    """Slope tensors of the rigid and deformed surfaces over the band, sliding along +x."""
    h = surfaces.self_affine(n, length=length, hurst=hurst, q_low=1, q_roll=1, q_cutoff=scales,
                             rms_slope=rms_slope, seed=seed, synthesis="random-phase")
    m = material(E0=E, glassy_ratio=glassy_ratio, tau=tau, nu=nu)
    out = solve(h, material=m, mean_pressure=mean_pressure, sliding_velocity=(speed_ratio * length / tau, 0.0),
                tol=tol, max_iter=max_iter, kernel=kernel)
    result = {"contact_area": float(out.contact_area),
              "friction_coefficient_interlocking": float(out.friction_coefficient_interlocking),
              "iterations": float(out.iterations), "residual": float(out.residual)}
    for name, field in (("surface", h), ("displacement", out.displacement)):
        result.update(anisotropy_summary(name, field, zeta1, zeta2))
    return result


def polar_shapes(grid: dict, constants: dict) -> list[tuple[int, ...]]:
    return [(constants["n"], constants["n"])]


STUDY = {"point": anisotropy_polar_point, "fft_shapes": polar_shapes}
