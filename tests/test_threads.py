"""Threaded sweeps: the same bits as the serial ones, and a solve on 2 threads agrees with 1."""

import numba
import numpy as np
import pytest

import contactlib
from contactlib import fft
from contactlib._numba import PARALLEL_MIN_SIZE, parallel_sweeps
from contactlib.operators import (_scale_spectrum_parallel, _scale_spectrum_serial, _weighted_power_sums_parallel,
                                  _weighted_power_sums_serial)
from contactlib.solvers import _fused as fz
from contactlib.surfaces import self_affine


@pytest.fixture
def two_threads():
    """FFTW and numba on 2 threads (as many as numba has, at most), restored afterwards."""
    before = fft.fft_options()["threads"]
    fft.set_fft_options(threads=2)
    numba.set_num_threads(min(2, numba.config.NUMBA_NUM_THREADS))
    yield
    fft.set_fft_options(threads=before)
    numba.set_num_threads(1)


def _fields(shape, seed=3):
    rng = np.random.default_rng(seed)
    u, g, t, z = (rng.standard_normal(shape) for _ in range(4))
    hp = -np.abs(rng.standard_normal(shape))
    p = np.maximum(rng.standard_normal(shape), 0.0)  # about half the points in contact
    return u, hp, p, g, t, z


@pytest.mark.parametrize("shape", [(96, 80), (7, 1000), (1, 513)])
def test_threaded_sweeps_give_the_serial_bits(shape, two_threads):
    """Every sweep returns the same sums and writes the same fields serial and threaded: each row's
    sums do not depend on the thread, and the rows are added in order."""
    u, hp, p, g, t, z = _fields(shape)
    S, P = fz._SERIAL, fz._PARALLEL
    outs = []
    for sweeps in (S, P):
        g_, t_, p_, masked, dest = g.copy(), t.copy(), p.copy(), np.empty(shape), np.empty(shape)
        sums = [sweeps.gap_and_contact_mean(u, 1.3, hp, p, g_),
                sweeps.measure(g_, p, 1.3, 0.1, masked, True),
                sweeps.contact_sums(z, g_, 0.1, p),
                sweeps.conjugate_direction(z, 0.2, g_, 0.1, p, 0.5, t_, dest),
                sweeps.step_project_reenter(p_, 1.1, t_, g_, 0.1, 0.3, 0.01, dest)]
        outs.append((np.concatenate(sums), g_, t_, p_, masked, dest))
    for a, b in zip(*outs):
        np.testing.assert_array_equal(a, b)
    assert outs[0][0][0] == np.count_nonzero(p > 0)  # the sums are what they say
    np.testing.assert_allclose(outs[0][0][1], np.sum(np.where(p > 0, 1.3 * u - hp, 0.0)), rtol=1e-12)


def test_threaded_spectrum_passes_give_the_serial_bits(two_threads):
    rng = np.random.default_rng(5)
    spectrum = rng.standard_normal((128, 65)) + 1j * rng.standard_normal((128, 65))
    multiplier = rng.random((128, 65))
    np.testing.assert_array_equal(_weighted_power_sums_serial(spectrum, multiplier, True),
                                  _weighted_power_sums_parallel(spectrum, multiplier, True))
    a, b = spectrum.copy(), spectrum.copy()
    _scale_spectrum_serial(a, multiplier)
    _scale_spectrum_parallel(b, multiplier)
    np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(a, spectrum * multiplier)  # numpy's bits: no fast-math in the multiply


def test_sweeps_thread_only_large_grids(two_threads):
    threaded = numba.config.NUMBA_NUM_THREADS >= 2  # numba sees the CPUs this process may use
    assert parallel_sweeps(256, 256 * 256) == threaded
    assert not parallel_sweeps(1, PARALLEL_MIN_SIZE * 4)  # a profile: one row
    assert not parallel_sweeps(128, 128 * 128)  # too small to pay for the threads
    fft.set_fft_options(threads=1)
    assert not parallel_sweeps(1024, 1024 * 1024)


def test_solve_on_two_threads_agrees_with_one():
    """A 256^2 rough solve with threaded FFTs and sweeps: same iterations, same answer to round-off
    (FFTW's threaded plans add in another order, so not bit for bit)."""
    heights = self_affine(256, hurst=0.8, rms_slope=0.1, q_roll=4, q_cutoff=32, seed=2)
    kwargs = dict(E=1.0, nu=0.0, mean_pressure=0.02, tol=1e-10)
    one = contactlib.solve(heights, **kwargs)
    before = fft.fft_options()["threads"]
    fft.set_fft_options(threads=2)
    try:
        two = contactlib.solve(heights, **kwargs)
    finally:
        fft.set_fft_options(threads=before)
    assert bool(two.attrs["converged"]) and bool(one.attrs["converged"])
    assert abs(int(two["iterations"]) - int(one["iterations"])) <= 1
    p1, p2 = one["pressure"].values, two["pressure"].values
    assert np.linalg.norm(p2 - p1) / np.linalg.norm(p1) < 1e-8
