"""Green's functions of the deformable body, as pure functions of the grid and material.

Periodic problems use Fourier multipliers (displacement spectrum over pressure spectrum);
non-periodic problems use real-space influence coefficients that the operator embeds in
a zero-padded periodic box. New bodies (finite layers, viscoelastic, Green's tensors)
add functions here with the same shape of signature.
"""

from .elastic import (halfspace_love_influence, halfspace_love_multiplier, halfspace_point_influence,
    halfspace_spectral_multiplier)

__all__ = [
    "halfspace_spectral_multiplier",
    "halfspace_love_multiplier",
    "halfspace_love_influence",
    "halfspace_point_influence",
]
