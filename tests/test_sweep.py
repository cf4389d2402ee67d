"""contactlib.pipeline.sweep: failure status, checkpoint/resume after interruption, labels, atomic writes, reproducibility."""

import functools
import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

import contactlib
from contactlib import studies
from contactlib.pipeline import sweep

CONSTANTS = dict(q_low=1, q_roll=2, q_cutoff=16, rms_slope=0.1, E=1.0, nu=0.5, tol=1e-8, max_iter=10000,
                 kernel="spectral")
GRID = {"hurst": [0.5, 0.8], "n": [64], "seed": [0, 1], "reduced_pressure": [0.05, 0.02, 0.1]}


def area_load(**kw):
    return sweep.run_grid(functools.partial(studies.area_load_point, **{**CONSTANTS, **kw.pop("constants", {})}),
                          kw.pop("grid", GRID), labels=studies.STUDY_VARIABLES,
                          progress=kw.pop("progress", False), fft_shapes=[(64, 64)], **kw)


def strip(ds):
    """Drop what legitimately differs between runs: wall_time and the creation stamps."""
    out = ds.drop_vars("wall_time")
    out.attrs = {k: v for k, v in ds.attrs.items() if k not in ("date_created", "history")}
    return out


class Counting:
    """Point function that counts its calls (serial runs call it in this process)."""

    def __init__(self, fn):
        self.fn, self.calls = fn, 0

    def __call__(self, **params):
        self.calls += 1
        return self.fn(**params)


@pytest.fixture(scope="module")
def reference():
    return area_load()


def test_grid_is_sorted_labelled_and_physical(reference):
    ds = reference
    assert list(ds.reduced_pressure.values) == [0.02, 0.05, 0.1]
    assert dict(ds.sizes) == {"hurst": 2, "n": 1, "seed": 2, "reduced_pressure": 3}
    assert (ds.status == 0).all()
    for name in list(ds.data_vars) + list(ds.coords):
        assert ds[name].attrs.get("units") and ds[name].attrs.get("long_name"), name
    for key in ("title", "source", "history", "Conventions", "contactlib_version", "git_revision", "date_created"):
        assert ds.attrs[key], key
    # area grows with load and stays in the small-load regime; kappa near the published 1.5-3 band
    assert (ds.contact_area.diff("reduced_pressure") > 0).all()
    assert float(ds.kappa.min()) > 1.5 and float(ds.kappa.max()) < 3.5
    # one point equals a direct call of the library
    direct = studies.area_load_point(hurst=0.8, n=64, seed=1, reduced_pressure=0.05, **CONSTANTS)
    assert float(ds.contact_area.sel(hurst=0.8, n=64, seed=1, reduced_pressure=0.05)) == direct["contact_area"]
    assert float(ds.residual.max()) <= CONSTANTS["tol"]


def test_failed_points_are_recorded_and_the_rest_completes():
    grid = {"max_iter": [3, 10000], "reduced_pressure": [-0.01, 0.05], "hurst": [0.8], "n": [64], "seed": [0]}
    constants = {k: v for k, v in CONSTANTS.items() if k != "max_iter"}
    ds = sweep.run_grid(functools.partial(studies.area_load_point, **constants), grid, progress=False,
                        labels={**studies.STUDY_VARIABLES, "max_iter": {"units": "1", "long_name": "iteration bound"}})
    pick = dict(hurst=0.8, n=64, seed=0)
    bad = ds.sel(reduced_pressure=-0.01, **pick)
    assert (bad.status == sweep.STATUS_BAD_INPUT).all()
    assert bad.contact_area.isnull().all() and bad.residual.isnull().all()
    stalled = ds.sel(max_iter=3, reduced_pressure=0.05, **pick)
    assert int(stalled.status) == sweep.STATUS_NOT_CONVERGED
    assert float(stalled.residual) > CONSTANTS["tol"] and np.isfinite(float(stalled.residual))
    assert np.isnan(float(stalled.contact_area)) and np.isnan(float(stalled.kappa))
    ok = ds.sel(max_iter=10000, reduced_pressure=0.05, **pick)
    assert int(ok.status) == sweep.STATUS_OK and 0 < float(ok.contact_area) < 0.3
    assert ds.status.dtype == np.int8 and ds.status.attrs["flag_meanings"] == "ok not_converged bad_input"


def test_unlabelled_output_is_refused():
    with pytest.raises(KeyError, match="mystery"):
        sweep.run_grid(lambda a: {"mystery": a}, {"a": [1.0]}, progress=False,
                       labels={"a": {"units": "1", "long_name": "a"}})


class Interrupt(Exception):
    pass


def test_interrupted_sweep_resumes_without_recomputing(tmp_path, reference):
    total = int(np.prod([len(v) for v in GRID.values()]))
    seen = []

    def stop_after_three(line):
        seen.append(line)
        if len(seen) == 3:
            raise Interrupt

    with pytest.raises(Interrupt):
        area_load(checkpoint_dir=tmp_path, progress=stop_after_three)
    assert len(list(tmp_path.glob("*.pkl"))) == 3
    assert not [p for p in tmp_path.iterdir() if p.suffix == ".tmp"]
    counting = Counting(functools.partial(studies.area_load_point, **CONSTANTS))
    lines = []
    resumed = sweep.run_grid(counting, GRID, checkpoint_dir=tmp_path, labels=studies.STUDY_VARIABLES,
                             progress=lines.append, fft_shapes=[(64, 64)])
    assert counting.calls == total - 3
    assert sum("cached" in line for line in lines) == 3 and "ETA" in lines[-1]
    xr.testing.assert_identical(strip(resumed), strip(reference))
    again = Counting(counting.fn)
    sweep.run_grid(again, GRID, checkpoint_dir=tmp_path, labels=studies.STUDY_VARIABLES, progress=False)
    assert again.calls == 0


