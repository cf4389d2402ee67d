"""Measurements of surfaces and contact fields."""

from .anisotropy import anisotropy_tensor
from .contact import contact_area_fraction, contact_clusters
from .friction import directional_slope, interlocking_friction
from .statistics import fit_hurst, psd, rms_height, rms_slope
from .viscoelastic import dissipated_power, traction_power

__all__ = ["rms_height", "rms_slope", "psd", "fit_hurst", "anisotropy_tensor", "contact_area_fraction",
           "contact_clusters", "interlocking_friction", "directional_slope", "dissipated_power", "traction_power"]
