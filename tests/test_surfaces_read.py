"""contactlib.surfaces.read: measured topography files in, the generators' labelled DataArray out."""

import hashlib
import sys

import numpy as np
import pytest
import xarray as xr

import contactlib
from contactlib import analysis
from contactlib.surfaces import read

LENGTH = 1e-3  # window [m]; n a power of 2, so length / n and n * spacing are exact in every format
ST_REASON = "SurfaceTopography (contactlib[topography]) is not installed: its formats cannot be read"


@pytest.fixture(scope="module")
def surface():
    return contactlib.surfaces.self_affine(64, length=LENGTH, hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=3)


@pytest.fixture(scope="module")
def profile():
    return contactlib.surfaces.self_affine(128, length=LENGTH, hurst=0.7, q_roll=2, q_cutoff=32, rms_slope=0.1,
                                           seed=4, dim=1)


def bare(h: xr.DataArray) -> np.ndarray:
    """The bare array of a surface, indexed ``[ix, iy]`` (as files without dim names and SurfaceTopography hold
    it): a contactlib surface is on ``("y", "x")``."""
    return h.transpose("x", ...).values


def write_native(h: xr.DataArray, path, fmt: str) -> dict:
    """Write ``h`` [m] in a native format; returns the read() arguments the file does not carry."""
    if fmt == "netcdf":
        h.to_dataset().to_netcdf(path)
        return {}
    if fmt == "npy":  # a bare array is indexed [ix, iy]
        np.save(path, bare(h))
        return {"length": LENGTH, "unit": "m", "periodic": True}
    if fmt == "matrix":  # one row per y, repr precision
        np.savetxt(path, h.transpose("y", "x").values if h.ndim == 2 else h.values[None, :], fmt="%.17g")
        return {"length": LENGTH, "unit": "m", "periodic": True}
    axes = ("x", "y")[: h.ndim]  # columns x (y) z
    columns = [*np.meshgrid(*(h[d].values for d in axes), indexing="ij"), bare(h)]
    np.savetxt(path, np.column_stack([c.ravel() for c in columns]), fmt="%.17g")
    return {"unit": "m", "periodic": True}


def assert_same_surface(read_back: xr.DataArray, h: xr.DataArray) -> None:
    assert read_back.dims == h.dims and read_back.name == "height"
    assert np.array_equal(read_back.values, h.values)  # bit for bit
    for d in h.dims:
        assert np.array_equal(read_back[d].values, h[d].values), d
        assert read_back[d].attrs == {"units": "m", "long_name": h[d].attrs["long_name"]}
    assert read_back.attrs["length"] == [LENGTH] * h.ndim
    assert read_back.attrs["units"] == "m" and read_back.attrs["long_name"] == "rigid surface height"


@pytest.mark.parametrize("dim", [2, 1])
@pytest.mark.parametrize("fmt, suffix", [("netcdf", ".nc"), ("npy", ".npy"), ("matrix", ".txt"), ("xyz", ".xyz")])
def test_native_formats_read_back_bit_identical(tmp_path, surface, profile, fmt, suffix, dim):
    h = surface if dim == 2 else profile
    path = tmp_path / f"surface{suffix}"
    given = write_native(h, path, fmt)
    out = read(path, detrend="none", **given)
    assert_same_surface(out, h)
    assert out.attrs["source_format"] == fmt and out.attrs["source_reader"] == "contactlib"
    assert out.attrs["source_file"] == path.name
    assert out.attrs["source_sha256"] == hashlib.sha256(path.read_bytes()).hexdigest()
    assert out.attrs["periodic"] == 1 and out.attrs["height_unit"] == "m" and out.attrs["fill"] == "none"
    assert out.attrs["length_from"] == ("argument" if "length" in given else "file")
    again = read(path, detrend="none", **given)
    assert again.values.tobytes() == out.values.tobytes()  # same file, same array


def test_read_file_solves_bit_for_bit_as_the_original(tmp_path, surface):
    path = tmp_path / "s.npy"
    write_native(surface, path, "npy")
    measured = read(path, length=LENGTH, unit="m", periodic=True, detrend="none")
    for load in ({"mean_pressure": 0.01}, {"penetration": 2e-6}):
        a, b = contactlib.solve(surface, E=1.0, nu=0.3, **load), contactlib.solve(measured, E=1.0, nu=0.3, **load)
        for name in ("pressure", "gap", "displacement"):
            assert np.array_equal(a[name].values, b[name].values), name
        assert float(a.contact_area) == float(b.contact_area) and int(a.iterations) == int(b.iterations)
    assert analysis.rms_slope(measured) == analysis.rms_slope(surface)  # the analysis functions take it too