def test_killed_process_resumes_and_leaves_no_partial_netcdf(tmp_path, reference):
    """SIGKILL a sweep in a subprocess after some points; rerun computes only the rest."""
    checkpoints, final = tmp_path / "ckpt", tmp_path / "area_load.nc"
    script = textwrap.dedent(f"""
        import functools, time
        from contactlib import studies
        from contactlib.pipeline import sweep
        def slow(**kw):
            time.sleep(0.3)
            return studies.area_load_point(**kw)
        ds = sweep.run_grid(functools.partial(slow, **{CONSTANTS!r}), {GRID!r}, checkpoint_dir={str(checkpoints)!r},
                            labels=studies.STUDY_VARIABLES, progress=False)
        sweep.write_netcdf(ds, {str(final)!r})
    """)
    proc = subprocess.Popen([sys.executable, "-c", script], start_new_session=True)
    try:
        deadline = time.monotonic() + 60
        while len(list(checkpoints.glob("*.pkl"))) < 3 and time.monotonic() < deadline and proc.poll() is None:
            time.sleep(0.05)
        assert proc.poll() is None, "the sweep finished before it could be killed"
        os.killpg(proc.pid, signal.SIGKILL)
    finally:
        proc.kill()
        proc.wait(timeout=30)
    done = len(list(checkpoints.glob("*.pkl")))
    assert 3 <= done < 12
    assert not final.exists() and not list(tmp_path.glob("*.nc*"))
    counting = Counting(functools.partial(studies.area_load_point, **CONSTANTS))
    resumed = sweep.run_grid(counting, GRID, checkpoint_dir=checkpoints, labels=studies.STUDY_VARIABLES,
                             progress=False)
    assert counting.calls == 12 - done
    xr.testing.assert_identical(strip(resumed), strip(reference))


def test_twice_run_bit_identical_and_netcdf_round_trip(tmp_path, reference):
    second = area_load()
    xr.testing.assert_identical(strip(second), strip(reference))
    path = sweep.write_netcdf(reference, tmp_path / "out.nc", sweep_dims=GRID)
    with xr.open_dataset(path) as back:
        xr.testing.assert_identical(back.load(), reference)
    assert [p.name for p in tmp_path.iterdir()] == ["out.nc"]


def test_failed_write_leaves_no_file_under_the_final_name(tmp_path, reference, monkeypatch):
    def broken(self, path, **kw):
        Path(path).write_bytes(b"partial")
        raise OSError("disk full")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", broken)
    with pytest.raises(OSError, match="disk full"):
        sweep.write_netcdf(reference, tmp_path / "out.nc")
    assert list(tmp_path.iterdir()) == []


def test_fields_are_stacked_with_their_coordinates(tmp_path):
    constants = dict(CONSTANTS, n=32, q_cutoff=8, hurst=0.8, angle=0.5, reduced_pressure=0.1, zeta1=2, zeta2=8,
                     save_fields=True)
    grid = {"anisotropy": [1.0, 0.3], "seed": [0]}
    ds = sweep.run_grid(functools.partial(studies.anisotropy_point, **constants), grid,
                        labels=studies.STUDY_VARIABLES, progress=False, attrs={"config": {"grid": grid}})
    assert ds.pressure.dims == ("anisotropy", "seed", "y", "x") and ds.pressure.attrs["units"] == "Pa"
    assert ds.x.attrs["units"] == "m"
    assert json.loads(ds.attrs["config"]) == {"grid": grid}
    # the more anisotropic surface gives the more anisotropic pressure field
    assert float(ds.pressure_gamma.sel(anisotropy=0.3, seed=0)) < float(ds.pressure_gamma.sel(anisotropy=1.0, seed=0))
    path = sweep.write_netcdf(ds, tmp_path / "fields.nc", sweep_dims=grid)
    with xr.open_dataset(path) as back:
        assert back.pressure.encoding["zlib"] and back.pressure.encoding["chunksizes"] == (1, 1, 32, 32)
        xr.testing.assert_identical(back.load(), ds)
    assert contactlib.__version__ == ds.attrs["contactlib_version"]


def test_load_paths_warm_start_and_resume_per_path(tmp_path, reference):
    point = functools.partial(studies.area_load_point, **CONSTANTS)
    kw = dict(labels=studies.STUDY_VARIABLES, fft_shapes=[(64, 64)], path_dim="reduced_pressure")
    paths = sweep.run_grid(point, GRID, progress=False, **kw)
    # the same physics as cold starts, to the solver tolerance, in fewer iterations
    assert (paths.status == 0).all() and float(paths.residual.max()) <= CONSTANTS["tol"]
    np.testing.assert_allclose(paths.mean_pressure, reference.mean_pressure, rtol=1e-12)
    assert float(abs(paths.contact_area - reference.contact_area).max()) <= 2 / 64**2
    assert int(paths.iterations.sum()) < int(reference.iterations.sum())
    seen = []

    def stop_after_first_path(line):
        seen.append(line)
        if len(seen) == 4:  # one path (3 loads) finished and checkpointed, the second under way
            raise Interrupt

    with pytest.raises(Interrupt):
        sweep.run_grid(point, GRID, checkpoint_dir=tmp_path, progress=stop_after_first_path, **kw)
    assert len(list(tmp_path.glob("*.pkl"))) == 2
    counting = Counting(point)
    resumed = sweep.run_grid(counting, GRID, checkpoint_dir=tmp_path, progress=False, **kw)
    assert counting.calls == 12 - 6
    xr.testing.assert_identical(strip(resumed), strip(paths))
