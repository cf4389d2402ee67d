"""Threaded sweeps: deterministic whatever the thread count, equal to the serial sweeps to round-off,
and a solve on 2 threads agrees with 1."""

import numba
import numpy as np
import pytest

import contactlib
from contactlib.core import fft
from contactlib.core import _numba
from contactlib.core._numba import PARALLEL_MIN_SIZE, parallel_sweeps
from contactlib.model.operators import (
    affine_spectrum,
    scale_and_power_sum,
    _scale_spectrum,
    _threaded_affine_spectrum,
    _threaded_scale_and_power_sum,
    _threaded_scale_spectrum,
    _threaded_weighted_power_sum,
    _weighted_power_sum,
)
from contactlib.solvers.symmetric import fused as fz
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


@pytest.fixture
def small_grids_threaded(monkeypatch):
    """Threaded sweeps from 256^2 up, so that small solves run them (by default only 4096^2 grids do)."""
    monkeypatch.setattr(_numba, "PARALLEL_MIN_SIZE", 1 << 16)


def _fields(shape, seed=3):
    rng = np.random.default_rng(seed)
    w, t, z = (rng.standard_normal(shape) for _ in range(3))
    p = np.maximum(rng.standard_normal(shape), 0.0)  # about half the points in contact
    return w, p, t, z


def _run(sweeps, shape):
    """Every sweep once, in the loop's order: (their sums, the fields they wrote)."""
    w, p, t, z = _fields(shape)
    contact = p > 0
    masked = np.empty(shape)
    sums = [(sweeps.contact_sum(w, contact),),
            sweeps.measure(w, 1.3, 0.1, p, masked, True),
            (sweeps.contact_sum(z, contact),),
            sweeps.conjugate_direction(z, 1.0, 0.2, w, 1.3, 0.1, contact, 0.5, t),
            sweeps.step_project_reenter(p, 1.1, t, w, 0.1, 0.3, 0.01, contact)]
    return np.array([x for s in sums for x in s]), (t, p, masked, contact)


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
    w, p, t, z = _fields(shape)  # the sums are what they say
    np.testing.assert_allclose(serial[0][0], np.sum(np.where(p > 0, w, 0.0)), rtol=1e-12)
    gap = 1.3 * w - 0.1
    np.testing.assert_allclose(serial[0][1:5], [np.sum(1.3 * p * np.abs(gap)), np.sum(np.where(p > 0, 0, np.maximum(-gap, 0))),
                                                np.sum(np.where(p > 0, gap**2, 0)), 1.3 * p.sum()], rtol=1e-12)
    direction = np.where(p > 0, z - 0.2 + 0.5 * t, 0.0)
    np.testing.assert_allclose(serial[0][6:8], [direction.sum(), np.sum(gap * direction)], rtol=1e-12)
    new_p = np.maximum(1.1 * p - 0.3 * direction, 0.0)
    reenter = (1.1 * p - 0.3 * direction <= 0) & (1.1 * w - 0.1 < 0)
    new_p[reenter] = -0.01 * (1.1 * w - 0.1)[reenter]
    np.testing.assert_allclose(serial[1][1], new_p, rtol=1e-12, atol=1e-15)  # re-entry: a difference
    np.testing.assert_array_equal(serial[1][3], new_p > 0)
    assert serial[0][9] == np.count_nonzero(reenter) and serial[0][11] == np.count_nonzero(new_p > 0)


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
    offset = rng.standard_normal((512, 257)) + 1j * rng.standard_normal((512, 257))
    a, b = spectrum.copy(), spectrum.copy()
    affine_spectrum(a, multiplier, offset, 0.7)
    _threaded_affine_spectrum(b, multiplier, offset, 0.7)
    np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(a, spectrum * multiplier - 0.7 * offset)
    a, b = spectrum.copy(), spectrum.copy()
    power = scale_and_power_sum(a, multiplier, True)
    numba.set_num_threads(1)
    assert _threaded_scale_and_power_sum(b.copy(), multiplier, True) == _threaded_scale_and_power_sum(b, multiplier, True)
    numba.set_num_threads(MAX_THREADS)
    b = spectrum.copy()
    assert _threaded_scale_and_power_sum(b, multiplier, True) == pytest.approx(power, rel=1e-13)
    assert power == pytest.approx(_weighted_power_sum(spectrum, multiplier, True), rel=1e-13)
    np.testing.assert_array_equal(a, b)
    np.testing.assert_allclose(a, spectrum * multiplier, rtol=1e-15)


