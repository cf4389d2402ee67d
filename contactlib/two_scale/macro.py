"""Macro scale: one force per asperity, with their elastic interaction (seed paper 1, eqs. 1-3).

With the rigid approach ``delta`` measured from the highest summit ``z_top``, asperity ``k`` indents
the body by its local penetration

    d_k = delta - (z_top - z_k) - u_k,    u_k = sum_l T_kl P_l,    P_k = f_k(d_k),

with Hertz's law ``f_k(d) = (4/3) E* sqrt(R_k) max(d, 0)^(3/2)`` (Johnson eq. 4.23) and the point-load
interaction ``T`` of :mod:`.interaction`. The seed writes eq. 3 in the forces; here the unknowns are
the local penetrations ``d_k``:

    F_k(d) = d_k - (delta - z_top + z_k) + sum_l T_kl f_l(d_l) = 0,

because ``f`` is C^1 with ``f'(0) = 0``, so ``F`` is C^1 across contact and separation and Newton's
method needs no active-set switching (an asperity leaving contact simply has ``d_k < 0`` and
``f_k' = 0``), while ``f^-1(P) ~ P^(2/3)`` would make the force form stiff at ``P = 0``.

Newton step: ``J = I + T D``, ``D = diag(f'(d))`` zero off contact. With ``y = D dd`` it reduces to the
symmetric positive definite system ``(D_A^-1 + T_AA) y_A = -F_A`` on the asperities in contact ``A``
(``D^-1`` is each Hertz contact's own compliance ``1 / (2 E* a)``), solved by preconditioned conjugate
gradients with the matrix-free ``T``; then ``dd = -F - T y``. Load control adds ``delta`` as unknown and
``sum_k P_k = P`` as equation (N + 1 equations): the bordered system is solved by block elimination
(a second solve ``J b = 1``). Damped by backtracking on the residual norm.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import scipy.fft as sfft

from .. import fft
from .._numba import jit
from ..solvers.state import dot
from .asperities import AsperityTable
from .interaction import PointInteraction, _fold, _gaussian_factors, _kernels, _unfold, add_pair_products


JACOBIAN_ACCURACY = 1e-3
"""Accuracy of the interaction products inside a Newton step's linear solve, when that solve stops at a relative
residual of at least this (:meth:`.PointInteraction.coarser`): the step is then as good as with the exact
products, and the residual, hence the answer, is still measured with the accurate ones. At 10^3 asperities 6 x 6
Gaussian nodes instead of 9 x 9, a product 0.16 instead of 0.26 ms, for 11 of the 14 products of a solve; the
Newton iterations and residuals unchanged at 10^3 (coverage 0.05-0.4), 3 x 10^3 and 10^4 asperities."""


@dataclass(frozen=True)
class MacroState:
    """Solution of the macro step.

    Attributes
    ----------
    force : ndarray
        ``P_k`` [force].
    local_penetration : ndarray
        ``d_k`` [length] (negative: separated by ``-d_k``).
    penetration : float
        Rigid approach ``delta`` from first contact of the highest summit [length].
    iterations : int
        Newton iterations.
    residual : float
        ``max_k |F_k|`` over the largest local penetration (and, under load control, the relative
        force error, whichever is larger) [1].
    converged : bool
    """

    force: np.ndarray
    local_penetration: np.ndarray
    penetration: float
    iterations: int
    residual: float
    converged: bool


class HertzLaw:
    """Single-asperity law ``P = (4/3) E* sqrt(R) d^(3/2)`` and its derivative ``2 E* a``, ``a = sqrt(R d)``."""

    def __init__(self, radius: np.ndarray, E_star: float):
        self.radius, self.E_star = np.asarray(radius, dtype=float), float(E_star)
        root = np.sqrt(self.radius)
        self._force_factor, self._slope_factor = 4.0 / 3.0 * self.E_star * root, 2.0 * self.E_star * root

    @property
    def length_scale(self) -> float:
        """A length of the law [length]: the largest radius."""
        return float(np.max(self.radius))

    def force(self, d: np.ndarray) -> np.ndarray:
        dp = np.maximum(d, 0.0)
        return self._force_factor * (dp * np.sqrt(dp))  # d^(3/2): a square root is 5x cheaper than a power

    def slope(self, d: np.ndarray) -> np.ndarray:
        return self._slope_factor * np.sqrt(np.maximum(d, 0.0))

    def contact_radius(self, d: np.ndarray) -> np.ndarray:
        return np.sqrt(self.radius * np.maximum(d, 0.0))

    def stiffness(self, force: np.ndarray) -> np.ndarray:
        """``dP/dd = 2 E* a`` at the force ``P``, ``a = (3 P R / (4 E*))^(1/3)`` [force/length]."""
        return 2.0 * self.E_star * np.cbrt(3.0 * np.maximum(force, 0.0) * self.radius / (4.0 * self.E_star))


class FiniteSize:
    """The finite size of the contacts in the interaction of Hertz contacts (symmetric, short-ranged).

    The displacement at ``l`` due to Hertz's pressure of radius ``a_k`` (``<rho^2> = 2 a_k^2 / 5``), averaged
    over ``l``'s contact with the weight of its force's sensitivity (a flat punch of radius ``a_l``:
    ``<rho^2> = 2 a_l^2 / 3``), is ``(P_k / (pi E* r)) [1 + a_k^2/(10 r^2) + a_l^2/(6 r^2) + O(r^-4)]`` (the 2D
    angular mean of ``1/|r - rho|`` is ``(1/r)(1 + rho^2/(4 r^2) + ...)``). Symmetrised, so that the Newton
    steps' system stays SPD: ``(a_k^2 + a_l^2) (2/15) / r^2``. Falling like ``r^-3``, it is summed over the
    neighbour pairs within the reach ``r_c`` of the Ewald sum's short-range part. The farther pairs of a periodic
    field (17-22 % of the term at 10^3 asperities, measured to 0.45 of the window, nearly even: its spread over
    the asperities 10-12 % of its mean) enter as a mean field, the continuum of summits at the field's density
    ``rho`` beyond ``r_c``: ``(2/15) / (pi E*) (2 pi rho / r_c) (a_k^2 <P> + <a^2 P>)`` (a rank-two term; in the
    residual only, the Newton steps keep the pair sum, so they stay SPD). At 10^3 asperities (coverage 0.2 and
    0.4) the pairs take the macro step's largest asperity-force error from 6.1e-3 and 1.1e-2 to 4.9e-3 and 5.3e-3
    of the largest force and the total force's from 4.3e-3 and 1.3e-2 to 1.5e-3 and 4.0e-3; the far tail then to
    4.5e-3 and 3.7e-3, and 8.3e-4 and 1.1e-3 (against the full solver at tol 1e-8; the same Newton steps)."""

    def __init__(self, table: AsperityTable, E_star: float):
        k, l, r = table.neighbour_pairs(table.neighbour_reach)  # the Ewald sum's pairs: no second query
        self._k, self._l = k, l
        self._g = (2.0 / 15.0) / (math.pi * E_star * (r * r * r))  # numpy's r**3 is a pow: 25x slower
        # the far pairs' mean field, per unit of <a^2 P>: a non-periodic field's far side is not a continuum
        self._tail = (2.0 / 15.0) / (math.pi * E_star) * 2 * math.pi / (table.length**2 * table.neighbour_reach) \
            if table.periodic else 0.0

    def weights(self, radius_squared: np.ndarray) -> np.ndarray:
        """The term's weight of each neighbour pair [length/force] at the contacts' squared radii [length^2]."""
        return self._g * (radius_squared[self._k] + radius_squared[self._l])

    def corrected(self, interaction, radius_squared: np.ndarray, *, reused: bool = False):
        """``T + S(a)`` over the neighbour pairs at fixed contact radii (``reused``: for several products): for an
        Ewald interaction over the same pairs, a copy with the term in its pair loop (one pair loop a product, not
        two), else a wrapper."""
        combined = interaction.with_pair_weights(self._k, self._l, self._g, radius_squared, reused=reused) \
            if isinstance(interaction, PointInteraction) else None
        return combined if combined is not None else \
            _Corrected(interaction, self._k, self._l, self.weights(radius_squared))

    def add_far_pairs(self, radius_squared: np.ndarray, forces: np.ndarray, out: np.ndarray) -> None:
        """``out +=`` the far pairs' mean field [length] (none for a non-periodic field)."""
        if self._tail:  # (N / A) (1/N) sums: the density and the means in one factor
            out += self._tail * (radius_squared * float(forces.sum()) + float(radius_squared @ forces))

    def __call__(self, radius_squared: np.ndarray, forces: np.ndarray) -> np.ndarray:
        """The displacement at each summit [length] due to the finite size of the others' contacts (squared
        radii [length^2]) carrying ``forces`` [force]."""
        out = np.zeros(forces.size)
        add_pair_products(self._k, self._l, self.weights(radius_squared), forces, out)
        self.add_far_pairs(radius_squared, forces, out)
        return out


