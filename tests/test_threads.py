"""Threaded sweeps: deterministic whatever the thread count, equal to the serial sweeps to round-off,
and a solve on 2 threads agrees with 1."""

import numba
import numpy as np
import pytest

import contactlib
from contactlib import fft
from contactlib._numba import PARALLEL_MIN_SIZE, parallel_sweeps
from contactlib.operators import (
    _scale_spectrum,
    _threaded_scale_spectrum,
    _threaded_weighted_power_sum,
    _weighted_power_sum,
)
from contactlib.solvers import _fused as fz
from contactlib.surfaces import self_affine

MAX_THREADS = min(2, numba.config.NUMBA_NUM_THREADS)


@pytest.fixture
def two_threads():
    """FFTW and numba on 2 threads (as many as numba has, at most), restored afterwards."""
    before = fft.threads()
    fft.set_fft_options(threads=2)
    numba.set_num_threads(MAX_THREADS)
    yield
    fft.set_fft_options(threads=before)
    numba.set_num_threads(1)


def _fields(shape, seed=3):
    rng = np.random.default_rng(seed)
    u, g, t, z = (rng.standard_normal(shape) for _ in range(4))
    hp = -np.abs(rng.standard_normal(shape))
    p = np.maximum(rng.standard_normal(shape), 0.0)  # about half the points in contact
    return u, hp, p, g, t, z


def _run(sweeps, shape):
    """Every sweep once, in the loop's order: (their sums, the fields they wrote)."""
    u, hp, p, g, t, z = _fields(shape)
    masked, dest = np.empty(shape), np.empty(shape)
    sums = [sweeps.gap_and_contact_mean(u, 1.3, hp, p, g),
            sweeps.measure(g, p, 1.3, 0.1, masked, True),
            sweeps.contact_sums(z, g, 0.1, p),
            sweeps.conjugate_direction(z, 0.2, g, 0.1, p, 0.5, t, dest),
            sweeps.step_project_reenter(p, 1.1, t, g, 0.1, 0.3, 0.01, dest)]
    return np.array([x for s in sums for x in s]), (g, t, p, masked, dest)


@pytest.mark.parametrize("shape", [(96, 80), (300, 200), (3, 5000), (1, 513)])
def test_threaded_sweeps_are_deterministic_and_agree_with_serial(shape, two_threads):
    """On 1 and 2 threads the threaded sweeps give the same bits (the row blocks are fixed by the
    shape and added in order); against the serial sweeps the fields are the same bits and the sums
    agree to round-off."""
    threaded = _run(fz.THREADED, shape)
    numba.set_num_threads(1)
    one_thread = _run(fz.THREADED, shape)
    numba.set_num_threads(MAX_THREADS)
    np.testing.assert_array_equal(threaded[0], one_thread[0])
    serial = _run(fz.SERIAL, shape)
    np.testing.assert_allclose(threaded[0], serial[0], rtol=1e-12)
    for a, b in zip(threaded[1], serial[1]):
        np.testing.assert_array_equal(a, b)
    u, hp, p, *_ = _fields(shape)  # the sums are what they say
    assert serial[0][0] == np.count_nonzero(p > 0)
    np.testing.assert_allclose(serial[0][1], np.sum(np.where(p > 0, 1.3 * u - hp, 0.0)), rtol=1e-12)


def test_threaded_spectrum_passes(two_threads):
    rng = np.random.default_rng(5)
    spectrum = rng.standard_normal((512, 257)) + 1j * rng.standard_normal((512, 257))
    multiplier = rng.random((512, 257))
    threaded = _threaded_weighted_power_sum(spectrum, multiplier, True)
    numba.set_num_threads(1)
    assert _threaded_weighted_power_sum(spectrum, multiplier, True) == threaded
    numba.set_num_threads(MAX_THREADS)
    assert threaded == pytest.approx(_weighted_power_sum(spectrum, multiplier, True), rel=1e-13)
    a, b = spectrum.copy(), spectrum.copy()
    _scale_spectrum(a, multiplier)
    _threaded_scale_spectrum(b, multiplier)
    np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(a, spectrum * multiplier)  # numpy's bits: no fast-math in the multiply


def test_sweeps_thread_only_large_grids(two_threads):
    threaded = numba.config.NUMBA_NUM_THREADS >= 2  # numba counts the CPUs this process may use
    assert parallel_sweeps(256, 256 * 256) == threaded
    assert fz.select((256, 256)) is (fz.THREADED if threaded else fz.SERIAL)
    assert not parallel_sweeps(1, PARALLEL_MIN_SIZE * 4)  # a profile: one row
    assert not parallel_sweeps(128, 128 * 128)  # too small to pay for the threads
    fft.set_fft_options(threads=1)
    assert not parallel_sweeps(1024, 1024 * 1024)
    assert fz.select((1024, 1024)) is fz.SERIAL


def test_solve_on_two_threads_agrees_with_one():
    """A 256^2 rough solve with threaded FFTs and sweeps: same iterations, same answer to round-off
    (FFTW's threaded plans and the threaded sums add in another order, so not bit for bit)."""
    heights = self_affine(256, hurst=0.8, rms_slope=0.1, q_roll=4, q_cutoff=32, seed=2)
    kwargs = dict(E=1.0, nu=0.0, mean_pressure=0.02, tol=1e-10)
    one = contactlib.solve(heights, **kwargs)
    before = fft.threads()
    fft.set_fft_options(threads=2)
    try:
        two = contactlib.solve(heights, **kwargs)
    finally:
        fft.set_fft_options(threads=before)
    assert bool(two.attrs["converged"]) and bool(one.attrs["converged"])
    assert abs(int(two["iterations"]) - int(one["iterations"])) <= 1
    p1, p2 = one["pressure"].values, two["pressure"].values
    assert np.linalg.norm(p2 - p1) / np.linalg.norm(p1) < 1e-8
