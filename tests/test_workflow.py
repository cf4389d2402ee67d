"""The Snakemake workflow: lint, dry runs, config validation, and one tiny end-to-end run (slow)."""

import hashlib
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import xarray as xr
import yaml

import contactlib

ROOT = Path(__file__).resolve().parents[1]
TINY = ROOT / "tests" / "data" / "tiny_config.yaml"

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    """A copy of the workflow, so the run writes results/ outside the checkout."""
    work = tmp_path_factory.mktemp("wf")
    shutil.copy(ROOT / "Snakefile", work / "Snakefile")
    shutil.copytree(ROOT / "workflow", work / "workflow")
    shutil.copytree(ROOT / "profiles", work / "profiles")
    shutil.copy(TINY, work / "tiny.yaml")
    return work


def snakemake(work, *args, timeout=120):
    return subprocess.run([sys.executable, "-m", "snakemake", *args], cwd=work, capture_output=True, text=True,
                          timeout=timeout)


def test_lint_and_dry_runs(workdir):
    lint = snakemake(workdir, "--lint")
    assert lint.returncode == 0 and "good condition" in lint.stdout + lint.stderr, lint.stdout + lint.stderr
    for extra in ([], ["--configfile", "tiny.yaml"], ["--config", "scale=paper"]):
        dry = snakemake(workdir, "-n", *extra)
        assert dry.returncode == 0, dry.stderr
        # the default profile (rerun-incomplete after a hard kill) is where Snakemake looks for it
        assert "Using workflow specific profile profiles/default" in dry.stderr
        assert "run_study" in dry.stdout and "plot_area_load" in dry.stdout
        assert "plot_speed_vs_error" in dry.stdout and "tabulate_speed_vs_error" in dry.stdout
        assert "plot_fig5_friction_area" in dry.stdout and "plot_fig6a_interlocking" in dry.stdout
        assert "plot_fig4_adhesive_layers" in dry.stdout and "plot_adhesive_rough" in dry.stdout


@pytest.mark.parametrize("path, value, message", [
    (("studies", "area_load", "quick", "grid", "hurst"), [0.5, 1.5], "1.5 is greater than the maximum of 1"),
    (("scale",), "huge", "'huge' is not one of ['quick', 'paper']"),
    (("material", "nu"), 0.7, "0.7 is greater than the maximum of 0.5"),
    (("studies", "validation", "quick", "grid", "n"), [64, 12], "12 is less than the minimum of 16"),
    (("studies", "fig6a_interlocking", "quick", "grid", "nu"), [0.3, 0.6], "0.6 is greater than the maximum of 0.5"),
    (("studies", "fig5_friction_area", "quick", "grid", "scaled_pressure"), [1.0, 0], "0 is less than or equal to"),
])
def test_bad_config_is_rejected_with_a_clear_message(workdir, path, value, message):
    config = yaml.safe_load(TINY.read_text())
    node = config
    for key in path[:-1]:
        node = node[key]
    node[path[-1]] = value
    bad = workdir / "bad.yaml"
    bad.write_text(yaml.safe_dump(config))
    out = snakemake(workdir, "-n", "--configfile", "bad.yaml")
    assert out.returncode != 0
    assert message in out.stdout + out.stderr


