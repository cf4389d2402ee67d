"""Command line round trip: NetCDF in and out, same numbers as the Python API."""

import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

import contactlib
from contactlib.cli import main


def test_surface_then_solve_matches_api(tmp_path):
    surf, out = tmp_path / "surf.nc", tmp_path / "out.nc"
    assert main(["surface", "--n", "64", "--hurst", "0.7", "--q-roll", "2", "--q-cutoff", "16", "--rms-slope",
                 "0.1", "--seed", "5", "-o", str(surf)]) == 0
    assert main(["solve", str(surf), "--E", "2.0", "--nu", "0.3", "--mean-pressure", "0.01", "-o", str(out)]) == 0
    api_surface = contactlib.surfaces.self_affine(64, hurst=0.7, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=5)
    api = contactlib.solve(api_surface, E=2.0, nu=0.3, mean_pressure=0.01)
    with xr.open_dataset(surf) as s:
        assert s.height.values.tobytes() == api_surface.values.tobytes()
    with xr.open_dataset(out) as o:
        for name in ("pressure", "gap", "displacement"):
            np.testing.assert_array_equal(o[name].values, api[name].values)
        for name in ("contact_area", "mean_pressure", "penetration", "iterations", "residual"):
            assert float(o[name]) == float(api[name])
            assert o[name].attrs["units"] and o[name].attrs["long_name"]


def test_console_script_help_and_errors(tmp_path):
    for args in (["--help"], ["surface", "--help"], ["solve", "--help"]):
        res = subprocess.run([sys.executable, "-m", "contactlib.cli", *args], capture_output=True, text=True,
                             timeout=60)
        assert res.returncode == 0 and "usage" in res.stdout
    surf = tmp_path / "s.nc"
    main(["surface", "--n", "16", "--hurst", "0.7", "--q-roll", "1", "--q-cutoff", "4", "--rms-height", "1e-6",
          "-o", str(surf)])
    res = subprocess.run([sys.executable, "-m", "contactlib.cli", "solve", str(surf), "--E", "-3", "--nu", "0.3",
                          "--mean-pressure", "1", "-o", str(tmp_path / "o.nc")], capture_output=True, text=True,
                         timeout=60)
    assert res.returncode == 2 and "E (Young's modulus)" in res.stderr
    assert not (tmp_path / "o.nc").exists()


def test_non_convergence_exit_status_keeps_partial_result(tmp_path):
    surf, out = tmp_path / "s.nc", tmp_path / "o.nc"
    main(["surface", "--n", "32", "--hurst", "0.7", "--q-roll", "1", "--q-cutoff", "8", "--rms-slope", "0.1",
          "-o", str(surf)])
    assert main(["solve", str(surf), "--E", "1", "--nu", "0.3", "--mean-pressure", "0.01", "--tol", "1e-14",
                 "--max-iter", "2", "-o", str(out)]) == 3
    with xr.open_dataset(out) as o:
        assert o.attrs["converged"] == 0


def test_exactly_one_load_on_the_command_line():
    with pytest.raises(SystemExit):
        main(["solve", "x.nc", "--E", "1", "--nu", "0.3", "--mean-pressure", "1", "--penetration", "1", "-o", "o"])


def test_solve_with_layer_and_friction_matches_api(tmp_path):
    surf, out = tmp_path / "s.nc", tmp_path / "o.nc"
    assert main(["surface", "--n", "64", "--hurst", "0.7", "--q-roll", "2", "--q-cutoff", "16", "--rms-slope",
                 "0.1", "--seed", "2", "-o", str(surf)]) == 0
    assert main(["solve", str(surf), "--E", "1.0", "--nu", "0.3", "--mean-pressure", "0.01", "--thickness", "0.05",
                 "--base", "confined", "--friction", "0.6", "--sliding-direction", "0.5", "-o", str(out)]) == 0
    with xr.open_dataset(surf) as s, xr.open_dataset(out) as o:
        api = contactlib.solve(s.height, E=1.0, nu=0.3, mean_pressure=0.01, layer=contactlib.Layer(0.05),
                               friction=0.6, sliding_direction=0.5)
        np.testing.assert_array_equal(o.pressure.values, api.pressure.values)
        assert float(o.friction_coefficient) == float(api.friction_coefficient)
        assert o.attrs["layer_base"] == "confined" and o.attrs["coupling"] == "normal-tangential"
    assert main(["solve", str(surf), "--E", "1.0", "--nu", "0.3", "--mean-pressure", "0.01", "--thickness", "-1",
                 "-o", str(out)]) == 2


def test_surface_from_a_measured_file_and_solve_reads_it_directly(tmp_path):
    h = contactlib.surfaces.self_affine(64, length=1e-3, hurst=0.7, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=5)
    matrix, surf, direct, via = (tmp_path / n for n in ("m.txt", "s.nc", "direct.nc", "via.nc"))
    np.savetxt(matrix, h.transpose("y", "x").values * 1e6, fmt="%.17g")  # micrometres, one row per y
    file_args = ["--length", "1000", "--unit", "um", "--periodic", "--detrend", "mean"]
    assert main(["surface", "--from", str(matrix), *file_args, "-o", str(surf)]) == 0
    api = contactlib.surfaces.read(matrix, length=1000, unit="um", periodic=True, detrend="mean")
    with xr.open_dataset(surf) as s:
        assert s.height.values.tobytes() == api.values.tobytes()
        assert s.height.attrs["source_file"] == "m.txt" and s.height.attrs["height_unit"] == "um"
        assert s.height.attrs["detrend"] == "mean" and s.height.attrs["periodic"] == 1
        assert s.x.attrs["units"] == "m" and float(s.x[1]) == 1e-3 / 64
    load = ["--E", "1e7", "--nu", "0.5", "--mean-pressure", "1e4"]
    assert main(["solve", str(matrix), *file_args, *load, "-o", str(direct)]) == 0
    assert main(["solve", str(surf), *load, "-o", str(via)]) == 0  # a .nc file is not detrended again
    reference = contactlib.solve(api, E=1e7, nu=0.5, mean_pressure=1e4)
    with xr.open_dataset(direct) as a, xr.open_dataset(via) as b:
        for o in (a, b):
            np.testing.assert_array_equal(o.pressure.values, reference.pressure.values)
            assert o.attrs["periodic"] == 1
    assert main(["solve", str(matrix), "--unit", "um", *load, "-o", str(tmp_path / "x.nc")]) == 2  # no size
    assert not (tmp_path / "x.nc").exists()
    assert main(["surface", "--n", "32", "-o", str(tmp_path / "y.nc")]) == 2  # neither --from nor a spectrum
