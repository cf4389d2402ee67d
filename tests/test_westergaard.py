"""Wavy surfaces against Westergaard's solution (periodic)."""

import numpy as np
import pytest

import contactlib
from contactlib.reference import westergaard


def subgrid_contact_fraction(pressure: np.ndarray) -> float:
    """Contact width of a single periodic patch centred at index 0, with its edges placed where
    p^2 (linear in distance near a square-root edge) extrapolates to zero."""
    n = pressure.size
    k = 0
    while k + 1 < n // 2 and pressure[k + 1] > 0:
        k += 1
    if k + 1 >= n // 2:
        return 1.0
    p_last, p_prev = pressure[k] ** 2, pressure[k - 1] ** 2
    edge = k + p_last / (p_prev - p_last)
    return 2 * edge / n


@pytest.mark.parametrize("kernel", ["spectral", "love"])
def test_partial_contact_1d_whole_range(material, kernel):
    n, length, amplitude = 2048, 1.0, 0.01
    h = contactlib.surfaces.wavy(n, length=length, amplitude=amplitude)
    params = dict(amplitude=amplitude, wavelength=length, E_star=material["E_star"])
    for fraction in np.linspace(0.05, 0.95, 10):
        p_mean = westergaard.mean_pressure(fraction, **params)
        out = contactlib.solve(h, E=material["E"], nu=material["nu"], mean_pressure=p_mean, kernel=kernel, tol=1e-10)
        measured = subgrid_contact_fraction(out.pressure.values)
        assert westergaard.mean_pressure(measured, **params) == pytest.approx(p_mean, rel=0.005), fraction
        # pressure field against Johnson eq. 13.8
        exact = westergaard.partial_contact_pressure(out.x.values, mean_pressure=p_mean, **params)
        assert np.sqrt(np.mean((out.pressure.values - exact) ** 2)) < 0.01 * np.sqrt(np.mean(exact**2))


@pytest.mark.parametrize("n", [64, 63])
def test_full_contact_eggbox_2d(material, n):
    length, amplitude = 1.0, 0.01
    h = contactlib.surfaces.wavy(n, length=length, amplitude=amplitude, dim=2)
    q = np.hypot(2 * np.pi, 2 * np.pi)
    p_mean = 1.5 * 0.5 * material["E_star"] * q * amplitude  # 1.5 x the full-contact threshold
    out = contactlib.solve(h, E=material["E"], nu=material["nu"], mean_pressure=p_mean, tol=1e-12)
    x, y = out.x.values[:, None], out.y.values[None, :]
    exact = westergaard.full_contact_field(x, y, mean_pressure=p_mean, amplitude=amplitude, wavelength=length,
                                           E_star=material["E_star"])
    assert float(out.contact_area) == 1.0
    np.testing.assert_allclose(out.pressure.transpose("x", "y").values, exact, rtol=0, atol=1e-9 * p_mean)


def test_eggbox_full_contact_threshold_2d(material):
    """p* = sqrt(2) pi E* amplitude / wavelength: 3 % below it the troughs stay open, 3 % above they close."""
    h = contactlib.surfaces.wavy(64, amplitude=0.01, dim=2)
    p_star = westergaard.full_contact_pressure(amplitude=0.01, wavelength=1.0, E_star=material["E_star"],
                                               wavelength_y=1.0)
    assert p_star == pytest.approx(np.sqrt(2) * np.pi * material["E_star"] * 0.01)
    below = contactlib.solve(h, E=material["E"], nu=material["nu"], mean_pressure=0.97 * p_star, tol=1e-10)
    above = contactlib.solve(h, E=material["E"], nu=material["nu"], mean_pressure=1.03 * p_star, tol=1e-10)
    assert float(below.contact_area) < 1.0
    assert float(above.contact_area) == 1.0


def test_beyond_full_contact_returns_full_contact_state(material):
    h = contactlib.surfaces.wavy(256, amplitude=0.01)
    p_star = westergaard.full_contact_pressure(amplitude=0.01, wavelength=1.0, E_star=material["E_star"])
    out = contactlib.solve(h, E=material["E"], nu=material["nu"], mean_pressure=3 * p_star)
    assert float(out.contact_area) == 1.0
    assert float(out.gap.max()) < 1e-8 * 0.01
    exact = westergaard.full_contact_field(out.x.values, mean_pressure=3 * p_star, amplitude=0.01, wavelength=1.0,
                                           E_star=material["E_star"])
    np.testing.assert_allclose(out.pressure.values, exact, rtol=1e-7)


def test_love_kernel_converges_to_spectral_full_contact(material):
    """The Love kernel differs from the exact multiplier by a discretisation error that vanishes
    under refinement (second order in the spacing for a smooth mode)."""
    errors = []
    for n in (16, 32, 64):
        h = contactlib.surfaces.wavy(n, amplitude=0.01, wavelengths=2)
        p = 2 * westergaard.full_contact_pressure(amplitude=0.01, wavelength=0.5, E_star=material["E_star"])
        out = contactlib.solve(h, E=material["E"], nu=material["nu"], mean_pressure=p, kernel="love", tol=1e-12)
        exact = westergaard.full_contact_field(out.x.values, mean_pressure=p, amplitude=0.01, wavelength=0.5,
                                               E_star=material["E_star"])
        errors.append(np.max(np.abs(out.pressure.values - exact)))
    order = np.log2(errors[1] / errors[2])
    assert 1.8 < order < 2.2