def test_tiny_end_to_end_run_and_report(workdir):
    run = snakemake(workdir, "--cores", "2", "--configfile", "tiny.yaml", timeout=600)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    assert "dashboard" in run.stderr and "ETA" in run.stderr
    # one cluster served every study (dask.shared), and it is gone with the run
    assert "shared LocalCluster 2 workers" in (workdir / "logs" / "dask_cluster.log").read_text()
    study_logs = list((workdir / "logs" / "run_study").glob("*.log"))
    assert len(study_logs) >= 10 and all("dask: scheduler tcp://" in f.read_text() for f in study_logs)
    assert not (workdir / ".snakemake" / "contactlib_dask.json").exists()
    results = workdir / "results"
    with xr.open_dataset(results / "area_load.nc") as ds:
        assert dict(ds.sizes) == {"hurst": 3, "n": 2, "seed": 2, "reduced_pressure": 4}  # 48 points
        assert (ds.status == 0).all()
        for name in list(ds.data_vars) + list(ds.coords):
            assert ds[name].attrs.get("units") and ds[name].attrs.get("long_name"), name
        assert ds.hurst.attrs["long_name"] == "Hurst exponent" and ds.mean_pressure.attrs["units"] == "Pa"
        for key in ("title", "source", "history", "Conventions", "contactlib_version", "git_revision",
                    "date_created", "config"):
            assert ds.attrs[key], key
        assert yaml.safe_load(ds.attrs["config"])["study"]["grid"]["n"] == [32, 64]
        assert 1.5 < float(ds.kappa.mean()) < 3.5
        assert ds.area_error_estimate.dims == ("n",) and float(ds.area_error_estimate.sel(n=64)) < 0.1
    with xr.open_dataset(results / "validation.nc") as ds:
        ratio = ds.hertz_peak_pressure / ds.hertz_peak_pressure_exact
        assert float(abs(ratio.sel(n=64) - 1).max()) < 0.05
    with xr.open_dataset(results / "surfaces" / "anisotropy.nc") as ds:
        assert ds.height.dims == ("anisotropy", "seed", "y", "x") and ds.height.attrs["units"] == "m"
    with xr.open_dataset(results / "speed_vs_error.nc") as ds:
        assert dict(ds.sizes) == {"scene": 4, "n": 2, "tol": 2, "kernel": 2}
        assert (ds.status == 0).all()
        for name in list(ds.data_vars) + list(ds.coords):
            assert ds[name].attrs.get("units") and ds[name].attrs.get("long_name"), name
        assert (ds.solve_time > 0).all() and (ds.max_error.sel(scene="rough") > 0).all()
        assert float(ds.pressure_error.sel(scene="wavy_2d", kernel="spectral").max()) < 1e-12  # exact: one mode
        hertz = ds.load_error.sel(scene="hertz", tol=1e-10, kernel="spectral")  # first order: halves
        assert 0.4 < float(hertz.sel(n=64) / hertz.sel(n=32)) < 0.8
    with xr.open_dataset(results / "fig5_friction_area.nc") as ds:
        assert dict(ds.sizes) == {"friction": 2, "scaled_layer_thickness": 2, "scaled_pressure": 2, "seed": 1}
        assert (ds.status == 0).all() and (ds.coupled == 1).all()
        for name in list(ds.data_vars) + list(ds.coords):
            assert ds[name].attrs.get("units") and ds[name].attrs.get("long_name"), name
        # a0 is the same solve whatever mu_c; a thick layer (q0 h = 5) barely couples: a = a0
        assert float(ds.frictionless_contact_area.std("friction").max()) == 0.0
        assert float(abs(ds.area_ratio.sel(scaled_layer_thickness=5.0) - 1).max()) < 0.01
        assert (ds.peak_height > 1.5 * ds.rms_height).all() and float(abs(ds.rms_slope - 0.13).max()) < 1e-12
    with xr.open_dataset(results / "fig6a_interlocking.nc") as ds:
        assert dict(ds.sizes) == {"nu": 2, "scaled_pressure": 2, "seed": 1} and (ds.status == 0).all()
        assert ds.nu.attrs["long_name"] == "Poisson ratio of the layer" and "nu" not in ds.attrs
        assert (ds.interlocking_ratio.sel(nu=0.5) > 0).all()  # geometric coupling alone resists sliding
    with xr.open_dataset(results / "fig6b_viscoelastic_layer.nc") as ds:
        assert (ds.status == 0).all() and ds.zeta.attrs["long_name"] == "dimensionless sliding speed V tau q0"
        mu = ds.interlocking_over_slope.sel(seed=0)
        assert float(mu.sel(friction=0.8, zeta=1000.0)) > 10 * abs(float(mu.sel(friction=0.0, zeta=1000.0)))
        assert float(mu.sel(friction=0.0, zeta=1e-2)) > 5 * float(mu.sel(friction=0.0, zeta=1000.0))
    with xr.open_dataset(results / "friction_speed.nc") as ds:
        assert (ds.status == 0).all() and (ds.viscoelastic_model.sel(zeta=0.1) == 1).all()
        area = ds.contact_area.isel(seed=0, glassy_ratio=0)
        assert float(area.sel(zeta=1e-3)) > float(area.sel(zeta=1000.0))  # relaxed to glassy
    with xr.open_dataset(results / "fig2_viscoelastic_map.nc") as ds:
        assert ds.pressure.dims == ("seed", "y", "x") and ds.pressure.attrs["units"] == "Pa"
        assert float(ds.contact_area.isel(seed=0)) < float(ds.contact_area_at_rest.isel(seed=0))
    with xr.open_dataset(results / "two_scale.nc") as ds:
        assert dict(ds.sizes) == {"count": 2, "coverage": 1, "seed": 1} and (ds.status == 0).all()
        for name in list(ds.data_vars) + list(ds.coords):
            assert ds[name].attrs.get("units") and ds[name].attrs.get("long_name"), name
        assert float(ds.two_scale_asperity_force_error.max()) < 1e-2 and (ds.macro_time > 0).all()
        assert float(ds.residual.max()) <= 1e-8  # the reference solve's (it was left NaN)
    with xr.open_dataset(results / "two_scale_transient.nc") as ds:
        assert (ds.status == 0).all() and ds.two_scale_creep_force_error.dims == (
            "count", "coverage", "glassy_ratio", "seed", "time")
        assert float(ds.residual.max()) <= 1e-8  # the reference's largest step residual (it was left NaN)
        for name in list(ds.data_vars) + list(ds.coords):
            assert ds[name].attrs.get("units") and ds[name].attrs.get("long_name"), name
        # the body creeps (the approach grows) and the two-scale steps follow the full solver's within 1 %
        growth = ds.reference_creep_penetration.isel(time=-1) / ds.reference_creep_penetration.isel(time=0)
        assert float(growth.min()) > 1.1 and float(ds.two_scale_creep_force_error.max()) < 1e-2
        assert float(ds.macro_creep_force_error.max()) < 5e-2 and (ds.macro_creep_time > 0).all()
    with xr.open_dataset(results / "fig4_adhesive_layers.nc") as ds:
        assert (ds.status == 0).all() and ds.scaled_penetration.attrs["long_name"] == "penetration Delta / Lambda"
        assert float(ds.residual.max()) == 0.0  # JKR's energy balance: each state exact (it was left NaN)
        one = ds.isel(scaled_penetration=0, branch=0)
        # the paper's trends: a thin confined layer pulls off harder; a thin remote-pressure layer holds no
        # partial contact under a compressive load (jumps to full contact), a thick one does
        pull = one.scaled_load_pull_off_pressure.sel(layer_base="confined")
        assert float(pull.sel(scaled_layer_thickness=1.0)) < float(pull.sel(scaled_layer_thickness=8.0)) < 0
        jump = one.jump_to_full_contact.sel(layer_base="remote_pressure")
        assert int(jump.sel(scaled_layer_thickness=1.0)) == 1 and int(jump.sel(scaled_layer_thickness=8.0)) == 0
    with xr.open_dataset(results / "adhesive_rough.nc") as ds:
        assert dict(ds.sizes) == {"rms_slope": 2, "work": 2, "seed": 1, "penetration_over_rms": 3, "branch": 2}
        assert (ds.status == 0).all() and (ds.converged == 1).all()
        assert float(ds.residual.max()) <= 1e-6  # each state's own (it was left NaN)
        for name in list(ds.data_vars) + list(ds.coords):
            assert ds[name].attrs.get("units") and ds[name].attrs.get("long_name"), name
        pull = ds.reduced_pull_off_pressure.isel(penetration_over_rms=0, branch=0, seed=0)
        # heights x 2, w x 4 (the range follows sqrt(w)) is the same scene in units of E* g: the same pull-off
        assert float(pull.sel(rms_slope=0.05, work=5e-5)) == pytest.approx(float(pull.sel(rms_slope=0.1, work=2e-4)),
                                                                           rel=1e-4)
        assert float(pull.sel(rms_slope=0.1, work=2e-4)) < float(pull.sel(rms_slope=0.1, work=5e-5)) < 0
    with xr.open_dataset(results / "viscoelastic_transient.nc") as ds:
        assert (ds.status == 0).all() and ds.creep_contact_area.dims == ("glassy_ratio", "seed", "time")
        creep = ds.creep_contact_area.isel(glassy_ratio=0, seed=0)
        # from the glassy to the relaxed elastic level; relaxation at fixed penetration ends at the load
        assert float(creep.isel(time=0)) == float(ds.glassy_contact_area.isel(glassy_ratio=0, seed=0))
        assert float(creep.isel(time=-1)) == pytest.approx(float(ds.relaxed_contact_area.isel(glassy_ratio=0, seed=0)),
                                                           rel=0.05)
        relaxed = ds.relaxation_mean_pressure.isel(time=-1) / ds.step_mean_pressure
        assert float(abs(relaxed - 1).max()) < 1e-3
    with xr.open_dataset(results / "reciprocating.nc") as ds:
        assert (ds.status == 0).all() and ds.loop_friction.dims == ("frequency", "seed", "phase")
        energy = ds.dissipated_energy_per_cycle.isel(seed=0)
        assert float(energy.sel(frequency=1e-2)) > float(energy.sel(frequency=1e-3))
        balance = (ds.friction_work_per_cycle / ds.dissipated_energy_per_cycle - 1).where(ds.settled == 1)
        assert float(abs(balance).max()) < 0.1 and int(ds.settled.sum()) >= 2  # 6 % at 32 steps per cycle
        for name in list(ds.data_vars) + list(ds.coords):
            assert ds[name].attrs.get("units") and ds[name].attrs.get("long_name"), name
    table = (results / "speed_vs_error_table.md").read_text()
    assert "| 1.00% | wavy_2d |" in table and "Convergence orders" in table
    for study in ("validation", "area_load", "anisotropy", "speed_vs_error", "fig5_friction_area",
                  "fig6a_interlocking", "fig2_viscoelastic_map", "fig3_anisotropy_polar", "fig6b_viscoelastic_layer",
                  "friction_speed", "two_scale", "fig4_adhesive_layers", "adhesive_rough", "viscoelastic_transient",
                  "reciprocating", "two_scale_transient"):
        assert (results / "figures" / f"{study}.png").stat().st_size > 10_000
    assert not list(results.glob(".*.tmp"))
    report = snakemake(workdir, "--configfile", "tiny.yaml", "--report", "results/report.html", timeout=300)
    assert report.returncode == 0, report.stderr[-3000:]
    assert (results / "report.html").stat().st_size > 10_000


