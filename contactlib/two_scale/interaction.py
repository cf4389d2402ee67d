"""Interaction of asperities through the half-space: point-load influence ``T_kl`` (seed paper 1, eq. 2).

The displacement at summit ``k`` due to the forces ``P_l`` on the others is ``u_k = sum_l T_kl P_l``
with Boussinesq's point-load solution ``T_kl = 1 / (pi E* r_kl)`` (Johnson, *Contact Mechanics*,
eq. 3.20). Non-periodic: ``T_kk = 0``, summed directly (``O(N^2)`` per product, in blocks).

Periodic: the sum over the images of every asperity, zero-mean as contactlib's periodic half-space
(its Fourier multiplier ``2/(E*|q|)`` is set to 0 at ``q = 0``), by **Ewald summation**
(split ``1/r = erfc(alpha r)/r + erf(alpha r)/r``):

* the short-range part ``erfc(alpha r) / (pi E* r)`` over neighbours within ``r_c``, ``alpha r_c =
  erfcinv(accuracy)`` (3.77 at the default 1e-7, 3.12 at 1e-5), a pair list from the table's one
  cell-list query, summed by a numba kernel (no sparse matrix to build);
* the smooth long-range part in Fourier space, ``(2/(E* q)) erfc(q / (2 alpha))``, evaluated by FFT on a
  mesh after spreading the forces with Gaussians and gathering with the same Gaussians ("spectral
  Ewald", Lindbo & Tornberg, J. Comput. Phys. 229 (2010) 8994, doi:10.1016/j.jcp.2010.08.026); the
  Gaussian's transform is divided out on the mesh, so the only errors are the truncations, all
  exponentially small, each set to the requested ``accuracy`` (:func:`ewald_parameters`): the macro solve
  asks for a tenth of its Newton tolerance, and its Newton steps' linear solves for 1e-3
  (:meth:`PointInteraction.coarser`);
* the constants: ``-2 alpha / (pi^(3/2) E*)`` on the diagonal (the self part of the long-range sum
  that the point load itself, Hertz's law, already holds) and ``-2 / (sqrt(pi) alpha A E*)`` for every
  pair, the dropped ``q = 0`` term of the short-range part.

``T_kk`` is then the regular part of the periodic kernel at ``r = 0``: the asperity's own images and
the zero-mean shift. ``alpha`` scales with the mean spacing ``L / sqrt(N)``, so each product costs
``O(N)`` neighbour terms plus an FFT on a mesh of ``O(N)`` points: 10^4 asperities in milliseconds,
where a dense ``N x N`` matrix would take 800 MB. Why Ewald and not a plain cut-off: a zero-mean
periodic ``1/r`` sum converges only conditionally, and a cut-off leaves an error falling like
``1/r_c``; why not an FFT on the surface's own grid: the macro step would then cost as much per
product as one iteration of the full solver. Why no dense matrix at small ``N``: a product with it is
4-20x cheaper (10^3: 0.19 ms against 0.8 ms; 10^2: 6 us against 0.14 ms), but building it takes ``N``
products (0.8 s at 10^3, 13 ms at 10^2), while a solve needs 20-40 (macro Newton and the coarse
corrections): it would pay only past about ``N`` products, which no solve reaches at any size. Built
directly instead (Ewald with ``alpha L = 7.2``, so that the real-space part is the nearest image's
``erfc(alpha r)/r`` over all pairs and the reciprocal part about 240 modes, a product of ``N x 240``
factors), at 10^3 asperities the real part took 78 ms and the reciprocal 64 ms (one core), 5x a whole
macro solve by products as it was then (about 20 ms; 2-3 ms now), and a Cholesky factor 21 ms more; at 200
asperities 11 ms against about 4 ms. Spreading and gathering use the Gaussians' separable form (:func:`spread_on_mesh`,
:func:`gather_from_mesh`): ``4 P`` numbers per asperity instead of a sparse matrix's ``2 P^2``, and nothing to
build but the 1D factors.
"""

