"""Measurements of surfaces and contact fields, and of a study's speed against its error (:mod:`.convergence`)."""

from .anisotropy import anisotropy_tensor
from .contact import contact_area_fraction, contact_clusters
from .convergence import (cheapest_settings, convergence_orders, fit_order, markdown_table, pareto_front,
                          tolerance_gain)
from .friction import directional_slope, interlocking_friction
from .statistics import fit_hurst, psd, rms_height, rms_slope
from .viscoelastic import dissipated_power, traction_power

__all__ = ["rms_height", "rms_slope", "psd", "fit_hurst", "anisotropy_tensor", "contact_area_fraction",
           "contact_clusters", "interlocking_friction", "directional_slope", "dissipated_power", "traction_power",
           "fit_order", "convergence_orders", "tolerance_gain", "pareto_front", "cheapest_settings", "markdown_table"]
