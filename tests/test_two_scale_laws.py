"""Tabulated single-asperity laws: from full solves of one asperity, against Hertz and Sneddon's cone,
and in the macro and two-scale solves of interacting cones against the full solver."""

import math

import numpy as np
import pytest

import contactlib
import contactlib.two_scale as ts

E, NU = 1.0, 0.5
E_STAR = E / (1 - NU**2)
SLOPE = 0.1  # the cones' flank slope, cot of the half-angle


@pytest.fixture(scope="module")
def cone_law():
    return ts.tabulated_law(lambda r: SLOPE * np.asarray(r), footprint_radius=0.09, max_penetration=0.006,
                            E=E, nu=NU, nodes=96, points=10)


def test_tabulated_sphere_is_hertz():
    """A spherical cap's table: force and contact radius within 0.5 % of Hertz between and beyond the
    tabulated points, down to d -> 0 (Johnson eq. 4.23)."""
    R = 1.0
    law = ts.tabulated_law(lambda r: R - np.sqrt(R * R - np.asarray(r) ** 2), footprint_radius=0.2,
                           max_penetration=0.004, E=E, nu=NU, nodes=96, points=8)
    d = np.geomspace(1e-6, 0.004, 40)
    np.testing.assert_allclose(law.force(d), 4 / 3 * E_STAR * math.sqrt(R) * d**1.5, rtol=5e-3)
    np.testing.assert_allclose(law.contact_radius(d), np.sqrt(R * d), rtol=5e-3)
    np.testing.assert_allclose(law.slope(d), 2 * E_STAR * np.sqrt(R * d), rtol=5e-3)
    assert law.force(np.array([-1e-3, 0.0])).tolist() == [0.0, 0.0]


def test_tabulated_cone_is_sneddon(cone_law):
    """A cone of flank slope s: P = (2 / pi) E* d^2 / s, a = 2 d / (pi s) (Sneddon; Johnson section 5.2),
    within 0.5 %; the stiffness at a given force, the Newton step's, agrees with dP/dd."""
    d = np.geomspace(1e-5, 0.006, 40)
    force = 2 / math.pi * E_STAR * d**2 / SLOPE
    np.testing.assert_allclose(cone_law.force(d), force, rtol=5e-3)
    np.testing.assert_allclose(cone_law.contact_radius(d), 2 * d / (math.pi * SLOPE), rtol=5e-3)
    np.testing.assert_allclose(cone_law.stiffness(force), 2 * force / d, rtol=5e-3)
    assert np.all(np.diff(cone_law.force(d)) > 0)


def five_cones(n=384):
    """Five cones of slope SLOPE and different summit heights on a flat base, two of them close."""
    centers = [[0.2, 0.2], [0.42, 0.25], [0.72, 0.3], [0.25, 0.72], [0.65, 0.7]]
    summit = np.array([0.008, 0.0083, 0.0079, 0.0085, 0.0081])
    h = contactlib.surfaces.spheres(n, radius=0.5, centers=centers, summit_height=summit)  # the table and grid
    x = np.arange(n) / n
    cones = np.zeros((n, n))
    for (cx, cy), z in zip(centers, summit):
        dx = (x - cx + 0.5) % 1 - 0.5
        dy = (x - cy + 0.5) % 1 - 0.5
        cones = np.maximum(cones, z - SLOPE * np.sqrt(dx[:, None] ** 2 + dy[None, :] ** 2))
    return h.copy(data=cones.T)  # cones is indexed [ix, iy]; h is on ("y", "x")


def test_interacting_cones_match_the_full_solver(cone_law):
    """Five interacting cones: the two-scale method with the tabulated law within 1 % of the full FFT solver
    on the same grid in every asperity force (measured 2e-8), the macro step within 1 % (measured 0.03 %);
    load control, 7-9 nodes per contact radius."""
    h = five_cones()
    load = 4e-4
    full = contactlib.solve(h, E=E, nu=NU, mean_pressure=load)
    table = ts.asperity_table(h, footprint_radius=cone_law.footprint_radius)
    reference = ts.asperity_forces(full.pressure, table)
    assert np.count_nonzero(reference) == 5
    two = ts.solve(h, E=E, nu=NU, mean_pressure=load, law=cone_law)
    macro = ts.solve(h, E=E, nu=NU, mean_pressure=load, law=cone_law, scale="macro")
    hertz = ts.solve(h, E=E, nu=NU, mean_pressure=load, scale="macro")  # the spheres' law, for contrast
    scale = reference.max()
    assert np.max(np.abs(two.force.values - reference)) < 1e-2 * scale
    assert np.max(np.abs(macro.force.values - reference)) < 1e-2 * scale
    assert np.max(np.abs(hertz.force.values - reference)) > 0.05 * scale
    assert two.attrs["single_asperity_law"] == "tabulated" and float(two.penetration) == pytest.approx(
        float(full.penetration), rel=1e-2)


def test_tabulated_law_refusals(cone_law):
    h = five_cones(128)
    d = np.geomspace(1e-4, 2e-3, 5)  # Sneddon's cone tabulated only to 2e-3
    short = ts.TabulatedLaw(d, 2 / math.pi * E_STAR * d**2 / SLOPE, 2 * d / (math.pi * SLOPE), footprint_radius=0.09,
                            attrs={"law_E_star": E_STAR})
    ts.solve(h, E=E, nu=NU, mean_pressure=1e-4, law=short, scale="macro")  # within the table
    with pytest.raises(ValueError, match="max_penetration"):
        ts.solve(h, E=E, nu=NU, mean_pressure=4e-4, law=short, scale="macro")
    with pytest.raises(ValueError, match="law"):
        ts.solve(h, E=2 * E, nu=NU, mean_pressure=1e-5, law=cone_law, scale="macro")
    with pytest.raises(ValueError, match="law"):
        ts.solve(h, E=E, nu=NU, mean_pressure=1e-5, law="cone", scale="macro")
    with pytest.raises(ValueError, match="max_penetration"):
        ts.tabulated_law(lambda r: SLOPE * r, footprint_radius=0.05, max_penetration=0.006, E=E, nu=NU)
    with pytest.raises(ValueError, match="drop"):
        ts.tabulated_law(0.1, footprint_radius=0.05, max_penetration=0.001, E=E, nu=NU)
    with pytest.raises(ValueError, match="force"):
        ts.TabulatedLaw([1e-3, 2e-3, 3e-3], [1.0, 0.5, 2.0], [1.0, 1.0, 1.0], footprint_radius=1.0)
