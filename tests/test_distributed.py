"""The distributed (MPI) contact solver against the serial one: library, FFT, surfaces, command line.

The cases run under ``mpiexec -n 1, 2, 3`` (3 oversubscribed on 2 cores): this file is also the worker script
(run as ``python tests/test_distributed.py OUT.json``), which solves every case on the ranks, the serial
reference on rank 0, and writes what the tests assert. Skipped where the ``mpi`` extra is not installed.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

try:
    import mpi4py  # noqa: F401

    HAVE_MPI = shutil.which("mpiexec") is not None
except ImportError:
    HAVE_MPI = False

# Open MPI refuses to run as root (containers, CI) without these; harmless otherwise
MPI_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "OMPI_MCA_rmaps_base_oversubscribe": "1", "OMP_NUM_THREADS": "1"}
ROOT = Path(__file__).resolve().parents[1]

SHAPES = [(64, 64), (65, 64)]  # an odd number of rows, not divisible by 2 or 3
LOADS = ["mean_pressure", "penetration"]


def _scene(shape, periodic):
    """Heights [m] and window [m]: a periodic rough surface, or a rough bump well inside its window."""
    import contactlib

    rough = contactlib.surfaces.self_affine(80, hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=1)
    rough = rough.transpose("x", "y").values[: shape[0], : shape[1]]  # rows of x, as slab_of splits them
    lengths = (shape[0] / 64, shape[1] / 64)
    if periodic:
        return rough, lengths
    x = (np.arange(shape[0]) - shape[0] / 2) / 64
    y = (np.arange(shape[1]) - shape[1] / 2) / 64
    return -5 * (x[:, None] ** 2 + y[None, :] ** 2) + 1e-3 * rough, lengths


def _load(kind, periodic, heights):
    if kind == "mean_pressure":
        return {"mean_pressure": 0.05 if periodic else 0.01}
    return {"penetration": 0.3 * float(heights.std()) if periodic else 0.01}


def _worker(out_path: str) -> None:
    """Every library case on the ranks of COMM_WORLD; rank 0 compares with the serial solver and writes JSON."""
    from mpi4py import MPI

    import contactlib
    from contactlib.distributed import solve
    from contactlib.distributed.fft import irfft2, rfft2
    from contactlib.distributed.slabs import Slabs, gather_field, slab_of
    from contactlib.distributed.surfaces import self_affine_slab

    import warnings

    warnings.filterwarnings("ignore", category=contactlib.ResolutionWarning)  # small grids on purpose
    comm = MPI.COMM_WORLD
    results = {"solve": [], "fft": [], "surface": [], "errors": {}}
    for shape in SHAPES:
        for periodic in (True, False):
            heights, lengths = _scene(shape, periodic)
            for kind in LOADS:
                load = _load(kind, periodic, heights)
                state = solve(slab_of(heights, comm), comm=comm, E=1.0, nu=0.3, length=lengths, periodic=periodic,
                              tol=1e-10, **load)
                pressure = gather_field(state.pressure, comm)
                gap = gather_field(state.gap, comm)
                if comm.rank == 0:
                    ref = contactlib.solve(heights, E=1.0, nu=0.3, length=lengths, periodic=periodic, tol=1e-10,
                                           **load)
                    p_ref = ref.pressure.transpose("x", "y").values  # rows of x, as the slabs gathered
                    g_ref = ref.gap.transpose("x", "y").values
                    results["solve"].append({
                        "case": f"{shape} periodic={periodic} {kind}",
                        "pressure_error": float(np.abs(pressure - p_ref).max() / p_ref.max()),
                        "gap_error": float(np.abs(gap - g_ref).max() / np.abs(g_ref).max()),
                        "same_contact_set": bool(np.array_equal(pressure > 0, p_ref > 0)),
                        "area": state.contact_area, "area_serial": float(ref.contact_area),
                        "mean_pressure": state.mean_pressure, "mean_pressure_serial": float(ref.mean_pressure),
                        "penetration": state.penetration, "penetration_serial": float(ref.penetration),
                        "iterations": state.iterations, "iterations_serial": int(ref.iterations),
                        "residual": state.residual, "converged": state.converged})
    # layers (periodic, frictionless): confined, remote-pressure (displacement control through the dual), and one
    # thick enough to be solved as the half-space with its uniform compression
    heights, lengths = _scene((65, 64), True)
    results["layers"] = []
    for thickness, base in [(0.1, "confined"), (0.5, "remote_pressure"), (50.0, "confined")]:
        layer = contactlib.Layer(thickness, base)
        for kind in LOADS:
            load = _load(kind, True, heights)
            state = solve(slab_of(heights, comm), comm=comm, E=1.0, nu=0.3, length=lengths, tol=1e-10, layer=layer,
                          **load)
            pressure = gather_field(state.pressure, comm)
            if comm.rank == 0:
                ref = contactlib.solve(heights, E=1.0, nu=0.3, length=lengths, tol=1e-10, layer=layer, **load)
                p_ref = ref.pressure.transpose("x", "y").values
                results["layers"].append({
                    "case": f"{layer} {kind} ({ref.attrs['model']})",
                    "pressure_error": float(np.abs(pressure - p_ref).max() / p_ref.max()),
                    "same_contact_set": bool(np.array_equal(pressure > 0, p_ref > 0)),
                    "penetration": state.penetration, "penetration_serial": float(ref.penetration),
                    "area": state.contact_area, "area_serial": float(ref.contact_area)})
    # a surface given by its generator's arguments: each rank makes its own rows
    spec = dict(n=64, hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=4)
    state = solve(spec, comm=comm, E=1.0, nu=0.3, mean_pressure=0.05, tol=1e-10)
    pressure = gather_field(state.pressure, comm)
    if comm.rank == 0:
        ref = contactlib.solve(contactlib.surfaces.self_affine(**spec), E=1.0, nu=0.3, mean_pressure=0.05, tol=1e-10)
        p_ref = ref.pressure.transpose("x", "y").values
        results["spec"] = {"pressure_error": float(np.abs(pressure - p_ref).max() / p_ref.max()),
                           "same_contact_set": bool(np.array_equal(pressure > 0, p_ref > 0))}
    # contactlib.solve(rows, ..., comm=): each rank its rows, labelled as the serial answer
    heights, lengths = _scene((65, 64), False)
    ds = contactlib.solve(slab_of(heights, comm), comm=comm, E=1.0, nu=0.3, length=lengths, periodic=False,
                          mean_pressure=0.01, tol=1e-10)
    pressure = gather_field(ds.pressure.transpose("x", "y").values, comm)  # rows of x
    x = np.concatenate(comm.allgather(ds.x.values))
    if comm.rank == 0:
        ref = contactlib.solve(heights, E=1.0, nu=0.3, length=lengths, periodic=False, mean_pressure=0.01, tol=1e-10)
        p_ref = ref.pressure.transpose("x", "y").values
        names = ("contact_area", "mean_pressure", "penetration", "mean_gap", "normal_force", "contact_radius")
        results["facade"] = {
            "pressure_error": float(np.abs(pressure - p_ref).max() / p_ref.max()),
            "same_contact_set": bool(np.array_equal(pressure > 0, p_ref > 0)),
            "scalars": {name: [float(ds[name]), float(ref[name])] for name in names},
            "invariants": [ds.attrs.get("invariants_checked"), ref.attrs.get("invariants_checked")],
            "rows": len(x), "x_steps": float(np.ptp(np.diff(x))), "dims": list(ds.pressure.dims),
            "labels_match": all(ds[v].attrs == ref[v].attrs for v in ("pressure", "gap", "displacement", *names))}
    for shape in [(63, 47), (65, 64)]:
        field = np.random.default_rng(2).standard_normal(shape)
        for padded in (False, True):
            spectrum = rfft2(comm, slab_of(field, comm), shape, padded=padded)
            back = irfft2(comm, spectrum, shape, padded=padded)
            reference = np.fft.rfft2(field, s=tuple(2 * n for n in shape) if padded else shape)
            columns = Slabs(reference.shape[1], comm.size).slice(comm.rank)
            error = float(np.abs(spectrum - reference[:, columns]).max() / np.abs(reference).max())
            error = comm.allreduce(error, op=MPI.MAX)
            round_trip = comm.allreduce(float(np.abs(back - slab_of(field, comm)).max()), op=MPI.MAX)
            results["fft"].append({"case": f"{shape} padded={padded}", "error": error, "round_trip": round_trip})
    for spec in [dict(n=64, hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=1),
                 dict(n=65, hurst=0.5, q_roll=4, q_cutoff=30, rms_height=1e-6, seed=7, length=2e-3),
                 dict(n=63, hurst=0.7, q_roll=1, q_cutoff=31, rms_slope=0.2, seed=3, anisotropy=0.5, angle=0.3,
                      synthesis="random-phase")]:
        local = self_affine_slab(comm, **spec)
        whole = gather_field(local.transpose("x", "y").values, comm)
        if comm.rank == 0:
            ref = contactlib.surfaces.self_affine(**spec)
            rows = ref.transpose("x", "y").values
            results["surface"].append({"case": str(spec), "identical": bool(np.array_equal(whole, rows)),
                                       "max_difference": float(np.abs(whole - rows).max()),
                                       "same_attrs": local.attrs == ref.attrs,
                                       "dims": [list(local.dims), list(ref.dims)]})
    # the normalisation's sums: numpy's rounding, bit for bit, where a plain sum of the ranks' sums is not
    from contactlib.distributed.reduce import pairwise_sum

    results["sums"] = []
    for shape in [(63, 64), (65, 47), (1031, 7), (3, 5)]:
        values = np.random.default_rng(3).standard_normal(shape) * 10 ** np.random.default_rng(4).uniform(-3, 3, shape)
        start, stop = Slabs(shape[0], comm.size).bounds(comm.rank)
        exact = pairwise_sum(comm, values[start:stop], start * shape[1], values.size)
        naive = comm.allreduce(float(np.sum(values[start:stop])))
        results["sums"].append({"shape": shape, "exact": exact == float(np.sum(values)),
                                "naive_differs": naive != float(np.sum(values))})
    # refusals and failures, named
    heights, lengths = _scene((64, 64), True)
    wrong = heights[: 3 + comm.rank]  # rows that are not this rank's slab
    for name, call in {
        "rows": lambda: solve(wrong, comm=comm, E=1.0, nu=0.3, length=lengths, mean_pressure=0.05),
        "length": lambda: solve(slab_of(heights, comm), comm=comm, E=1.0, nu=0.3, mean_pressure=0.05),
        "both_loads": lambda: solve(slab_of(heights, comm), comm=comm, E=1.0, nu=0.3, length=lengths,
                                    mean_pressure=0.05, penetration=0.01),
        "edge": lambda: solve(slab_of(heights, comm), comm=comm, E=1.0, nu=0.3, length=lengths, periodic=False,
                              mean_pressure=0.05),
        "plate": lambda: solve(slab_of(heights, comm), comm=comm, E=1.0, nu=0.3, length=lengths, mean_pressure=0.05,
                               layer=contactlib.Layer(0.01, "remote_pressure")),
        "max_iter": lambda: solve(slab_of(heights, comm), comm=comm, E=1.0, nu=0.3, length=lengths,
                                  mean_pressure=0.05, max_iter=2),
        "facade_friction": lambda: contactlib.solve(slab_of(heights, comm), comm=comm, E=1.0, nu=0.3, length=lengths,
                                                    mean_pressure=0.05, friction=0.3),
    }.items():
        try:
            call()
            results["errors"][name] = "none"
        except contactlib.ConvergenceError as err:
            state = getattr(err, "state", None)
            results["errors"][name] = (f"ConvergenceError residual={err.residual:.3e} "
                                       f"iterations={state.iterations if state else None}")
        except ValueError as err:
            results["errors"][name] = f"ValueError: {err}"
    if comm.rank == 0:
        Path(out_path).write_text(json.dumps(results))


def _mpiexec(ranks: int, *command: str, timeout: int = 300) -> subprocess.CompletedProcess:
    env = {**os.environ, **MPI_ENV, "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT),
                                                                                  os.environ.get("PYTHONPATH")]))}
    flags = ["--oversubscribe"] if ranks > (os.cpu_count() or 1) else []
    return subprocess.run(["mpiexec", "-n", str(ranks), *flags, *command], env=env, capture_output=True, text=True,
                          timeout=timeout)


pytestmark = pytest.mark.skipif(not HAVE_MPI, reason="the mpi extra (mpi4py and an mpiexec) is not installed: "
                                                     "pip install 'contactlib[mpi]'")


@pytest.fixture(scope="module", params=[1, 2, 3])
def run(request, tmp_path_factory):
    out = tmp_path_factory.mktemp(f"ranks{request.param}") / "results.json"
    done = _mpiexec(request.param, sys.executable, __file__, str(out))
    assert done.returncode == 0, done.stderr[-3000:]
    return request.param, json.loads(out.read_text())


def test_solve_matches_serial(run):
    """Pressure within 1e-10 of its peak, the same contact set and area, periodic and not, load and displacement
    control, 64 and 65 rows, on 1, 2 and 3 ranks."""
    ranks, results = run
    assert len(results["solve"]) == len(SHAPES) * 2 * len(LOADS)
    for case in results["solve"]:
        assert case["converged"], case
        assert case["pressure_error"] < 1e-10, case
        assert case["gap_error"] < 1e-10, case
        assert case["same_contact_set"], case
        assert case["area"] == case["area_serial"] and 0 < case["area"] < 1, case
        assert abs(case["mean_pressure"] - case["mean_pressure_serial"]) <= 1e-10 * case["mean_pressure_serial"], case
        assert abs(case["penetration"] - case["penetration_serial"]) <= 1e-10 * abs(case["penetration_serial"]), case
        assert abs(case["iterations"] - case["iterations_serial"]) <= 1, case


def test_layers_match_serial(run):
    """A periodic frictionless layer: confined, remote-pressure, and one reduced to the half-space, under load and
    displacement control, as the serial solver (pressure within 1e-10 of its peak, same contact set and area)."""
    ranks, results = run
    assert len(results["layers"]) == 6
    for case in results["layers"]:
        assert case["pressure_error"] < 1e-10 and case["same_contact_set"], case
        assert case["area"] == case["area_serial"], case
        assert abs(case["penetration"] - case["penetration_serial"]) <= 1e-10 * abs(case["penetration_serial"]), case


def test_solve_from_surface_arguments(run):
    """Heights given as the generator's arguments: each rank generates its rows; the serial answer on that surface."""
    ranks, results = run
    assert results["spec"]["pressure_error"] < 1e-10 and results["spec"]["same_contact_set"], results["spec"]