from __future__ import annotations

import copy
import functools
import math

import numpy as np
import scipy.fft as sfft
from scipy import sparse
from scipy.special import erfc, erfcinv

from ..core import fft
from ..core._numba import jit
from .asperities import NEIGHBOUR_SPACINGS, AsperityTable
from .ewald_weights import short_range_weights

ACCURACY = 1e-7
"""Default ``accuracy`` of :class:`PointInteraction`: the displacements within about ``1e-7`` of the largest."""
EWALD_NEIGHBOURS = NEIGHBOUR_SPACINGS
"""``r_c`` in mean spacings ``L / sqrt(N)``: about 20 neighbours per asperity in the real-space sum.
Larger than the balance of the two sums' arithmetic, because the spreading, not the FFT, is the mesh
part's cost: a coarser mesh (smaller ``alpha``) costs fewer FFT points, the same spreading."""
GAUSSIAN_WIDTH = 0.35
"""Spreading Gaussian's standard deviation ``s`` times ``alpha``: the deconvolved multiplier
``erfc(q/2 alpha) exp(q^2 s^2)`` still decays like ``exp(-0.13 q^2 / alpha^2)``."""


def ewald_parameters(accuracy: float) -> tuple[float, float, float]:
    """``(alpha r_c, h alpha, support)`` of the Ewald sum for displacements within about ``accuracy`` of the
    largest [1], each of its three truncations at ``accuracy``:

    * ``alpha r_c = erfcinv(accuracy)``: the short-range terms left out are below ``accuracy`` of ``1/r_c``;
    * the mesh spacing ``h``: gathering is a trapezoid rule over the mesh of the product of a Gaussian
      (spectrum ``exp(-a q^2)``, ``a = s^2/2``) and the smooth field (``exp(-b q^2)``, ``b = 1/4 alpha^2 -
      s^2/2``), whose spectrum at the sampling wavenumber ``Q = 2 pi / h`` is ``exp(-Q^2 ab/(a+b))``;
    * the Gaussian's support, in widths ``s`` each side: ``exp(-support^2 / 2) = accuracy``.

    Measured on 10^3 asperities (coverage 0.4) against a much finer sum: error/accuracy 0.9, 0.8, 0.6, 0.6 at
    1e-4 ... 1e-7 (7, 9, 11, 13 mesh nodes per axis and asperity); the spectral Ewald error falls like
    ``exp(-pi P / 2)`` in the ``P`` nodes (Lindbo & Tornberg 2010)."""
    if not (math.isfinite(accuracy) and 0 < accuracy < 1):
        raise ValueError(f"accuracy must lie in (0, 1), got {accuracy!r}")
    log = math.log(1.0 / accuracy)
    a = 0.5 * GAUSSIAN_WIDTH**2
    b = 0.25 - a
    spacing = 2 * math.pi * math.sqrt(a * b / (a + b) / log)
    return float(erfcinv(accuracy)), spacing, math.sqrt(2 * log)