class _Corrected:
    """``T + S(a)``: the interaction with the finite-size pair weights at fixed contact radii, for the Newton steps."""

    def __init__(self, interaction, k: np.ndarray, l: np.ndarray, weights: np.ndarray):
        self.interaction, self._pairs = interaction, (k, l, weights)
        self.diagonal = interaction.diagonal

    def __call__(self, forces: np.ndarray) -> np.ndarray:
        out = self.interaction(forces)
        add_pair_products(*self._pairs, forces, out)
        return out


def solve_macro(table: AsperityTable, interaction: PointInteraction, law: HertzLaw, *,
                penetration: float | None = None, total_force: float | None = None, z_top: float | None = None,
                known_displacement: np.ndarray | None = None, tol: float = 1e-10, max_iter: int = 100,
                finite_size: FiniteSize | None = None) -> MacroState:
    """Solve eq. 3 of the seed for the asperity forces, under displacement or load control.

    Parameters
    ----------
    table, interaction, law
        The asperities, their interaction operator ``T`` and the single-asperity law.
    penetration : float
        Displacement control: ``delta`` [length].
    total_force : float
        Load control: ``sum_k P_k`` [force]; ``delta`` is then an unknown.
    z_top : float, optional
        Height from which ``delta`` is measured [length] (default: the highest summit).
    known_displacement : ndarray, optional
        A displacement of the body at each summit that does not depend on the forces sought [length]:
        the hook for a time-stepping caller (the seed's eq. 4: over a step with a constant pressure rate,
        the history's displacement is known and the increment solves this elastic problem with the
        step's effective modulus in ``interaction`` and ``law``).
    tol : float
        Target of :attr:`MacroState.residual`.
    max_iter : int
        Newton iterations at most; the state returned says whether it converged.
    finite_size : FiniteSize, optional
        Add the finite size of the contacts to the point-load interaction (Hertz contacts; the Newton steps
        take it at the current contact radii, the residual at the exact ones).
    """
    z_top = float(table.summit_height.max()) if z_top is None else float(z_top)
    # a known displacement lowers the summits it lifts the body above: the same problem, shifted heights
    z = table.summit_height if known_displacement is None else \
        table.summit_height - np.asarray(known_displacement, dtype=float)
    load_control = total_force is not None
    if load_control:
        if total_force == 0:
            return MacroState(np.zeros_like(z), z - z_top, 0.0, 0, 0.0, True)
        delta = _uncoupled_approach(z - z_top, law, total_force)
    else:
        delta = float(penetration)
    d = delta + z - z_top  # uncoupled start: each asperity as if alone
    scale = max(float(np.max(np.abs(delta + z - z_top))), 1e-300)

    def residual_of(d, delta):
        forces = law.force(d)
        if finite_size is None:
            F = interaction(forces)
        else:  # the term in the product's own pair loop, its far pairs after
            radius_squared = law.radius * np.maximum(d, 0.0)
            F = finite_size.corrected(interaction, radius_squared)(forces)
            finite_size.add_far_pairs(radius_squared, forces, F)
        F += d - (delta + z - z_top)
        norm = float(np.max(np.abs(F))) / scale
        if load_control:
            norm = max(norm, abs(float(law.force(d).sum()) - total_force) / total_force)
        return F, norm

    F, norm = residual_of(d, delta)
    jacobian = None
    it = 0
    for it in range(1, max_iter + 1):
        if norm <= tol:
            it -= 1
            break
        slope = law.slope(d)
        # inexact Newton: the linear solve only as tight as the step needs, and never tighter than what
        # brings the residual (quadratic from here) to a tenth of tol (10^4 asperities: 54 -> 34 products)
        rtol = min(1e-2, max(0.1 * norm, 0.1 * tol / norm))
        operator = interaction
        if rtol >= JACOBIAN_ACCURACY:  # the linear solve stops above the coarser products' error: they do
            jacobian = interaction.coarser(JACOBIAN_ACCURACY) if jacobian is None else jacobian
            operator = jacobian
        if finite_size is not None:  # in the step too: without it, 3 Newton steps instead of 2 at coverage 0.4
            operator = finite_size.corrected(operator, law.radius * np.maximum(d, 0.0), reused=True)
        a = _newton_solve(operator, slope, -F, rtol=rtol)
        if load_control:
            b = _newton_solve(operator, slope, np.ones_like(d), rtol=rtol)
            sb = float(slope @ b)
            if sb <= 0:
                raise ValueError("mean_pressure: no asperity in contact during the Newton iteration")
            step_delta = (total_force - float(law.force(d).sum()) - float(slope @ a)) / sb
            step = a + b * step_delta
        else:
            step_delta, step = 0.0, a
        lam = 1.0
        for _ in range(40):  # backtracking: accept the first step that lowers the residual
            d_new, delta_new = d + lam * step, delta + lam * step_delta
            F_new, norm_new = residual_of(d_new, delta_new)
            if norm_new < norm or lam < 1e-10:
                break
            lam *= 0.5
        d, delta, F, norm = d_new, delta_new, F_new, norm_new
    return MacroState(law.force(d), d, float(delta), it, norm, norm <= tol)


