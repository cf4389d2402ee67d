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
gradients with the matrix-free ``T`` (:mod:`.compliance`); then ``dd = -F - T y``. Load control adds
``delta`` as unknown and ``sum_k P_k = P`` as equation (N + 1 equations): the bordered system is solved by block
elimination (a second solve ``J b = 1``). Damped by backtracking on the residual norm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .asperities import AsperityTable
from .compliance import solve_contact_compliance
from .interaction import PointInteraction, add_pair_products


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
    """Single-asperity law ``P = (4/3) E* sqrt(R) d^(3/2)`` and its derivative ``2 E* a``, ``a = sqrt(R d)``.

    Parameters
    ----------
    radius : ndarray
        Sphere radius of each asperity [length].
    E_star : float
        Contact modulus [pressure].
    """

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

    Returns
    -------
    MacroState
        Forces, local penetrations, approach, iterations, residual and convergence.

    Raises
    ------
    ValueError
        Naming ``mean_pressure`` when no asperity is in contact during the iteration or no approach carries the
        load.
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