class PointInteraction:
    """The influence operator ``P -> u = T P`` of point loads on an elastic half-space.

    Parameters
    ----------
    table : AsperityTable
        Summit positions and the window.
    E_star : float
        Contact modulus [pressure].
    accuracy : float
        Periodic: the products' error over their largest value [1] (:func:`ewald_parameters`); each
        tenfold costs about two more mesh nodes per axis and asperity in the spreading.

    Attributes
    ----------
    method : str
        ``"ewald"`` (periodic) or ``"direct"`` (non-periodic).
    diagonal : ndarray
        ``T_kk`` [length/force].
    """

    def __init__(self, table: AsperityTable, E_star: float, accuracy: float = ACCURACY):
        self.count = table.count
        self.accuracy = float(accuracy)
        self.E_star = float(E_star)
        self.periodic = table.periodic
        if table.periodic:
            self._setup_ewald(table)
        else:
            self.method = "direct"
            self.centers = table.centers
            self.diagonal = np.zeros(self.count)
            self.attrs = {"interaction": "direct"}

    def _setup_ewald(self, table: AsperityTable) -> None:
        L, N = table.length, table.count
        cutoff = table.neighbour_reach if EWALD_NEIGHBOURS == NEIGHBOUR_SPACINGS else \
            min(EWALD_NEIGHBOURS * (L / math.sqrt(N)), 0.45 * L)  # r_c < L/2: one image per pair at most
        cutoff_factor, mesh_spacing, support = ewald_parameters(self.accuracy)
        alpha = cutoff_factor / cutoff
        self.method = "ewald"
        k, l, r = table.neighbour_pairs(cutoff)
        # the short-range pairs as a list for a numba kernel: no sparse matrix to sort and build (0.7 ms at 10^3)
        # the table's own arrays (np.asarray with a dtype returns a new view even when it matches, and
        # with_pair_weights recognises the pairs by identity)
        self._pair_k, self._pair_l = (v if v.dtype == np.int64 else v.astype(np.int64) for v in (k, l))
        self._pair_w = short_range_weights(alpha, r, self.E_star)
        self._pair_term = (_NO_PAIRS, _NO_PAIRS)  # no pair term (:meth:`with_pair_weights`)
        self._shift = -2.0 / (math.sqrt(math.pi) * alpha * L * L * self.E_star)
        self_term = -2.0 * alpha / (math.pi**1.5 * self.E_star)
        self._self_term = self_term
        self._geometry = (table.centers, L, alpha)
        self._setup_mesh(mesh_spacing, support)
        self.attrs = {"interaction": "ewald", "ewald_alpha": alpha, "ewald_cutoff": cutoff, "ewald_mesh": self._mesh,
                      "ewald_gaussian_width": GAUSSIAN_WIDTH / alpha, "ewald_support": self._gx.shape[1],
                      "ewald_accuracy": self.accuracy}

    def _setup_mesh(self, mesh_spacing: float, support: float) -> None:
        """The long-range part's mesh and Gaussians (:func:`ewald_parameters`' ``h alpha`` and support)."""
        centers, L, alpha = self._geometry
        m, multiplier, mesh_diagonal = _ewald_mesh(L, alpha, self.E_star, mesh_spacing / alpha)
        self._multiplier, self._mesh = multiplier, m
        self._rows, self._cols, self._gx, self._gy = gaussian_factors(centers, L, m, GAUSSIAN_WIDTH / alpha, support)
        # T_kk: no pair is an asperity with itself (r_c < L/2), so the short-range part adds nothing
        self.diagonal = np.full(self.count, self._self_term + self._shift + mesh_diagonal)

    @property
    def geometry(self) -> tuple[np.ndarray, float] | None:
        """``(centers, length)`` of a periodic (Ewald) interaction [length]; None for the direct sum."""
        return (self._geometry[0], self._geometry[1]) if self.method == "ewald" else None

    def coarser(self, accuracy: float) -> "PointInteraction":
        """The same operator with its long-range part (mesh and Gaussians) at the looser ``accuracy`` [1] and
        the rest shared (the pairs, ``alpha``): for the Newton steps' linear solves, which stop at a relative
        residual of 1e-2 to 1e-3 and so need no more (their products are 11 of 14 in a macro solve at 10^3
        asperities), while the residual is measured with this one. Itself where it is no looser."""
        if self.method != "ewald" or accuracy <= self.accuracy:
            return self
        other = copy.copy(self)
        other.accuracy = float(accuracy)
        _, mesh_spacing, support = ewald_parameters(other.accuracy)
        other._setup_mesh(mesh_spacing, support)
        return other

    def with_pair_weights(self, k: np.ndarray, l: np.ndarray, factor: np.ndarray, node_values: np.ndarray, *,
                          reused: bool = False) -> "PointInteraction | None":
        """The same operator with ``factor_i (node_values[k_i] + node_values[l_i])`` [length/force] added to the
        short-range weight of pair ``i``, when ``(k, l)`` are its own pair arrays (the table's one neighbour
        query): one pair loop a product for a pair term such as :class:`.macro.FiniteSize`. None otherwise.
        ``reused``: the copy makes several products (a Newton step's solve), so the weights are formed once in an
        array; else in its pair loop (10 us more a product at 10^3 asperities, no pass of its own)."""
        if self.method != "ewald" or k is not self._pair_k or l is not self._pair_l or self._pair_term[0].size:
            return None  # (a copy that has a pair term already: the caller's wrapper adds the second)
        other = copy.copy(self)
        factor, node_values = np.ascontiguousarray(factor, dtype=float), np.ascontiguousarray(node_values, dtype=float)
        if reused:
            other._pair_w = _pair_weights(self._pair_k, self._pair_l, self._pair_w, factor, node_values)
        else:
            other._pair_term = (factor, node_values)
        return other

    def __call__(self, forces: np.ndarray) -> np.ndarray:
        """Displacement [length] at each summit due to the point forces [force] on all of them, images
        included, the singular self term excluded."""
        forces = np.asarray(forces, dtype=float)
        if self.method == "direct":
            return _direct_sum(self.centers, forces, self.E_star)
        plan = fft.get_fft((self._mesh, self._mesh), slot="ewald")
        plan.real.fill(0.0)
        spread_on_mesh(self._rows, self._cols, self._gx, self._gy, forces, plan.real)
        spectrum = plan.forward()
        spectrum *= self._multiplier
        out = np.empty(self.count)
        # the node area is in the multiplier
        gather_from_mesh(self._rows, self._cols, self._gx, self._gy, plan.inverse(), out)
        _add_short_range(self._pair_k, self._pair_l, self._pair_w, *self._pair_term, forces, self._self_term,
                         self._shift, out)
        return out


