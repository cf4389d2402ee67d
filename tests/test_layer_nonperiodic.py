"""A confined layer on a non-periodic window (zero-padded), checked against the periodic layer solver on a
window 8x wider (the same spacing, the indenter at its centre): there the images are seven windows away, so
both answer the isolated contact, by different embeddings."""

import numpy as np
import pytest

import contactlib


def _indenter(n, length, dim, radius=1.0):
    x = (np.arange(n) - n // 2) * (length / n)
    if dim == 1:
        return -x**2 / (2 * radius)
    X, Y = np.meshgrid(x, x, indexing="ij")
    return -(X**2 + Y**2) / (2 * radius)


def _against_wide_periodic(n, dim, nu, thickness, mean_pressure, wider=8):
    layer = contactlib.Layer(thickness)
    padded = contactlib.solve(_indenter(n, 1.0, dim), length=1.0, E=1.0, nu=nu, mean_pressure=mean_pressure,
                              periodic=False, layer=layer, tol=1e-10)
    wide = contactlib.solve(_indenter(wider * n, float(wider), dim), length=float(wider), E=1.0, nu=nu,
                            mean_pressure=mean_pressure / wider**dim, periodic=True, layer=layer, tol=1e-10)
    start = (wider - 1) * n // 2
    reference = wide.pressure.values[(slice(start, start + n),) * dim]
    return padded, wide, reference


@pytest.mark.parametrize("nu, thickness", [(0.3, 0.05), (0.3, 0.15), (0.5, 0.1)])
def test_sphere_on_a_confined_layer_matches_a_wide_periodic_window(nu, thickness):
    padded, wide, reference = _against_wide_periodic(64, 2, nu, thickness, 1e-3)
    pressure = padded.pressure.values
    assert padded.attrs["body"] == "layer"
    assert padded.attrs["layer_window_thicknesses"] >= contactlib.model.bodies.LAYER_WINDOW
    assert 0.01 < float(padded.contact_area) < 0.2  # a contact of 40-800 elements, clear of the window's edge
    assert np.abs(pressure - reference).max() <= 2e-5 * pressure.max()
    assert float(padded.penetration) == pytest.approx(float(wide.penetration), rel=1e-5)
    # the layer matters here: the zero-padded half-space under the same load is far off
    half = contactlib.solve(_indenter(64, 1.0, 2), length=1.0, E=1.0, nu=nu, mean_pressure=1e-3, periodic=False)
    assert abs(float(half.penetration) / float(padded.penetration) - 1) > 0.1


def test_cylinder_on_a_thin_incompressible_layer_matches_a_wide_periodic_window():
    """A profile, and an incompressible layer: its uniform mode carries no compliance (the q = 0 entry 0)."""
    padded, wide, reference = _against_wide_periodic(512, 1, 0.5, 0.05, 5e-4)
    pressure = padded.pressure.values
    assert np.abs(pressure - reference).max() <= 2e-5 * pressure.max()
    assert float(padded.penetration) == pytest.approx(float(wide.penetration), rel=1e-5)


def test_creep_relaxation_on_a_padded_layer_follows_the_modulus():
    """Constant penetration: the contact does not move, so the load relaxes as E(t) exactly, from the glassy
    load that the periodic solver gives on a window 4x wider."""
    material = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.3)
    times = np.linspace(0.0, 3.0, 7)
    layer = contactlib.Layer(0.05)
    out = contactlib.solve_transient(_indenter(64, 1.0, 2), length=1.0, times=times, material=material,
                                     penetration=5e-3, periodic=False, layer=layer)
    load = out.mean_pressure.values
    assert np.all(out.contact_area.values == out.contact_area.values[0])
    np.testing.assert_allclose(load / load[0], material.relaxation(times) / material.relaxation(0.0), rtol=1e-6)
    glassy = contactlib.solve(_indenter(256, 4.0, 2), length=4.0, E=10.0, nu=0.3, penetration=5e-3, periodic=True,
                              layer=layer, tol=1e-10)
    assert load[0] == pytest.approx(float(glassy.mean_pressure) * 16, rel=1e-5)


@pytest.mark.parametrize("law", [contactlib.Adhesion(work=1e-4, range=4e-3, model="maugis"),
                                 contactlib.Adhesion(work=1e-4, model="jkr")])
