"""Contact with a compliance that is a complex Fourier multiplier ``M(q)``, ``Re M > 0``, however skew.

A viscoelastic body in steady sliding where the loss modulus dominates (``E_inf / E0 = 1000`` at
``V tau q0 ~ 1e-4 .. 1e-2``: ``|Im M| / Re M`` up to 16 over much of the band, ``|M|`` spanning 1e5) is
where the fixed point on the skew part (:mod:`.coupled`) stalls. The complementarity problem

    p >= 0,   g = M p - h - d >= 0,   p g = 0,   mean(p) = P  (or d given)

is the monotone inclusion ``0 in (M p - h - d) + N(p)`` (``N`` the normal cone of ``p >= 0``; ``d`` the
multiplier of the load), and Douglas-Rachford splitting (Lions & Mercier, SIAM J. Numer. Anal. 16, 1979)
converges for any monotone ``M``, symmetric or not, and any step ``gamma > 0``. Its two resolvents are
cheap here: the projection onto ``p >= 0`` is pointwise, and ``(I + gamma M)^-1`` is the multiplier
``1 / (1 + gamma M(q))`` (one FFT pair), with the mean mode fixed by the load (where ``d`` enters). The
iteration on ``z`` (the modulus-based iteration of Bai, Numer. Linear Algebra Appl. 17, 2010)::

    p = max(z, 0);   y = (I + gamma A)^-1 (2 p - z);   z <- z + y - p,

has at its fixed point ``p = max(z, 0)`` and ``gamma g = max(-z, 0)``: ``z = p - gamma g``.

Its rate depends on ``gamma`` against the spread of ``|M|`` on the contact set, which no single number
fits (a Fourier-diagonal metric would make the projection a contact problem itself). Measured on a
1024-point profile, E_inf/E0 = 1000: the best ``gamma`` is near ``10 |p| / |g|`` at the solution (the
balance of the two halves of ``z``) at partial contact, larger at full contact; so ``gamma`` starts at
the balance of the load and the roughness and is re-balanced every :data:`BALANCE_EVERY` iterations
(``z`` rescaled so ``p`` and ``g`` stay) until :data:`BALANCE_UNTIL`, then frozen (convergence holds
for the frozen step). Anderson mixing on the fixed-point map (type II, safeguarded as Zhang,
O'Donoghue & Boyd, SIAM J. Optim. 30, 2020: a mixed step is kept only while the fixed-point residual
keeps falling, else the plain step is taken and the memory cleared) cuts the iterations further.

The residual is :func:`.contact_residual` of the projected pressure (mean rescaled to the load) and
its true gap, so ``tol`` means what it means for every solver.

Douglas-Rachford converges linearly, and slowly where the contact is small: 3 000-16 000 iterations on a
1024-point profile at 0.3-2 % contact. A caller may pass ``finish``, a local method tried from the iterate
(the semismooth Newton loop, :mod:`.nonsymmetric_choice`): near the answer its contact set is nearly the
final one, where that loop converges in a few set updates even on bodies where it diverges from a cold start.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from ...core import fft
from ...kernels.viscoelastic import real_where_self_conjugate
from ..anderson import Anderson
from ..state import ContactState, contact_residual, height_scale

BALANCE_FACTOR = 10.0
"""``gamma = BALANCE_FACTOR |p| / |g|``: measured best within 3x on E_inf/E0 = 1000, V tau q0 = 1e-3, 1e-2."""

BALANCE_EVERY = 50
"""Iterations between re-balancings of ``gamma``."""

BALANCE_UNTIL = 2000
"""Iterations after which ``gamma`` is frozen."""

CHECK_EVERY = 10
"""Iterations between evaluations of the contact residual (one more FFT pair)."""

SPLIT_ABOVE = 4.0
"""A viscoelastic body whose factor has ``max |Im f| / Re f`` above this is solved here directly, not by the
fixed point on the skew part. Measured on a 1024-point profile, load 0.5 E0: E_inf/E0 = 10 (ratio 1.4)
and E_inf/E0 = 1000 at V tau q0 = 1 (ratio 1.0) converge there, 0.3-15x faster than here; E_inf/E0 = 1000
at V tau q0 = 1e-4 .. 1e-2 (ratio 15.8) stalls there (residual 1e-5 .. 0.6) and converges here in
750-1100 iterations. Friction's skew part is left to the coupled solver's ``|W|`` split, which converges
(thin confined layer, ratio 15: as fast as here); a stall of it falls back here anyway."""

ANDERSON_MEMORY = 10
"""Past differences kept by the Anderson mixing."""

ANDERSON_RIDGE = 1e-10
"""Relative ridge of the mixing's normal equations (:class:`.anderson.Anderson`)."""