@functools.lru_cache(maxsize=16)
def _ewald_mesh(L: float, alpha: float, E_star: float, spacing: float) -> tuple[int, np.ndarray, float]:
    """What depends on the window and ``alpha`` alone (cached: the same field under another load, or the
    next solve of a load sweep, reuses it): the mesh size ``m`` (fine enough to sample the Gaussian of width
    ``s`` at ``spacing`` or finer; even, and a fast FFT size), the deconvolved long-range multiplier on
    its rfft layout (read-only), and the long-range part of ``T_kk``, the Fourier sum
    ``(1/A) sum_q (2/(E* q)) erfc(q/2 alpha)`` at r = 0 (Hermitian weights), the same for every asperity."""
    s = GAUSSIAN_WIDTH / alpha
    m = even_fast_size(L / spacing)
    h = L / m
    q, weight = mesh_wavenumbers(L, m)
    long_range = np.zeros_like(q)
    nz = q > 0
    long_range[nz] = 2.0 / (E_star * q[nz]) * erfc(q[nz] / (2 * alpha))
    # fftw's inverse is unnormalised: the 1/m^2 goes into the multiplier, and the gathering's node area h^2
    multiplier = long_range * np.exp((q * s) ** 2) * (h * h / (m * m))
    multiplier.setflags(write=False)
    diagonal = float(np.sum(weight * long_range)) / (m * m * h * h)
    return m, multiplier, diagonal


def even_fast_size(points: float) -> int:
    """The smallest even fast FFT size (real transforms) of at least ``points`` nodes."""
    m = sfft.next_fast_len(max(int(math.ceil(points)), 2), real=True)
    while m % 2:
        m = sfft.next_fast_len(m + 1, real=True)
    return m


