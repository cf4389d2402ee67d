"""The Anderson mixer (:mod:`contactlib.solvers.anderson`) on linear contractions whose fixed points are known."""

import numpy as np
import pytest

from contactlib.solvers.anderson import Anderson


def contraction(n, rate, seed=0):
    """``T(x) = M x + b`` with ``M`` non-symmetric of spectral radius ``rate``, and its fixed point
    ``(I - M)^-1 b``."""
    rng = np.random.default_rng(seed)
    V = np.eye(n) + 0.3 * rng.standard_normal((n, n)) / np.sqrt(n)  # eigenvectors not orthogonal
    eigen = rate * np.linspace(-1.0, 1.0, n)  # the slow modes at both ends: plain iteration crawls, damping cannot help
    M = V @ np.diag(eigen) @ np.linalg.inv(V)
    b = rng.standard_normal(n)
    return M, b, np.linalg.solve(np.eye(n) - M, b)


def iterate(step, x, target, tol, most):
    """Iterations of ``x <- step(x)`` until ``|x - target| <= tol |target|`` (``most + 1`` if never)."""
    for k in range(1, most + 1):
        x = step(x)
        if np.linalg.norm(x - target) <= tol * np.linalg.norm(target):
            return k, x
    return most + 1, x


@pytest.mark.parametrize("fused", [False, True])
def test_mixing_converges_far_faster_than_the_plain_iteration(fused):
    """Spectral radius 0.98: the plain iteration needs log(1e-10) / log(0.98) ~ 1140 steps (1135); with memory 6 the
    mixed one converges in about a tenth of them (96; memory 3: 171, 10: 61), both mixers alike."""
    M, b, fixed = contraction(40, 0.98)
    T = lambda x: M @ x + b  # noqa: E731
    plain, _ = iterate(T, np.zeros(40), fixed, 1e-10, 5000)
    assert 1000 < plain < 1300
    mixer = Anderson(6, fused=fused)
    mixed, x = iterate(lambda x: mixer(x, T(x)), np.zeros(40), fixed, 1e-10, 5000)
    assert mixed <= 100 and mixed < plain / 10
    assert np.linalg.norm(x - fixed) <= 1e-10 * np.linalg.norm(fixed)


def test_full_memory_is_gmres_and_ends_in_n_plus_two_steps():
    """With memory >= n the unit-step mixing of an n-dimensional linear map is GMRES (Walker & Ni 2011): the
    fixed point in at most n + 2 calls, to round-off, where the plain iteration (rate 0.99) would take ~2300."""
    n = 8
    M, b, fixed = contraction(n, 0.99, seed=3)
    mixer = Anderson(n, ridge=0.0)
    steps, x = iterate(lambda x: mixer.next(M @ x + b, M @ x + b - x), np.zeros(n), fixed, 1e-9, 50)
    assert steps <= n + 2
    assert np.linalg.norm(x - fixed) <= 1e-9 * np.linalg.norm(fixed)


@pytest.mark.parametrize("fused", [False, True])
def test_clipped_mixing_stays_within_the_bounds_and_converges(fused):
    """Bounds ``[min x*, max x*]``, the fixed point on both (as the cohesive traction on ``[-sigma_0, 0]``): the
    unclipped mix leaves them (by 1-2 % of their span), the clipped one never does and still converges in about as
    many steps (rate 0.98: the plain iteration takes ~1100)."""
    M, b, fixed = contraction(40, 0.98, seed=2)
    lower, upper = float(fixed.min()), float(fixed.max())
    span = upper - lower
    T = lambda x: M @ x + b  # noqa: E731

    def run(mixer):
        x, outside = np.zeros(40), 0.0
        for k in range(1, 300):
            x = mixer(x, T(x))
            outside = max(outside, float(x.max()) - upper, lower - float(x.min()))
            if np.linalg.norm(x - fixed) <= 1e-10 * np.linalg.norm(fixed):
                break
        return k, outside, x

    free_steps, free_outside, _ = run(Anderson(6, fused=fused))
    steps, outside, x = run(Anderson(6, bounds=(lower, upper), fused=fused))
    assert free_outside > 0.01 * span and free_steps < 100
    assert outside == 0.0 and steps < 100
    assert np.linalg.norm(x - fixed) <= 1e-10 * np.linalg.norm(fixed)


