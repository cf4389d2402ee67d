"""The ``anisotropy`` study: the spectral anisotropy (gamma, theta_d, M) of a rigid anisotropic surface
against that of its contact pressure."""

from __future__ import annotations

from .. import analysis
from ..problems.contact import solve
from ..model.materials import contact_modulus
from ._common import anisotropy_summary, rough_surface

VARIABLES: dict[str, dict[str, str]] = {
    "anisotropy": {"units": "1", "long_name": "target anisotropy ratio gamma of the surface"},
    "surface_gamma": {"units": "1", "long_name": "anisotropy ratio gamma of the rigid surface"},
    "surface_theta_d": {"units": "rad", "long_name": "principal direction theta_d of the rigid surface"},
    "pressure_gamma": {"units": "1", "long_name": "anisotropy ratio gamma of the contact pressure"},
    "pressure_theta_d": {"units": "rad", "long_name": "principal direction theta_d of the contact pressure"},
    "pressure": {"units": "Pa", "long_name": "contact pressure (compressive positive)"},
}
"""Labels of the study's own names (the shared ones are in :data:`contactlib.studies._common.COMMON_VARIABLES`)."""

for _field in ("surface", "pressure"):
    for _ij in ("xx", "xy", "yy"):
        VARIABLES[f"{_field}_m_{_ij}"] = {
            "units": "1" if _field == "surface" else "Pa2 m-2",
            "long_name": f"anisotropy tensor component M_{_ij} of the {'rigid surface' if _field == 'surface' else 'contact pressure'}",
        }


def anisotropy_point(*, anisotropy: float, seed: int, n: int, hurst: float, angle: float, reduced_pressure: float,
                     q_low: float, q_roll: float, q_cutoff: float, rms_slope: float, zeta1: float, zeta2: float,
                     E: float, nu: float, tol: float, max_iter: int, kernel: str, save_fields: bool = False) -> dict:
    """Anisotropy (gamma, theta_d, M) of a rigid anisotropic surface and of its contact pressure."""
    h = rough_surface(n=n, hurst=hurst, seed=seed, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff,
                      rms_slope=rms_slope, anisotropy=anisotropy, angle=angle)
    slope = analysis.rms_slope(h)
    E_star = contact_modulus(E, nu)
    out = solve(h, E=E, nu=nu, mean_pressure=reduced_pressure * E_star * slope, tol=tol, max_iter=max_iter,
                kernel=kernel)
    result = {"contact_area": float(out.contact_area), "mean_pressure": float(out.mean_pressure),
              "iterations": float(out.iterations), "residual": float(out.residual)}
    for name, field in (("surface", h), ("pressure", out.pressure)):
        result.update(anisotropy_summary(name, field, zeta1, zeta2))
    if save_fields:
        p = out.pressure.reset_coords(drop=True)
        p.attrs = {}
        result["pressure"] = p
    return result


def anisotropy_shapes(grid: dict, constants: dict) -> list[tuple[int, ...]]:
    """FFT shapes of the anisotropy study: its one periodic grid."""
    return [(constants["n"], constants["n"])]


STUDY = {"point": anisotropy_point, "fft_shapes": anisotropy_shapes, "surface_keys": ("anisotropy", "seed")}
"""This study's entry of :data:`contactlib.studies.STUDIES`."""
