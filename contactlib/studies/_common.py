"""What several studies share: the labels of the names more than one of them takes or returns, and the
seeded rough surface of a study point."""

from __future__ import annotations

from .. import analysis, surfaces

COMMON_VARIABLES: dict[str, dict[str, str]] = {
    "contact_fraction": {"units": "1", "long_name": "target contact size (Hertz: 4a/L, Westergaard: 2a/wavelength)"},
    "hurst": {"units": "1", "long_name": "Hurst exponent"},
    "reduced_pressure": {"units": "1", "long_name": "mean pressure / (E* rms slope)"},
    "rms_slope": {"units": "1", "long_name": "rms slope of the discretised surface"},
    "contact_area": {"units": "1", "long_name": "contact area fraction"},
    "mean_pressure": {"units": "Pa", "long_name": "mean contact pressure over the window"},
    "iterations": {"units": "1", "long_name": "solver iterations"},
    "tol": {"units": "1", "long_name": "solver tolerance on the scale-free residual"},
    "kernel": {"units": "1", "long_name": "compliance kernel (spectral, love)"},
    "area_error_estimate": {"units": "1", "long_name": "contact-area error expected at this resolution "
                            "(contactlib.accuracy.expected_error of n / q_cutoff)"},
    "x": {"units": "m", "long_name": "position along x"},
    "y": {"units": "m", "long_name": "position along y"},
}
"""Labels (units, long_name) of the swept names and outputs that more than one study has; a study's
own names are in its module's ``VARIABLES``."""


def rough_surface(*, n: int, hurst: float, seed: int, q_low: float, q_roll: float, q_cutoff: float,
                  rms_slope: float, anisotropy: float = 1.0, angle: float = 0.0):
    """The seeded self-affine surface of a study point (also written by the workflow's surfaces rule)."""
    return surfaces.self_affine(n, length=1.0, hurst=hurst, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff,
                                rms_slope=rms_slope, seed=seed, anisotropy=anisotropy, angle=angle)


def anisotropy_summary(name: str, field, zeta1: float, zeta2: float) -> dict[str, float]:
    """``<name>_gamma``, ``<name>_theta_d`` and the tensor components ``<name>_m_xx``, ``_xy``, ``_yy`` of
    ``field`` over the band ``zeta1 q0 < |q| < zeta2 q0`` (:func:`contactlib.analysis.anisotropy_tensor`)."""
    t = analysis.anisotropy_tensor(field, zeta1, zeta2)
    m = t.M.values
    return {f"{name}_gamma": float(t.gamma), f"{name}_theta_d": float(t.theta_d),
            f"{name}_m_xx": float(m[0, 0]), f"{name}_m_xy": float(m[0, 1]), f"{name}_m_yy": float(m[1, 1])}