def test_slab_split():
    """Rows split with at most one row of imbalance, in order, covering the grid; too few rows refused."""
    from contactlib.distributed.slabs import Slabs

    for n, size in [(65, 2), (65, 3), (7, 7), (4096, 6)]:
        split = Slabs(n, size)
        assert split.counts.sum() == n and split.counts.max() - split.counts.min() <= 1
        assert [split.bounds(r)[0] for r in range(size)] == list(split.starts)
        assert split.bounds(size - 1)[1] == n
    with pytest.raises(ValueError, match="rows cannot be split"):
        Slabs(2, 3)


def test_fft_matches_numpy(run):
    """The slab FFT equals numpy's rfft2 to round-off on odd grids, zero-padded or not, and inverts."""
    ranks, results = run
    for case in results["fft"]:
        assert case["error"] < 1e-14 and case["round_trip"] < 1e-13, case


def test_surface_bit_for_bit(run):
    """Each rank's slab of a self-affine surface is the serial generator's, bit for bit, attributes included."""
    ranks, results = run
    for case in results["surface"]:
        assert case["identical"] and case["max_difference"] == 0.0 and case["same_attrs"], case
        assert case["dims"] == [["y", "x"], ["y", "x"]], case  # a rank's rows of x, labelled as the serial surface


def test_sums_round_as_numpy(run):
    """The distributed pairwise sum equals numpy's sum of the whole array bit for bit (on more than one rank, a
    plain sum of the ranks' sums does not, on some of these arrays: the test can tell them apart)."""
    ranks, results = run
    assert all(case["exact"] for case in results["sums"]), results["sums"]
    if ranks > 1:
        assert any(case["naive_differs"] for case in results["sums"]), results["sums"]