def test_a_measurement_is_solved_non_periodic_unless_told(tmp_path):
    sphere = contactlib.surfaces.paraboloid(64, length=LENGTH, radius=5e-3)  # an isolated footprint
    path = tmp_path / "sphere.txt"
    np.savetxt(path, sphere.transpose("y", "x").values, fmt="%.17g")  # one row per y
    measured = read(path, length=LENGTH, unit="m", detrend="none")
    assert measured.attrs["periodic"] == 0
    out = contactlib.solve(measured, E=1.0, nu=0.5, mean_pressure=1e-6)
    reference = contactlib.solve(sphere, E=1.0, nu=0.5, mean_pressure=1e-6, periodic=False)
    assert out.attrs["periodic"] == 0 and np.array_equal(out.pressure.values, reference.pressure.values)
    periodic = contactlib.solve(measured, E=1.0, nu=0.5, mean_pressure=1e-6, periodic=True)  # the caller's choice
    assert periodic.attrs["periodic"] == 1


def test_units_are_converted_to_metres_and_recorded(tmp_path, surface):
    path = tmp_path / "s_um.npy"
    np.save(path, bare(surface) * 1e6)
    out = read(path, length=LENGTH * 1e6, unit="um", periodic=True, detrend="none")
    np.testing.assert_allclose(out.values, surface.values, rtol=4e-16, atol=0)  # one rounding each way
    np.testing.assert_allclose(out.x.values, surface.x.values, rtol=4e-16, atol=0)
    assert out.attrs["height_unit"] == "um" and out.attrs["length"] == pytest.approx([LENGTH] * 2, rel=1e-15)
    assert read(path, length=LENGTH * 1e6, unit="µm", periodic=True, detrend="none").values.tobytes() == \
        out.values.tobytes()


def test_plane_detrending_removes_an_added_plane_and_is_recorded(tmp_path, surface):
    x, y = np.meshgrid(surface.x.values, surface.y.values, indexing="ij")
    slope_x, slope_y, offset = 0.03, -0.02, 5e-6  # [1], [1], [m]: a tilt far above the roughness (rms slope 0.1)
    tilted = bare(surface) + offset + slope_x * x + slope_y * y
    np.save(tmp_path / "plain.npy", bare(surface))
    np.save(tmp_path / "tilted.npy", tilted)
    args = {"length": LENGTH, "unit": "m", "periodic": False}
    plain, out = read(tmp_path / "plain.npy", **args), read(tmp_path / "tilted.npy", **args)
    rounding = 1e-15 * np.abs(tilted).max()
    np.testing.assert_allclose(out.values, plain.values, rtol=0, atol=10 * rounding)
    assert out.attrs["detrend"] == "plane"
    assert out.attrs["detrend_slope_x"] - plain.attrs["detrend_slope_x"] == pytest.approx(slope_x, rel=1e-12)
    assert out.attrs["detrend_slope_y"] - plain.attrs["detrend_slope_y"] == pytest.approx(slope_y, rel=1e-12)
    # the plane is gone: what is left has no mean and no tilt
    rest = np.polynomial.polynomial.polyfit(x.ravel(), bare(out).ravel(), 1)
    assert abs(rest[0]) < 10 * rounding and abs(rest[1]) < 1e-12
    mean = read(tmp_path / "tilted.npy", detrend="mean", **args)
    assert abs(float(mean.mean())) < 10 * rounding and mean.attrs["detrend"] == "mean"
    assert mean.attrs["detrend_offset"] == pytest.approx(float(tilted.mean()), rel=1e-14)


def test_line_detrending_of_a_profile(tmp_path, profile):
    line = 2e-6 + 0.05 * profile.x.values
    np.save(tmp_path / "p.npy", profile.values + line)
    out = read(tmp_path / "p.npy", length=LENGTH, unit="m", detrend="plane")
    base = read(tmp_path / "p.npy", length=LENGTH, unit="m", detrend="none")
    assert out.dims == ("x",) and out.attrs["detrend"] == "line"
    slope, intercept = np.polyfit(profile.x.values, base.values, 1)
    np.testing.assert_allclose(out.values, base.values - (slope * profile.x.values + intercept), rtol=0,
                               atol=1e-15 * np.abs(base.values).max() * 10)
    assert out.attrs["detrend_slope_x"] == pytest.approx(slope, rel=1e-12)
    with pytest.raises(ValueError, match="'line' is for profiles"):
        read(_save(tmp_path / "m.npy", np.zeros((4, 4))), length=1, unit="m", detrend="line")


def _save(path, values):
    np.save(path, values)
    return path