def _newton_solve(interaction: PointInteraction, slope: np.ndarray, rhs: np.ndarray, *,
                  rtol: float = 1e-12) -> np.ndarray:
    """Solve ``(I + T D) x = rhs``, ``D = diag(slope)``, through the SPD system on the contact set
    (``x = rhs - T y``, with ``T y`` from the conjugate gradients' own products)."""
    _, product = solve_contact_compliance(interaction, slope, rhs, rtol=rtol, with_product=True)
    return rhs - product


def solve_contact_compliance(interaction: PointInteraction, slope: np.ndarray, rhs: np.ndarray, *,
                             rtol: float = 1e-12, with_product: bool = False, smooth_preconditioner: bool = True):
    """``y`` with ``(D_A^-1 + T_AA) y_A = rhs_A`` on the asperities in contact ``A = {slope > 0}`` and 0
    elsewhere: the compliance of the contacts (each Hertz contact's own, ``1 / slope``, plus the
    interaction) inverted by conjugate gradients, to ``||r|| <= rtol ||rhs_A||`` [force per unit of ``rhs``],
    preconditioned by :class:`SmoothPreconditioner` where it applies (``smooth_preconditioner``), else by the
    diagonal. ``with_product``: also return ``T y`` on every asperity, summed from the iteration's own products
    ``T p`` (no extra product).

    A loop of its own rather than :func:`scipy.sparse.linalg.cg`: it sums ``T y`` from its products, and
    scipy's wrappers cost as much again per call as a product when one took 0.6 ms at 10^3 asperities."""
    n = slope.size
    y = np.zeros(n)
    product = np.zeros(n)
    active = np.flatnonzero(slope > 0)
    if active.size:
        every = active.size == n  # all in contact: no scatter and gather around each product
        compliance, inverse, r, z, direction = (np.empty(active.size) for _ in range(5))
        diagonal = np.ascontiguousarray(interaction.diagonal, dtype=float)
        rr, rz = _cg_start(active, slope, diagonal, np.ascontiguousarray(rhs, dtype=float), compliance, inverse, r,
                           z, direction)
        smooth = SmoothPreconditioner.for_contacts(interaction, active, compliance + diagonal[active]) \
            if smooth_preconditioner else None
        if smooth is not None:
            rz, smooth = _smooth_or_diagonal(smooth, r, z, inverse, 0.0, direction)
        target = max(rtol, 1e-12) * math.sqrt(rr)
        x = np.zeros(active.size)
        full = np.zeros(n)
        for _ in range(10 * active.size + 100):
            if math.sqrt(rr) <= target:
                break
            if every:
                t_full = interaction(direction)
            else:
                full[active] = direction
                t_full = interaction(full)
            rr, rz_next = _cg_iteration(rz, direction, t_full, every, active, compliance, x, r, inverse, z, product,
                                        smooth is None)
            if smooth is None:
                rz = rz_next
            else:
                rz, smooth = _smooth_or_diagonal(smooth, r, z, inverse, rz, direction)
        y[active] = x
    return (y, product) if with_product else y


