"""The measured_area_load study: its point reads the prepared surface file and scales the load by its slope."""

import numpy as np
import pytest

import contactlib
from contactlib import studies
from contactlib.studies import measured_area_load as study


def test_rms_gradient_periodic_spectral_and_non_periodic_by_differences(tmp_path):
    h = contactlib.surfaces.self_affine(64, length=1e-3, hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=2)
    assert study.rms_gradient(h) == contactlib.analysis.rms_slope(h)  # periodic: the spectral slope
    x, y = np.meshgrid(h.x.values, h.y.values, indexing="ij")
    np.save(tmp_path / "tilt.npy", 0.03 * x - 0.04 * y)  # a plane: central differences are exact on it
    tilt = contactlib.surfaces.read(tmp_path / "tilt.npy", length=1e-3, unit="m", detrend="none")
    assert tilt.attrs["periodic"] == 0
    assert study.rms_gradient(tilt) == pytest.approx(0.05, rel=1e-12)


def test_point_solves_the_prepared_surface_and_carries_its_provenance(tmp_path):
    h = contactlib.surfaces.self_affine(64, length=1e-3, hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=2)
    np.savetxt(tmp_path / "m.txt", h.transpose("y", "x").values, fmt="%.17g")  # one row per y
    prepared = contactlib.surfaces.read(tmp_path / "m.txt", length=1e-3, unit="m", periodic=True, detrend="mean")
    prepared.to_dataset().to_netcdf(tmp_path / "m.nc")
    constants = {"surface_file": str(tmp_path / "m.nc"), "E": 1.0, "nu": 0.5, "tol": 1e-8, "max_iter": 1000,
                 "kernel": "spectral"}
    point = studies.STUDIES["measured_area_load"]["point"](reduced_pressure=0.05, **constants)
    reference = contactlib.solve(prepared, E=1.0, nu=0.5, mean_pressure=0.05 * (4 / 3) * point["rms_slope"])
    assert point["contact_area"] == float(reference.contact_area) and point["kappa"] == point["contact_area"] / 0.05
    assert study.measured_area_load_shapes({}, constants) == [(64, 64)]
    attrs = study.measured_area_load_attrs(constants)
    assert attrs["source_file"] == "m.txt" and attrs["detrend"] == "mean" and attrs["periodic"] == 1
    assert attrs["length"] == [1e-3, 1e-3] and len(attrs["source_sha256"]) == 64