def test_missing_points_are_refused_with_their_count_or_filled(tmp_path):
    n = 32
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    plane = 1e-6 * (3.0 + 0.25 * i - 0.5 * j)  # linear interpolation reproduces a plane exactly
    holes = plane.copy()
    holes[10:13, 5:9] = np.nan  # interior hole, 12 points
    holes[20, 20] = np.nan
    holes[0, 0] = np.nan  # a corner: outside the hull of the hole borders, so the nearest height
    path = _save(tmp_path / "holes.npy", holes)
    with pytest.raises(ValueError, match=r"holes.npy: 14 of 1024 heights are missing \(NaN\)"):
        read(path, length=1e-4, unit="m")
    args = {"length": 1e-4, "unit": "m", "detrend": "none"}
    mean = read(path, fill="mean", **args)
    valid = np.isfinite(holes)
    assert np.all(bare(mean)[~valid] == holes[valid].mean()) and np.array_equal(bare(mean)[valid], holes[valid])
    assert mean.attrs["fill"] == "mean" and mean.attrs["filled_points"] == 14
    interp = read(path, fill="interpolate", **args)
    interior = ~valid.copy()
    interior[0, 0] = False
    np.testing.assert_allclose(bare(interp)[interior], plane[interior], rtol=1e-13)
    assert bare(interp)[0, 0] in (plane[0, 1], plane[1, 0], plane[1, 1])  # a nearest neighbour's height
    assert interp.attrs["fill"] == "interpolate" and np.array_equal(bare(interp)[valid], holes[valid])
    line = np.linspace(0, 1e-6, 50)
    gappy = line.copy()
    gappy[[0, 20, 21, 22]] = np.nan
    filled = read(_save(tmp_path / "p.npy", gappy), fill="interpolate", **args)
    np.testing.assert_allclose(filled.values[1:], line[1:], rtol=1e-13)
    assert filled.values[0] == line[1]  # flat past the end
    detrended = read(path, fill="mean", length=1e-4, unit="m", detrend="plane")  # trend fitted to the finite points
    np.testing.assert_allclose(detrended.values, 0, atol=1e-13 * np.abs(plane).max())


@pytest.mark.parametrize("content, message", [
    ("1 2 3 4\n5 6 7 8\n9 10 11\n", "ragged rows in a text matrix"),
    ("0 0 1\n1 0 2\n3 0 3\n0 1 4\n1 1 5\n3 1 6\n", "the x positions are not a uniform grid"),
    ("0 0 1\n1 0 2\n2 0 3\n0 1 4\n1 1 5\n", "do not fill the 3 x 2 grid their coordinates span (1 nodes missing"),
    ("0 0 1\n1 0 2\n0 1 3\n1 1 4\n1 1 5\n", "do not fill the 2 x 2 grid"),
])
def test_bad_text_files_are_refused_naming_the_file(tmp_path, content, message):
    path = tmp_path / "bad.txt"
    path.write_text(content)
    with pytest.raises(ValueError) as err:
        read(path, length=1.0, unit="m")
    assert str(err.value).startswith(str(path)) and message in str(err.value)


def test_missing_size_or_unit_and_contradictions_are_refused(tmp_path, surface):
    path = _save(tmp_path / "s.npy", bare(surface))
    with pytest.raises(ValueError, match=r"s.npy: the file does not carry its physical size; pass length="):
        read(path, unit="m")
    with pytest.raises(ValueError, match=r"s.npy: the file does not state its length unit; pass unit="):
        read(path, length=LENGTH)
    with pytest.raises(ValueError, match="unknown length unit 'furlong'"):
        read(path, length=LENGTH, unit="furlong")
    nc = tmp_path / "s.nc"
    surface.to_dataset().to_netcdf(nc)
    with pytest.raises(ValueError, match=r"s.nc: the file carries its size .* leave length= out"):
        read(nc, length=2 * LENGTH)
    with pytest.raises(ValueError, match=r"s.nc: the file states its unit as 'm', not 'nm'"):
        read(nc, unit="nm")
    assert read(nc, length=LENGTH, unit="m", detrend="none").values.tobytes() == surface.values.tobytes()
    with pytest.raises(FileNotFoundError, match="nothing.npy: no such file"):
        read(tmp_path / "nothing.npy")


@pytest.mark.parametrize("installed", [True, False])
def test_unknown_format_lists_the_supported_ones(tmp_path, monkeypatch, installed):
    if installed:
        pytest.importorskip("SurfaceTopography", reason=ST_REASON)
    else:
        monkeypatch.setitem(sys.modules, "SurfaceTopography", None)  # as if the extra were not installed
    path = tmp_path / "scan.qqq"
    path.write_bytes(b"\x00\x01not a topography\xff" * 10)
    with pytest.raises(ValueError) as err:
        read(path, length=1.0, unit="m")
    text = str(err.value)
    assert text.startswith(f"{path}: unknown topography format")
    for native in ("netcdf", "npy", "matrix", "xyz", "contactlib[topography]"):
        assert native in text
    assert ("installed here" in text) == installed