def test_sweeps_thread_only_large_grids(two_threads):
    threaded = numba.config.NUMBA_NUM_THREADS >= 2  # numba counts the CPUs this process may use
    assert parallel_sweeps(4096, 4096 * 4096) == threaded
    assert fz.select((4096, 4096)) is (fz.THREADED if threaded else fz.SERIAL)
    assert not parallel_sweeps(1, PARALLEL_MIN_SIZE * 4)  # a profile: one row
    assert not parallel_sweeps(2048, 2048 * 2048)  # too small to pay for the threads
    assert fz.select((2048, 2048)) is fz.SERIAL
    fft.set_fft_options(threads=1)
    assert not parallel_sweeps(4096, 4096 * 4096)
    assert fz.select((4096, 4096)) is fz.SERIAL


def test_solve_on_two_threads_agrees_with_one(small_grids_threaded):
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


def test_concurrent_threaded_solves_share_the_workqueue(two_threads, small_grids_threaded):
    """Two Python threads solving on threaded FFTs and sweeps at once (a dask worker with two threads):
    numba's workqueue layer (chosen because OpenMP's spinning pools fought FFTW's) takes one launch
    at a time, which the launch lock ensures; both answers equal a solve run alone, to round-off."""
    import os
    import threading

    heights = self_affine(256, hurst=0.8, rms_slope=0.1, q_roll=4, q_cutoff=32, seed=4)
    kwargs = dict(E=1.0, nu=0.0, mean_pressure=0.02, tol=1e-10)
    answers = [None, None, None]

    def run(k):
        answers[k] = contactlib.solve(heights, **kwargs)["pressure"].values

    # The solve alone runs in a fresh thread too: FFT plans are cached per thread, and the main
    # thread's may date from an earlier wisdom state of the process (another FFTW algorithm, other
    # round-off), which once made this comparison fail by 1e-15 in a full run.
    alone = threading.Thread(target=run, args=(2,))
    alone.start()
    alone.join()
    if "NUMBA_THREADING_LAYER" not in os.environ and numba.config.NUMBA_NUM_THREADS >= 2:
        assert numba.threading_layer() == "workqueue"
    workers = [threading.Thread(target=run, args=(k,)) for k in range(2)]
    for worker in workers:
        worker.start()
    for worker in workers:
        worker.join()
    # Equal to round-off, not bit for bit: twice on a loaded machine (CI, 2026-11-28; a six-job load) one thread's
    # answer differed from the lone solve's by 1e-15 (1e-9 relative on near-zero pressures), 38 % of the points, the
    # mark of another FFT algorithm (plans are per thread, FFTW_MEASURE times them), not of a sweep racing another:
    # a race writes whole blocks wrong, orders of magnitude above this bound.
    for answer in answers[:2]:
        np.testing.assert_allclose(answer, answers[2], rtol=0, atol=1e-12 * float(np.abs(answers[2]).max()))


def test_fftw_openmp_team_follows_the_thread_setting():
    """pyFFTW's FFTW runs its threaded transforms on an OpenMP team sized by OMP_NUM_THREADS, not by
    the plan: with OMP_NUM_THREADS=1 a 2-thread plan ran on one thread, slower than a serial plan.
    contactlib sizes the team of the thread that runs its plans to the thread setting."""
    import os
    import subprocess
    import sys

    script = (
        "from contactlib.core import fft\n"
        "fft.set_fft_options(threads=2)\n"
        "fft.get_fft((64, 64))\n"
        "runtimes = fft._openmp_runtimes()\n"
        "print(len(runtimes), [runtime.omp_get_max_threads() for runtime in runtimes])\n"
    )
    env = dict(os.environ, OMP_NUM_THREADS="1")
    out = subprocess.run([sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True).stdout
    count, teams = out.split(" ", 1)
    if int(count) == 0:
        pytest.skip("no OpenMP runtime loaded: this FFTW build does not thread with OpenMP")
    assert eval(teams) == [2] * int(count)
