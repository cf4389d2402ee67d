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
    (dict(max_iter=2.5), "max_iter must be a whole number"),
    (dict(max_iter=float("nan")), "max_iter must be a whole number"),
    (dict(tol=1.0), "tol must be a number in \\(0, 1\\)"),  # the initial guess met it: "converged", 0 iterations
    (dict(tol=2.0), "tol must be a number in"),
    (dict(mean_pressure="0.01"), "mean_pressure must be a number"),
    (dict(initial_pressure=np.full((32, 32), np.nan)), "initial_pressure contains NaN"),  # was a ZeroDivisionError
    (dict(initial_pressure=np.zeros((32, 32)), method="active-set"), "initial_pressure: a warm start is for"),
    (dict(length=(1.0, 1.0, 1.0)), "length must be a number or one per axis"),
])
def test_bad_parameters(heights, kwargs, match):
    args = dict(E=1.0, nu=0.3, mean_pressure=0.01)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        contactlib.solve(heights, **args)


def test_coordinates_set_the_window_and_must_be_a_grid(heights):
    """A DataArray's window comes from its coordinates: a different ``length`` was used silently (area 0.70 instead
    of 0.22), and an uneven coordinate gave a window from its first step; both refused, naming the parameter."""
    with pytest.raises(ValueError, match="length 5.0 differs from the heights' window"):
        contactlib.solve(heights, E=1.0, nu=0.3, mean_pressure=0.01, length=5.0)
    same = contactlib.solve(heights, E=1.0, nu=0.3, mean_pressure=0.01, length=1.0)  # agreeing: accepted
    assert float(same.contact_area) == float(contactlib.solve(heights, E=1.0, nu=0.3, mean_pressure=0.01).contact_area)
    x = heights.x.values.copy()
    x[5] = 0.9
    with pytest.raises(ValueError, match="coordinate 'x' must be finite, increasing and evenly spaced"):
        contactlib.solve(heights.assign_coords(x=x), E=1.0, nu=0.3, mean_pressure=0.01)


def test_numpy_scalars_are_numbers(heights):
    """np.float32 values (not Python floats) were refused as "must be a finite number" for tol, friction, the
    layer's thickness and the adhesion law; np.float64 always passed."""
    f32 = np.float32
    out = contactlib.solve(heights, E=1.0, nu=f32(0.3), mean_pressure=f32(0.01), tol=f32(1e-6), friction=f32(0.3),
                           sliding_direction=f32(0.0), layer=contactlib.Layer(f32(0.2)))
    assert out.attrs["converged"] == 1
    assert contactlib.Adhesion(work=f32(1e-5), range=f32(1e-3)).work == pytest.approx(1e-5)


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_non_finite_heights(heights, bad):
    values = heights.values.copy()
    values[3, 4] = bad
    with pytest.raises(ValueError, match="heights"):
        contactlib.solve(values, E=1.0, nu=0.3, mean_pressure=0.01)


@pytest.mark.parametrize("call", [
    lambda h: contactlib.solve(h.astype(complex), E=1.0, nu=0.3, mean_pressure=0.01),
    lambda h: contactlib.solve(h.values.astype(complex), E=1.0, nu=0.3, mean_pressure=0.01),
    lambda h: contactlib.analysis.rms_slope(h.astype(complex)),
    lambda h: contactlib.analysis.contact_area_fraction(h.values + 0j),
    lambda h: contactlib.analysis.rms_height(h.values + 0j),
    lambda h: contactlib.analysis.directional_slope(h.values + 0j, lengths=1.0),
    lambda h: contactlib.analysis.interlocking_friction(h.values + 0j, h.values, lengths=1.0),
    lambda h: contactlib.solve(h, E=1.0, nu=0.3, mean_pressure=0.01, initial_pressure=np.ones(h.shape) + 0j),
])
def test_complex_fields_are_refused(heights, call):
    """Complex heights or fields (a spectrum passed for the field) were read as their real part with numpy's
    ComplexWarning; now refused by name."""
    with pytest.raises(ValueError, match="(heights|field|pressure|initial_pressure) must be real"):
        call(heights)


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


