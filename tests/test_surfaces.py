"""Surface generation and statistics."""

import numpy as np
import pytest

import contactlib
from contactlib import analysis


@pytest.mark.parametrize("hurst", [0.3, 0.8])
def test_fitted_psd_slope_recovers_hurst_2d(hurst):
    h = contactlib.surfaces.self_affine(512, hurst=hurst, q_roll=4, q_cutoff=128, rms_height=1e-6, seed=5)
    assert analysis.fit_hurst(h, q_min=8, q_max=128) == pytest.approx(hurst, abs=0.02)


def test_fitted_psd_slope_recovers_hurst_1d():
    h = contactlib.surfaces.self_affine(2**16, hurst=0.6, q_roll=4, q_cutoff=2**13, rms_height=1.0, seed=2, dim=1)
    assert analysis.fit_hurst(h, q_min=8, q_max=2**13) == pytest.approx(0.6, abs=0.02)


def test_rms_normalisation_exact():
    h = contactlib.surfaces.self_affine(128, hurst=0.5, q_roll=2, q_cutoff=32, rms_height=3e-6, seed=1)
    assert analysis.rms_height(h) == pytest.approx(3e-6, rel=1e-12)
    s = contactlib.surfaces.self_affine(128, length=2e-3, hurst=0.5, q_roll=2, q_cutoff=32, rms_slope=0.2, seed=1)
    assert analysis.rms_slope(s) == pytest.approx(0.2, rel=1e-12)
    # the spectral slope agrees with a finite-difference slope for a well-resolved surface
    s = contactlib.surfaces.self_affine(128, length=2e-3, hurst=0.5, q_roll=2, q_cutoff=6, rms_slope=0.2, seed=1)
    fd = np.gradient(s.values, s.x.values[1] - s.x.values[0], axis=(0, 1))
    assert np.sqrt(np.mean(fd[0] ** 2 + fd[1] ** 2)) == pytest.approx(0.2, rel=0.05)


def test_psd_integrates_to_variance():
    h = contactlib.surfaces.self_affine(256, length=1e-3, hurst=0.8, q_roll=2, q_cutoff=64, rms_height=1e-6, seed=9)
    c = analysis.psd(h)
    assert c.attrs["units"] == "m4"
    # radial average: integral of C(q) 2 pi q dq ~ <h^2> (binning error only)
    dq = 2 * np.pi / 1e-3
    variance = float(np.sum(c.values * 2 * np.pi * c.wavenumber.values * dq))
    assert variance == pytest.approx(1e-12, rel=0.05)


def test_same_seed_same_bits_and_different_seed_differs():
    kwargs = dict(hurst=0.8, q_roll=2, q_cutoff=32, rms_slope=0.1)
    a = contactlib.surfaces.self_affine(128, seed=42, **kwargs)
    b = contactlib.surfaces.self_affine(128, seed=42, **kwargs)
    c = contactlib.surfaces.self_affine(128, seed=43, **kwargs)
    assert a.values.tobytes() == b.values.tobytes()
    assert not np.array_equal(a.values, c.values)


@pytest.mark.parametrize("length", [1e-6, 1e-5, 1e-4, 1.0, 10**2.25])
def test_one_mode_band_is_that_mode_at_every_length(length):
    """``q_low = q_roll = q_cutoff = 1`` is the one mode ``q0``. Its rounded ``q / q0`` came out an ulp above 1 at
    some windows (1e-6, 1e-4, 10^2.25), left the band, and the rms normalisation divided by zero."""
    kw = dict(hurst=1, q_low=1, q_roll=1, q_cutoff=1, rms_slope=1, dim=1)
    h = contactlib.surfaces.self_affine(8, length=length, **kw)
    assert analysis.rms_slope(h) == pytest.approx(1.0, rel=1e-12)
    power = np.abs(np.fft.rfft(h.values)) ** 2
    assert power[1] / power.sum() == pytest.approx(1.0, abs=1e-12)
    # the same surface on the window's coordinates: at unit rms slope the heights scale with the window
    unit = contactlib.surfaces.self_affine(8, length=1.0, **kw)
    np.testing.assert_allclose(h.values / length, unit.values, rtol=0, atol=1e-12 * float(np.abs(unit).max()))


@pytest.mark.parametrize("band", [dict(dim=1, q_roll=1, q_cutoff=2), dict(q_roll=2, q_cutoff=5),
                                  dict(q_low=2, q_roll=2, q_cutoff=5, anisotropy=0.5)])