FINISH_FIRST = 1000
"""Iterations before the first try of ``finish`` (:func:`solve_splitting`); then after twice as many, and so on,
and once more when ``max_iter`` passes. Where Douglas-Rachford converges sooner (500-1500 iterations at 10-60 %
contact) nothing is tried."""

FINISH_BELOW = 1e-4
"""``finish`` is tried only from an iterate whose residual is below this: from 1e-3 the Newton loop failed on two
of six 1024-point profiles (E_inf/E0 = 1000), from 1e-4 on none."""


def loss_dominated(factor: np.ndarray | None) -> bool:
    """Whether a viscoelastic factor (:func:`contactlib.kernels.viscoelastic.steady_sliding_factor`; None: an
    elastic body) is skew beyond :data:`SPLIT_ABOVE` at some non-zero wavevector."""
    if factor is None:
        return False
    nonzero = factor.reshape(-1)[1:]  # every wavevector but q = 0 (a slice: no masked copy)
    return float(np.max(np.abs(nonzero.imag) / nonzero.real)) > SPLIT_ABOVE


def fourier_multiplier(compliance, coupling=None) -> np.ndarray:
    """The complex multiplier ``M(q)`` of a periodic body on the rfft layout, in the convention
    ``displacement = irfftn(M rfftn(p))`` [length/pressure]: the symmetric compliance's plus the skew part's
    (the body model's split, whatever it is, sums back to ``K + i W``).

    On the modes that are their own mirror image (index 0 or Nyquist on every axis) the inverse real
    transform keeps only the real part of a spectrum, so there the operators act with ``Re M``: the
    multiplier says so, or the resolvent ``1 / (1 + gamma M)`` would be another operator's (a residual
    floor near 1e-7 on a frictional 2D scene). The rest of the Nyquist planes are made even where the kernels are
    built (:mod:`contactlib.kernels.nyquist`): the last axis's Nyquist column holds the pairs ``(i, n/2)`` and
    ``(-i, n/2)``, one mode and its conjugate, which a kernel taken at numpy's sign did not give conjugate values
    (Douglas-Rachford stagnated at 2e-5 on a viscoelastic slide off the grid's axes)."""
    count = float(np.prod(compliance.work_shape))
    total = compliance.multiplier.astype(complex) * count
    if coupling is not None:
        total = total + coupling.multiplier * count
    return real_where_self_conjugate(compliance.grid, total)


