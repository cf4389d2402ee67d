"""The deformable body of a scene: an elastic half-space (``layer=None``) or a :class:`Layer`,
and the rule that models only what a scene needs (:func:`body_model`).

The rule, in one place:

* a layer whose factors (normal, and coupling where friction is on) are within ``0.1 tol`` of the
  half-space's at every non-zero wavevector of the grid is modelled as the half-space (its
  ``q = 0`` compliance kept: a confined compressible layer's uniform compression fixes where the
  penetration is measured from);
* on a non-periodic window a confined layer is the periodic model of the doubled window (friction's coupling
  included) applied to the window alone, on a window of at least :data:`LAYER_WINDOW` thicknesses, never the
  half-space (which holds the longest waves, where a layer differs most);
* the normal-tangential coupling is left out where ``friction = 0`` or where ``friction * |c(q)| /
  Czz(q) <= 0.1 tol`` at every wavevector (``nu = 0.5`` on a half-space: exactly 0);
* a viscoelastic body in steady sliding is modelled elastic, with its relaxed modulus ``E0`` (or its
  glassy ``E_inf``), where ``|E*(q . V) - E0| <= 0.1 tol E0`` (or ``E_inf``) at every non-zero
  wavevector of the grid (the complex modulus, not its magnitude: the loss modulus moves first); at
  rest it is relaxed. Otherwise every multiplier is the elastic one times
  :func:`contactlib.kernels.viscoelastic.steady_sliding_factor`: the real, even part of the normal
  operator is its symmetric part and the imaginary, odd part its skew part, as friction's.

The choice is recorded in the dataset's attrs (``body``, ``coupling``, ``model``, ``material_model``).

Where friction meets a lagging material (a thin confined viscoelastic layer, ``mu_c = 0.8``) the symmetric
part of the normal operator goes negative at the longest waves: the geometric coupling ``~1.5 mu / (q h)``
times the loss tangent. The operator is then not monotone, and uniqueness is no longer implied; it holds
for every profile exactly when the discrete operator ``M`` is a P-matrix (all principal minors positive).
That cannot be checked in general, but its order-1 and order-2 minors can (:func:`order_two_minors`: one
inverse FFT): where one is not positive (a coarse grid, elements longer than the layer is thick, so that an
element's own compliance is negative) two distinct contact solutions of one profile exist
(``tests/test_viscoelastic_thin_layer.py`` builds them), and the scene is refused with the thinnest layer
that passes on its grid. Otherwise it is solved (``attrs['monotone'] = 0``): on rough profiles down to
``q0 h = 0.1`` a dense primal-dual active set from a dozen random starts finds one solution, that of the
coupled solver, to 1e-10. The coupled solver's symmetric operator is then ``K + s |W|``, with ``s`` large
enough that it is positive (:data:`SHIFT_MARGIN`).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from functools import partial

import numpy as np

from ..core import fft
from ..core.grid import Grid
from ..core.inputs import number
from ..kernels.layer import BASES, zero_mode_compliance
from ..kernels.elastic import halfspace_love_multiplier
from ..kernels.tensor import SurfaceGreenTensor, halfspace_coupling_influence, surface_green_tensor
from ..kernels.viscoelastic import real_where_self_conjugate, sliding_factor, sliding_factor_and_deviations
from .materials import Elastic
from .operators import Compliance, Coupling

REDUCTION_FRACTION = 0.1
"""A term is left out where it changes the kernel by at most this fraction of ``tol`` (relative)."""

SHIFT_ABOVE = 2.0
"""Where friction couples strongly (``max |W(q)| / K(q)`` above this: thin layers at ``q h`` below about
``mu``), the symmetric operator of the coupled solve is ``K + |W|`` and its outer loop iterates on
``W - |W|`` (:mod:`contactlib.solvers.nonsymmetric.coupled`). Measured on 512^2, nu = 0.5, mu = 1, 50 % contact:
at q0 h = 0.1 (ratio 15) the plain split stalls at residual 2 and this one converges in 77 outer
iterations; at q0 h = 0.3 (ratio 5) 38 outer iterations instead of 47; at q0 h = 1 (ratio 1.5) it
costs 15 % more, hence the threshold."""


SHIFT_MARGIN = 2.0
"""A non-monotone operator (symmetric part ``k = Re M <= 0`` at some wavevector, skew part ``w``): the coupled
solve's symmetric operator is ``k + s |w|`` with ``s = max(1, SHIFT_MARGIN max(-k / |w|))``, positive
everywhere, and ``W - s |W|`` the outer part. Measured on 1024 points, q0 h = 0.1, mu = 0.8, E_inf/E0 = 10
(phase of ``M`` up to 140 degrees): converged across V tau q0 = 1e-2 .. 1e2."""

MINOR_FLOOR = 1e-9
"""An order-1 or order-2 principal minor of the scaled operator (diagonal scaled to its largest entry of
the half-space) at or below this is taken as not positive (round-off)."""


@dataclass(frozen=True)
class Layer:
    """An elastic layer of finite ``thickness`` [length] on a ``base``.

    ``base="confined"``: bonded to a rigid base (a coating on a hard substrate); ``"remote_pressure"``:
    the back face is free and carries only the uniform pressure that balances the load (a thin one
    bends like a plate). Raises ``ValueError`` naming the parameter on a thickness that is not a
    finite number > 0 or an unknown base.

    Parameters
    ----------
    thickness : float
        Layer thickness [length], finite and > 0.
    base : {"confined", "remote_pressure"}
        The back face: bonded to a rigid base, or free under the balancing pressure.

    Raises
    ------
    ValueError
        Naming ``thickness`` or ``base``.
    """

    thickness: float
    base: str = "confined"

    def __post_init__(self):
        number("thickness (layer thickness)", self.thickness, lower=0.0, lower_open=True)
        if self.base not in BASES:
            raise ValueError(f"base must be one of {BASES}, got {self.base!r}")


@dataclass
class BodyModel:
    """What :func:`contactlib.solve` runs: the symmetric compliance, the skew part (friction coupling and
    the viscoelastic loss part; or None), the tensor for post-processing (periodic only; viscoelastic:
    complex, times :attr:`factor`) and the attrs naming the model."""

    compliance: Compliance
    coupling: Coupling | None
    tensor: SurfaceGreenTensor | None
    attrs: dict
    factor: np.ndarray | None = None
    """The viscoelastic factor of every multiplier (:func:`contactlib.kernels.viscoelastic.steady_sliding_factor`),
    None for an elastic model."""


def body_model(grid: Grid, *, material, layer: Layer | None, friction: float, direction: float,
               tol: float, kernel: str, periodic: bool, velocity=None, kernels: KernelCache | None = None) -> BodyModel:
    """The compliance and skew part of a scene, reduced as the module docstring says.

    ``material`` is a :class:`contactlib.model.materials.Elastic` or ``Viscoelastic``; ``velocity`` [length/time]
    the steady sliding velocity of the rigid surface (None: no motion, the material relaxed); ``kernels`` the
    store of a prepared problem (:class:`KernelCache`) that keeps the half-space tensor across its solves.
    """
    nu = float(material.nu)
    limit = REDUCTION_FRACTION * tol
    attrs = {"friction": float(friction), "sliding_direction": float(direction)}
    factor, E, note_material = _material_factor(grid, material, velocity, limit, attrs)
    E_star = E / (1 - nu**2)
    if layer is not None:
        attrs.update(layer_thickness=float(layer.thickness), layer_base=layer.base)
    if not periodic and layer is not None:  # a confined layer (a plate and steady sliding are refused before)
        return _padded_layer(grid, material=material, layer=layer, friction=friction, direction=direction, tol=tol,
                             kernels=kernels)
    if not periodic:  # zero-padded half-space (steady viscoelastic sliding is refused before)
        coupled = friction > 0 and nu < 0.5
        coupling = Coupling(grid, periodic=False, friction=friction,
                            influence=halfspace_coupling_influence(grid, E, nu, direction)) if coupled else None
        attrs.update(body="half-space", coupling="normal-tangential" if coupled else "none",
                     model="half-space" + (", Coulomb friction coupled" if coupled else "") + note_material)
        return BodyModel(Compliance(grid, E_star=E_star, kernel=kernel, periodic=False), coupling, None, attrs)

    if layer is None and friction == 0 and factor is None:
        # the frictionless elastic half-space: no tensor built, none held during the solve
        attrs.update(body="half-space", coupling="none", model="half-space" + note_material)
        return BodyModel(Compliance(grid, E_star=E_star, kernel=kernel, periodic=True), None, None, attrs)
    half = surface_green_tensor(grid, E, nu) if kernels is None else kernels.halfspace(grid, E, nu)
    if kernel == "love":  # Love's uniform elements (frictionless half-space only: checked by the caller)
        aliased = None if factor is None else partial(sliding_factor, material, velocity)
        love = halfspace_love_multiplier(grid, E_star, factor=aliased)  # each alias at its own frequency
        half = dataclasses.replace(half, normal=love if factor is None else real_where_self_conjugate(grid, love))
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
    if E != material.E0 and tensor.normal.flat[0] > 0:
        # an elastic shortcut at the glassy modulus: the uniform compression does not move, it is relaxed
        # (on a copy: the tensor may be a reused one, :class:`KernelCache`)
        tensor = dataclasses.replace(tensor, normal=tensor.normal.copy())
        tensor.normal.flat[0] *= E / material.E0
    total = tensor.normal.astype(complex)
    if friction > 0:
        total += friction * tensor.coupling_multiplier(grid, direction)
    if factor is not None and kernel != "love":
        total *= factor
        # frictionless, ``total`` is the scaled normal entry (a complex times a real or a complex with a zero
        # imaginary part: the same values)
        tensor = tensor.scaled(factor, normal=total if friction == 0 else None)
    symmetric, skew = total.real, total.imag
    # the non-zero wavevectors are every entry but the first of the rfft layout: slices, not masks (a tenth of
    # the cost, once per speed of a sweep)
    symmetric_q, skew_q = symmetric.reshape(-1)[1:], skew.reshape(-1)[1:]
    monotone = bool(symmetric_q.min() > 0)
    shift = 1.0
    if not monotone:
        worst = order_two_minors(grid, total)
        if worst <= MINOR_FLOOR:
            thinnest = _thinnest_well_posed(grid, E, nu, layer, friction, direction, factor, kernel)
            where = "" if thinnest is None else (
                f"; on this grid, at this friction and sliding velocity, the thinnest well-posed layer is "
                f"q0 h = {thinnest * 2 * math.pi / grid.lengths[0]:.3g} (h = {thinnest:.4g}; this one: q0 h = "
                f"{layer.thickness * 2 * math.pi / grid.lengths[0]:.3g}), and finer elements move it down")
            raise ValueError(
                f"friction = {friction:g} with this material and sliding velocity: the normal operator is not a "
                f"P-matrix (a principal minor of order 1 or 2 is {worst:.3g} <= 0: an element's own compliance, or "
                "a pair's, is not positive, because its symmetric part is negative at long waves and the elements "
                "are too coarse to carry the short waves that outweigh it), so some profiles have two distinct "
                f"contact solutions; lower the friction coefficient, refine the grid or thicken the layer{where}")
        shift = max(1.0, SHIFT_MARGIN * float(np.max(-symmetric[nonzero] / np.maximum(np.abs(skew[nonzero]), 1e-300))))
        attrs["monotone"] = 0
        attrs["monotone_message"] = (
            f"the symmetric part of the normal operator is negative at {int(np.count_nonzero(symmetric_q <= 0))} "
            "long wave(s) (friction coupling times the material's lag): uniqueness is not implied by monotonicity; "
            f"the order-1 and order-2 principal minors are positive (min {worst:.3g})")
    ratio = float(np.abs(skew_q / symmetric_q).max()) if (friction > 0 or factor is not None) else 0.0
    coupled = ratio > limit or not monotone
    transfer = None if (tensor is half and factor is None) else symmetric
    coupling = None
    if coupled:
        multiplier = 1j * skew
        what = ", Coulomb friction coupled" if friction > 0 else ""
        what += ", viscoelastic (loss part skew)" if factor is not None else ""
        note += f"{what} (max |W|/K = {ratio:.3g})"
        if ratio > SHIFT_ABOVE or not monotone:
            # strong skew part: |W| joins the symmetric operator, W - |W| is what the outer loop iterates
            # (not monotone: s |W|, s > 1, so that the symmetric operator stays positive)
            transfer = symmetric + shift * np.abs(skew)
            multiplier = multiplier - shift * np.abs(skew)
            note += ", |W| in the symmetric part" if shift == 1.0 else f", {shift:.3g} |W| in the symmetric part"
            if not monotone:
                note += " (not monotone)"
        coupling = Coupling(grid, periodic=True, friction=1.0, transfer=multiplier)
    elif friction > 0:
        note += ", friction uncoupled (coupling vanishes)"
    compliance = Compliance(grid, E_star=E_star, kernel="spectral" if transfer is not None else kernel,
                            periodic=True, transfer=transfer)
    attrs.update(body=body, coupling="normal-tangential" if (coupled and friction > 0) else "none",
                 model=note + note_material)
    return BodyModel(compliance, coupling, tensor, attrs, factor)


LAYER_WINDOW = 6.0
"""A confined layer on a non-periodic window is the periodic layer of the doubled window (:meth:`Grid.padded`)
loaded on the window alone: exact where its influence has died out at the images, a window's length away. Its
influence falls exponentially over its thickness, slowest when incompressible, so the window must be at least this
many thicknesses on its shortest side. Measured against a periodic window 8x wider (tol 1e-10; a sphere on 64^2 at a
contact radius of about 0.07 of the window, a cylinder on 512 points): at 6 thicknesses the penetration within 2.9e-7
/ 1.5e-5 (2D, nu = 0.3 / 0.5) and 5.0e-7 / 5.2e-5 (1D), at 5 within 1.1e-6 / 5.7e-5 and 3.2e-6 / 2.1e-4, at 2.5
within 6.8e-5 / 1.6e-3 and 2.4e-4 / 6.8e-3; the pressure within 1.2e-6 to 1.1e-5 of its peak at 6 (the band-limited
kernel's own ripple). A criterion on the influence itself, over the element's own, falls with the element's size: it
let a layer as thick as the window through on 256^2 (penetration 2.2e-3 off) and refused thin ones on 32^2."""


def _padded_layer(grid: Grid, *, material, layer: Layer, friction: float, direction: float, tol: float,
                  kernels: KernelCache | None = None) -> BodyModel:
    """A confined layer on a non-periodic window: the periodic model of the doubled window (:func:`body_model`, its
    reductions and friction's coupling with it), its operators applied to the window alone. Refused
    (``ValueError``) on a window narrower than :data:`LAYER_WINDOW` thicknesses. Never reduced to the half-space:
    the zero-padded half-space holds every wavelength, the longest ones included, where a layer much thicker than the
    window still differs (its base lowers the whole window's displacement, by about the contact's size over the
    thickness)."""
    thicknesses = min(grid.lengths) / layer.thickness
    if thicknesses < LAYER_WINDOW:
        raise ValueError(
            f"layer: on a non-periodic window the confined layer of thickness {layer.thickness:g} acts across the "
            f"window ({thicknesses:.3g} thicknesses, fewer than {LAYER_WINDOW:g}): its influence would reach the "
            f"window's images. Widen the window to at least {LAYER_WINDOW * layer.thickness:g}, use periodic=True, "
            "or, for a layer far thicker than the contact, leave it out (the half-space)")
    padded = grid.padded()
    doubled = body_model(padded, material=material, layer=layer, friction=friction, direction=direction, tol=tol,
                         kernel="spectral", periodic=True, kernels=kernels)
    # the doubled window's transfers, now on zero-padded fields (its multipliers hold the 1 / (2N)^d of the FFT pair);
    # six thicknesses put its lowest wave at q h <= pi / 6, far from the half-space, so it is never reduced to it
    normal = doubled.compliance.transfer
    if normal is None:
        raise RuntimeError("layer: the doubled window's model lost the layer's kernel")  # not reached
    coupling = None if doubled.coupling is None else \
        Coupling(grid, periodic=False, friction=1.0, transfer=doubled.coupling.transfer)
    attrs = {**doubled.attrs, "layer_window_thicknesses": thicknesses,
             "model": doubled.attrs["model"] + f", zero-padded ({thicknesses:.3g} thicknesses wide)"}
    return BodyModel(Compliance(grid, E_star=doubled.compliance.E_star, periodic=False, transfer=normal), coupling,
                     None, attrs)


class KernelCache:
    """What a prepared problem (:class:`contactlib.Problem`) keeps of its body's kernels between its solves: the
    last half-space Green's tensor, reused for the same grid and elastic constants, so that a speed sweep builds it
    once (four grid-sized arrays, about 1 ms at 512^2 per speed). Its arrays are read-only while kept. It lives as
    long as the problem that holds it."""

    def __init__(self):
        self.key = None
        self.tensor: SurfaceGreenTensor | None = None

    def halfspace(self, grid: Grid, E: float, nu: float) -> SurfaceGreenTensor:
        """:func:`surface_green_tensor` of the half-space, the kept one where grid and constants are the same."""
        key = (tuple(grid.shape), tuple(float(length) for length in grid.lengths), float(E), float(nu))
        if self.tensor is not None and self.key == key:
            return self.tensor
        tensor = surface_green_tensor(grid, E, nu)
        for array in (tensor.normal, tensor.coupling, tensor.inplane, tensor.antiplane):
            array.flags.writeable = False
        self.key, self.tensor = key, tensor
        return tensor


def _material_factor(grid: Grid, material, velocity, limit: float, attrs: dict):
    """``(factor, E, note)``: the viscoelastic factor of the multipliers (None where the scene is elastic
    to ``limit``: :func:`contactlib.kernels.viscoelastic.modulus_deviation`), the modulus the elastic
    kernels are built with, and what the model note adds. Records the choice in ``attrs``."""
    if isinstance(material, Elastic):
        return None, float(material.E), ""
    attrs.update(E0=material.E0, E_inf=material.E_inf)
    moving = velocity is not None and any(float(v) != 0 for v in velocity)
    if not moving:
        attrs["material_model"] = "elastic, relaxed modulus E0 (no sliding: the material is relaxed)"
        return None, material.E0, ", viscoelastic body at rest: relaxed (E0)"
    factor, (relaxed, glassy) = sliding_factor_and_deviations(grid, material, velocity, (material.E0, material.E_inf))
    if relaxed <= limit:
        attrs["material_model"] = (f"elastic, relaxed modulus E0: |E*(q.V) - E0| <= {relaxed:.1e} E0 on the grid, "
                                   f"<= {REDUCTION_FRACTION} tol")
        return None, material.E0, ", viscoelastic body modelled elastic (E0: slow sliding)"
    if glassy <= limit:
        attrs["material_model"] = (f"elastic, glassy modulus E_inf: |E*(q.V) - E_inf| <= {glassy:.1e} E_inf on the "
                                   f"grid, <= {REDUCTION_FRACTION} tol")
        return None, material.E_inf, ", viscoelastic body modelled elastic (E_inf: fast sliding)"
    attrs["material_model"] = "viscoelastic steady sliding (complex modulus at q.V)"
    return factor, material.E0, ", viscoelastic steady sliding"


def order_two_minors(grid: Grid, total: np.ndarray) -> float:
    """The smallest principal minor of order 1 and 2 of the periodic operator with transfer ``total`` (rfft
    layout, complex) [1], the diagonal scaled to 1 where it is positive: ``c0`` and ``(c0^2 - c_r c_-r) /
    c0^2`` over every offset ``r``, with ``c`` the displacement due to a unit load on one element.
    Negative (``c0`` itself, scaled by the half-space's) where the element's own compliance is not
    positive. A minor <= 0 means the operator is not a P-matrix: some profile has two contact solutions."""
    response = fft.irfftn(real_where_self_conjugate(grid, total.copy()), grid.shape)
    c0 = float(response.flat[0])
    if c0 <= 0:
        return c0 / float(np.abs(total).max())
    mirrored = np.roll(np.flip(response), 1, axis=tuple(range(grid.dim)))  # c_{-r} at r
    pairs = 1.0 - (response * mirrored) / c0**2
    pairs.flat[0] = 1.0
    return float(min(1.0, pairs.min()))


def _thinnest_well_posed(grid: Grid, E: float, nu: float, layer: Layer | None, friction: float, direction: float,
                         factor, kernel: str) -> float | None:
    """The thinnest layer [length] (same base, grid, friction, material and speed) whose order-1 and order-2
    minors are positive: doubling, then bisection to 1 % (None without a layer or beyond 2^20 times)."""
    if layer is None:
        return None

    def passes(thickness):
        tensor = surface_green_tensor(grid, E, nu, thickness, layer.base)
        total = tensor.normal.astype(complex) + friction * tensor.coupling_multiplier(grid, direction)
        if factor is not None and kernel != "love":
            total = total * factor
        return order_two_minors(grid, total) > MINOR_FLOOR

    low, high = layer.thickness, layer.thickness
    for _ in range(20):
        high *= 2
        if passes(high):
            break
        low = high
    else:
        return None
    while high / low > 1.01:
        mid = math.sqrt(low * high)
        low, high = (low, mid) if passes(mid) else (mid, high)
    return high