@pytest.mark.parametrize("call, match", [
    (lambda h: contactlib.analysis.contact_area_fraction(np.full((8, 8), np.nan)), "pressure must be"),
    (lambda h: contactlib.analysis.contact_clusters(np.ones((8, 8)), element_area=-1.0), "element_area"),
    (lambda h: contactlib.analysis.anisotropy_tensor(h.values, 0.1, 0.5), "holds no wavevector"),
    (lambda h: contactlib.analysis.anisotropy_tensor(h.values, 1.0, 4.0, n_theta=0), "n_theta"),
    (lambda h: contactlib.analysis.fit_hurst(h.values, q_min=8, q_max=2), "q_min < q_max"),
    (lambda h: contactlib.analysis.psd(h.values, bins=-1), "bins"),
    (lambda h: contactlib.analysis.rms_slope(np.full((8, 8), np.nan)), "NaN"),
    (lambda h: contactlib.analysis.directional_slope(h.values, lengths=-1.0), "lengths"),
    (lambda h: contactlib.analysis.dissipated_power(h.values, material=1.0, sliding_velocity=(1.0, 0.0)), "material"),
    (lambda h: contactlib.analysis.dissipated_power(h.values, material=contactlib.Elastic(1.0, 0.3),
                                                    sliding_velocity=(1.0, 0.0, 0.0)), "sliding_velocity"),
])
def test_bad_analysis_input_names_the_parameter(heights, call, match):
    """NaN pressures counted as out of contact (area 0), a band with no modes gave a plausible theta_d, negative
    lengths flipped a slope's sign; others failed with numpy's errors. Each now names the parameter."""
    with pytest.raises(ValueError, match=match):
        call(heights)


def test_review_of_the_checks(heights):
    """What a review of the new checks found: float32 coordinates (rounded to 6e-8 of their size) are a grid; a 0-d
    array is a number; a 1D direction typed as 3.1416 is pi; the two-scale tolerances are relative (in (0, 1)); an
    infinite count is a ValueError, not an OverflowError."""
    h32 = heights.assign_coords(x=heights.x.values.astype(np.float32), y=heights.y.values.astype(np.float32))
    a = contactlib.solve(h32, E=1.0, nu=0.3, mean_pressure=0.01)
    b = contactlib.solve(heights, E=1.0, nu=0.3, mean_pressure=np.array(0.01))
    assert float(a.contact_area) == float(b.contact_area)
    x = np.arange(64) / 64
    profile = 0.01 * np.cos(2 * np.pi * x) + 0.002 * np.sin(6 * np.pi * x)
    typed = contactlib.solve(profile, E=1.0, nu=0.3, mean_pressure=0.01, friction=0.5, sliding_direction=3.1416)
    exact = contactlib.solve(profile, E=1.0, nu=0.3, mean_pressure=0.01, friction=0.5, sliding_direction=np.pi)
    assert np.array_equal(typed.pressure.values, exact.pressure.values)
    field = contactlib.surfaces.spheres(64, radius=0.5, lattice=4, summit_height=0.01, height_std=0.001)
    with pytest.raises(ValueError, match="tol must be a number in"):
        contactlib.two_scale.solve(field, E=1.0, nu=0.5, mean_pressure=1e-4, tol=2.0)
    for call, match in ((lambda: contactlib.analysis.psd(heights, bins=np.inf), "bins"),
                        (lambda: contactlib.analysis.anisotropy_tensor(heights, 1, 4, n_theta=np.inf), "n_theta"),
                        (lambda: contactlib.analysis.contact_clusters(np.ones((4, 4)), element_area=None),
                         "element_area"),
                        (lambda: contactlib.surfaces.wavy("8", amplitude=0.1), "n must be")):
        with pytest.raises(ValueError, match=match):
            call()