@jit
def _cg_start(active, slope, diagonal, rhs, compliance, inverse, r, z, direction):
    """The start of :func:`solve_contact_compliance` on the contact set ``active``, in one pass: each Hertz
    contact's own compliance ``1 / slope``, the diagonal preconditioner, the residual ``r`` (the right-hand side),
    ``z = inverse r`` and the first direction; returns ``(r.r, r.z)``."""
    rr = 0.0
    rz = 0.0
    for i in range(active.size):
        k = active[i]
        compliance[i] = 1.0 / slope[k]  # 1 / (2 E* a)
        inverse[i] = 1.0 / (compliance[i] + max(diagonal[k], 0.0))
        r[i] = rhs[k]
        z[i] = inverse[i] * r[i]
        direction[i] = z[i]
        rr += r[i] * r[i]
        rz += r[i] * z[i]
    return rr, rz


@jit
def _cg_iteration(rz, direction, product_full, every, active, compliance, x, r, inverse, z, product, diagonal):
    """One preconditioned CG iteration after the product ``T p`` on every asperity (``product_full``; the contact
    set's entries at ``active`` unless ``every``): the step, ``x``, ``r``, the sum of the products ``T y`` and,
    with the ``diagonal`` preconditioner, ``z = inverse r`` and the next direction, in place; returns ``(r.r,
    r.z)`` (``r.z`` 0 without ``diagonal``: :func:`_cg_direction` follows the caller's preconditioner). As numpy
    expressions these passes, with their three inner products, cost more than the product's own arithmetic at
    10^3 asperities."""
    curvature = 0.0
    for i in range(x.size):
        t = product_full[i] if every else product_full[active[i]]
        curvature += direction[i] * (compliance[i] * direction[i] + t)
    step = rz / curvature
    rr = 0.0
    rz_next = 0.0
    for i in range(x.size):
        t = product_full[i] if every else product_full[active[i]]
        x[i] += step * direction[i]
        r[i] -= step * (compliance[i] * direction[i] + t)
        rr += r[i] * r[i]
        if diagonal:
            z[i] = inverse[i] * r[i]
            rz_next += r[i] * z[i]
    for j in range(product.size):
        product[j] += step * product_full[j]
    if diagonal:
        beta = rz_next / rz
        for i in range(x.size):
            direction[i] = z[i] + beta * direction[i]
    return rr, rz_next


