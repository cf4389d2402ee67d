"""Bad input is refused with an error naming the parameter; non-convergence is never silent."""

import numpy as np
import pytest

import contactlib


@pytest.fixture
def heights():
    return contactlib.surfaces.self_affine(32, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, seed=0)


@pytest.mark.parametrize("kwargs,match", [
    (dict(E=0.0), "E"),
    (dict(E=-1.0), "E"),
    (dict(E=float("nan")), "E"),
    (dict(nu=0.6), "nu"),
    (dict(nu=-1.0), "nu"),
    (dict(tol=0.0), "tol"),
    (dict(tol=-1e-8), "tol"),
    (dict(mean_pressure=-0.1), "mean_pressure"),
    (dict(mean_pressure=float("inf")), "mean_pressure"),
    (dict(mean_pressure=0.01, penetration=0.001), "exactly one"),
    (dict(mean_pressure=None), "exactly one"),
    (dict(kernel="boussinesq"), "kernel"),
    (dict(method="newton"), "method"),
    (dict(max_iter=0), "max_iter"),
])
def test_bad_parameters(heights, kwargs, match):
    args = dict(E=1.0, nu=0.3, mean_pressure=0.01)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        contactlib.solve(heights, **args)


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_non_finite_heights(heights, bad):
    values = heights.values.copy()
    values[3, 4] = bad
    with pytest.raises(ValueError, match="heights"):
        contactlib.solve(values, E=1.0, nu=0.3, mean_pressure=0.01)


@pytest.mark.parametrize("shape", [(1,), (1, 16), (16, 1), (2, 2, 2)])
def test_grid_too_small_or_wrong_rank(shape):
    with pytest.raises(ValueError, match="heights|grid"):
        contactlib.solve(np.zeros(shape), E=1.0, nu=0.3, mean_pressure=0.01)


def test_bad_length():
    with pytest.raises(ValueError, match="length"):
        contactlib.solve(np.zeros((8, 8)), E=1.0, nu=0.3, mean_pressure=0.01, length=-1.0)


def test_round_off_floor_stalls_early_instead_of_running_to_max_iter(heights):
    """tol 1e-17 is below the round-off floor (~1e-15 here): the solve must say so, not spin."""
    with pytest.raises(contactlib.ConvergenceError, match="stalled") as info:
        contactlib.solve(heights, E=1.0, nu=0.3, mean_pressure=0.01, tol=1e-17, max_iter=1_000_000)
    from contactlib.solvers.ccg import STALL_ITERATIONS
    assert int(info.value.dataset.iterations) < 3 * STALL_ITERATIONS
    assert 0 < info.value.residual < 1e-12


def test_non_convergence_raises_with_residual_and_partial_dataset(heights):
    with pytest.raises(contactlib.ConvergenceError) as info:
        contactlib.solve(heights, E=1.0, nu=0.3, mean_pressure=0.01, tol=1e-12, max_iter=3)
    err = info.value
    assert err.residual > 1e-12
    assert err.dataset.attrs["converged"] == 0
    assert int(err.dataset.iterations) == 3
    assert float(err.dataset.residual) == pytest.approx(err.residual)
    assert "residual" in str(err)