def mesh_wavenumbers(L: float, m: int) -> tuple[np.ndarray, np.ndarray]:
    """``|q|`` [1/length] on the rfft layout of an ``m x m`` mesh (``m`` even) of the window ``L``, and the
    Hermitian weights that sum a real field's spectrum over every mode (2, but 1 on the first and last columns)."""
    h = L / m
    q = 2 * np.pi * np.sqrt(np.fft.fftfreq(m, h)[:, None] ** 2 + np.fft.rfftfreq(m, h)[None, :] ** 2)
    weight = np.full(q.shape, 2.0)
    weight[:, 0] = 1.0
    weight[:, -1] = 1.0
    return q, weight


@jit
def add_pair_products(k, l, w, forces, out):
    """``out += T_short forces`` from the symmetric pair list ``(k, l, w)``, ``k < l``."""
    for i in range(k.size):
        a, b = k[i], l[i]
        out[a] += w[i] * forces[b]
        out[b] += w[i] * forces[a]


_NO_PAIRS = np.empty(0)


@jit
def _pair_weights(k, l, w, factor, node_values):
    """``w + factor (node_values[k] + node_values[l])``, pair by pair (:meth:`PointInteraction.with_pair_weights`)."""
    out = np.empty(w.size)
    for i in range(w.size):
        out[i] = w[i] + factor[i] * (node_values[k[i]] + node_values[l[i]])
    return out


@jit
def _add_short_range(k, l, w, factor, node_values, forces, self_term, shift, out):
    """``out += T_short forces + self_term forces + shift sum(forces)``: the pairs (:func:`add_pair_products`) and
    the constants, in one pass; where ``factor`` is not empty, each pair's weight plus ``factor[i] (node_values[k]
    + node_values[l])`` (:meth:`PointInteraction.with_pair_weights`)."""
    total = 0.0
    for i in range(forces.size):
        total += forces[i]
    total *= shift
    for i in range(forces.size):
        out[i] += self_term * forces[i] + total
    if factor.size == 0:
        add_pair_products(k, l, w, forces, out)
        return
    for i in range(k.size):
        a, b = k[i], l[i]
        weight = w[i] + factor[i] * (node_values[a] + node_values[b])
        out[a] += weight * forces[b]
        out[b] += weight * forces[a]


def gaussian_factors(centers: np.ndarray, L: float, m: int, s: float, support: float):
    """The periodised Gaussian ``exp(-r^2/2s^2) / (2 pi s^2)`` of each centre on the mesh nodes ``i L / m``
    within ``support s`` along each axis, in its separable form: mesh rows ``(N, P)`` (wrapped), each
    block's first column ``(N,)`` and the 1D factors ``gx``, ``gy`` ``(N, P)``; the node
    ``(rows[k, i], (cols[k] + j) mod m)`` weighs ``gx[k, i] gy[k, j]``. :func:`spread_on_mesh` and
    :func:`gather_from_mesh` read ``4 P`` numbers per asperity where the sparse matrix of :func:`_gaussian_gather`
    holds ``2 P^2``."""
    h = L / m
    reach = support * s / h
    p = int(math.floor(2 * reach + 1e-9)) + 1  # nodes within [c - reach h, c + reach h] along an axis
    n = len(centers)
    scale = 1.0 / (2 * s * s)
    # each block's first node and its offset x0 from the centre, and the exponentials of x0 by numpy (vectorised:
    # math.exp in the loop below, four an asperity, took 30 of its 39 us at 10^3 asperities)
    first = np.ceil(np.asarray(centers, dtype=float) / h - reach - 1e-9)
    offset = first * h - centers
    start = np.exp(offset * offset * -scale) * (1.0 / (math.sqrt(2 * math.pi) * s))
    ratio = np.exp(offset * (-2.0 * h * scale))
    steps = np.exp((np.arange(p) * h) ** 2 * -scale)
    rows, cols = np.empty((n, p), np.int64), np.empty(n, np.int64)
    gx, gy = np.empty((n, p)), np.empty((n, p))
    _fill_gaussians(first, start, ratio, steps, m, rows, cols, gx, gy)
    return rows, cols, gx, gy


