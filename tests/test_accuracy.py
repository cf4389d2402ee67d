"""The speed_vs_error point, the surface resampling it relies on, and the measured accuracy rule."""

import math
import warnings

import numpy as np
import pytest
import xarray as xr

import contactlib
from contactlib import accuracy, analysis, studies
from contactlib.pipeline import sweep
from contactlib.reference import westergaard
from contactlib.studies import speed_vs_error

SCENE = dict(E=1.0, nu=0.5, max_iter=10_000, radius=1.0, contact_fraction=0.6, amplitude=0.01,
             full_contact_margin=2.0, hurst=0.8, seed=0, q_low=1, q_roll=2, q_cutoff=4, rms_slope=0.1,
             reduced_pressure=0.05, n_max_2d=128, n_max_rough=128)


def point(scene, n, tol=1e-10, kernel="spectral", **kw):
    return studies.speed_error_point(scene=scene, n=n, tol=tol, kernel=kernel, **{**SCENE, **kw})


@pytest.mark.parametrize("synthesis", ["filtered-noise", "random-phase"])
def test_resample_keeps_the_modes_that_reseeding_does_not(synthesis):
    kw = dict(hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, seed=3, synthesis=synthesis)
    coarse = contactlib.surfaces.self_affine(32, **kw)
    fine = contactlib.surfaces.resample(coarse, 128)
    scale = float(abs(coarse).max())
    assert np.abs(fine.values[::4, ::4] - coarse.values).max() < 1e-12 * scale  # same nodes
    modes_c = np.fft.rfft2(coarse.values)[:9, :9] / 32**2
    modes_f = np.fft.rfft2(fine.values)[:9, :9] / 128**2
    assert np.abs(modes_f - modes_c).max() < 1e-12 * np.abs(modes_c).max()  # same Fourier modes
    assert np.abs(np.fft.rfft2(fine.values)[:, 9:65]).max() < 1e-10 * np.abs(modes_f).max() * 128**2  # nothing new
    reseeded = contactlib.surfaces.self_affine(128, **kw)  # same seed, 4x grid: another surface
    assert np.abs(reseeded.values[::4, ::4] - coarse.values).max() > 0.5 * float(coarse.std())
    back = contactlib.surfaces.resample(fine, 32)
    assert np.abs(back.values - coarse.values).max() < 1e-12 * scale


def test_wavy_2d_full_contact_closed_form_and_love_second_order():
    """Egg-box in full contact: p = mean + E* |q| h / 2 cos cos. Exact for the spectral kernel (one
    Fourier mode), second order for Love's."""
    E_star = 4.0 / 3.0
    p_mean = 2.0 * E_star * 2 * math.pi * math.sqrt(2) * 0.01 / 2
    h = contactlib.surfaces.wavy(48, amplitude=0.01, dim=2)
    out = contactlib.solve(h, E=1.0, nu=0.5, mean_pressure=p_mean, tol=1e-12)
    x = out.x.values
    exact = westergaard.full_contact_field(x[:, None], x[None, :], mean_pressure=p_mean, amplitude=0.01,
                                           wavelength=1.0, E_star=E_star)
    assert float(out.contact_area) == 1.0
    np.testing.assert_allclose(out.pressure.values, exact, rtol=0, atol=1e-10 * p_mean)
    assert point("wavy_2d", 32)["pressure_error"] < 1e-12
    love = [point("wavy_2d", n, kernel="love")["pressure_error"] for n in (32, 64, 128)]
    orders = np.log2(np.array(love[:-1]) / np.array(love[1:]))
    np.testing.assert_allclose(orders, 2.0, atol=0.1)  # second order (1.89 from 16 to 32: pre-asymptotic)