def test_fused_and_unfused_mixers_take_the_same_steps():
    """The fused sweeps (ring buffers, least squares) and the unfused mixer (image differences, LU) are one algorithm:
    relaxed (beta 1.3) and clipped, past the wrap of the memory, their iterates agree to round-off."""
    M, b, _ = contraction(30, 0.9, seed=2)
    T = lambda x: np.clip(M @ x + b, -1.0, 1.0)  # noqa: E731
    one, two = (Anderson(3, beta=1.3, bounds=(-1.0, 1.0), ridge=1e-12, fused=f) for f in (False, True))
    x1 = x2 = np.zeros(30)
    for _ in range(12):
        x1, x2 = one(x1, T(x1)), two(x2, T(x2))
        np.testing.assert_allclose(x1, x2, rtol=0, atol=1e-9 * np.abs(x1).max())


def test_carried_fields_are_mixed_with_the_same_weights():
    """A field carried along (the coupled solver's ``W p``) comes back as the linear map of the mixed iterate."""
    M, b, fixed = contraction(20, 0.95, seed=4)
    W = np.random.default_rng(5).standard_normal((20, 20))
    mixer = Anderson(4)
    x = np.zeros(20)
    for _ in range(8):
        y = M @ x + b
        x, Wx = mixer.next(y, y - x, W @ y)
        np.testing.assert_allclose(Wx, W @ x, rtol=0, atol=1e-11 * np.abs(W @ x).max())


def test_safeguard_takes_the_plain_step_when_the_mixed_one_raises_the_residual():
    """:meth:`Anderson.retreat`: after a mixed step whose residual grew, the plain step of that call, and a fresh
    memory; a falling residual goes on."""
    mixer = Anderson(3)
    image = np.arange(4.0)
    mixer.next(image, np.ones(4))
    mixed = mixer.next(image + 1.0, np.full(4, 0.5))
    assert mixer.active and not np.array_equal(mixed, image + 1.0)
    assert mixer.retreat(np.full(4, 0.5)) is None  # |f| noted
    mixer.next(image + 2.0, np.full(4, 0.25))
    assert mixer.retreat(np.full(4, 0.1)) is None  # fell: keep the mixed step
    mixer.next(image + 3.0, np.full(4, 0.05))
    plain = mixer.retreat(np.full(4, 0.2))  # rose
    assert np.array_equal(plain, image + 3.0) and not mixer.active


@pytest.mark.parametrize("kwargs, name", [(dict(memory=-1), "memory"), (dict(memory=2.5), "memory"),
                                          (dict(memory=3, beta=0.0), "beta"), (dict(memory=3, ridge=-1.0), "ridge"),
                                          (dict(memory=3, bounds=(1.0, 0.0)), "bounds")])
def test_bad_options_are_refused_by_name(kwargs, name):
    with pytest.raises(ValueError, match=name):
        Anderson(**kwargs)


def test_carried_fields_need_the_unit_unclipped_step():
    with pytest.raises(ValueError, match="carried"):
        Anderson(3, beta=1.3).next(np.ones(4), np.ones(4), np.ones(4))
    with pytest.raises(ValueError, match="carried"):
        Anderson(3, bounds=(0.0, 1.0)).next(np.ones(4), np.ones(4), np.ones(4))


def test_the_fused_mixer_needs_the_iterate_and_carries_nothing():
    mixer = Anderson(3, fused=True)
    with pytest.raises(ValueError, match="iterate x"):
        mixer.next(np.ones(4), np.ones(4))
    with pytest.raises(ValueError, match="iterate x"):
        mixer.next(np.ones(4), None, np.ones(4), x=np.zeros(4))
