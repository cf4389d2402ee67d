"""The resolution guard (issue 38, finding 6): every entry point measures its own resolution, records it, and warns
once (contactlib.ResolutionWarning) where the measured rules predict more than 1 % in contact area or pressure."""

import math
import warnings

import numpy as np
import pytest

import contactlib
from contactlib import Adhesion, resolution
from contactlib.pipeline import sweep
from contactlib.reference import hertz


def rough(n, q_cutoff, seed=0):
    return contactlib.surfaces.self_affine(n, hurst=0.8, q_roll=2, q_cutoff=q_cutoff, rms_slope=0.1, seed=seed)


def resolution_warnings(record):
    return [w for w in record if issubclass(w.category, contactlib.ResolutionWarning)]


def test_four_points_per_wavelength_warns_once_saying_what_to_change():
    """Finding 6's resolution (q_cutoff 64 on 256^2) on a 64^2 surface with q_cutoff 16: 4 points per wavelength."""
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        out = contactlib.solve(rough(64, 16), E=1.0, nu=0.5, mean_pressure=0.005)
    found = resolution_warnings(record)
    assert len(found) == 1 and found[0].filename == __file__  # points at the caller
    w = found[0].message
    fit = contactlib.accuracy.ROUGH_FITS["contact_area"]
    expected = fit["measured_constant"] / (1 - 4.0 ** -fit["order"]) * 4.0 ** -fit["order"]  # 15.3 %
    assert w.measure == "points_per_wavelength" and w.value == 4.0
    assert w.predicted_error == pytest.approx(expected, rel=1e-12) and 0.15 < expected < 0.16
    assert "4 grid points per shortest wavelength" in str(w) and "15.3%" in str(w)
    assert "n >= 1024" in str(w) and "resample" in str(w)  # 62 points per wavelength at q_cutoff 16
    assert isinstance(w, contactlib.accuracy.AccuracyWarning)
    assert out.attrs["points_per_wavelength"] == 4.0
    assert out.attrs["predicted_resolution_error"] == pytest.approx(expected, rel=1e-12)
    assert out.attrs["resolution_rule"] == "points_per_wavelength"
    assert "ResolutionWarning" in contactlib.__all__


def test_coarse_steady_viscoelastic_sliding_warns():
    """Finding 6: steady sliding at 4 points per wavelength (its power balance 5-7 % off) said nothing."""
    m = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)
    with pytest.warns(contactlib.ResolutionWarning, match="points per shortest wavelength"):
        out = contactlib.solve(rough(32, 8), material=m, mean_pressure=0.01, sliding_velocity=(0.05, 0.0))
    assert out.attrs["predicted_resolution_error"] > 0.1


def test_well_resolved_rough_surface_is_quiet_and_records():
    h = rough(256, 4)  # 64 points per shortest wavelength: 0.96 % on the area, 0.62 % on the pressure
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out = contactlib.solve(h, E=1.0, nu=0.5, mean_pressure=0.005)
    assert out.attrs["points_per_wavelength"] == 64.0
    assert 0.009 < out.attrs["predicted_resolution_error"] < 0.01


def test_warnings_filters_silence_it():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        warnings.filterwarnings("ignore", category=contactlib.ResolutionWarning)
        out = contactlib.solve(rough(32, 8), E=1.0, nu=0.5, mean_pressure=0.005)
    assert out.attrs["predicted_resolution_error"] > 0.1  # recorded all the same


def test_target_error_asks_its_own_bound_instead():
    """target_error's rule (with its safety factor) passes at 24 points per wavelength for 5 %: the 1 % guard
    stays silent there, and records."""
    settings = contactlib.accuracy.settings_for(0.05, q_cutoff=4)
    h = rough(settings["n"], 4)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out = contactlib.solve(h, E=1.0, nu=0.5, mean_pressure=0.005, target_error=0.05)
    assert out.attrs["predicted_resolution_error"] > 0.01


@pytest.mark.parametrize("spacings, warns", [(3, True), (32, False)])
def test_hertz_sphere_by_spacings_per_contact_radius(spacings, warns):
    n, R, E, nu = 128, 1.0, 1.0, 0.3
    a = spacings / n
    load = hertz.sphere_load(a * a / R, radius=R, E_star=E / (1 - nu**2))
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        out = contactlib.solve(contactlib.surfaces.paraboloid(n, radius=R), E=E, nu=nu, mean_pressure=load,
                               periodic=False)
    found = resolution_warnings(record)
    assert out.attrs["points_per_contact_radius"] == pytest.approx(spacings, rel=0.15)
    assert out.attrs["resolution_rule"] == "points_per_contact_radius"
    if warns:
        assert len(found) == 1 and "grid spacings per contact radius" in str(found[0].message)
        assert out.attrs["predicted_resolution_error"] > 0.05
    else:
        assert not found and out.attrs["predicted_resolution_error"] < 0.01


def test_maugis_sphere_with_an_unresolved_process_zone_warns_by_the_zone():
    """Below one element across the process zone (0.83: 72 % off the load of a resolved grid, CONTACT_FITS' scene)."""
    h = contactlib.surfaces.paraboloid(24, length=1.0, radius=1.0)
    law = Adhesion(work=1e-4, range=2e-3, model="maugis")
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        out = contactlib.solve(h, E=1.0, nu=0.3, penetration=5e-4, adhesion=law, periodic=False)
    found = resolution_warnings(record)
    assert len(found) == 1 and found[0].message.measure == "process_zone_elements"
    assert out.attrs["process_zone_elements"] == pytest.approx(0.8286, rel=1e-3)
    assert out.attrs["resolution_rule"] == "process_zone_elements"
    assert out.attrs["predicted_resolution_error"] == pytest.approx(
        resolution.predicted_error("process_zone_elements", 0.8286, law="maugis"), rel=1e-3)
    assert "cohesive process zone" in str(found[0].message) and "range" in str(found[0].message)