def test_point_errors_are_finite_and_decrease_with_n():
    hertz = [point("hertz", n) for n in (32, 64, 128)]
    loads = [r["load_error"] for r in hertz]
    assert all(math.isfinite(v) for r in hertz for v in (r["area_error"], r["pressure_error"], r["solve_time"]))
    assert loads[0] > loads[1] > loads[2] and loads[2] < 5e-3
    assert all(math.isnan(r["gap_error"]) for r in hertz)
    wave = [point("westergaard_1d", n)["pressure_error"] for n in (64, 256, 1024)]
    assert wave[0] > wave[1] > wave[2] and wave[2] < 1e-3
    rough = [point("rough", n) for n in (16, 32, 64)]
    area = [r["area_error"] for r in rough]
    assert area[0] > area[1] > area[2] and area[2] < 0.1
    assert math.isnan(rough[0]["load_error"]) and rough[0]["resolution"] == 4.0
    assert all(r["max_error"] == max(r["area_error"], r["pressure_error"], r["gap_error"]) for r in rough)
    with pytest.raises(ValueError, match="n_max_2d"):
        point("hertz", 256)
    with pytest.raises(ValueError, match="q_cutoff"):
        point("rough", 8)


@pytest.mark.parametrize("seed, hurst, q_cutoff, reduced_pressure, target", [
    (7, 0.5, 4, 0.05, 0.05),   # the worst of the six surfaces behind accuracy.SAFETY
    (2, 0.8, 4, 0.02, 0.03),   # the lowest load of the validity range
    (21, 0.6, 6, 0.03, 0.05),  # not seen before the constants were fixed
])
def test_settings_reach_the_target_on_an_independent_rough_surface(seed, hurst, q_cutoff, reduced_pressure, target):
    """The rule was fitted on H = 0.8, seed 0, q_cutoff 8, reduced pressure 0.05; here other surfaces and
    loads, on the smallest even grid the rule allows (not rounded up to a power of two)."""
    settings = accuracy.settings_for(target, q_cutoff=q_cutoff)
    n = 2 * math.ceil(settings["points_per_wavelength"] * q_cutoff / 2)
    assert settings["n"] >= n
    h = contactlib.surfaces.self_affine(n, hurst=hurst, q_roll=2, q_cutoff=q_cutoff, rms_slope=0.1, seed=seed)
    load = reduced_pressure * 4.0 / 3.0 * 0.1
    with warnings.catch_warnings():
        warnings.simplefilter("error", accuracy.AccuracyWarning)
        out = contactlib.solve(h, E=1.0, nu=0.5, mean_pressure=load, target_error=target)
    assert out.attrs["tol"] == settings["tol"] and out.attrs["target_error"] == target
    fine = contactlib.solve(contactlib.surfaces.resample(h, 4 * n), E=1.0, nu=0.5, mean_pressure=load, tol=1e-11)
    error = abs(float(out.contact_area) / float(fine.contact_area) - 1)
    assert error <= target


def test_solve_target_error_warns_on_a_coarse_grid_and_refuses_tol_too(rough64):
    # rough64: q_cutoff 16 on 64 points, 4 points per shortest wavelength
    assert accuracy.grid_points_per_wavelength(rough64) == 4.0
    with pytest.warns(accuracy.AccuracyWarning, match="points per shortest wavelength"):
        out = contactlib.solve(rough64, E=1.0, nu=0.5, mean_pressure=0.01, target_error=0.01)
    assert out.attrs["tol"] == accuracy.tolerance_for(0.01)
    with pytest.raises(ValueError, match="not both"):
        contactlib.solve(rough64, E=1.0, nu=0.5, mean_pressure=0.01, target_error=0.01, tol=1e-6)
    with pytest.raises(ValueError, match="target_error"):
        accuracy.settings_for(2.0)


def test_rule_is_monotone_and_documented_constants_are_consistent():
    ppw = [accuracy.points_per_wavelength(t) for t in (0.1, 0.01, 0.001)]
    assert ppw[0] < ppw[1] < ppw[2]
    fit = accuracy.ROUGH_FITS["contact_area"]
    np.testing.assert_allclose(fit["constant"] * ppw[1] ** -fit["order"], 0.01, rtol=1e-12)
    assert accuracy.tolerance_for(1e-3) < accuracy.tolerance_for(1e-2) <= 1e-4