@jit
def _fill_gaussians(first, start, ratio, steps, m, rows, cols, gx, gy):
    """The factors of :func:`gaussian_factors` from each block's first node ``first`` (N, 2), its Gaussian
    ``start`` and ``ratio`` (N, 2) and the table ``steps`` (P,). Along an axis from the first node's offset ``x0``,
    ``exp(-(x0 + i h)^2 / 2s^2) = exp(-x0^2 / 2s^2) exp(-x0 h / s^2)^i exp(-i^2 h^2 / 2s^2)``: two exponentials per
    asperity and axis and a table of ``p`` (fast Gaussian gridding, Greengard & Lee, SIAM Rev. 46 (2004) 443),
    where one per node took 0.1 ms at 10^3 asperities and ``p = 9``; the same factors to a few units of the last
    place."""
    n, p = gx.shape
    for k in range(n):
        cols[k] = int(first[k, 1]) % m
        row = int(first[k, 0]) % m
        for i in range(p):
            rows[k, i] = row
            row = row + 1 if row + 1 < m else 0
        for axis, g in ((0, gx), (1, gy)):
            value, step = start[k, axis], ratio[k, axis]
            for i in range(p):
                g[k, i] = value * steps[i]
                value *= step


def spread_on_mesh(rows, cols, gx, gy, forces, mesh):
    """``mesh += sum_k forces[k] G_k`` (:func:`gaussian_factors`' separable Gaussians; ``mesh`` zeroed by the
    caller): into a copy of the mesh widened by the support ``P`` (no wrap inside the loops), folded back."""
    p = gx.shape[1]
    if p > mesh.shape[1]:  # supports wider than the mesh: the kernel that wraps every column
        _spread_wrapping(rows, cols, gx, gy, forces, mesh)
        return
    widened = np.zeros((mesh.shape[0], mesh.shape[1] + p))
    _kernels(p)[0](rows, cols, gx, gy, forces, widened)
    _fold(widened, mesh)


def gather_from_mesh(rows, cols, gx, gy, mesh, out):
    """``out[k] = sum_nodes G_k mesh``: from a copy of the mesh widened by the support (its first columns
    repeated), as :func:`spread_on_mesh`."""
    p = gx.shape[1]
    if p > mesh.shape[1]:
        _gather_wrapping(rows, cols, gx, gy, mesh, out)
        return
    widened = np.empty((mesh.shape[0], mesh.shape[1] + p))
    _unfold(mesh, widened)
    _kernels(p)[1](rows, cols, gx, gy, widened, out)


@functools.lru_cache(maxsize=16)  # compiled code, one pair per support width in use (a handful)
def _kernels(p: int):
    """Spreading and gathering compiled for a support of ``p`` nodes a side (a constant of the code, so the
    inner loops unroll: 10^3 asperities at ``p = 9``, 75 -> 36 us spreading and 80 -> 24 us gathering), on a
    mesh widened by ``p`` columns."""

    @jit
    def spread(rows, cols, gx, gy, forces, widened):
        for k in range(gx.shape[0]):
            c = cols[k]
            g = gy[k]
            for i in range(p):
                a = forces[k] * gx[k, i]
                line = widened[rows[k, i], c:c + p]
                for j in range(p):
                    line[j] += a * g[j]

    @jit
    def gather(rows, cols, gx, gy, widened, out):  # indexed, not through row views: 60 -> 24 us at p = 9
        for k in range(gx.shape[0]):
            c = cols[k]
            total = 0.0
            for i in range(p):
                r = rows[k, i]
                row = 0.0
                for j in range(p):
                    row += gy[k, j] * widened[r, c + j]
                total += gx[k, i] * row
            out[k] = total

    return spread, gather


@jit
def _fold(widened, mesh):
    """``mesh +=`` the widened mesh, its extra columns added to the first ones (the periodic wrap)."""
    m = mesh.shape[1]
    for r in range(mesh.shape[0]):
        for j in range(m):
            mesh[r, j] += widened[r, j]
        for j in range(widened.shape[1] - m):
            mesh[r, j] += widened[r, m + j]