def test_refusals_and_nonconvergence(run):
    """Bad input raises ValueError naming the parameter; too few iterations raise ConvergenceError with the residual."""
    ranks, errors = run[0], run[1]["errors"]
    assert errors["length"].startswith("ValueError: length"), errors
    assert "mean_pressure or penetration" in errors["both_loads"], errors
    assert "edge of the window" in errors["edge"], errors
    assert errors["plate"].startswith("ValueError: layer: a plate-like layer"), errors
    assert errors["max_iter"].startswith("ConvergenceError residual=") and "iterations=2" in errors["max_iter"], errors
    if ranks > 1:  # on one rank every array is that rank's slab
        assert errors["rows"].startswith("ValueError: heights"), errors


def test_cli_files_match_serial(tmp_path):
    """``mpirun -n 2 contactlib surface|solve`` write the serial commands' files: the surface bit for bit, the
    solution's pressure within 1e-10 of its peak with the same contact set and area."""
    import xarray as xr

    surface = ["surface", "--n", "64", "--hurst", "0.8", "--q-roll", "2", "--q-cutoff", "16", "--rms-slope", "0.1",
               "--seed", "5"]
    cli = [sys.executable, "-m", "contactlib.cli"]
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")]))}
    serial = subprocess.run([*cli, *surface, "-o", str(tmp_path / "s1.nc")], env=env, capture_output=True, text=True)
    assert serial.returncode == 0, serial.stderr
    done = _mpiexec(2, *cli, *surface, "-o", str(tmp_path / "s2.nc"))
    assert done.returncode == 0, done.stderr[-3000:]
    with xr.open_dataset(tmp_path / "s1.nc") as a, xr.open_dataset(tmp_path / "s2.nc") as b:
        assert a.height.dims == b.height.dims == ("y", "x")  # a rank's rows of x are a column block of the file
        assert np.array_equal(a.height.values, b.height.values)
        for ds in (a, b):
            ds.height.attrs.pop("command")  # the command lines differ by the output's name
        xr.testing.assert_identical(a, b)
    solve = ["solve", str(tmp_path / "s1.nc"), "--E", "1", "--nu", "0.3", "--mean-pressure", "0.05", "--tol", "1e-10"]
    serial = subprocess.run([*cli, *solve, "-o", str(tmp_path / "o1.nc")], env=env, capture_output=True, text=True)
    assert serial.returncode == 0, serial.stderr
    done = _mpiexec(2, *cli, *solve, "-o", str(tmp_path / "o2.nc"))
    assert done.returncode == 0, done.stderr[-3000:]
    assert "iteration 0: residual" in done.stderr  # progress, logged once (rank 0)
    assert done.stdout.count("contact_area=") == 1 and serial.stdout.split()[0] == done.stdout.split()[0]
    with xr.open_dataset(tmp_path / "o1.nc") as a, xr.open_dataset(tmp_path / "o2.nc") as b:
        assert list(a.data_vars) == list(b.data_vars) and list(a.coords) == list(b.coords)
        assert a.pressure.dims == b.pressure.dims == ("y", "x")
        p, q = a.pressure.values, b.pressure.values
        assert np.abs(p - q).max() < 1e-10 * p.max()
        assert np.array_equal(p > 0, q > 0) and float(a.contact_area) == float(b.contact_area)
        for name in a.variables:
            assert a[name].attrs == b[name].attrs and a[name].dtype == b[name].dtype, name
        # the invariants are checked over the ranks; the resolution rule is not measured distributed
        serial_only = {"points_per_wavelength", "points_per_contact_radius",
                       "predicted_resolution_error", "resolution_rule"}
        assert set(a.attrs) - set(b.attrs) == serial_only and set(b.attrs) - set(a.attrs) == {"distributed_ranks"}
        for key in set(a.attrs) & set(b.attrs) - {"wall_time"}:
            assert str(a.attrs[key]) == str(b.attrs[key]), key