def test_studies_state_the_area_error_of_their_resolution():
    """area_load at n = 256 and 512 with q_cutoff 64 (4 and 8 points per shortest wavelength)."""
    ds = xr.Dataset({"contact_area": ("n", [0.1, 0.09])}, coords={"n": [256, 512]})
    out = studies.add_error_estimate(ds, "area_load", {"q_cutoff": 64})
    np.testing.assert_allclose(out.area_error_estimate.values, accuracy.expected_error(np.array([4.0, 8.0])))
    assert out.area_error_estimate.attrs["units"] == "1" and "q_cutoff" in out.area_error_estimate.long_name
    fit = accuracy.ROUGH_FITS["contact_area"]
    c = fit["measured_constant"] / (1 - 4.0 ** -fit["order"])  # against the continuum, no safety factor
    assert float(out.area_error_estimate.sel(n=256)) == pytest.approx(c * 4.0 ** -fit["order"], rel=1e-12)
    scalar = studies.add_error_estimate(xr.Dataset({"a": ("seed", [1.0])}), "anisotropy", {"n": 256, "q_cutoff": 64})
    assert scalar.area_error_estimate.ndim == 0
    assert "area_error_estimate" not in studies.add_error_estimate(ds, "validation", {"q_cutoff": 64})


def test_analysis_helpers():
    r = np.array([4.0, 8.0, 16.0, 32.0])
    order, constant = analysis.fit_order(r, 0.3 * r**-1.5)
    assert order == pytest.approx(1.5, rel=1e-12) and constant == pytest.approx(0.3, rel=1e-12)
    assert math.isnan(analysis.fit_order(r[:2], r[:2])[0])
    cost, err = np.array([1.0, 2.0, 3.0, 4.0]), np.array([0.5, 0.6, 0.1, 0.1])
    assert analysis.pareto_front(cost, err).tolist() == [True, False, True, False]
    ds = xr.Dataset(
        {"max_error": (("scene", "n", "tol", "kernel"), np.array([0.1, 0.01, 0.02, 0.001]).reshape(1, 2, 1, 2)),
         "solve_time": (("scene", "n", "tol", "kernel"), np.array([1.0, 2.0, 3.0, 4.0]).reshape(1, 2, 1, 2)),
         "status": (("scene", "n", "tol", "kernel"), np.zeros((1, 2, 1, 2), dtype=np.int8))},
        coords={"scene": ["s"], "n": [32, 64], "tol": [1e-8], "kernel": ["love", "spectral"]})
    rows = analysis.cheapest_settings(ds, [0.05, 0.005, 1e-4])
    assert (rows[0]["kernel"], rows[0]["n"], rows[0]["solve_time"]) == ("spectral", 32, 2.0)
    assert (rows[1]["kernel"], rows[1]["n"]) == ("spectral", 64)
    assert rows[2]["kernel"] == "" and rows[2]["best_error"] == 0.001
    table = analysis.markdown_table(rows)
    assert "| 5.00% | s | spectral | 32 | 1e-08 | 2 |" in table and "not reached" in table


def test_group_dims_share_one_task_and_give_the_same_dataset():
    calls = []

    def f(a, b, c):
        calls.append((a, b, c))
        return {"v": a * 100 + b * 10 + c}

    grid = {"a": [1, 2], "b": [1, 2, 3], "c": [0, 1]}
    labels = {k: {"units": "1", "long_name": k} for k in ("a", "b", "c", "v")}
    plain = sweep.run_grid(f, grid, labels=labels, progress=False)
    assert len(sweep._groups(*_points(grid), ("b", "c"), "")) == 2
    grouped = sweep.run_grid(f, grid, labels=labels, progress=False, group_dims=("b", "c"))
    xr.testing.assert_identical(plain.v, grouped.v)
    with pytest.raises(ValueError, match="not both"):
        sweep.run_grid(f, grid, labels=labels, progress=False, group_dims=("b",), path_dim="c")


def _points(grid):
    _, points = sweep.grid_points(grid)
    return points, [sweep.point_key(p) for p in points]


@pytest.mark.parametrize("scene, n", [("hertz", 64), ("rough", 32), ("westergaard_1d", 256)])
def test_tolerance_ladder_gives_each_point_its_own_solves_answer(scene, n):
    """The study's one-solve-per-ladder path: same errors and iterations as solving each tol alone."""
    ladder = (1e-4, 1e-8, 1e-12)
    for tol in ladder:
        alone, shared = point(scene, n, tol=tol), point(scene, n, tol=tol, tol_ladder=ladder)
        for name in ("load_error", "area_error", "pressure_error", "gap_error", "iterations", "residual",
                     "reference_residual"):
            assert alone[name] == shared[name] or (math.isnan(alone[name]) and math.isnan(shared[name])), name
        assert shared["residual"] <= tol and shared["solve_time"] > 0
    with pytest.raises(ValueError, match="tol_ladder"):
        point(scene, n, tol=1e-6, tol_ladder=ladder)