def solve_splitting(
    multiplier: np.ndarray,
    heights: np.ndarray,
    *,
    mean_pressure: float | None = None,
    penetration: float | None = None,
    tol: float = 1e-8,
    max_iter: int = 100_000,
    initial_pressure: np.ndarray | None = None,
    memory: int = ANDERSON_MEMORY,
    finish=None,
) -> ContactState:
    """Pressure under ``heights`` [length] on a periodic body of compliance multiplier ``multiplier``.

    Parameters
    ----------
    multiplier : ndarray, complex
        ``M(q)`` on the rfft layout of ``heights`` (:func:`fourier_multiplier`), ``Re M >= 0``; ``M(0)``
        is the uniform compliance (0 on a half-space: displacements zero-mean).
    mean_pressure, penetration : float
        Exactly one: the load [pressure], or the approach from first contact [length].
    tol : float
        Target of :func:`.contact_residual`.
    max_iter : int
        Douglas-Rachford iterations (each one FFT pair) before returning unconverged; ``finish``'s own iterations
        come on top of them.
    initial_pressure : ndarray, optional
        Warm start.
    finish : callable, optional
        ``finish(pressure) -> ContactState``: a local method started from an iterate (residual below
        :data:`FINISH_BELOW`, after :data:`FINISH_FIRST`, twice as many, ... iterations, and at ``max_iter``); its
        converged state is returned, its iterations added to these. An unconverged one is dropped and the
        iteration goes on.

    Returns
    -------
    ContactState
        ``converged`` False (with the residual reached) when ``max_iter`` passes.
    """
    load_control = mean_pressure is not None
    if load_control == (penetration is not None):
        raise ValueError("give exactly one of mean_pressure and penetration")
    shape, count = heights.shape, heights.size
    scale = height_scale(heights)
    relative = heights - heights.max()  # gap = M p - relative - d
    relative_hat = fft.rfftn(relative)
    M0 = float(multiplier.flat[0].real)
    if load_control and mean_pressure <= 0:
        zero = np.zeros(shape)
        return ContactState(zero, -relative, zero.copy(), 0.0, 0.0, 0, 0.0, True, "douglas-rachford")
    if not load_control and penetration <= 0:  # p = 0 leaves every gap open: the (unique) solution
        zero = np.zeros(shape)
        return ContactState(zero, -relative - penetration, zero.copy(), float(penetration), 0.0, 0, 0.0, True,
                            "douglas-rachford")

    load = mean_pressure if load_control else None

    def resolvent(v_hat, gamma, inverse):
        """``(I + gamma A)^-1`` on the spectrum of ``v``: the new ``y`` spectrum and the approach ``d``."""
        y_hat = (v_hat + gamma * relative_hat) * inverse
        if load_control:  # the mean mode carries the load; d is what makes it so
            y0 = load * count
            d = (y0 * (1 + gamma * M0) - gamma * relative_hat.flat[0].real - v_hat.flat[0].real) / (gamma * count)
            y_hat.flat[0] = y0
        else:
            d = float(penetration)
            y_hat.flat[0] = (v_hat.flat[0].real + gamma * (relative_hat.flat[0].real + d * count)) / (1 + gamma * M0)
        return y_hat, d

    def evaluate(p, d):
        """The state at ``p`` (its mean set to the load) with the approach that fits it best."""
        if load_control and p.mean() > 0:
            p = p * (load / p.mean())
        u = fft.irfftn(multiplier * fft.rfftn(p), shape)
        # the approach: the one under load control from the iteration; a penetration is given
        gap = u - relative - d
        return p, u, gap, contact_residual(p, gap, scale)

    if initial_pressure is not None and np.any(initial_pressure > 0):
        p0 = np.maximum(initial_pressure, 0.0)
        if load_control:
            p0 = p0 * (load / p0.mean())
    else:
        p0 = np.full(shape, load if load_control else 0.0)
        if not load_control:  # start from the rigid-punch guess: pressure where the approach overlaps
            p0 = np.maximum(relative + penetration, 0.0) / max(scale, 1e-300)
    # first gamma: the load over the roughness, the balance of a state with full contact
    typical = float(np.mean(p0)) if np.mean(p0) > 0 else 1.0
    gamma = BALANCE_FACTOR * typical / scale
    inverse = 1.0 / (1.0 + gamma * multiplier)
    z = p0.copy()  # gap 0 guess
    mixer = Anderson(memory, ridge=ANDERSON_RIDGE)
    best, d, state_fields = np.inf, 0.0, None
    it, finish_at, finish_iterations, best_at, tried = 0, FINISH_FIRST, 0, 0, set()

    def finished(p, residual, of, done):
        """``finish``'s converged state from ``p`` (residual ``residual``, the iterate of iteration ``of``, after
        ``done`` iterations), or None; an iterate tried once is not tried again (the same deterministic failure)."""
        nonlocal finish_iterations
        if finish is None or residual > FINISH_BELOW or of in tried:
            return None
        tried.add(of)
        state = finish(p)
        finish_iterations += state.iterations
        if not state.converged:
            return None
        return dataclasses.replace(state, iterations=done + finish_iterations,
                                   solver=f"douglas-rachford+{state.solver}")

    for it in range(1, max_iter + 1):
        p = np.maximum(z, 0.0)
        y_hat, d = resolvent(fft.rfftn(2 * p - z), gamma, inverse)
        y = fft.irfftn(y_hat, shape)
        Tz = z + y - p
        f = y - p
        plain = mixer.retreat(f)
        if plain is not None:  # safeguard: the mixed step did not lower the fixed-point residual: the plain one
            z = plain
            continue
        if it % CHECK_EVERY == 0:
            fields = evaluate(p, d)
            if fields[3] < best:
                best, state_fields, best_at = fields[3], (fields, d), it
            if fields[3] <= tol:
                break
            if it >= finish_at:
                finish_at *= 2
                done = finished(fields[0], fields[3], it, it)
                if done is not None:
                    return done
        if it % BALANCE_EVERY == 0 and it <= BALANCE_UNTIL:
            g = np.maximum(-z, 0.0) / gamma
            gnorm = _norm(g)
            if gnorm > 0:
                target = BALANCE_FACTOR * _norm(p) / gnorm
                if not 0.5 < target / gamma < 2.0:
                    gamma = target
                    inverse = 1.0 / (1.0 + gamma * multiplier)
                    z = p - gamma * g
                    mixer.reset()
                    continue
        z = mixer.next(Tz, f) if memory > 0 else Tz
    if state_fields is None:  # stopped before the first check
        state_fields = (evaluate(np.maximum(z, 0.0), d), d)
    (p, u, gap, residual), d = state_fields
    if residual > tol:  # max_iter passed: a last try from the best iterate
        done = finished(p, residual, best_at, it)
        if done is not None:
            return done
    return ContactState(pressure=p, gap=gap, displacement=u, penetration=float(d), mean_pressure=float(p.mean()),
                        iterations=it + finish_iterations, residual=residual, converged=bool(residual <= tol),
                        solver="douglas-rachford")


def _dot(a: np.ndarray, b: np.ndarray) -> float:
    """Inner product without BLAS (whose threads fight over shared cores for these short vectors)."""
    return float(np.einsum("i,i->", a.ravel(), b.ravel()))


def _norm(a: np.ndarray) -> float:
    return float(np.sqrt(_dot(a, a)))
