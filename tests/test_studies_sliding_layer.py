"""The seed-2 section 4.3 studies (fig5_friction_area, fig6a_interlocking): scene, limits, signs and failures."""

import functools
import math

import numpy as np
import pytest

import contactlib
from contactlib import studies
from contactlib.pipeline import sweep
from contactlib.studies._sliding_layer import sliding_layer_scene

PROFILE = dict(n=256, hurst=0.8, q_low=1, q_roll=1, q_cutoff=32, rms_slope=0.13, layer_base="confined")
SOLVER = dict(E=1.0, tol=1e-8, max_iter=10000, kernel="spectral")


def fig5(**kw):
    return studies.friction_area_point(**{**PROFILE, **SOLVER, "nu": 0.5, "seed": 0, **kw})


def fig6a(**kw):
    return studies.interlocking_point(**{**PROFILE, **SOLVER, "seed": 0, "scaled_layer_thickness": 0.5,
                                         "friction": 0.5, **kw})


def test_scene_load_and_layer_follow_the_papers_scaling():
    h, layer, p, measures = sliding_layer_scene(**PROFILE, seed=1, scaled_layer_thickness=0.5, scaled_pressure=2.0,
                                                E=3.0, nu=0.3)
    q0 = 2 * math.pi
    assert measures["peak_height"] == pytest.approx(float(h.max() - h.mean()), rel=1e-15)
    assert p == pytest.approx(2.0 * 3.0 / (1 - 0.3**2) * q0 * measures["peak_height"] / 2, rel=1e-15)
    assert layer.thickness * q0 == pytest.approx(0.5) and layer.base == "confined"
    assert measures["rms_slope"] == pytest.approx(0.13, rel=1e-12)
    assert measures["rms_height"] == pytest.approx(contactlib.analysis.rms_height(h), rel=1e-15)


def test_both_studies_are_registered_with_labels():
    for name in ("fig5_friction_area", "fig6a_interlocking"):
        assert name in studies.STUDY_MODULES and studies.STUDIES[name]["fft_shapes"]({}, {"n": 256}) == [(256,)]
    for key in ("area_ratio", "frictionless_contact_area", "interlocking_ratio", "scaled_pressure",
                "scaled_layer_thickness", "friction", "nu", "peak_height", "friction_coefficient_interlocking"):
        label = studies.STUDY_VARIABLES[key]
        assert label["long_name"] and label["units"] == ("m" if key == "peak_height" else "1"), key


def test_no_friction_is_one_frictionless_solve():
    out = fig5(friction=0.0, scaled_layer_thickness=0.5, scaled_pressure=1.0)
    assert out["area_ratio"] == 1.0 and out["friction_coefficient_interlocking"] == 0.0
    assert out["outer_iterations"] == 0 and out["coupled"] == 0.0


def test_thick_layer_decouples_and_thin_layer_couples():
    thick = fig5(friction=1.0, scaled_layer_thickness=5.0, scaled_pressure=1.0)
    assert abs(thick["area_ratio"] - 1) < 0.01 and abs(thick["friction_coefficient_interlocking"]) < 1e-3
    thin = fig5(friction=1.0, scaled_layer_thickness=0.5, scaled_pressure=1.0)
    assert thin["coupled"] == 1.0 and thin["outer_iterations"] > 0 and thin["residual"] <= SOLVER["tol"]
    assert thin["contact_area"] != thin["frictionless_contact_area"]
    assert thin["friction_coefficient_interlocking"] > 0  # geometric coupling alone: resists sliding


def test_interlocking_sign_by_poisson_ratio():
    """Seed 2 Fig. 6a: positive at nu = 0.5 (geometric coupling only); material coupling can turn it over."""
    incompressible = fig6a(nu=0.5, scaled_pressure=1.0)
    compressible = fig6a(nu=0.2, scaled_pressure=1.0)
    assert incompressible["interlocking_ratio"] > 0 > compressible["interlocking_ratio"]
    assert incompressible["interlocking_ratio"] == pytest.approx(
        incompressible["friction_coefficient_interlocking"] / (0.5 * incompressible["rms_slope"]), rel=1e-15)


def test_failures_are_recorded_not_raised():
    constants = {**PROFILE, **SOLVER, "nu": 0.5}
    del constants["tol"]
    grid = {"tol": [1e-30, 1e-8], "friction": [1.0], "scaled_layer_thickness": [0.5], "scaled_pressure": [3.0],
            "seed": [0]}
    ds = sweep.run_grid(functools.partial(studies.friction_area_point, **constants), grid,
                        labels=studies.STUDY_VARIABLES, progress=False)
    stalled, ok = ds.sel(tol=1e-30).squeeze(), ds.sel(tol=1e-8).squeeze()
    assert int(stalled.status) == sweep.STATUS_NOT_CONVERGED and np.isfinite(float(stalled.residual))
    assert np.isnan(float(stalled.area_ratio)) and int(ok.status) == sweep.STATUS_OK
    constants = {**PROFILE, **SOLVER, "scaled_layer_thickness": 0.5}
    ds = sweep.run_grid(functools.partial(studies.interlocking_point, **constants),
                        {"friction": [0.0, 0.5], "nu": [0.5], "scaled_pressure": [1.0], "seed": [0]},
                        labels=studies.STUDY_VARIABLES, progress=False)
    assert ds.status.squeeze().values.tolist() == [sweep.STATUS_BAD_INPUT, sweep.STATUS_OK]
