"""The surface Green's tensor on a q-grid: normal, tangential and normal-tangential compliances.

A traction ``(tau_x, tau_y, p)`` with wavevector ``q`` on a half-space or layer splits into plane
strain along ``q`` (``p`` and ``tau . q/|q|``) and anti-plane shear across it (``tau . t``, with
``t = (-q_y, q_x)/|q|``), which moves the surface only across ``q``. So on the rfft layout::

    u_z = Czz p - i c (q . tau) / |q|
    u   = i c p q/|q| + Cxx (q . tau) q/|q|^2 + Canti (t . tau) t         (in-plane, 2D)

with ``u_z`` positive into the body. ``Czz, c, Cxx, Canti`` are functions of ``|q|`` alone: the
half-space's (``2/(E* |q|)``, Johnson eqs. 2.19-2.20) times the layer factors of
:mod:`.layer`. A profile (plane strain) has ``q/|q| = sgn(q)`` and no anti-plane part. The
coupling ``c`` is odd in ``q``, so the normal-tangential blocks are antisymmetric (Betti) in
real space: a Coulomb traction ``mu p s`` makes the normal operator ``Czz - i mu c (q . s)/|q|``
non-symmetric, with the symmetric part ``Czz``.

Every array here is an unnormalised transfer function (displacement spectrum per traction
spectrum) [length/pressure]; :func:`contactlib.core.fft.convolution_multiplier` turns it into a
multiplier.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.grid import Grid
from .elastic import padded_offsets
from .layer import halfspace_factors, layer_factors, zero_mode_compliance
from .nyquist import even_on_nyquist, unit_projections


@dataclass(frozen=True)
class SurfaceGreenTensor:
    """The four scalar compliances of :mod:`this module <contactlib.kernels.tensor>` on a grid's
    rfft layout [length/pressure], the ``q = 0`` entries included."""

    normal: np.ndarray
    coupling: np.ndarray
    inplane: np.ndarray
    antiplane: np.ndarray

    def scaled(self, factor: np.ndarray, normal: np.ndarray | None = None) -> SurfaceGreenTensor:
        """Every entry times ``factor`` (the viscoelastic body's :func:`.viscoelastic.steady_sliding_factor`:
        the same material compliance multiplies all of them at a constant Poisson ratio), each formed on first
        use (:class:`ScaledGreenTensor`); ``normal``: ``self.normal * factor``, already formed by the caller."""
        return ScaledGreenTensor(base=self, factor=factor, normal=normal)

    def coupling_multiplier(self, grid: Grid, direction: float) -> np.ndarray:
        """``-i c (q . s)/|q|``: the normal displacement per unit tangential traction along
        ``s = (cos direction, sin direction)`` (1D: ``cos direction = +-1``, along ``+-x``) [length/pressure],
        complex. Odd in ``q``: its component along a Nyquist wavenumber is zero (:mod:`.nyquist`)."""
        s = (np.cos(direction), np.sin(direction))[: grid.dim]

        def along(*q):  # (q . s)/|q|, 0 at q = 0
            k = np.abs(q[0]) if grid.dim == 1 else np.sqrt(q[0] ** 2 + q[1] ** 2)
            return np.where(k > 0, sum(qi * si for qi, si in zip(q, s)) / np.where(k > 0, k, 1.0), 0.0)

        return -1j * self.coupling * even_on_nyquist(grid, along, along(*grid.wavevectors()))

    def tangential_displacement(self, grid: Grid, pressure_spectrum: np.ndarray, traction_spectra) -> tuple:
        """In-plane surface displacement spectra ``(u_x,)`` (1D) or ``(u_x, u_y)`` (2D) due to a pressure
        and a tangential traction (its spectra per axis), unnormalised like :func:`numpy.fft.rfftn`.

        2D, with ``n = q/|q|`` and ``(t_x, t_y)`` the traction: ``u_x = i c n_x p + Cxx (n_x^2 t_x + n_x n_y t_y)
        + Canti (n_y^2 t_x - n_x n_y t_y)`` and ``u_y`` its mirror; the odd products (``n_x``, ``n_x n_y``) are
        zero along a Nyquist wavenumber (:mod:`.nyquist`)."""
        n = unit_projections(grid)
        if grid.dim == 1:
            return (1j * self.coupling * n["x"] * pressure_spectrum + self.inplane * traction_spectra[0],)
        tx, ty = traction_spectra
        normal_part = 1j * self.coupling * pressure_spectrum
        inplane, antiplane = self.inplane, self.antiplane
        ux = normal_part * n["x"] + inplane * (n["xx"] * tx + n["xy"] * ty) + antiplane * (n["yy"] * tx - n["xy"] * ty)
        uy = normal_part * n["y"] + inplane * (n["xy"] * tx + n["yy"] * ty) + antiplane * (n["xx"] * ty - n["xy"] * tx)
        # q = 0: a uniform traction shears the body uniformly (no direction to split along)
        ux[0, 0] = inplane[0, 0] * tx[0, 0]
        uy[0, 0] = inplane[0, 0] * ty[0, 0]
        return ux, uy


class ScaledGreenTensor(SurfaceGreenTensor):
    """A :class:`SurfaceGreenTensor` times a factor whose entries are formed on first use (then kept): a
    frictionless viscoelastic solve reads only the normal one, and the three others are three grid-sized complex
    arrays per speed of a sweep (3 ms at 512^2, most of it the kernel's zeroing of their fresh pages). Given the
    four entries instead of ``base`` and ``factor`` (as :func:`dataclasses.replace` does), a plain tensor."""

    def __init__(self, normal=None, coupling=None, inplane=None, antiplane=None, *, base=None, factor=None):
        entries = {name: value for name, value in
                   (("normal", normal), ("coupling", coupling), ("inplane", inplane), ("antiplane", antiplane))
                   if value is not None}
        if base is None and len(entries) < 4:
            raise ValueError("ScaledGreenTensor: give base and factor, or all four entries")
        object.__setattr__(self, "_base", base)
        object.__setattr__(self, "_factor", factor)
        object.__setattr__(self, "_entries", entries)

    def _entry(self, name: str) -> np.ndarray:
        entries = self._entries
        if name not in entries:
            entries[name] = getattr(self._base, name) * self._factor
        return entries[name]

    normal = property(lambda self: self._entry("normal"))
    coupling = property(lambda self: self._entry("coupling"))
    inplane = property(lambda self: self._entry("inplane"))
    antiplane = property(lambda self: self._entry("antiplane"))


def surface_green_tensor(grid: Grid, E: float, nu: float, thickness: float | None = None,
                         base: str = "confined") -> SurfaceGreenTensor:
    """The surface Green's tensor of a half-space (``thickness=None``) or a layer on ``grid``.

    Parameters
    ----------
    grid : Grid
        Periodic grid; the tensor is sampled at its wavevectors (the continuous kernel).
    E, nu : float
        Young's modulus [pressure] and Poisson ratio (validated by the caller).
    thickness : float, optional
        Layer thickness [length]; ``None`` for the half-space.
    base : {"confined", "remote_pressure"}
        The layer's back face: bonded to a rigid base, or free and loaded by the balancing pressure.

    The ``q = 0`` entries are :func:`.layer.zero_mode_compliance`'s (0 for a half-space: its mean
    displacement is undetermined, so periodic displacements are zero-mean).
    """
    k = grid.wavenumber()
    positive = k > 0
    unit = np.zeros_like(k)
    unit[positive] = 2 * (1 - nu**2) / (E * k[positive])
    if thickness is None:
        factors = {name: np.full_like(k, value) for name, value in halfspace_factors(nu).items()}
        zero = {"normal": 0.0, "tangential": 0.0}
    else:
        X = np.where(positive, k * thickness, 1.0)
        factors = layer_factors(X, nu, base)
        zero = zero_mode_compliance(thickness, E, nu, base)
    anti_unit = unit / (1 - nu)  # 2 (1 + nu) / (E |q|)
    tensor = SurfaceGreenTensor(normal=unit * factors["normal"], coupling=unit * factors["coupling"],
                                inplane=unit * factors["inplane"], antiplane=anti_unit * factors["antiplane"])
    origin = (0,) * grid.dim
    tensor.normal[origin] = zero["normal"]
    tensor.coupling[origin] = 0.0
    tensor.inplane[origin] = zero["tangential"]
    tensor.antiplane[origin] = zero["tangential"]
    return tensor


def halfspace_coupling_influence(grid: Grid, E: float, nu: float, direction: float) -> np.ndarray:
    """Non-periodic normal displacement per unit tangential traction along ``direction``, on the padded
    ``2n`` circular layout (the real-space counterpart of :meth:`SurfaceGreenTensor.coupling_multiplier`).

    1D: ``(1 - 2 nu)(1 + nu) / (2 E) dx sgn(x) cos(direction)`` (Johnson eq. 2.20b; exact for a uniform element at the
    nodes). 2D: Cerruti's ``(1 - 2 nu)(1 + nu) / (2 pi E) dA (x . s) / r^2`` for the element's load at
    its node (Johnson eq. 3.86); both odd, so an element's own term is zero.
    """
    off = padded_offsets(grid)
    k0 = (1 - 2 * nu) * (1 + nu) / (2 * E)
    if grid.dim == 1:
        return k0 * grid.spacing[0] * np.sign(off[0]) * np.cos(direction)
    x, y = off
    r2 = x**2 + y**2
    along = x * np.cos(direction) + y * np.sin(direction)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(r2 > 0, k0 / np.pi * grid.element_area * along / r2, 0.0)
    return out
