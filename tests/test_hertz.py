"""Hertz contact on a non-periodic window: sphere (2D) and cylinder (1D, plane strain)."""

import numpy as np
import pytest

import contactlib
from contactlib.reference import hertz


@pytest.mark.parametrize("kernel", ["spectral", "love"])
@pytest.mark.parametrize("n", [256, 255])
def test_sphere_displacement_control(material, kernel, n):
    length, radius = 1.0, 1.0
    dx = length / n
    a_exact = 40 * dx  # >= 30 spacings
    penetration = a_exact**2 / radius
    h = contactlib.surfaces.paraboloid(n, length=length, radius=radius)
    out = contactlib.solve(h, E=material["E"], nu=material["nu"], penetration=penetration, periodic=False,
                           kernel=kernel)
    load = float(out.mean_pressure) * length**2
    assert load == pytest.approx(hertz.sphere_load(penetration, radius=radius, E_star=material["E_star"]), rel=0.01)
    a_num = np.sqrt(float(out.contact_area) * length**2 / np.pi)
    assert abs(a_num - a_exact) < 2 * dx
    assert float(out.residual) <= 1e-8
    # force balance: the reported mean pressure is the field's mean
    assert float(out.pressure.mean()) == pytest.approx(float(out.mean_pressure), rel=1e-12)


def test_sphere_load_control_pressure_profile(material):
    n, length, radius = 256, 1.0, 1.0
    h = contactlib.surfaces.paraboloid(n, length=length, radius=radius)
    load = hertz.sphere_load((40 / n) ** 2, radius=radius, E_star=material["E_star"])
    out = contactlib.solve(h, E=material["E"], nu=material["nu"], mean_pressure=load / length**2, periodic=False,
                           kernel="love")
    penetration = hertz.sphere_penetration(load, radius=radius, E_star=material["E_star"])
    assert float(out.penetration) == pytest.approx(penetration, rel=0.01)
    x = out.x.values - length / 2
    r = np.hypot(x[:, None], x[None, :])
    exact = hertz.sphere_pressure(r, load=load, radius=radius, E_star=material["E_star"])
    p0 = exact.max()
    assert float(out.pressure.max()) == pytest.approx(p0, rel=0.01)
    # pointwise error away from the edge singularity of the slope
    inner = r < 0.8 * np.sqrt(radius * penetration)
    assert np.max(np.abs(out.pressure.transpose("x", "y").values[inner] - exact[inner])) < 0.01 * p0


@pytest.mark.parametrize("kernel", ["spectral", "love"])
def test_cylinder_line_contact(material, kernel):
    n, length, radius = 2048, 1.0, 1.0
    dx = length / n
    h = contactlib.surfaces.paraboloid(n, length=length, radius=radius, dim=1)
    b = 60 * dx
    line_load = np.pi * material["E_star"] * b**2 / (4 * radius)
    out = contactlib.solve(h, E=material["E"], nu=material["nu"], mean_pressure=line_load / length, periodic=False,
                           kernel=kernel)
    assert float(out.mean_pressure) * length == pytest.approx(line_load, rel=1e-10)
    assert abs(float(out.contact_area) * length / 2 - b) < 2 * dx
    p0 = 2 * line_load / (np.pi * b)
    assert float(out.pressure.max()) == pytest.approx(p0, rel=0.01)
    x = out.x.values - length / 2
    exact = hertz.cylinder_pressure(x, line_load=line_load, radius=radius, E_star=material["E_star"])
    assert np.sqrt(np.mean((out.pressure.values - exact) ** 2)) < 0.01 * np.sqrt(np.mean(exact**2))


def test_sphere_refinement_reduces_load_error(material):
    """Spectral kernel: the load error at fixed physical penetration shrinks as the grid is refined."""
    errors = []
    for n in (64, 128, 256):
        h = contactlib.surfaces.paraboloid(n, length=1.0, radius=1.0)
        d = 0.15**2
        out = contactlib.solve(h, E=material["E"], nu=material["nu"], penetration=d, periodic=False)
        errors.append(abs(float(out.mean_pressure) / hertz.sphere_load(d, radius=1.0, E_star=material["E_star"]) - 1))
    assert errors[2] < errors[1] < errors[0]
