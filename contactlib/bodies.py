"""The deformable body of a scene: an elastic half-space (``layer=None``) or a :class:`Layer`,
and the rule that models only what a scene needs (:func:`body_model`).

The rule, in one place:

* a layer whose factors (normal, and coupling where friction is on) are within ``0.1 tol`` of the
  half-space's at every non-zero wavevector of the grid is modelled as the half-space (its
  ``q = 0`` compliance kept: a confined compressible layer's uniform compression fixes where the
  penetration is measured from);
* the normal-tangential coupling is left out where ``friction = 0`` or where ``friction * |c(q)| /
  Czz(q) <= 0.1 tol`` at every wavevector (``nu = 0.5`` on a half-space: exactly 0).

The choice is recorded in the dataset's attrs (``body``, ``coupling``, ``model``).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from .grid import Grid
from .kernels.layer import BASES, zero_mode_compliance
from .kernels.tensor import SurfaceGreenTensor, halfspace_coupling_influence, surface_green_tensor
from .operators import Compliance, Coupling

REDUCTION_FRACTION = 0.1
"""A term is left out where it changes the kernel by at most this fraction of ``tol`` (relative)."""

SHIFT_ABOVE = 2.0
"""Where friction couples strongly (``max |W(q)| / K(q)`` above this: thin layers at ``q h`` below about
``mu``), the symmetric operator of the coupled solve is ``K + |W|`` and its outer loop iterates on
``W - |W|`` (:mod:`contactlib.solvers.coupled`). Measured on 512^2, nu = 0.5, mu = 1, 50 % contact:
at q0 h = 0.1 (ratio 15) the plain split stalls at residual 2 and this one converges in 77 outer
iterations; at q0 h = 0.3 (ratio 5) 38 outer iterations instead of 47; at q0 h = 1 (ratio 1.5) it
costs 15 % more, hence the threshold."""


@dataclass(frozen=True)
class Layer:
    """An elastic layer of finite ``thickness`` [length] on a ``base``.

    ``base="confined"``: bonded to a rigid base (a coating on a hard substrate); ``"remote_pressure"``:
    the back face is free and carries only the uniform pressure that balances the load (a thin one
    bends like a plate). Raises ``ValueError`` naming the parameter on a thickness that is not a
    finite number > 0 or an unknown base.
    """

    thickness: float
    base: str = "confined"

    def __post_init__(self):
        t = self.thickness
        if isinstance(t, bool) or not isinstance(t, (int, float)) or not math.isfinite(t) or t <= 0:
            raise ValueError(f"thickness (layer thickness) must be a finite number > 0, got {t!r}")
        if self.base not in BASES:
            raise ValueError(f"base must be one of {BASES}, got {self.base!r}")


@dataclass
class BodyModel:
    """What :func:`contactlib.solve` runs: the symmetric compliance, the skew coupling (or None), the
    tensor for post-processing (periodic only) and the attrs naming the model."""

    compliance: Compliance
    coupling: Coupling | None
    tensor: SurfaceGreenTensor | None
    attrs: dict


def body_model(grid: Grid, *, E: float, nu: float, layer: Layer | None, friction: float, direction: float,
               tol: float, kernel: str, periodic: bool) -> BodyModel:
    """The compliance and coupling of a scene, reduced as the module docstring says."""
    E_star = E / (1 - nu**2)
    limit = REDUCTION_FRACTION * tol
    attrs = {"friction": float(friction), "sliding_direction": float(direction)}
    if layer is not None:
        attrs.update(layer_thickness=float(layer.thickness), layer_base=layer.base)
    if not periodic:  # zero-padded half-space (layers are refused before this point)
        coupled = friction > 0 and nu < 0.5
        coupling = Coupling(grid, periodic=False, friction=friction,
                            influence=halfspace_coupling_influence(grid, E, nu, direction)) if coupled else None
        attrs.update(body="half-space", coupling="normal-tangential" if coupled else "none",
                     model="half-space" + (", Coulomb friction coupled" if coupled else ""))
        return BodyModel(Compliance(grid, E_star=E_star, kernel=kernel, periodic=False), coupling, None, attrs)

    if layer is None and friction == 0:  # the frictionless half-space: no tensor built, none held during the solve
        attrs.update(body="half-space", coupling="none", model="half-space")
        return BodyModel(Compliance(grid, E_star=E_star, kernel=kernel, periodic=True), None, None, attrs)
    half = surface_green_tensor(grid, E, nu)
    nonzero = grid.wavenumber() > 0
    tensor, body, note = half, "half-space", "half-space"
    if layer is not None:
        full = surface_green_tensor(grid, E, nu, layer.thickness, layer.base)
        deviation = np.abs(full.normal[nonzero] / half.normal[nonzero] - 1).max()
        if friction > 0:
            deviation = max(deviation, friction * np.abs((full.coupling - half.coupling)[nonzero]
                                                         / half.normal[nonzero]).max())
        if deviation > limit:
            tensor, body, note = full, "layer", f"{layer.base} layer, h = {layer.thickness:g}"
        else:
            note = (f"half-space (the {layer.base} layer of h = {layer.thickness:g} is within {deviation:.1e} of it, "
                    f"<= {REDUCTION_FRACTION} tol, on this grid)")
            zero = zero_mode_compliance(layer.thickness, E, nu, layer.base)["normal"]
            if zero > 0:  # keep its uniform compression: penetrations from the undeformed surface
                tensor = dataclasses.replace(half, normal=half.normal.copy())
                tensor.normal.flat[0] = zero
    ratio = friction * np.abs(tensor.coupling[nonzero] / tensor.normal[nonzero]).max() if friction > 0 else 0.0
    coupled = ratio > limit
    transfer = None if tensor is half else tensor.normal
    coupling = None
    if coupled:
        multiplier = tensor.coupling_multiplier(grid, direction)
        note += f", Coulomb friction coupled (max |W|/K = {ratio:.3g})"
        if ratio > SHIFT_ABOVE:
            # strong coupling: |W| joins the symmetric operator, W - |W| is what the outer loop iterates
            transfer = tensor.normal + friction * np.abs(multiplier)
            multiplier = multiplier - np.abs(multiplier)
            note += ", |W| in the symmetric part"
        coupling = Coupling(grid, periodic=True, friction=friction, transfer=multiplier)
    elif friction > 0:
        note += ", friction uncoupled (coupling vanishes)"
    compliance = Compliance(grid, E_star=E_star, kernel=kernel, periodic=True, transfer=transfer)
    attrs.update(body=body, coupling="normal-tangential" if coupled else "none", model=note)
    return BodyModel(compliance, coupling, tensor, attrs)
