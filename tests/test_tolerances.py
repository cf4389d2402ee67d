"""solve_tolerances: one solve at the tightest tolerance gives every looser solve's answer exactly."""

import numpy as np
import pytest

import contactlib
from contactlib import ConvergenceError, solve, solve_tolerances, surfaces

TOLS = [1e-4, 1e-10, 1e-6, 1e-8]  # unsorted on purpose: the answer keeps the caller's order


def _rough(n=128):
    return surfaces.self_affine(n, hurst=0.8, q_roll=2, q_cutoff=32, rms_slope=0.1, seed=3)


SCENES = {
    "rough, load control (preconditioned)": (lambda: _rough(), {"mean_pressure": 0.004}),
    "hertz, displacement control, non-periodic": (
        lambda: surfaces.paraboloid(96, length=1.0, radius=1.0), {"penetration": 0.01, "periodic": False,
                                                                  "kernel": "love"}),
    "rough, periodic displacement control (dual)": (lambda: _rough(), {"penetration": 0.004}),
    "profile, load control": (lambda: surfaces.wavy(512, length=1.0, amplitude=0.01, dim=1),
                              {"mean_pressure": 0.005}),
}


@pytest.mark.parametrize("scene", SCENES)
def test_each_tolerance_matches_its_own_solve_bit_for_bit(scene):
    make, load = SCENES[scene]
    h = make()
    ladder = solve_tolerances(h, TOLS, E=1.0, nu=0.5, **load)
    iterations = []
    for tol, got in zip(TOLS, ladder):
        alone = solve(h, E=1.0, nu=0.5, tol=tol, **load)
        assert got.attrs["tol"] == tol and got.attrs["converged"] == 1
        assert int(got.iterations) == int(alone.iterations)
        assert float(got.residual) == float(alone.residual) <= tol
        for name in ("pressure", "gap", "displacement"):
            np.testing.assert_array_equal(got[name].values, alone[name].values)
        assert float(got.penetration) == float(alone.penetration)
        assert float(got.contact_area) == float(alone.contact_area)
        iterations.append(int(got.iterations))
    # tighter tolerances take more iterations, so the ladder did pass through distinct states
    order = np.argsort(TOLS)[::-1]
    assert np.all(np.diff(np.asarray(iterations)[order]) > 0)


def test_time_to_each_tolerance_grows_with_tightness():
    h = _rough(256)
    ladder = solve_tolerances(h, [1e-4, 1e-10], E=1.0, nu=0.5, mean_pressure=0.004)
    assert 0 < ladder[0].attrs["wall_time"] < ladder[1].attrs["wall_time"]


def test_unreached_tolerance_raises_with_every_answer():
    h = _rough()
    reachable = solve(h, E=1.0, nu=0.5, mean_pressure=0.004, tol=1e-4)
    cap = int(reachable.iterations) + 1
    with pytest.raises(ConvergenceError, match="did not converge") as info:
        solve_tolerances(h, [1e-4, 1e-12], E=1.0, nu=0.5, mean_pressure=0.004, max_iter=cap)
    loose, tight = info.value.datasets
    assert loose.attrs["converged"] == 1 and int(loose.iterations) == int(reachable.iterations)
    assert tight.attrs["converged"] == 0 and int(tight.iterations) == cap
    assert info.value.residual == float(tight.residual) > 1e-12
    # the partial answer says why it is partial, in the words of the error
    assert tight.attrs["convergence_message"] == str(info.value)
    assert "convergence_message" not in loose.attrs


@pytest.mark.parametrize("tols, message", [([], "at least one"), ([1e-6, 0.0], "tols"),
                                           ([float("nan")], "tols")])
def test_bad_tolerances_are_refused(tols, message):
    with pytest.raises(ValueError, match=message):
        solve_tolerances(_rough(64), tols, E=1.0, nu=0.5, mean_pressure=0.004)


def test_public():
    assert "solve_tolerances" in contactlib.__all__