def test_adhesive_sphere_on_a_padded_layer_matches_a_wide_periodic_window(law):
    """Adhesion on the padded layer (a cohesive law with a process zone of 9 elements, and the JKR limit): the
    same contact as on a periodic window 4x wider."""
    n, wider, layer = 64, 4, contactlib.Layer(0.05)
    padded = contactlib.solve(_indenter(n, 1.0, 2), length=1.0, E=1.0, nu=0.3, adhesion=law, layer=layer,
                              periodic=False, penetration=1.5e-3, tol=1e-8)
    wide = contactlib.solve(_indenter(wider * n, float(wider), 2), length=float(wider), E=1.0, nu=0.3, adhesion=law,
                            layer=layer, periodic=True, penetration=1.5e-3, tol=1e-8)
    start = (wider - 1) * n // 2
    reference = wide.pressure.values[start:start + n, start:start + n]
    pressure = padded.pressure.values
    assert float(padded.mean_pressure) < 0  # held by adhesion
    assert np.abs(pressure - reference).max() <= 1e-4 * np.abs(pressure).max()
    assert float(padded.mean_pressure) == pytest.approx(float(wide.mean_pressure) * wider**2, rel=1e-4)
    assert float(padded.contact_area) * n**2 == float(wide.contact_area) * (wider * n) ** 2


@pytest.mark.parametrize("dim, n, nu, thickness, friction, match", [(2, 64, 0.3, 0.1, 0.3, 1e-2),
                                                                   (1, 512, 0.3, 0.05, 0.8, 1e-4)])
def test_friction_on_a_padded_layer_matches_a_wide_periodic_window(dim, n, nu, thickness, friction, match):
    """Coulomb friction with its normal-tangential coupling on the padded layer: the change friction makes to the
    pressure (4-16 % of it here) is the one a periodic window 4x wider makes, to 6e-3 in 2D (the material coupling's
    band-limited kernel, singular like x / r^2, ripples further than the normal one) and 1e-5 in 1D."""
    load, wider, layer = (1e-3 if dim == 2 else 5e-4), 4, contactlib.Layer(thickness)
    start = (wider - 1) * n // 2
    out = {}
    for mu in (0.0, friction):
        padded = contactlib.solve(_indenter(n, 1.0, dim), length=1.0, E=1.0, nu=nu, mean_pressure=load,
                                  periodic=False, layer=layer, friction=mu, tol=1e-10)
        wide = contactlib.solve(_indenter(wider * n, float(wider), dim), length=float(wider), E=1.0, nu=nu,
                                mean_pressure=load / wider**dim, periodic=True, layer=layer, friction=mu, tol=1e-10)
        out[mu] = padded, wide, wide.pressure.values[(slice(start, start + n),) * dim]
    (plain, _, plain_wide), (padded, wide, reference) = out[0.0], out[friction]
    assert padded.attrs["coupling"] == "normal-tangential"
    change, change_wide = padded.pressure.values - plain.pressure.values, reference - plain_wide
    assert np.linalg.norm(change_wide) > 0.03 * np.linalg.norm(reference)  # friction matters here
    assert np.linalg.norm(change - change_wide) <= match * np.linalg.norm(change_wide)
    # mu_a from the deformed surface: central differences off a periodic window, so the wide one's the same way
    wide_mu_a = contactlib.analysis.interlocking_friction(wide.pressure, wide.displacement,  # x and y by name
                                                          lengths=(float(wider),) * dim, periodic=False)
    assert float(padded.friction_coefficient_interlocking) == pytest.approx(wide_mu_a, rel=1e-5)
    assert float(padded.friction_coefficient_interlocking) == pytest.approx(
        float(wide.friction_coefficient_interlocking), rel=0.05)  # spectral there: 4.4 % (2D) and 0.7 % (1D) apart
    assert float(padded.penetration) == pytest.approx(float(wide.penetration), rel=1e-5)


@pytest.mark.parametrize("kwargs, name", [
    ({"layer": contactlib.Layer(0.05, "remote_pressure")}, "layer"),
    ({"layer": contactlib.Layer(0.6)}, "layer"),  # acting across the window
    ({"layer": contactlib.Layer(1.0 / 5.9)}, "layer"),  # just under six thicknesses
])
def test_padded_layer_refusals_name_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=name):
        contactlib.solve(_indenter(128, 1.0, 2), length=1.0, E=1.0, nu=0.3, mean_pressure=1e-3, periodic=False,
                         **kwargs)


@pytest.mark.parametrize("n", [32, 256])
def test_padded_layer_window_rule_does_not_depend_on_the_grid(n):
    """Six thicknesses across, on a coarse grid and a fine one, is taken; the rule is the window's, not the
    elements'."""
    out = contactlib.solve(_indenter(n, 1.0, 2), length=1.0, E=1.0, nu=0.3, mean_pressure=1e-3, periodic=False,
                           layer=contactlib.Layer(1.0 / 6.0))
    assert out.attrs["body"] == "layer" and out.attrs["layer_window_thicknesses"] == pytest.approx(6.0)