def _smooth_or_diagonal(smooth, r, z, inverse, rz, direction):
    """The next direction with the smooth preconditioner, or, where it is not positive on this residual (contacts
    far from evenly scattered, which its Fourier multiplier assumes), a restart with the diagonal one from here on
    (conjugate gradients need a positive preconditioner; this checks it on the residuals met, not everywhere);
    returns ``(r.z, the preconditioner kept)``."""
    if smooth(r, z) > 0:
        return _cg_direction(z, r, rz, direction), smooth
    np.multiply(inverse, r, out=z)
    return _cg_direction(z, r, 0.0, direction), None  # a steepest-descent step: the directions start again


@jit
def _cg_direction(z, r, rz, direction):
    """The next CG direction ``z + (r.z / rz) direction`` from the preconditioned residual ``z`` (the first one,
    ``z``, where ``rz`` is 0); returns ``r.z``."""
    rz_next = 0.0
    for i in range(z.size):
        rz_next += r[i] * z[i]
    beta = rz_next / rz if rz != 0.0 else 0.0
    for i in range(z.size):
        direction[i] = z[i] + beta * direction[i]
    return rz_next


SMOOTH_WIDTH = 0.5
""":class:`SmoothPreconditioner`'s Gaussian width in mean spacings of the asperities in contact."""
SMOOTH_MIN_CONTACTS = 64
"""Fewer asperities in contact: the diagonal preconditioner (a handful of iterations anyway)."""