def test_measured_surface_study_end_to_end(workdir):
    """The study of measured files on a text matrix the workflow writes itself; none by default."""
    default = snakemake(workdir, "-n")
    assert default.returncode == 0 and "run_measured_study" not in default.stdout  # empty list: no jobs
    target = "results/figures/measured_area_load/demo.png"
    run = snakemake(workdir, "--cores", "2", target, "--configfile", "workflow/config.measured.yaml", timeout=300)
    assert run.returncode == 0, run.stdout[-3000:] + run.stderr[-3000:]
    results = workdir / "results"
    source = results / "example_topographies" / "demo.txt"
    surface = contactlib.surfaces.read(source, length=100.0, unit="um", periodic=True, detrend="mean")
    with xr.open_dataset(results / "surfaces" / "measured_area_load" / "demo.nc") as s:
        assert s.height.values.tobytes() == surface.values.tobytes()  # read once, the same bits
    with xr.open_dataset(results / "measured_area_load" / "demo.nc") as ds:
        assert dict(ds.sizes) == {"reduced_pressure": 4} and (ds.status == 0).all()
        for name in list(ds.data_vars) + list(ds.coords):
            assert ds[name].attrs.get("units") and ds[name].attrs.get("long_name"), name
        assert ds.attrs["source_file"] == "demo.txt" and ds.attrs["source_format"] == "matrix"
        assert ds.attrs["source_sha256"] == hashlib.sha256(source.read_bytes()).hexdigest()
        assert ds.attrs["detrend"] == "mean" and ds.attrs["height_unit"] == "um" and ds.attrs["periodic"] == 1
        assert yaml.safe_load(ds.attrs["length"]) == [1e-4, 1e-4] and ds.attrs["fill"] == "none"
        # the rms slope the loads are scaled by is the surface's; kappa as for the synthetic area_load study
        assert float(abs(ds.rms_slope - contactlib.analysis.rms_slope(surface)).max()) == 0.0
        assert 1.5 < float(ds.kappa.mean()) < 3.5
    assert (workdir / target).stat().st_size > 10_000
    bad = yaml.safe_load((workdir / "workflow" / "config.measured.yaml").read_text())
    bad["studies"]["measured_area_load"]["surfaces"][0]["unit"] = "furlong"
    (workdir / "bad_measured.yaml").write_text(yaml.safe_dump(bad))
    out = snakemake(workdir, "-n", target, "--configfile", "bad_measured.yaml")
    assert out.returncode != 0 and "'furlong' is not one of" in out.stdout + out.stderr