@jit
def _unfold(mesh, widened):
    """The widened mesh: ``mesh`` and, after each row, its first columns again."""
    m = mesh.shape[1]
    for r in range(mesh.shape[0]):
        for j in range(m):
            widened[r, j] = mesh[r, j]
        for j in range(widened.shape[1] - m):
            widened[r, m + j] = mesh[r, j]


@jit
def _spread_wrapping(rows, cols, gx, gy, forces, mesh):
    """:func:`spread_on_mesh` on a mesh narrower than the support. ``cols[k]`` is the first column of asperity ``k``'s
    block: a contiguous run of the row unless it wraps past the mesh's edge."""
    n, p = gx.shape
    m = mesh.shape[1]
    for k in range(n):
        c = cols[k]
        for i in range(p):
            a = forces[k] * gx[k, i]
            line = mesh[rows[k, i]]
            if c + p <= m:
                for j in range(p):
                    line[c + j] += a * gy[k, j]
            else:
                for j in range(p):
                    line[(c + j) % m] += a * gy[k, j]


@jit
def _gather_wrapping(rows, cols, gx, gy, mesh, out):
    """:func:`gather_from_mesh` on a mesh narrower than the support."""
    n, p = gx.shape
    m = mesh.shape[1]
    for k in range(n):
        c = cols[k]
        total = 0.0
        for i in range(p):
            line = mesh[rows[k, i]]
            row = 0.0
            if c + p <= m:
                for j in range(p):
                    row += gy[k, j] * line[c + j]
            else:
                for j in range(p):
                    row += gy[k, j] * line[(c + j) % m]
            total += gx[k, i] * row
        out[k] = total


def _gaussian_gather(centers: np.ndarray, L: float, m: int, s: float, support: float) -> sparse.csr_matrix:
    """Sparse ``(N, m*m)`` matrix of the periodised Gaussians of :func:`gaussian_factors`: the gathering
    operator; its transpose spreads. Built row by row directly in CSR (``P^2`` entries a row). The
    products use the separable kernels instead; this matrix is their independent check (tests)."""
    h = L / m
    reach = support * s / h
    p = int(math.floor(2 * reach + 1e-9)) + 1  # nodes within [c - reach h, c + reach h] along an axis
    first = np.ceil(centers / h - reach - 1e-9).astype(int)  # (N, 2)
    offsets = np.arange(p)
    ix = first[:, 0:1] + offsets[None, :]  # (N, P)
    iy = first[:, 1:2] + offsets[None, :]
    gx = np.exp(-((ix * h - centers[:, 0:1]) ** 2) / (2 * s * s)) / (math.sqrt(2 * math.pi) * s)
    gy = np.exp(-((iy * h - centers[:, 1:2]) ** 2) / (2 * s * s)) / (math.sqrt(2 * math.pi) * s)
    n = len(centers)
    columns = ((ix % m).astype(np.int32)[:, :, None] * m + (iy % m).astype(np.int32)[:, None, :]).reshape(n, p * p)
    values = (gx[:, :, None] * gy[:, None, :]).reshape(n, p * p)
    indptr = np.arange(n + 1) * (p * p)
    return sparse.csr_matrix((values.ravel(), columns.ravel(), indptr), shape=(n, m * m))


def _direct_sum(centers: np.ndarray, forces: np.ndarray, E_star: float, block: int = 1024) -> np.ndarray:
    """``u_k = sum_{l != k} P_l / (pi E* r_kl)`` in row blocks (no N x N matrix kept)."""
    out = np.empty(len(forces))
    for start in range(0, len(forces), block):
        rows = slice(start, start + block)
        d = centers[rows, None, :] - centers[None, :, :]
        r = np.sqrt(np.sum(d * d, axis=-1))
        with np.errstate(divide="ignore"):
            inv = np.where(r > 0, 1.0 / r, 0.0)
        out[rows] = inv @ forces
    return out / (math.pi * E_star)