class SmoothPreconditioner:
    """An approximate inverse of the contact compliance ``K = D + T`` on the asperities in contact (``D`` each
    Hertz contact's own compliance), for the conjugate gradients of :func:`solve_contact_compliance`.

    With the diagonal alone, the contacts' collective compliance at long wavelengths sets the condition number
    (5-6 at 10^3 asperities, coverage 0.4: a Newton step's solve takes 4 and 7 products at ``rtol`` 1e-2 and
    1.3e-3). Here ``T`` is split into its diagonal and its part smooth at the scale of the spacing,
    ``T_s = S G S^T``: the forces spread with Gaussians of width :data:`SMOOTH_WIDTH` spacings onto a mesh of
    about one node per asperity, Boussinesq's multiplier ``G = 2 / (E* q)`` there, gathered back with the same
    Gaussians. ``D' + T_s`` (``D' = diag(K) - diag(T_s)``) is inverted by Woodbury's identity, its mesh-sized
    inner inverse ``(I + W G)^-1``, ``W = S^T D'^-1 S``, replaced by the Fourier multiplier of ``W`` for
    uniformly scattered contacts, ``rho <1/D'> exp(-s^2 q^2)``:

        M z = D'^-1 r - D'^-1 S [G / (1 + rho <1/D'> exp(-s^2 q^2) G)] S^T D'^-1 r,

    a spreading, an FFT pair on a mesh of about ``N`` nodes and a gathering (about 20 us at 10^3 asperities,
    against 80 us for a product). Measured on the Newton steps at 10^3 asperities (coverage 0.4): condition
    number 1.3-1.7 with the exact inner inverse, 4 -> 2 and 7 -> 3 products with this one; the periodic
    (Ewald) interaction only. Positive definite for evenly scattered contacts, not guaranteed for clustered ones
    (114 contacts in a disc of a 400-asperity window: smallest eigenvalue -1.5e-4 of the largest 0.029; the CG
    converged, in 17 products against the diagonal's 15): the CG restarts with the diagonal on a residual where
    ``r.z <= 0``, which no field of the benchmark met."""

    def __init__(self, centers: np.ndarray, length: float, E_star: float, diagonal: np.ndarray, *,
                 factors: tuple | None = None):
        count = len(centers)
        width = SMOOTH_WIDTH * length / math.sqrt(count)
        # one node per two widths: the Gaussians are a smoothing here, not a quadrature to be resolved
        self._mesh = m = _smooth_mesh_size(length, width)
        spacing = length / m
        self.factors = _gaussian_factors(centers, length, m, width, 3.0) if factors is None else factors
        if self.factors[2].shape[1] > m:  # the widened mesh folds back p columns: p <= m (10 contacts or more)
            raise ValueError(f"SmoothPreconditioner: {count} contacts make a {m}^2 mesh narrower than the Gaussians")
        boussinesq, smoothing, self_term = _smooth_symbols(length, m, width, E_star)
        # D' keeps diag(D' + T_s) = diag(K); floored: a preconditioner must stay positive definite
        self._inverse = 1.0 / np.maximum(diagonal - self_term, 0.5 * diagonal)
        density_compliance = float(self._inverse.sum()) / length**2
        # fftw's inverse is unnormalised; the spreading and gathering leave out the node area: h^2 / m^2
        self._multiplier = boussinesq / (1.0 + density_compliance * smoothing * boussinesq) * (
            spacing * spacing / (m * m))
        self._plan = fft.get_fft((m, m), slot="smooth-preconditioner")  # this thread's: a solve uses it, no other
        # the mesh widened by the support (no wrap inside the compiled loops), as the interaction's products
        self._widened = np.empty((m, m + max(self.factors[2].shape[1], 1)))

    @classmethod
    def for_contacts(cls, interaction, active: np.ndarray, diagonal: np.ndarray) -> "SmoothPreconditioner | None":
        """The preconditioner of the contacts ``active`` with the diagonal ``diag(K)`` [length/force], for an
        Ewald (periodic) interaction and at least :data:`SMOOTH_MIN_CONTACTS` contacts; None otherwise. The
        Gaussians of the last contact set are kept for the next (a solve's Newton steps share their set)."""
        geometry = getattr(interaction, "geometry", None)
        if geometry is None or active.size < SMOOTH_MIN_CONTACTS or not float(diagonal.min()) > 0:
            return None  # (T_kk < 0 is about -1 / (E* L), far below a separate contact's compliance 1 / (2 E* a))
        centers, length = geometry
        last = _last_factors[0]  # one read: another thread may replace it meanwhile
        reuse = last is not None and last[0] is centers and last[1] == length and np.array_equal(last[2], active)
        preconditioner = cls(centers[active], length, interaction.E_star, diagonal,
                             factors=last[3] if reuse else None)
        if not reuse:
            _last_factors[0] = (centers, length, active.copy(), preconditioner.factors)
        return preconditioner

    def __call__(self, residual: np.ndarray, out: np.ndarray) -> float:
        """``out = M residual``; returns ``residual . out``."""
        rows, cols, gx, gy = self.factors
        spread, gather = _kernels(gx.shape[1])
        plan, widened = self._plan, self._widened
        widened.fill(0.0)
        spread(rows, cols, gx, gy, self._inverse * residual, widened)
        plan.real.fill(0.0)
        _fold(widened, plan.real)
        spectrum = plan.forward()
        spectrum *= self._multiplier
        _unfold(plan.inverse(), widened)
        gather(rows, cols, gx, gy, widened, out)
        return _smooth_finish(self._inverse, residual, out)


