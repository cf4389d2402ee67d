"""Axis order of the labelled fields (issue 40): every 2D field contactlib returns is on ``("y", "x")``, so that
xarray's ``.plot()`` draws x horizontally; every entry point reads a DataArray's ``x`` and ``y`` by name (either
order gives the same answer, bit for bit); a bare array is indexed ``[ix, iy]``."""

import math

import matplotlib
import numpy as np
import pytest
import xarray as xr

import contactlib
from contactlib import analysis

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

pytestmark = pytest.mark.filterwarnings("ignore::contactlib.ResolutionWarning")

E, NU = 1.0, 0.5
SLIDING = contactlib.Viscoelastic(E0=1.0, prony=[(9.0, 1.0)], nu=0.5)  # E_inf / E0 = 10, tau = 1


def rough(n=32, **kw):
    return contactlib.surfaces.self_affine(n, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, seed=3, **kw)


def horizontal_label(field: xr.DataArray) -> str:
    """The horizontal axis label of ``field.plot()`` (a 2D field: a pcolormesh)."""
    fig = plt.figure()
    try:
        return field.plot().axes.get_xlabel()
    finally:
        plt.close(fig)


def assert_fields_on_y_x(ds: xr.Dataset, expected: set) -> None:
    """Every field of ``ds`` with both x and y is on (..., "y", "x"), ``expected`` among them, and plots x
    horizontally (a time series: its last saved field)."""
    fields = {name for name, v in ds.data_vars.items() if "x" in v.dims and "y" in v.dims}
    assert expected <= fields, sorted(fields)
    for name in fields:
        assert ds[name].dims[-2:] == ("y", "x"), (name, ds[name].dims)
        field = ds[name].isel({d: -1 for d in ds[name].dims[:-2]})
        assert horizontal_label(field).startswith("position along x"), name


# --- (a) every public entry point that returns a 2D field -----------------------------------------------------------

def _path(h):
    return contactlib.solve_speeds(h, [(0.5, 0.0), (1.0, 0.0)], material=SLIDING, mean_pressure=0.02)[-1]


ENTRY_POINTS = {
    "solve": (lambda h: contactlib.solve(h, E=E, nu=NU, mean_pressure=0.02), {"pressure", "gap", "displacement"}),
    "prepare(...).solve": (lambda h: contactlib.prepare(h, E=E, nu=NU).solve(contact_area=0.2), {"pressure"}),
    "solve with friction": (lambda h: contactlib.solve(h, E=E, nu=0.3, mean_pressure=0.02, friction=0.3,
                                                       sliding_direction=0.5),
                            {"pressure", "tangential_traction_x", "tangential_traction_y",
                             "tangential_displacement_x", "tangential_displacement_y"}),
    "solve sliding": (lambda h: contactlib.solve(h, material=SLIDING, mean_pressure=0.02, sliding_velocity=(1.0, 0.0)),
                      {"pressure", "gap", "displacement"}),
    "solve adhesive": (lambda h: contactlib.solve(h, E=E, nu=NU, mean_pressure=0.02,
                                                  adhesion=contactlib.Adhesion(work=1e-4, range=6e-3)),
                       {"pressure", "adhesive_pressure"}),
    "solve_tolerances": (lambda h: contactlib.solve_tolerances(h, [1e-4, 1e-8], E=E, nu=NU, mean_pressure=0.02)[0],
                         {"pressure"}),
    "solve_speeds": (_path, {"pressure"}),
    "solve_transient": (lambda h: contactlib.solve_transient(h, times=[0.0, 0.5], material=SLIDING, mean_pressure=0.02,
                                                             save_fields=True), {"pressure", "gap", "displacement"}),
}


@pytest.mark.parametrize("entry", list(ENTRY_POINTS))
def test_solvers_return_fields_on_y_x_and_plot_x_horizontally(entry):
    solve, expected = ENTRY_POINTS[entry]
    assert_fields_on_y_x(solve(rough()), expected)


def test_two_scale_fields_on_y_x():
    field = contactlib.two_scale.random_asperity_field(9, coverage=0.3, nodes_per_spacing=12, seed=0)
    assert field.dims == ("y", "x") and horizontal_label(field).startswith("position along x")
    out = contactlib.two_scale.solve(field, E=E, nu=NU, mean_pressure=1e-4)
    assert_fields_on_y_x(out, {"pressure", "gap", "displacement"})


def test_surfaces_on_y_x_and_plot_x_horizontally(tmp_path):
    h = rough()
    h.to_dataset().to_netcdf(tmp_path / "h.nc")
    made = {"self_affine": h, "wavy": contactlib.surfaces.wavy(16, amplitude=0.01, dim=2),
            "paraboloid": contactlib.surfaces.paraboloid(16, radius=1.0),
            "spheres": contactlib.surfaces.spheres(32, radius=0.1, lattice=4, summit_height=0.01),
            "resample": contactlib.surfaces.resample(h, 48),
            "read": contactlib.surfaces.read(tmp_path / "h.nc", detrend="none")}
    for name, surface in made.items():
        assert surface.dims == ("y", "x"), name
        assert horizontal_label(surface).startswith("position along x"), name
    xr.testing.assert_identical(made["read"].transpose("y", "x").drop_attrs(), h.drop_attrs())


# --- (b) a (y, x) DataArray and its (x, y) transpose give the same solve, bit for bit -------------------------------

def _without_times(ds: xr.Dataset) -> xr.Dataset:
    ds = ds.copy()
    ds.attrs.pop("wall_time", None)
    return ds