def test_resolved_maugis_sphere_is_quiet():
    """The same sphere on a window of 0.4 radii at 192^2: 16.6 elements across the zone, 37 spacings per radius."""
    h = contactlib.surfaces.paraboloid(192, length=0.4, radius=1.0)
    law = Adhesion(work=1e-4, range=2e-3, model="maugis")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out = contactlib.solve(h, E=1.0, nu=0.3, penetration=5e-4, adhesion=law, periodic=False)
    assert out.attrs["process_zone_elements"] > 10 and out.attrs["points_per_contact_radius"] > 25
    assert out.attrs["predicted_resolution_error"] < 0.01


def test_contact_radius_measure_and_rules():
    x = np.arange(-40, 41)
    for r in (5.0, 12.0, 30.0):
        disc = x[:, None] ** 2 + x[None, :] ** 2 <= r * r
        assert resolution.points_per_contact_radius(disc) == pytest.approx(r, rel=0.07)  # a staircase disc
    strip = np.zeros(100, dtype=bool)
    strip[10:30] = True
    assert resolution.points_per_contact_radius(strip) == 10.0
    assert resolution.points_per_contact_radius(np.ones((8, 8), bool), periodic=True) == math.inf
    assert math.isnan(resolution.points_per_contact_radius(np.zeros(8, bool)))
    for measure in resolution.MEASURES:
        need = resolution.needed_resolution(measure)
        assert resolution.predicted_error(measure, need) == pytest.approx(0.01, rel=1e-12)
        assert resolution.predicted_error(measure, need / 2) > 0.01 > resolution.predicted_error(measure, 2 * need)
    assert resolution.needed_resolution("points_per_wavelength") == pytest.approx(62.1, abs=0.1)
    with pytest.raises(ValueError, match="measure"):
        resolution.predicted_error("spacing", 1.0)


def test_a_sweep_records_the_prediction_instead_of_warning(caplog):
    def point(n):
        out = contactlib.solve(rough(int(n), 8), E=1.0, nu=0.5, mean_pressure=0.005)
        return {"contact_area": float(out.contact_area)}

    labels = {"contact_area": {"units": "1", "long_name": "contact area fraction"}}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ds = sweep.run_grid(point, {"n": [32, 512]}, labels=labels, progress=False)
    error = ds.predicted_resolution_error
    assert error.sel(n=32) == pytest.approx(resolution.predicted_error("points_per_wavelength", 4.0), rel=1e-12)
    assert float(error.sel(n=512)) < 0.01 and error.attrs["units"] == "1"
    assert ds.attrs["resolution_summary"].startswith("resolution: 1 of 2 points")
    assert sum("resolution: 1 of 2" in r.getMessage() for r in caplog.records) == 1


def test_time_stepping_and_speed_paths_warn_once_per_call():
    m = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)
    h = rough(64, 8)  # 8 points per wavelength: 7.7 % predicted
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        out = contactlib.solve_transient(h, material=m, times=[0.0, 0.5, 1.0], mean_pressure=0.01)
        paths = contactlib.solve_speeds(h, [(0.01, 0.0), (0.1, 0.0), (1.0, 0.0)], material=m, mean_pressure=0.01)
    found = resolution_warnings(record)
    assert [str(w.message).split(":")[0] for w in found] == ["solve_transient", "solve_speeds"]
    assert out.attrs["points_per_wavelength"] == 8.0
    assert all(p.attrs["points_per_wavelength"] == 8.0 for p in paths)


def test_two_scale_weighs_the_asperities_by_area():
    h = contactlib.surfaces.spheres(64, radius=0.5, lattice=4, summit_height=0.01, height_std=0.001, seed=1)
    with pytest.warns(contactlib.ResolutionWarning, match="two_scale.solve"):
        out = contactlib.two_scale.solve(h, E=1.0, nu=0.5, mean_pressure=1e-4)
    radii = out.contact_radius.values[out.contact_radius.values > 0] / (1.0 / 64)
    errors = [resolution.predicted_error("points_per_contact_radius", a) for a in radii]
    assert out.attrs["predicted_resolution_error"] == pytest.approx(np.sum(radii**2 * errors) / np.sum(radii**2))


def test_adhesion_curve_measures_the_pull_off_contact_and_the_zone():
    """A Maugis sphere's path on the coarse grid of the test above: the zone (0.83 elements) speaks."""
    h = contactlib.surfaces.paraboloid(24, length=1.0, radius=1.0)
    law = Adhesion(work=1e-4, range=2e-3, model="maugis")
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        ds = contactlib.adhesion_curve(h, E=1.0, nu=0.3, adhesion=law, penetrations=[0.0, 5e-4], periodic=False)
    found = resolution_warnings(record)
    assert len(found) == 1 and str(found[0].message).startswith("adhesion_curve:")
    assert ds.attrs["process_zone_elements"] == pytest.approx(0.8286, rel=1e-3)
    assert ds.attrs["resolution_rule"] == "process_zone_elements" and ds.attrs["points_per_contact_radius"] < 3
