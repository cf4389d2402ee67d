"""Rigid surfaces: self-affine random fields, wavy and asperity geometries, and measured topography files
(xarray DataArrays)."""

from .measured import read
from .resample import resample
from .shapes import paraboloid, spheres, wavy
from .spectra import self_affine_psd
from .synthesis import self_affine

__all__ = ["self_affine", "self_affine_psd", "wavy", "spheres", "paraboloid", "resample", "read"]