@pytest.mark.parametrize("scene", [dict(E=E, nu=NU, mean_pressure=0.02),
                                   dict(E=E, nu=0.3, mean_pressure=0.02, friction=0.3, sliding_direction=0.5),
                                   dict(material=SLIDING, mean_pressure=0.02, sliding_velocity=(1.0, 0.5))])
def test_transposed_dataarray_gives_the_same_solve_bit_for_bit(scene):
    h = rough()
    a, b = contactlib.solve(h.transpose("y", "x"), **scene), contactlib.solve(h.transpose("x", "y"), **scene)
    xr.testing.assert_identical(_without_times(a), _without_times(b))


def test_bare_array_is_indexed_x_y_on_a_rectangular_window():
    """A 24 x 16 window 1.5 x 1 long: the bare array [ix, iy] with length=(Lx, Ly) and the (y, x) DataArray give one
    answer, the labelled fields with 24 points along x (a transposed reading would be refused by its shape or
    solve a different surface)."""
    nx, ny, lx, ly = 24, 16, 1.5, 1.0
    x, y = np.arange(nx) * lx / nx, np.arange(ny) * ly / ny
    bare = 0.01 * (np.cos(2 * np.pi * x / lx)[:, None] * (1 + 0.5 * np.cos(2 * np.pi * y / ly))[None, :])
    labelled = xr.DataArray(bare.T, dims=("y", "x"), coords={"x": x, "y": y})
    a = contactlib.solve(bare, length=(lx, ly), E=E, nu=NU, mean_pressure=0.005)
    b = contactlib.solve(labelled, E=E, nu=NU, mean_pressure=0.005)
    assert a.pressure.sizes == {"y": ny, "x": nx} and a.pressure.dims == ("y", "x")
    np.testing.assert_array_equal(a.pressure.values, b.pressure.values)
    np.testing.assert_array_equal(a.x.values, x)
    # the pressure peaks where the heights do: on the crest x = 0, y = 0
    peak = a.pressure.argmax(dim=("x", "y"))
    assert (int(peak["x"]), int(peak["y"])) == (0, 0)


# --- (c) an anisotropic surface: the same answer from the DataArray and from its bare array, sliding along x -------

def test_anisotropic_surface_read_by_name_and_sliding_along_x():
    angle = 0.4  # not symmetric about the diagonal: a swapped reading gives pi/2 - angle
    h = contactlib.surfaces.self_affine(64, hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=3,
                                        anisotropy=0.3, angle=angle, synthesis="random-phase")
    bare = h.transpose("x", "y").values
    assert float(analysis.anisotropy_tensor(h, 0, 32).theta_d) == pytest.approx(angle, abs=0.05)
    assert float(analysis.anisotropy_tensor(bare, 0, 32, length=1.0).theta_d) == pytest.approx(angle, abs=0.05)
    assert float(analysis.anisotropy_tensor(h.values, 0, 32, length=1.0).theta_d) == \
        pytest.approx(math.pi / 2 - angle, abs=0.05)  # the (y, x) values read as [ix, iy]: the mirror image
    for scene in (dict(E=E, nu=NU), dict(material=SLIDING, sliding_velocity=(1.0, 0.0))):
        a = contactlib.solve(h, mean_pressure=0.02, **scene)
        b = contactlib.solve(bare, length=1.0, mean_pressure=0.02, **scene)
        np.testing.assert_array_equal(a.pressure.values, b.pressure.values)
    # sliding along +x: the labelled fields' interlocking friction along x (read by name) is the solver's mu_a
    mu = float(a.friction_coefficient_interlocking)
    along_x = analysis.interlocking_friction(a.pressure, a.displacement, lengths=(1.0, 1.0), direction=0.0)
    along_y = analysis.interlocking_friction(a.pressure, a.displacement, lengths=(1.0, 1.0), direction=math.pi / 2)
    assert mu > 0 and along_x == pytest.approx(mu, rel=1e-9)
    assert abs(along_y) < 0.2 * mu, (along_y, mu)  # 0.07 mu here; the (y, x) values read as [ix, iy]: 0.07 mu


# --- the MPI files: written on (y, x), read by name, older (x, y) files too ----------------------------------------

class OneRank:
    """The communicator calls of :mod:`contactlib.distributed.io` on one rank (no MPI needed for the file layout;
    tests/test_distributed.py runs them on 1-3 ranks under mpirun)."""

    def Get_size(self):
        return 1

    def Get_rank(self):
        return 0

    def allreduce(self, value, op=None):
        return value

    def bcast(self, value, root=0):
        return value

    def Barrier(self):
        pass


def test_slab_files_are_on_y_x_and_read_by_name(tmp_path):
    from contactlib.distributed.io import read_slab, write_slabs

    h = rough(24)
    rows = h.transpose("x", "y").values  # a rank's slab: rows of x
    header = xr.Dataset(coords={d: (d, h[d].values, dict(h[d].attrs)) for d in ("x", "y")})
    write_slabs(OneRank(), tmp_path / "slabs.nc", shape=rows.shape, fields={"height": (rows, dict(h.attrs))},
                header=header)
    with xr.open_dataset(tmp_path / "slabs.nc") as written:
        assert written.height.dims == ("y", "x")
        np.testing.assert_array_equal(written.height.values, h.values)
    h.to_dataset().to_netcdf(tmp_path / "new.nc")
    h.transpose("x", "y").to_dataset().to_netcdf(tmp_path / "old.nc")  # as contactlib wrote them before
    for name in ("slabs.nc", "new.nc", "old.nc"):
        slab = read_slab(OneRank(), tmp_path / name)
        assert slab.dims == ("y", "x"), name
        np.testing.assert_array_equal(slab.values, h.values, err_msg=name)
        xr.testing.assert_equal(contactlib.surfaces.read(tmp_path / name, detrend="none"), slab)
