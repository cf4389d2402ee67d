"""Solving to a target contact area (``solve(..., contact_area=)``) and the window scalars a user needs besides the
solver's own (``mean_gap``; an isolated footprint's ``normal_force`` and ``contact_radius``)."""

import numpy as np
import pytest

import contactlib
from contactlib.reference import hertz

pytestmark = pytest.mark.filterwarnings("ignore::contactlib.ResolutionWarning")

E, NU = 1.0, 0.5
E_STAR = E / (1 - NU**2)


@pytest.fixture(scope="module")
def sphere():
    """A sphere of radius 1 on a 128^2 window of side 1, solved to 5 % contact area (a ~ 16 spacings)."""
    heights = contactlib.surfaces.paraboloid(128, length=1.0, radius=1.0)
    return heights, contactlib.solve(heights, E=E, nu=NU, contact_area=0.05, periodic=False)


def test_sphere_contact_area_is_the_target_to_the_grid(sphere):
    heights, out = sphere
    # a ring of the symmetric grid enters at once: at most 8 elements of 128^2 (3.1 % of the contact's 819)
    assert abs(float(out.contact_area) - 0.05) * heights.size <= 8
    assert out.attrs["target_contact_area"] == 0.05


def test_sphere_radius_and_force_match_hertz(sphere):
    _, out = sphere
    force = float(out.normal_force)
    assert force == pytest.approx(float(out.mean_pressure) * 1.0**2, rel=1e-12)  # mean pressure x window area
    a_hertz = hertz.sphere_contact_radius(hertz.sphere_penetration(force, radius=1.0, E_star=E_STAR), radius=1.0)
    # 16 spacings per radius: the resolution rule predicts 1.5 % on the area; the radius is its square root
    assert float(out.contact_radius) == pytest.approx(a_hertz, rel=0.01)
    assert float(out.contact_radius) == pytest.approx(np.sqrt(float(out.contact_area) / np.pi), rel=1e-12)


def test_the_load_found_gives_the_area(sphere):
    heights, out = sphere
    again = contactlib.solve(heights, E=E, nu=NU, mean_pressure=float(out.mean_pressure), periodic=False)
    assert abs(float(again.contact_area) - float(out.contact_area)) * heights.size <= 8


def test_mean_gap_is_the_mean_of_the_gap_field(sphere):
    _, out = sphere
    assert float(out.mean_gap) == pytest.approx(float(out.gap.mean()), rel=1e-12)
    assert out.mean_gap.attrs["units"] == "m" and out.normal_force.attrs["units"] == "Pa m2"


def test_rough_surface_area_targets_are_met_by_rising_loads():
    heights = contactlib.surfaces.self_affine(64, hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=3)
    areas, loads = [], []
    for target in (0.02, 0.05, 0.1, 0.2):
        out = contactlib.solve(heights, E=E, nu=NU, contact_area=target)
        assert abs(float(out.contact_area) - target) * heights.size <= 2  # separate asperities: a cell or two a jump
        assert "normal_force" not in out  # a periodic window's force depends on the window
        areas.append(float(out.contact_area))
        loads.append(float(out.mean_pressure))
    assert np.all(np.diff(loads) > 0) and np.all(np.diff(areas) > 0)


def test_profile_gives_line_load_and_half_width():
    heights = contactlib.surfaces.paraboloid(512, length=1.0, radius=1.0, dim=1)
    out = contactlib.solve(heights, E=E, nu=NU, contact_area=0.1, periodic=False)
    b = hertz.cylinder_half_width(float(out.line_load), radius=1.0, E_star=E_STAR)
    assert float(out.contact_half_width) == pytest.approx(b, rel=0.02)  # 25 spacings per half-width
    assert abs(float(out.contact_area) - 0.1) * 512 <= 2


@pytest.mark.parametrize("kwargs, match", [
    ({"contact_area": 1.5}, "contact_area"),
    ({"contact_area": 0.0}, "contact_area"),
    ({"contact_area": 0.1, "mean_pressure": 0.01}, "contact_area"),
    ({"contact_area": 0.1, "penetration": 0.01}, "contact_area"),
    ({"contact_area": 0.1, "adhesion": contactlib.Adhesion(work=1e-3, model="jkr")}, "contact_area"),
])
def test_contact_area_refuses_bad_input_by_name(kwargs, match):
    heights = contactlib.surfaces.paraboloid(32, length=1.0, radius=1.0)
    with pytest.raises(ValueError, match=match):
        contactlib.solve(heights, E=E, nu=NU, periodic=False, **kwargs)