def test_periodic_surface_with_plane_detrending_warns(tmp_path, surface):
    nc = tmp_path / "s.nc"
    surface.to_dataset().to_netcdf(nc)
    with pytest.warns(UserWarning, match="non-periodic"):
        out = read(nc)
    assert out.attrs["periodic"] == 1 and out.attrs["detrend"] == "plane"


# --- SurfaceTopography's formats (contactlib[topography]) ---

def _topography(h: xr.DataArray, unit="m", scale=1.0):
    st = pytest.importorskip("SurfaceTopography", reason=ST_REASON)
    sizes = tuple(h.attrs["length"] * scale for _ in h.dims)
    if h.ndim == 1:
        return st.UniformLineScan(h.values * scale, sizes[0], unit=unit, periodic=True)
    return st.Topography(bare(h) * scale, sizes, unit=unit, periodic=True)


@pytest.mark.parametrize("fmt", ["x3p", "gwy"])
def test_surfacetopography_formats_read_back_bit_identical(tmp_path, surface, fmt):
    topography = _topography(surface)
    path = tmp_path / f"s.{fmt}"
    getattr(topography, f"to_{fmt}")(str(path))
    out = read(path, detrend="none", periodic=True)
    assert_same_surface(out, surface)
    assert out.attrs["source_format"] == fmt and out.attrs["source_reader"].startswith("SurfaceTopography ")
    assert out.attrs["length_from"] == "file" and out.attrs["height_unit"] == "m"


def test_same_surface_in_two_formats_gives_the_same_array(tmp_path, surface):
    """SurfaceTopography's axis convention is ours (x along the first axis): its X3P file and its text
    matrix (one row per y, read by contactlib's own reader) give one array, with the size and unit the
    files carry, and a file in micrometres reads as the metres it holds."""
    topography = _topography(surface)
    topography.to_x3p(str(tmp_path / "s.x3p"))
    topography.to_matrix(str(tmp_path / "s.txt"))
    a = read(tmp_path / "s.x3p", detrend="none", periodic=True)
    b = read(tmp_path / "s.txt", detrend="none", periodic=True)
    assert b.attrs["source_reader"] == "contactlib" and b.attrs["length_from"] == "file"
    xr.testing.assert_equal(a, b)
    micrometres = _topography(surface, unit="µm", scale=1e6)  # (X3P and GWY store metres whatever the unit)
    micrometres.to_netcdf(str(tmp_path / "um.nc"))
    micrometres.to_matrix(str(tmp_path / "um.txt"))
    for name in ("um.nc", "um.txt"):
        c = read(tmp_path / name, detrend="none", periodic=True)
        assert c.attrs["height_unit"] == "µm" and c.attrs["length"] == [LENGTH] * 2, name
        np.testing.assert_allclose(c.values, surface.values, rtol=4e-16, atol=0)  # x 1e6, then / 1e6


def test_surfacetopography_file_without_size_needs_length(tmp_path, surface):
    pytest.importorskip("SurfaceTopography", reason=ST_REASON)
    h5py = pytest.importorskip("h5py", reason="h5py (a SurfaceTopography dependency) is not installed")
    path = tmp_path / "challenge.h5"  # the Contact Mechanics Challenge's HDF5 layout: a 'surface' array
    with h5py.File(path, "w") as f:
        f["surface"] = bare(surface)
    with pytest.raises(ValueError, match="challenge.h5: the file does not carry its physical size"):
        read(path, unit="m")
    out = read(path, length=LENGTH, unit="m", periodic=True, detrend="none")
    assert_same_surface(out, surface)
    assert out.attrs["source_format"] == "h5"


def test_a_trend_the_finite_heights_do_not_determine_is_refused(tmp_path):
    """A map whose finite heights lie on one row (the rest missing, filled): the plane fit's normal equations were
    singular and numpy's LinAlgError escaped; now refused naming ``detrend``. The mean still works."""
    heights = np.full((16, 16), np.nan)
    heights[3, :] = np.linspace(0.0, 1e-6, 16)
    path = _save(tmp_path / "row.npy", heights)
    with pytest.raises(ValueError, match="detrend='plane': the 16 finite heights do not determine a plane"):
        read(path, length=1e-4, unit="m", fill="mean", detrend="plane")
    assert read(path, length=1e-4, unit="m", fill="mean", detrend="mean").attrs["detrend"] == "mean"