def test_band_edge_modes_are_kept_whatever_the_window(band):
    """Modes on ``q_low`` or ``q_cutoff`` belong to the band at every window length. At L = 10^1.5 the rounded
    ``q / q0`` of the q0 mode (1D), of (3, 4) and (5, 0) on ``q_cutoff = 5`` (2D), of (2, 0) on ``q_low = 2``
    (anisotropic) fell outside, and the mode was dropped: heights 1.87 off at unit rms in 1D."""
    dim = band.get("dim", 2)
    n = 8 if dim == 1 else 16
    kw = dict(hurst=1, rms_height=1.0, seed=0) | band
    unit = contactlib.surfaces.self_affine(n, length=1.0, **kw)
    # the band's modes counted exactly on the integer lattice: k^2 = i^2 + j^2 / anisotropy (angle 0; 0.5 is exact)
    i = np.fft.fftfreq(n, 1 / n)[:, None] if dim == 2 else np.arange(n // 2 + 1)
    j = np.arange(n // 2 + 1)[None, :] if dim == 2 else 0
    k2 = i**2 + j**2 / band.get("anisotropy", 1.0)
    expected = (k2 >= band.get("q_low", 1) ** 2) & (k2 <= band["q_cutoff"] ** 2)
    for length in [1.0, 3.0, 7.0, 10**1.5]:
        h = contactlib.surfaces.self_affine(n, length=length, **kw)
        amplitude = np.abs(np.fft.rfftn(h.transpose("x", ...).values))  # indexed [ix, iy], as i and j
        np.testing.assert_array_equal(amplitude > 1e-9 * amplitude.max(), expected, err_msg=f"length={length}")
        np.testing.assert_allclose(h.values, unit.values, rtol=0, atol=1e-12)


@pytest.mark.parametrize("gamma,angle", [(0.3, 0.0), (0.5, np.pi / 3), (0.2, 2.0)])
def test_anisotropy_recovered(gamma, angle):
    h = contactlib.surfaces.self_affine(256, hurst=0.8, q_roll=2, q_cutoff=64, rms_slope=0.1, seed=4,
                                        anisotropy=gamma, angle=angle, synthesis="random-phase")
    tensor = analysis.anisotropy_tensor(h, 0, 128)
    assert float(tensor.gamma) == pytest.approx(gamma, rel=0.05)
    diff = (float(tensor.theta_d) - angle + np.pi / 2) % np.pi - np.pi / 2
    assert abs(diff) < 0.05 * np.pi / 2
    # mu2 is maximal along theta_d, and its max/min ratio matches gamma
    assert float(tensor.mu2.min() / tensor.mu2.max()) == pytest.approx(float(tensor.gamma), rel=1e-3)


def test_anisotropy_of_gaussian_surfaces_on_average():
    """Filtered noise: each realisation scatters (few long-wavelength modes); the seed average holds."""
    gammas = [float(analysis.anisotropy_tensor(contactlib.surfaces.self_affine(
        256, hurst=0.8, q_roll=2, q_cutoff=64, rms_slope=0.1, seed=s, anisotropy=0.5, angle=1.0), 0, 128).gamma)
        for s in range(8)]
    assert np.mean(gammas) == pytest.approx(0.5, rel=0.05)


def test_isotropic_surface_has_gamma_near_one():
    h = contactlib.surfaces.self_affine(256, hurst=0.8, q_roll=2, q_cutoff=64, rms_slope=0.1, seed=4)
    assert float(analysis.anisotropy_tensor(h, 0, 128).gamma) > 0.85


def test_anisotropy_tensor_matches_slope_products():
    h = contactlib.surfaces.self_affine(128, hurst=0.8, q_roll=2, q_cutoff=32, rms_slope=0.1, seed=4,
                                        anisotropy=0.4, angle=0.5)
    m = analysis.anisotropy_tensor(h, 0, 64).M.values
    gx, gy = (np.fft.ifftn(1j * q * np.fft.fftn(h.transpose("x", "y").values)).real for q in np.meshgrid(
        2 * np.pi * np.fft.fftfreq(128, 1 / 128), 2 * np.pi * np.fft.fftfreq(128, 1 / 128), indexing="ij"))
    np.testing.assert_allclose(m, [[np.mean(gx * gx), np.mean(gx * gy)], [np.mean(gx * gy), np.mean(gy * gy)]],
                               rtol=1e-10)


def test_wavy_and_spheres():
    w = contactlib.surfaces.wavy(64, amplitude=2.0, dim=2)
    assert float(w.max()) == pytest.approx(2.0) and w.dims == ("y", "x")
    lattice = contactlib.surfaces.spheres(64, radius=0.1, lattice=4, summit_height=0.01)
    assert float(lattice.max()) <= 0.01 + 1e-15
    labels, areas = analysis.contact_clusters(lattice.values > 0)
    assert len(areas) == 16 and np.ptp(areas) == 0
    rand = contactlib.surfaces.spheres(64, radius=0.05, count=10, height_std=0.002, seed=3)
    rand2 = contactlib.surfaces.spheres(64, radius=0.05, count=10, height_std=0.002, seed=3)
    assert rand.values.tobytes() == rand2.values.tobytes()


def test_clusters_merge_across_periodic_edges():
    mask = np.zeros((8, 8))
    mask[0, 3] = mask[7, 3] = 1  # one patch split by the x edge
    mask[4, 0] = mask[4, 7] = 1  # one patch split by the y edge
    _, areas = analysis.contact_clusters(mask)
    assert sorted(areas) == [2.0, 2.0]
    _, areas_np = analysis.contact_clusters(mask, periodic=False)
    assert len(areas_np) == 4
    assert analysis.contact_area_fraction(mask) == 4 / 64


@pytest.mark.parametrize("kwargs,name", [
    (dict(hurst=1.5), "hurst"),
    (dict(q_cutoff=100), "q_cutoff"),
    (dict(rms_height=1.0), "exactly one"),
    (dict(anisotropy=0.0), "anisotropy"),
])
def test_bad_surface_parameters(kwargs, name):
    base = dict(hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1)
    base.update(kwargs)
    with pytest.raises(ValueError, match=name):
        contactlib.surfaces.self_affine(64, **base)


def test_generated_surfaces_carry_their_provenance():
    """Every generator writes its parameters, seed and the library version into the heights' attrs (an
    adhesion_curve Dataset too): a surface saved on its own says what made it."""
    made = [contactlib.surfaces.self_affine(16, hurst=0.8, q_roll=1, q_cutoff=4, rms_slope=0.1, seed=7),
            contactlib.surfaces.wavy(16, amplitude=0.1), contactlib.surfaces.paraboloid(16, length=1.0, radius=1.0),
            contactlib.surfaces.spheres(32, radius=0.5, lattice=2, summit_height=0.01)]
    for h in made:
        assert h.attrs["contactlib_version"] == contactlib.__version__ and h.attrs["generator"].startswith("contactlib")
    assert made[0].attrs["seed"] == 7
    curve = contactlib.adhesion_curve(made[1], E=1.0, nu=0.0, adhesion=contactlib.Adhesion(work=1e-4, model="jkr"),
                                      mean_pressures=[0.0, 0.01])
    assert curve.attrs["contactlib_version"] == contactlib.__version__


@pytest.mark.parametrize("make, match", [
    (lambda: contactlib.surfaces.spheres(32, radius=0.5, lattice=2, summit_height=float("nan")), "summit_height"),
    (lambda: contactlib.surfaces.spheres(32, radius=0.5, lattice=2, summit_height=-0.1), "no asperity rises"),
    (lambda: contactlib.surfaces.spheres(32, radius=0.1, lattice=2, summit_height=0.4), "must not exceed radius"),
    (lambda: contactlib.surfaces.spheres(32, radius=float("nan"), lattice=2, summit_height=0.01), "radius"),
    (lambda: contactlib.surfaces.spheres(32, radius=0.5, lattice=0, summit_height=0.01), "lattice"),
    (lambda: contactlib.surfaces.spheres(32, radius=0.5, count=2.5, summit_height=0.01), "count"),
    (lambda: contactlib.surfaces.spheres(32, radius=0.5, centers=[[0.1, 0.2, 0.3]], summit_height=0.01), "centers"),
    (lambda: contactlib.surfaces.spheres(32, radius=[0.5, 0.4, 0.3], lattice=2, summit_height=0.01), "radius"),
    (lambda: contactlib.surfaces.spheres(32, radius=0.5, lattice=2, summit_height=0.01, height_std=-1.0),
     "height_std"),
    (lambda: contactlib.surfaces.wavy(32, amplitude=0.01, wavelengths=1.5), "wavelengths"),
    (lambda: contactlib.surfaces.wavy(32, amplitude=0.01, wavelengths=0), "wavelengths"),
    (lambda: contactlib.surfaces.wavy(32, amplitude=0.01, wavelengths=40), "wavelengths"),
    (lambda: contactlib.surfaces.self_affine(32, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, anisotropy=0.5,
                                             angle=float("nan")), "angle"),
    (lambda: contactlib.surfaces.self_affine(8, hurst=0.8, q_low=1.2, q_roll=1.3, q_cutoff=1.5, rms_height=1.0,
                                             dim=1), "q_cutoff"),  # no multiple of q0 in the band
    (lambda: contactlib.surfaces.self_affine(16, hurst=0.8, q_low=1, q_roll=1, q_cutoff=1, rms_height=1.0,
                                             anisotropy=0.5, angle=0.3), "q_cutoff"),  # stretched past q0: no mode
    (lambda: contactlib.surfaces.self_affine(8, hurst=0.8, q_low=4, q_roll=4, q_cutoff=4, rms_slope=0.1, dim=1),
     "rms_slope"),  # only the Nyquist mode, which has no defined slope
    (lambda: contactlib.two_scale.random_asperity_field(9, coverage=0.2, nodes_per_spacing=8,
                                                        height_scatter=float("nan")), "height_scatter"),
    (lambda: contactlib.two_scale.random_asperity_field(9, coverage=0.2, nodes_per_spacing=8, height_scatter=-0.5),
     "height_scatter"),
    (lambda: contactlib.two_scale.random_asperity_field(2.7, coverage=0.2, nodes_per_spacing=8), "count"),
    (lambda: contactlib.two_scale.random_asperity_field(9, coverage=0.2, nodes_per_spacing=8, n=40.5), "n must be"),
    (lambda: contactlib.two_scale.random_asperity_field(9, coverage=0.2, nodes_per_spacing=-3), "nodes_per_spacing"),
])
def test_bad_surface_parameters_are_named(make, match):
    """Each of these returned a flat, a cliffed, an aliased or a truncated surface, or failed with a ZeroDivisionError
    or a numpy error; now a ValueError names the parameter."""
    with pytest.raises(ValueError, match=match):
        make()