def test_serial_path_never_imports_mpi4py():
    """Without mpirun, ``contactlib.solve`` and the command line never import mpi4py."""
    code = ("import sys, contactlib, contactlib.cli\n"
            "h = contactlib.surfaces.self_affine(32, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, seed=1)\n"
            "contactlib.solve(h, E=1.0, nu=0.3, mean_pressure=0.05)\n"
            "assert 'mpi4py' not in sys.modules, 'mpi4py imported'\n"
            "import contactlib.distributed\n"
            "assert 'mpi4py' not in sys.modules, 'mpi4py imported by contactlib.distributed'\n")
    env = {k: v for k, v in os.environ.items() if k not in ("OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "MPI_LOCALNRANKS")}
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")]))
    done = subprocess.run([sys.executable, "-W", "ignore", "-c", code], env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr[-2000:]


if __name__ == "__main__":
    _worker(sys.argv[1])


def test_solve_with_comm_labels_each_ranks_rows(run):
    """``contactlib.solve(rows, ..., comm=)``: each rank gets its rows of the serial answer (pressure within 1e-10 of
    its peak, the same contact set), labelled as it (units, long names), with the whole grid's scalars and the same
    invariants checked; an option the distributed path does not take is refused by name."""
    ranks, results = run
    case = results["facade"]
    assert case["dims"] == ["y", "x"], case  # this rank's rows of x, labelled on (y, x) as the serial answer
    assert case["pressure_error"] < 1e-10 and case["same_contact_set"], case
    for name, (distributed, serial) in case["scalars"].items():
        assert abs(distributed - serial) <= 1e-10 * abs(serial), (name, distributed, serial)
    assert case["invariants"][0] and case["invariants"][0] == case["invariants"][1], case
    assert case["rows"] == 65 and case["x_steps"] < 1e-12 and case["labels_match"], case
    assert results["errors"]["facade_friction"].startswith("ValueError: friction"), results["errors"]
