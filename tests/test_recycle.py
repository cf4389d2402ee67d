"""Krylov vectors carried across GMRES solves (contactlib.solvers.recycle): the map they make is exact where the
operator has not changed, and a path of speeds that carries them gives the cold solves' answers."""

import numpy as np
import pytest

import contactlib
from contactlib.solvers import krylov
from contactlib.solvers.recycle import RecycledSpace

SLS = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)


def dense_system(n=80, seed=0):
    rng = np.random.default_rng(seed)
    skew = rng.normal(size=(n, n))
    A = np.eye(n) * 4 + 0.3 * rng.normal(size=(n, n)) + 0.5 * (skew - skew.T)
    return A, 1 / np.diag(A)


def test_kept_pairs_solve_their_span_in_one_step():
    """After one solve, a right-hand side in the span of the images it computed (``A P x``) is solved by the
    corrected preconditioner in one GMRES step, to round-off; one outside it still converges to the dense
    solution. The pairs map onto a smaller set by restriction, and a set that moved too much drops them."""
    A, diagonal = dense_system()
    n = A.shape[0]
    index = np.arange(n)
    space = RecycledSpace(size=40)
    rng = np.random.default_rng(1)

    def solve(b, tol=1e-12):
        op, pre = space.wrap(index, n, lambda v: (A @ v, 0.0), lambda v: diagonal * v)
        x, used, _ = krylov.gmres(op, pre, b, np.zeros(n), tol, 500, restart=30)
        return x, used

    b = rng.normal(size=n)
    x, used = solve(b)
    assert np.linalg.norm(x - np.linalg.solve(A, b)) < 1e-9 * np.linalg.norm(x) and used > 10
    images = np.array([z for _, z in space.pairs])
    assert len(images) == min(40, used)  # from zero: every application is a step's
    target = rng.normal(size=len(images)) @ images
    x, used = solve(target, tol=1e-9 * np.linalg.norm(target))
    assert np.linalg.norm(A @ x - target) <= 1e-9 * np.linalg.norm(target)
    assert used == 1  # from zero the start's residual is b: one step
    other = rng.normal(size=n)
    x, _ = solve(other)
    assert np.linalg.norm(x - np.linalg.solve(A, other)) < 1e-9 * np.linalg.norm(x)
    kept = len(space.pairs)
    space.moved = 0.05
    space._follow(index[1:], n)  # one point of 80 leaves (1/79 <= 0.05): the pairs restricted to the set
    assert len(space.pairs) == kept and all(x.size == n - 1 for x, _ in space.pairs)
    space.moved = 0.01
    space._follow(index[2:], n)  # one more (1/78 > 0.01): dropped
    assert space.pairs == []


def test_a_problem_holds_its_own_space():
    """The carried vectors are a field of the prepared problem that asked for them: a problem made from it at another
    speed shares them, a fresh one holds none (no state outlives its problem, none passes between problems)."""
    h = contactlib.surfaces.self_affine(16, hurst=0.8, q_roll=2, q_cutoff=4, rms_slope=0.1, seed=3)
    plain = contactlib.prepare(h, material=SLS, sliding_velocity=(1.0, 0.0))
    assert plain.recycled is None and plain.at_speed((2.0, 0.0)).recycled is None
    carrying = plain.recycling()
    assert isinstance(carrying.recycled, RecycledSpace) and plain.recycled is None
    assert carrying.at_speed((2.0, 0.0)).recycled is carrying.recycled
    assert carrying.at_speed((2.0, 0.0)).kernels is carrying.kernels is plain.kernels
    with pytest.raises(ValueError, match="size"):
        RecycledSpace(size=0)


def test_recycled_speeds_equal_cold_solves():
    """Speeds where the contact set settles (zeta = V tau q0 from 1 to 300): the carried vectors are used, the
    answers agree with cold solves within 1e-6 (pressure, relative L2; friction coefficient, relative to the
    largest of the path: it crosses zero near zeta = 200, where a relative error of tol-sized answers exceeds
    1e-5), and the path takes fewer GMRES iterations than without them."""
    h = contactlib.surfaces.self_affine(64, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, seed=3)
    velocities = [(zeta / (2 * np.pi), 0.0) for zeta in np.logspace(0, 2.5, 8)]
    space = RecycledSpace()
    path = contactlib.solve_speeds(h, velocities, material=SLS, mean_pressure=0.02, tol=1e-8, recycle=space)
    assert space.uses > 5
    plain = contactlib.solve_speeds(h, velocities, material=SLS, mean_pressure=0.02, tol=1e-8, recycle=False)
    largest = max(abs(float(o.friction_coefficient_interlocking)) for o in path)
    for velocity, warm in zip(velocities, path):
        cold = contactlib.solve(h, material=SLS, mean_pressure=0.02, sliding_velocity=velocity, tol=1e-8)
        assert warm.residual <= 1e-8
        dp = np.linalg.norm(warm.pressure.values - cold.pressure.values) / np.linalg.norm(cold.pressure.values)
        assert dp < 1e-6
        assert float(warm.friction_coefficient_interlocking) == pytest.approx(
            float(cold.friction_coefficient_interlocking), abs=1e-6 * largest)
    assert sum(int(o.iterations) for o in path) < sum(int(o.iterations) for o in plain)
    again = contactlib.solve_speeds(h, velocities, material=SLS, mean_pressure=0.02, tol=1e-8, recycle=True)
    assert [int(o.iterations) for o in again] == [int(o.iterations) for o in path]  # the same carried space