def test_tolerance_ladder_reports_unreached_tolerances_as_not_converged():
    ladder = (1e-4, 1e-12)
    loose = point("hertz", 64, tol=1e-4)
    cap = int(loose["iterations"]) + 2
    assert point("hertz", 64, tol=1e-4, tol_ladder=ladder, max_iter=cap)["iterations"] == loose["iterations"]
    with pytest.raises(contactlib.ConvergenceError, match="did not converge") as info:
        point("hertz", 64, tol=1e-12, tol_ladder=ladder, max_iter=cap)
    assert info.value.residual > 1e-12
    result = sweep.evaluate_point(point, {"scene": "hertz", "n": 64, "tol": 1e-12, "tol_ladder": ladder,
                                          "max_iter": cap})
    assert result["status"] == sweep.STATUS_NOT_CONVERGED and result["residual"] > 1e-12


def test_failed_rough_reference_is_solved_once_and_reported_per_point(monkeypatch):
    """A reference short of REFERENCE_FLOOR * tol fails every point of its task, as not converged,
    without being solved again for each of them (at 8192^2 one attempt costs ten minutes)."""
    monkeypatch.setattr(speed_vs_error, "REFERENCE_MAX_ITER", 2)  # where _speed_error_results reads it
    speed_vs_error.rough_reference.cache_clear()
    speed_vs_error._speed_error_results.cache_clear()
    ladder = (1e-4, 1e-8)
    for kernel in ("love", "spectral"):
        for tol in ladder:
            result = sweep.evaluate_point(point, {"scene": "rough", "n": 32, "tol": tol, "kernel": kernel,
                                                  "tol_ladder": ladder})
            assert result["status"] == sweep.STATUS_NOT_CONVERGED
            assert "rough reference on 128^2" in result["message"] and result["residual"] > 1e-12 * 1000
    assert speed_vs_error.rough_reference.cache_info().misses == 1
    speed_vs_error.rough_reference.cache_clear()
    speed_vs_error._speed_error_results.cache_clear()


@pytest.mark.parametrize("control", ["penetration", "mean_pressure"])
def test_target_error_holds_for_a_small_contact_in_a_wide_window(control):
    """A sphere on a window of four radii (rms height 843x the approach): the rule's tol alone left a pressure error
    of 2.8e-2 at target 1e-2; tightened for the scene (``accuracy.tolerance_for_scene``) the solver's share stays
    below a tenth of the target, under either control."""
    n, length = 512, 4.0
    x = (np.arange(n) - n // 2) * (length / n)
    h = -(x[:, None] ** 2 + x[None, :] ** 2) / 2.0
    reference = contactlib.solve(h, length=length, E=1.0, nu=0.3, penetration=1e-3, periodic=False, tol=1e-11)
    load = {"penetration": 1e-3} if control == "penetration" else {"mean_pressure": float(reference.mean_pressure)}
    out = contactlib.solve(h, length=length, E=1.0, nu=0.3, periodic=False, target_error=1e-2, **load)
    assert out.attrs["tol"] < accuracy.tolerance_for(1e-2) / 100
    error = np.linalg.norm(out.pressure.values - reference.pressure.values) / np.linalg.norm(reference.pressure.values)
    assert error <= 1e-3
    assert float(out.mean_pressure) == pytest.approx(float(reference.mean_pressure), rel=1e-3)


def test_target_error_tightening_stops_at_the_tightest_tol():
    """A flat punch pressed by 1e-12 of its height: the scene's ratio asks for tol 1e-16, which no solver reaches
    (it raised ConvergenceError); the tightening stops at ``TIGHTEST_TOL`` and converges there."""
    h = np.zeros((128, 128))
    h[32:96, 32:96] = 0.25
    out = contactlib.solve(h, length=1.0, E=1.0, nu=0.3, penetration=1e-12, periodic=False, target_error=1e-2)
    assert out.attrs["tol"] == accuracy.TIGHTEST_TOL and out.attrs["converged"] == 1
    assert float(out.contact_area) == pytest.approx(64 * 64 / 128**2)