@jit
def _smooth_finish(inverse, residual, out):
    """``out = D'^-1 (residual - out)`` (``out`` the gathered mesh); returns ``residual . out``."""
    rz = 0.0
    for k in range(out.size):
        out[k] = inverse[k] * (residual[k] - out[k])
        rz += residual[k] * out[k]
    return rz


_last_factors = [None]
"""``(centers, length, active, Gaussian factors)`` of the last :class:`SmoothPreconditioner` built."""


def _smooth_mesh_size(length: float, width: float) -> int:
    """An even fast FFT size with a node every two Gaussian widths or closer."""
    m = max(sfft.next_fast_len(int(math.ceil(length / (2.0 * width))), real=True), 4)
    while m % 2:
        m = sfft.next_fast_len(m + 1, real=True)
    return m


@functools.lru_cache(maxsize=16)
def _smooth_symbols(length: float, m: int, width: float, E_star: float) -> tuple[np.ndarray, np.ndarray, float]:
    """On the rfft layout of an ``m x m`` mesh of the window: Boussinesq's multiplier ``2 / (E* q)`` (0 at
    ``q = 0``: the periodic, zero-mean half-space), the Gaussians' squared transform ``exp(-s^2 q^2)``, and the
    smooth part's own value at ``r = 0``, ``(1/A) sum_q G exp(-s^2 q^2)`` (read-only; cached per window)."""
    h = length / m
    q = 2 * np.pi * np.sqrt(np.fft.fftfreq(m, h)[:, None] ** 2 + np.fft.rfftfreq(m, h)[None, :] ** 2)
    boussinesq = np.zeros_like(q)
    boussinesq[q > 0] = 2.0 / (E_star * q[q > 0])
    smoothing = np.exp(-(width * q) ** 2)
    weight = np.full(q.shape, 2.0)  # the rfft layout's Hermitian weights (m even)
    weight[:, 0] = 1.0
    weight[:, -1] = 1.0
    self_term = float(np.sum(weight * boussinesq * smoothing)) / length**2
    for array in (boussinesq, smoothing):
        array.setflags(write=False)
    return boussinesq, smoothing, self_term


def _uncoupled_approach(offsets: np.ndarray, law: HertzLaw, total_force: float) -> float:
    """``delta`` with ``sum_k f_k(delta + offsets_k) = total_force`` and no interaction (bisection)."""
    lo = 0.0
    scale = max(float(np.ptp(offsets)), law.length_scale * 1e-6)
    hi = scale
    while float(law.force(hi + offsets).sum()) < total_force:
        hi *= 2.0
        if not math.isfinite(hi):
            raise ValueError(f"mean_pressure {total_force!r}: no approach carries this load")
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if float(law.force(mid + offsets).sum()) < total_force:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-15 * max(hi, 1e-300):
            break
    return 0.5 * (lo + hi)
