"""The two-scale asperity method against Hertz, an independent periodic kernel and contactlib's full solver."""

import math

import numpy as np
import pytest
import xarray as xr

import contactlib
import contactlib.two_scale as ts
from contactlib.core.grid import Grid
from contactlib.model.operators import Compliance
from contactlib.reference import hertz
from contactlib.two_scale import interaction as interaction_module

E, NU = 1.0, 0.5
E_STAR = E / (1 - NU**2)


class Material:
    """A duck-typed elastic material (anything with E and nu)."""

    def __init__(self, E, nu):
        self.E, self.nu = E, nu


def footprint_forces(pressure: xr.DataArray, table: ts.AsperityTable) -> np.ndarray:
    """Force on each asperity from a full-grid pressure field: the pressure inside its footprint (the
    test's own loop over the whole grid, to check :func:`contactlib.two_scale.asperity_forces`)."""
    pressure = pressure.transpose("x", "y").values  # indexed [ix, iy], as dx and dy below
    n = pressure.shape[0]
    h = table.length / n
    x = np.arange(n) * h
    out = np.zeros(table.count)
    for k, (c, rf) in enumerate(zip(table.centers, table.footprint_radius)):
        dx = (x - c[0] + table.length / 2) % table.length - table.length / 2
        dy = (x - c[1] + table.length / 2) % table.length - table.length / 2
        out[k] = pressure[(dx[:, None] ** 2 + dy[None, :] ** 2) < rf**2].sum() * h * h
    assert math.isclose(out.sum(), pressure.sum() * h * h, rel_tol=1e-12)  # all the load is on some asperity
    np.testing.assert_allclose(ts.asperity_forces(pressure, table), out, rtol=1e-12, atol=1e-300)
    return out


def test_spheres_carry_their_asperity_table():
    h = contactlib.surfaces.spheres(64, radius=0.1, lattice=2, summit_height=0.01, height_std=0.001, seed=2)
    table = ts.asperity_table(h)
    np.testing.assert_allclose(table.centers, [[0.25, 0.25], [0.25, 0.75], [0.75, 0.25], [0.75, 0.75]])
    assert table.summit_height.std() > 0 and np.all(table.radius == 0.1)
    # the table reproduces the heights: the grid maximum is the highest summit sampled near its node
    assert abs(float(h.max()) - table.summit_height.max()) < 1e-3 * table.summit_height.max()


def test_ewald_interaction_matches_the_periodic_grid_kernel():
    """Pair sums against contactlib's periodic half-space kernel (2/(E*|q|), 1024^2) at node positions,
    and independence of the Ewald splitting parameter."""
    rng = np.random.default_rng(0)
    n, length, count = 1024, 1.0, 6
    nodes = rng.integers(0, n, size=(count, 2))
    table = ts.AsperityTable(nodes * length / n, np.ones(count), np.full(count, 1e-3), length, True)
    forces = rng.uniform(0.5, 1.5, count)
    op = ts.PointInteraction(table, E_STAR)
    pairs = op(forces) - op.diagonal * forces
    response = Compliance(Grid((n, n), (length, length)), E_star=E_STAR).response() / (length / n) ** 2
    expected = [sum(response[tuple((nodes[k] - nodes[l]) % n)] * forces[l] for l in range(count) if l != k)
                for k in range(count)]
    np.testing.assert_allclose(pairs, expected, rtol=1e-6)
    original = interaction_module.EWALD_NEIGHBOURS
    try:
        interaction_module.EWALD_NEIGHBOURS = 1.0
        np.testing.assert_allclose(ts.PointInteraction(table, E_STAR)(forces), op(forces), rtol=1e-7)
    finally:
        interaction_module.EWALD_NEIGHBOURS = original


@pytest.mark.parametrize("n", [128, 131])
def test_single_asperity_is_hertz(n):
    """Non-periodic single sphere, a/h ~ 20: force within 0.5 % of Hertz at the same approach, both scales;
    the grid solution is the full solver's to 1e-5."""
    radius, delta = 1.0, 0.0015  # a = 0.0387
    h = contactlib.surfaces.spheres(n, length=0.25, radius=radius, centers=[[0.125, 0.125]], summit_height=0.02)
    h.attrs["periodic"] = 0
    # the approach counts from the highest grid node (as contactlib.solve): off-node summits sit higher
    indentation = delta + 0.02 - float(h.max())
    P_hertz = hertz.sphere_load(indentation, radius=radius, E_star=E_STAR)
    macro = ts.solve(h, material=Material(E, NU), penetration=delta, scale="macro")
    assert float(macro.force[0]) == pytest.approx(P_hertz, rel=1e-12)
    two = ts.solve(h, E=E, nu=NU, penetration=delta)
    assert float(two.force[0]) == pytest.approx(P_hertz, rel=5e-3)
    assert float(two.contact_radius[0]) == pytest.approx(math.sqrt(radius * indentation), rel=0.03)  # area by node count
    full = contactlib.solve(h, E=E, nu=NU, penetration=delta)
    assert float(two.mean_pressure) == pytest.approx(float(full.mean_pressure), rel=1e-5)


def test_periodic_single_asperity_images():
    """The Ewald self term (the asperity's own images, zero-mean displacement) gives the full periodic
    solver's approach to 0.2 %; without it the macro step would be Hertz's, 6.7 % off."""
    h = contactlib.surfaces.spheres(256, radius=1.0, centers=[[0.5, 0.5]], summit_height=0.05)
    macro = ts.solve(h, E=E, nu=NU, mean_pressure=1e-4, scale="macro")
    full = contactlib.solve(h, E=E, nu=NU, mean_pressure=1e-4)
    assert float(macro.penetration) == pytest.approx(float(full.penetration), rel=2e-3)
    assert abs(hertz.sphere_penetration(1e-4, radius=1.0, E_star=E_STAR) / float(full.penetration) - 1) > 0.05


def _few_asperities():
    """Seven asperities of different radii and heights, two nearly touching, one too low to touch."""
    centers = [[0.2, 0.2], [0.27, 0.21], [0.7, 0.3], [0.25, 0.7], [0.62, 0.72], [0.85, 0.85], [0.5, 0.48]]
    radius = [0.1, 0.08, 0.12, 0.1, 0.09, 0.11, 0.1]
    summit = [0.006, 0.0061, 0.0062, 0.0058, 0.006, 0.0059, 0.003]
    return contactlib.surfaces.spheres(384, radius=radius, centers=centers, summit_height=summit)


@pytest.fixture(scope="module")
def few():
    h = _few_asperities()
    load = 2e-5
    full = contactlib.solve(h, E=E, nu=NU, mean_pressure=load)
    macro = ts.solve(h, E=E, nu=NU, mean_pressure=load, scale="macro")
    two = ts.solve(h, E=E, nu=NU, mean_pressure=load)
    return h, full, macro, two


def test_few_asperities_match_the_full_solver(few):
    h, full, macro, two = few
    table = ts.asperity_table(h)
    reference = footprint_forces(full.pressure, table)
    scale = reference.max()
    # two-scale: the full solver's answer (forces within 1 %, here far closer), pressure field and approach
    np.testing.assert_allclose(two.force, reference, rtol=0, atol=1e-2 * scale)
    assert np.max(np.abs(two.force.values - reference)) < 1e-4 * scale
    assert float(two.penetration) == pytest.approx(float(full.penetration), rel=1e-4)
    assert np.max(np.abs(two.pressure.values - full.pressure.values)) < 1e-3 * float(full.pressure.max())
    assert float(two.contact_area) == pytest.approx(float(full.contact_area), rel=0.02)
    # the residual, summed over the footprints only, is the full solver's measure of the assembled fields
    from contactlib.solvers.state import contact_residual, height_scale
    assert float(two.residual) == pytest.approx(
        contact_residual(two.pressure.values, two.gap.values, height_scale(h.values)), rel=1e-10)
    # macro: Hertz + point loads, a few percent off where contacts are close (reported, not the 1 % goal)
    np.testing.assert_allclose(macro.force, reference, rtol=0, atol=0.03 * scale)


def test_out_of_contact_asperities_carry_zero_force(few):
    h, full, macro, two = few
    reference = footprint_forces(full.pressure, ts.asperity_table(h))
    low = 6  # summit 0.003 below the others' ~0.006
    assert reference[low] == 0.0
    assert float(two.force[low]) == 0.0 and float(macro.force[low]) == 0.0
    assert float(macro.local_penetration[low]) < 0 and float(two.contact_radius[low]) == 0.0
    assert np.all(two.force.values[:low] > 0)


def test_load_and_penetration_control_agree(few):
    h, _, macro, two = few
    for scale, by_load in (("macro", macro), ("two-scale", two)):
        by_approach = ts.solve(h, E=E, nu=NU, penetration=float(by_load.penetration), scale=scale)
        np.testing.assert_allclose(by_approach.force, by_load.force, rtol=0, atol=1e-5 * float(by_load.force.max()))
        assert float(by_approach.mean_pressure) == pytest.approx(float(by_load.mean_pressure), rel=1e-5)


def test_periodic_lattice_and_random_field_three_ways():
    """Macro, two-scale and full solver on a lattice with scattered heights and on a random field."""
    lattice = contactlib.surfaces.spheres(320, radius=0.1, lattice=5, summit_height=0.01, height_std=0.001, seed=4)
    rng = np.random.default_rng(5)
    centers = []
    while len(centers) < 12:  # random sequential addition: footprints (radius 0.031) do not overlap
        c = rng.uniform(0, 1, 2)
        if all(np.hypot(*((c - o + 0.5) % 1 - 0.5)) > 0.07 for o in centers):
            centers.append(c)
    random_field = contactlib.surfaces.spheres(320, radius=0.08, centers=centers, summit_height=0.006,
                                               height_std=0.0006, seed=6)
    for h, load in ((lattice, 1e-5), (random_field, 3e-6)):
        table = ts.asperity_table(h)
        full = contactlib.solve(h, E=E, nu=NU, mean_pressure=load)
        reference = footprint_forces(full.pressure, table)
        two = ts.solve(h, E=E, nu=NU, mean_pressure=load)
        macro = ts.solve(h, E=E, nu=NU, mean_pressure=load, scale="macro")
        scale = reference.max()
        assert np.max(np.abs(two.force.values - reference)) < 1e-2 * scale
        assert np.max(np.abs(macro.force.values - reference)) < 3e-2 * scale
        assert np.count_nonzero(reference) == np.count_nonzero(two.force.values)


def test_dataset_input_equals_the_dataarray():
    h = _few_asperities()
    table = ts.asperity_table(h)
    ds = xr.Dataset({"center_x": ("asperity", table.centers[:, 0]), "center_y": ("asperity", table.centers[:, 1]),
                     "radius": ("asperity", table.radius), "summit_height": ("asperity", table.summit_height)},
                    attrs={"length": 1.0})
    a = ts.solve(h, E=E, nu=NU, mean_pressure=2e-5, scale="macro", fields=False)
    b = ts.solve(ds, E=E, nu=NU, mean_pressure=2e-5, scale="macro", n=384, fields=False)
    np.testing.assert_allclose(a.force, b.force, rtol=1e-12)
    c = ts.solve(ds, E=E, nu=NU, mean_pressure=2e-5, scale="macro")  # no grid: per-asperity answer only
    assert "pressure" not in c and np.allclose(c.force, a.force, rtol=1e-12)


def test_labels_and_provenance(few, tmp_path):
    _, _, _, two = few
    assert two.force.dims == ("asperity",) and two.pressure.dims == ("y", "x")
    for name in list(two.data_vars) + list(two.coords):
        assert {"units", "long_name"} <= set(two[name].attrs), name
    assert two.force.attrs["units"] == "Pa m2"
    for key in ("contactlib_version", "E", "nu", "scale", "interaction", "tol", "wall_time", "micro_iterations"):
        assert key in two.attrs
    two.to_netcdf(tmp_path / "two.nc")
    xr.testing.assert_identical(xr.open_dataset(tmp_path / "two.nc").load(), two)


def test_direct_dataset_equals_the_public_constructor():
    """The labels' direct construction (no merge) gives the Dataset xarray's constructor gives: variables, coords,
    indexes and attrs; a conflict of dimensions is still refused."""
    from contactlib.core.labels import dataset

    rng = np.random.default_rng(1)
    coords = {"asperity": ("asperity", np.arange(5), {"units": "1", "long_name": "asperity"}),
              "radius": ("asperity", rng.random(5), {"units": "m", "long_name": "r"}),
              "x": ("x", np.linspace(0, 1, 4), {"units": "m", "long_name": "x"}),
              "y": (("y",), np.linspace(0, 1, 3), {"units": "m", "long_name": "y"})}
    data = {"force": ("asperity", rng.random(5), {"units": "N", "long_name": "f"}),
            "pressure": (("x", "y"), rng.random((4, 3)), {"units": "Pa", "long_name": "p"}),
            "iterations": ((), 3, {"units": "1", "long_name": "its"})}
    attrs = {"scale": "macro", "tol": 1e-6}
    direct, public = dataset(data, coords, attrs), xr.Dataset(data, coords=coords, attrs=attrs)
    xr.testing.assert_identical(direct, public)
    assert list(direct.variables) == list(public.variables) and set(direct.xindexes) == {"asperity", "x", "y"}
    assert all(direct.xindexes[d].equals(public.xindexes[d]) for d in ("asperity", "x", "y"))
    assert float(direct.force.sel(asperity=2)) == data["force"][1][2]
    with pytest.raises(ValueError):
        dataset({"force": ("asperity", np.ones(4), {})}, coords, attrs)
    # names that clash go to the constructor, which refuses a name in both, and indexes a variable named like a dim
    with pytest.raises(ValueError, match="radius"):
        dataset({"radius": ("asperity", np.ones(5), {})}, coords, attrs)
    clash = {"y": (("y",), np.arange(3.0), {})}
    xr.testing.assert_identical(dataset(clash, {}, attrs), xr.Dataset(clash, attrs=attrs))


def test_newton_through_asperities_entering_contact():
    """A load path over which asperities come in one after another: Newton converges at every load."""
    h = contactlib.surfaces.spheres(64, radius=0.05, lattice=6, summit_height=0.004, height_std=0.0005, seed=1)
    counts = []
    for load in (1e-8, 1e-7, 1e-6, 5e-6):
        out = ts.solve(h, E=E, nu=NU, mean_pressure=load, scale="macro", macro_tol=1e-10)
        assert out.attrs["macro_residual"] <= 1e-10 and out.attrs["macro_iterations"] < 30
        assert float(out.mean_pressure) == pytest.approx(load, rel=1e-9)
        counts.append(int(np.count_nonzero(out.force.values)))
    assert counts[0] < counts[-1] and counts == sorted(counts)


def test_non_convergence_raises_with_residual():
    h = _few_asperities()
    with pytest.raises(contactlib.ConvergenceError) as err:
        ts.solve(h, E=E, nu=NU, mean_pressure=2e-5, max_iter=1)  # the macro Newton iteration
    assert err.value.residual > 1e-10 and err.value.dataset.attrs["converged"] == 0
    with pytest.raises(contactlib.ConvergenceError, match="micro") as err:
        ts.solve(h, E=E, nu=NU, mean_pressure=2e-5, tol=1e-15, max_iter=3)  # below the local solves' floor
    assert err.value.residual > 1e-15 and err.value.dataset.attrs["converged"] == 0


def _table(**columns):
    base = {"center_x": [0.2, 0.6], "center_y": [0.5, 0.5], "radius": [0.1, 0.1], "summit_height": [0.01, 0.01]}
    base.update(columns)
    return xr.Dataset({k: ("asperity", np.asarray(v, dtype=float)) for k, v in base.items()}, attrs={"length": 1.0})


@pytest.mark.parametrize("columns, match", [
    ({"center_x": [0.2, 0.25]}, "overlap"),
    ({"radius": [0.1, 0.0]}, "radius"),
    ({"radius": [-0.1, 0.1]}, "radius"),
    ({"center_y": [np.nan, 0.5]}, "center_y"),
    ({"summit_height": [0.01, 0.2]}, "summit_height"),
])
def test_bad_asperities_are_refused(columns, match):
    with pytest.raises(ValueError, match=match):
        ts.solve(_table(**columns), E=E, nu=NU, mean_pressure=1e-6, scale="macro")


def test_bad_arguments_are_refused():
    table = _table()
    with pytest.raises(ValueError, match="scale"):
        ts.solve(table, E=E, nu=NU, mean_pressure=1e-6, scale="micro")
    with pytest.raises(ValueError, match="material"):
        ts.solve(table, mean_pressure=1e-6, scale="macro")
    with pytest.raises(ValueError, match="n"):
        ts.solve(table, E=E, nu=NU, mean_pressure=1e-6)
    with pytest.raises(ValueError, match="mean_pressure or penetration"):
        ts.solve(table, E=E, nu=NU, scale="macro")


def test_load_beyond_separate_contacts_is_refused():
    """A cap pressed down to its base: the method says where it breaks instead of answering."""
    with pytest.raises(ValueError, match="mean_pressure.*asperity [01] is pressed .* beyond its summit height"):
        ts.solve(_table(), E=E, nu=NU, mean_pressure=2e-3, scale="macro")
    ok = ts.solve(_table(), E=E, nu=NU, mean_pressure=5e-4, scale="macro")  # below that: answered
    assert np.all(ok.local_penetration.values < ok.summit_height.values)
    h = _few_asperities()
    with pytest.raises(ValueError, match="mean_pressure"):
        ts.solve(h, E=E, nu=NU, mean_pressure=2e-3)


def test_random_field_is_separate_and_reproducible():
    a = ts.random_asperity_field(200, coverage=0.45, nodes_per_spacing=8, seed=3)
    b = ts.random_asperity_field(200, coverage=0.45, nodes_per_spacing=8, seed=3)
    xr.testing.assert_identical(a, b)
    table = ts.asperity_table(a)  # validates: no overlapping footprints
    assert table.count == 200 and a.shape == (113, 113)
    exclusion = math.sqrt(0.45 / (math.pi * 200))
    assert table.footprint_radius.max() <= exclusion * (1 + 1e-9)
    with pytest.raises(ValueError, match="coverage"):
        ts.random_asperity_field(10, coverage=0.6, nodes_per_spacing=8)


def test_many_sagging_asperities_converge_with_the_coarse_correction(monkeypatch):
    """300 asperities whose body sags by about their height scatter: plain block Jacobi oscillates and
    diverges there (ratio about -1.4 per sweep); with the macro coarse correction the outer iteration
    converges in a few sweeps, to the full solver's forces."""
    field = ts.random_asperity_field(300, coverage=0.2, nodes_per_spacing=24, seed=0)
    table = ts.asperity_table(field)
    approach = float(field.max()) - 0.6 * float(np.mean(table.summit_height))
    two = ts.solve(field, E=E, nu=NU, penetration=approach, tol=1e-4)
    assert two.attrs["micro_iterations"] <= 6
    full = contactlib.solve(field, E=E, nu=NU, penetration=approach)
    reference = ts.asperity_forces(full.pressure, table)
    assert np.max(np.abs(two.force.values - reference)) < 1e-3 * reference.max()
    assert float(two.mean_pressure) == pytest.approx(float(full.mean_pressure), rel=1e-4)
    # plain block Jacobi (no coarse correction) does not converge on the same field
    from contactlib.two_scale import micro
    monkeypatch.setattr(micro, "_coarse_correction", lambda *args, **kwargs: (np.ones(table.count), 0.0))
    with pytest.raises((contactlib.ConvergenceError, ValueError)):
        ts.solve(field, E=E, nu=NU, penetration=approach, tol=1e-4, max_iter=12)


def test_windows_grow_when_a_contact_outgrows_them(monkeypatch, few):
    """Windows sized below the contacts: the micro step enlarges them and gives the same answer."""
    h, _, _, two = few
    from contactlib.two_scale import micro
    monkeypatch.setattr(micro, "WINDOW_MARGIN", 0.4)
    monkeypatch.setattr(micro, "WINDOW_PAD", 1)
    small = ts.solve(h, E=E, nu=NU, mean_pressure=2e-5)
    assert small.attrs["micro_window"] > 2 * (math.ceil(0.4 * float(two.contact_radius.max()) * 384) + 1)
    np.testing.assert_allclose(small.force, two.force, rtol=0, atol=1e-5 * float(two.force.max()))


def test_non_periodic_field_matches_the_full_solver():
    """An isolated (zero-padded) window: direct point-load sums, zero-padded global and local FFTs."""
    h = _few_asperities()
    h.attrs["periodic"] = 0
    full = contactlib.solve(h, E=E, nu=NU, mean_pressure=2e-5)
    reference = ts.asperity_forces(full.pressure, ts.asperity_table(h))
    two = ts.solve(h, E=E, nu=NU, mean_pressure=2e-5)
    macro = ts.solve(h, E=E, nu=NU, mean_pressure=2e-5, scale="macro")
    assert two.attrs["interaction"] == "direct" and two.attrs["periodic"] == 0
    assert np.max(np.abs(two.force.values - reference)) < 1e-4 * reference.max()
    assert np.max(np.abs(macro.force.values - reference)) < 1e-2 * reference.max()
    assert float(two.penetration) == pytest.approx(float(full.penetration), rel=1e-5)


def test_known_displacement_hook_for_time_stepping(few):
    """The hook a viscoelastic time stepper needs: a known displacement of the body. A uniform one, c, is
    the same as an approach smaller by c (macro and micro); a non-uniform one moves the forces."""
    h, _, _, two = few
    table = ts.asperity_table(h)
    interaction = ts.PointInteraction(table, E_STAR)
    law = ts.HertzLaw(table.radius, E_STAR)
    z_top, delta, c = float(h.max()), float(two.penetration), 2e-4
    shifted = ts.solve_macro(table, interaction, law, penetration=delta - c, z_top=z_top)
    hooked = ts.solve_macro(table, interaction, law, penetration=delta, z_top=z_top,
                            known_displacement=np.full(table.count, c))
    np.testing.assert_allclose(hooked.force, shifted.force, rtol=1e-9)
    micro_shifted = ts.solve_micro(table, shifted, law, E_STAR, interaction, z_top=z_top, total_force=None,
                                   tol=1e-6, max_iter=50)
    micro_hooked = ts.solve_micro(table, hooked, law, E_STAR, interaction, z_top=z_top, total_force=None,
                                  tol=1e-6, max_iter=50, known_displacement=np.full(h.shape, c))
    np.testing.assert_allclose(micro_hooked.force, micro_shifted.force, rtol=0, atol=1e-6 * shifted.force.max())
    tilted = ts.solve_macro(table, interaction, law, penetration=delta, z_top=z_top,
                            known_displacement=c * table.centers[:, 0])
    assert not np.allclose(tilted.force, shifted.force, rtol=1e-3)


def test_study_point_is_labelled_and_accurate():
    from contactlib import studies
    row = studies.two_scale_point(count=10, coverage=0.2, seed=0, nodes_per_radius=3, full_tol=1e-4,
                                  two_scale_tol=1e-3, repeats=1, E=E, nu=NU, tol=1e-8)
    assert set(row) - {"residual"} <= set(studies.STUDY_VARIABLES)  # the sweep's own variable: the reference's
    assert row["residual"] <= 1e-8
    assert row["two_scale_asperity_force_error"] < 1e-2 and row["full_asperity_force_error"] < 1e-3
    assert row["macro_asperity_force_error"] < 5e-2 and row["in_contact"] == 10
    assert all(row[f"{m}_time"] > 0 for m in ("macro", "two_scale", "full"))


def test_force_tolerance_stops_within_it_of_the_full_solver():
    """``force_tol``: the sweeps stop on the change of the asperity forces; one sweep from the macro
    forces already lands within the target of the full solver (300 sagging asperities, coverage 0.2)."""
    field = ts.random_asperity_field(300, coverage=0.2, nodes_per_spacing=24, seed=0)
    table = ts.asperity_table(field)
    approach = float(field.max()) - 0.6 * float(np.mean(table.summit_height))
    full = contactlib.solve(field, E=E, nu=NU, penetration=approach)
    reference = ts.asperity_forces(full.pressure, table)
    for force_tol in (1e-2, 1e-4):
        two = ts.solve(field, E=E, nu=NU, penetration=approach, force_tol=force_tol)
        assert two.attrs["micro_force_change"] <= force_tol and two.attrs["force_tol"] == force_tol
        assert np.max(np.abs(two.force.values - reference)) < force_tol * reference.max()
    with pytest.raises(ValueError, match="force_tol"):
        ts.solve(field, E=E, nu=NU, penetration=approach, force_tol=0.0)


def test_force_stop_estimates_the_next_sweep():
    """``force_tol`` stops on the change the next sweep would make, estimated from the convolution that
    sweep (or the returned fields) needs: each contact's mean interference shift times its Hertz stiffness.
    Against the change that sweep does make (tight local solves, so that it is the coupling's alone), under
    both displacement and load control (300 sagging asperities, coverage 0.4: the macro start 1e-2 off)."""
    field = ts.random_asperity_field(300, coverage=0.4, nodes_per_spacing=20, seed=1)
    table = ts.asperity_table(field)
    interaction = ts.PointInteraction(table, E_STAR)
    law = ts.HertzLaw(table.radius, E_STAR)
    z_top = float(field.max())
    approach = z_top - 0.6 * float(np.mean(table.summit_height))
    total = None  # displacement control, then load control at the force it gave
    for _ in range(2):
        macro = ts.solve_macro(table, interaction, law, z_top=z_top, tol=1e-10,
                               **({"penetration": approach} if total is None else {"total_force": total}))
        kw = dict(z_top=z_top, total_force=total, tol=1e-6, force_tol=1e-6)
        one = ts.solve_micro(table, macro, law, E_STAR, interaction, max_iter=1, **kw)
        two = ts.solve_micro(table, macro, law, E_STAR, interaction, max_iter=2, **kw)
        assert one.iterations == 1 and two.iterations == 2 and not one.converged
        with pytest.raises(ValueError, match="max_iter"):  # at least one sweep: its fields are the answer's
            ts.solve_micro(table, macro, law, E_STAR, interaction, max_iter=0, **kw)
        actual = np.max(np.abs(two.force - one.force)) / one.force.max()
        assert 1e-4 < actual < 1e-2  # a change worth estimating (2.2e-3, 1.7e-3; estimates 2.3e-3, 2.1e-3)
        assert one.force_change == pytest.approx(actual, rel=0.25)
        total = float(one.force.sum())
    # under tol, force_change is the last sweep's own change
    on_tol = ts.solve_micro(table, macro, law, E_STAR, interaction, max_iter=2, z_top=z_top, total_force=total,
                            tol=1e-6)
    assert on_tol.iterations == 2 and 1e-5 < on_tol.force_change < 1e-2


def test_stacked_local_solves_match_the_single_window_solver():
    """The micro scale's vectorised constrained CG (all windows at once) against contactlib's own
    Polonsky-Keer solver on each window alone: caps of different radii, offsets and approaches."""
    from contactlib.solvers import solve_polonsky_keer
    from contactlib.two_scale.local import WindowStack, solve_stack

    w, h = 24, 0.01
    stack = WindowStack(w, h, E_STAR)
    x = (np.arange(w) - w // 2) * h
    rng = np.random.default_rng(1)
    heights = []
    for _ in range(12):
        R, (cx, cy) = 0.5 + rng.random(), rng.random(2) * h
        cap = -((x[:, None] - cx) ** 2 + (x[None, :] - cy) ** 2) / (2 * R)
        heights.append(cap - cap.max())
    approaches = 4e-4 * (1 + rng.random(12))
    interference = np.array(heights) + approaches[:, None, None]
    p, u, iterations, residual = solve_stack(stack, interference, tol=1e-8, max_iter=2000)
    assert np.all(residual <= 1e-8)
    np.testing.assert_allclose(u, stack(p), rtol=0, atol=1e-12 * np.abs(u).max())
    for k in range(12):
        single = solve_polonsky_keer(stack.operator, heights[k], penetration=approaches[k], tol=1e-8)
        assert p[k].sum() == pytest.approx(single.pressure.sum(), rel=1e-6)
        assert np.max(np.abs(p[k] - single.pressure)) < 1e-5 * single.pressure.max()


def test_dense_window_compliance_equals_the_padded_fft():
    """Small windows apply their compliance as a dense matrix: the same numbers as the zero-padded FFT,
    and the same as contactlib's non-periodic operator on one window."""
    from contactlib.two_scale.local import DENSE_WINDOW, WindowStack

    pressure = np.random.default_rng(3).uniform(size=(5, 16, 16))
    stack = WindowStack(16, 0.01, E_STAR)
    assert 16 <= DENSE_WINDOW and stack._dense is not None
    fft_way = stack._convolve(pressure)
    np.testing.assert_allclose(stack(pressure), fft_way, rtol=0, atol=1e-13 * np.abs(fft_way).max())
    np.testing.assert_allclose(fft_way[2], stack.operator(pressure[2]), rtol=1e-12)
    assert WindowStack(DENSE_WINDOW + 2, 0.01, E_STAR)._dense is None  # large windows: the FFT


@pytest.mark.parametrize("accuracy", [1e-4, 1e-5, 1e-7])
def test_ewald_accuracy_is_what_was_asked(monkeypatch, accuracy):
    """The Ewald products at a requested ``accuracy`` (their cut-off, mesh and Gaussian support from
    :func:`ewald_parameters`) against a sum at 1e-12 with another splitting (cut-off 2.0 spacings instead of
    2.5) on 2000 random asperities: the displacements within ``accuracy`` of the largest (0.4-0.8 of it
    measured), the diagonal within 1e-2 of it (1e-3 measured); the loosest spreads on 8 x 8 nodes, the
    default on 13 x 13."""
    field = ts.random_asperity_field(2000, coverage=0.2, nodes_per_spacing=4, seed=5)
    table = ts.asperity_table(field)
    rng = np.random.default_rng(5)
    loads = (rng.uniform(0.5, 1.5, table.count), rng.uniform(0.0, 1.0, table.count) ** 4)
    op = ts.PointInteraction(table, E_STAR, accuracy=accuracy)
    monkeypatch.setattr(interaction_module, "EWALD_NEIGHBOURS", 2.0)
    fine = ts.PointInteraction(table, E_STAR, accuracy=1e-12)
    assert fine.attrs["ewald_alpha"] > op.attrs["ewald_alpha"] and fine.attrs["ewald_support"] > 20
    assert op.attrs["ewald_support"] <= {1e-4: 8, 1e-5: 9, 1e-7: 13}[accuracy]
    for forces in loads:
        u_fine = fine(forces)
        assert np.max(np.abs(op(forces) - u_fine)) < accuracy * np.max(np.abs(u_fine))
    np.testing.assert_allclose(op.diagonal, fine.diagonal, rtol=0.01 * accuracy)


def test_separable_spreading_matches_the_sparse_matrix():
    """The Ewald product's spreading and gathering by the separable Gaussian kernels against the sparse
    gathering matrix (and its transpose) built independently from the same Gaussians, on a mesh where the
    supports wrap around the periodic window: the mesh fields and the gathered values agree to 1e-13. Also
    on a mesh narrower than the support (the kernels that wrap every column)."""
    from contactlib.two_scale.interaction import _gaussian_gather, gather_from_mesh as _gather, \
        gaussian_factors as _gaussian_factors, spread_on_mesh as _spread

    rng = np.random.default_rng(7)
    centers = rng.uniform(0.0, 1.0, (300, 2))
    centers[:3] = [[0.0, 0.0], [0.999, 0.5], [0.01, 0.995]]  # supports across the window's edges
    for m, s, wider in ((64, 0.02, False), (6, 0.2, True)):  # supports of 13 nodes on 64, then on 6
        rows, cols, gx, gy = _gaussian_factors(centers, 1.0, m, s, 4.8)
        assert (gx.shape[1] > m) == wider
        matrix = _gaussian_gather(centers, 1.0, m, s, 4.8)
        forces = rng.uniform(-1.0, 1.0, 300)
        mesh = np.zeros((m, m))
        _spread(rows, cols, gx, gy, forces, mesh)
        expected = (matrix.T @ forces).reshape(m, m)
        assert np.max(np.abs(mesh - expected)) < 1e-13 * np.max(np.abs(expected))
        field = rng.standard_normal((m, m))
        out = np.empty(300)
        _gather(rows, cols, gx, gy, field, out)
        gathered = matrix @ field.ravel()
        assert np.max(np.abs(out - gathered)) < 1e-13 * np.max(np.abs(gathered))


@pytest.mark.parametrize("count, smooth", [(40, False), (200, True), (200, "not positive")])
def test_contact_compliance_cg_matches_a_dense_solve(count, smooth, monkeypatch):
    """The macro step's own preconditioned CG: ``(D_A^-1 + T_AA) y_A = b_A`` against a dense solve of the
    matrix assembled column by column from the Ewald operator, some asperities out of contact; the
    product ``T y`` it sums from its iterations equals ``T`` applied to its answer. With the diagonal
    preconditioner (32 contacts), the smooth one (160), and a smooth one that is not positive (the restart with
    the diagonal)."""
    from contactlib.two_scale import compliance
    from contactlib.two_scale.compliance import SmoothPreconditioner, solve_contact_compliance

    field = ts.random_asperity_field(count, coverage=0.2, nodes_per_spacing=8, seed=2)
    table = ts.asperity_table(field)
    op = ts.PointInteraction(table, E_STAR)
    rng = np.random.default_rng(2)
    slope = rng.uniform(0.5, 2.0, table.count) * 0.05
    slope[::5] = 0.0  # out of contact
    rhs = rng.standard_normal(table.count) * 1e-3
    used, applied = [], []
    built = SmoothPreconditioner.for_contacts

    def spy(interaction, active, diagonal):
        preconditioner = built(interaction, active, diagonal)
        used.append(preconditioner is not None)
        if preconditioner is None:
            return None
        if smooth == "not positive":
            preconditioner._inverse = -preconditioner._inverse  # negative definite

        def counted(residual, out):
            applied.append(1)
            return preconditioner(residual, out)
        return counted

    monkeypatch.setattr(compliance.SmoothPreconditioner, "for_contacts", staticmethod(spy))
    y, product = solve_contact_compliance(op, slope, rhs, rtol=1e-12, with_product=True)
    assert used == [bool(smooth)]
    assert (len(applied) == 1) == (smooth == "not positive")  # refused at once, the diagonal from there on
    T = np.column_stack([op(unit) for unit in np.eye(table.count)])
    active = slope > 0
    dense = np.diag(1.0 / slope[active]) + T[np.ix_(active, active)]
    expected = np.linalg.solve(dense, rhs[active])
    np.testing.assert_allclose(y[active], expected, rtol=0, atol=1e-10 * np.abs(expected).max())
    assert np.all(y[~active] == 0)
    np.testing.assert_allclose(product, op(y), rtol=0, atol=1e-10 * np.abs(op(y)).max())


def test_smooth_preconditioner_is_symmetric_positive_and_saves_products():
    """:class:`contactlib.two_scale.compliance.SmoothPreconditioner` on 300 asperities at coverage 0.4 (Hertz slopes at
    a Newton start): symmetric to round-off, positive on random vectors, and the contact-compliance CG at rtol 1e-3
    takes 2 products instead of the diagonal's 4 (measured), to the same answer within that tolerance."""
    from contactlib.two_scale.compliance import SmoothPreconditioner, solve_contact_compliance
    from contactlib.two_scale.macro import HertzLaw

    field = ts.random_asperity_field(300, coverage=0.4, nodes_per_spacing=8, seed=1)
    table = ts.asperity_table(field)
    op = ts.PointInteraction(table, E_STAR, accuracy=1e-4)
    penetration = 0.4 * table.summit_height.mean() - (table.summit_height.max() - table.summit_height)
    slope = HertzLaw(table.radius, E_STAR).slope(penetration)
    active = np.flatnonzero(slope > 0)
    preconditioner = SmoothPreconditioner(table.centers[active], table.length, E_STAR,
                                          1 / slope[active] + op.diagonal[active])
    rng = np.random.default_rng(3)
    a, b = rng.standard_normal((2, active.size))
    Ma, Mb = np.empty(active.size), np.empty(active.size)
    assert preconditioner(a, Ma) == pytest.approx(a @ Ma, rel=1e-12)  # it returns r . M r
    preconditioner(b, Mb)
    assert abs(b @ Ma - a @ Mb) < 1e-12 * abs(b @ Ma)
    for v in rng.standard_normal((50, active.size)):
        assert preconditioner(v, np.empty(active.size)) > 0
    rhs = rng.standard_normal(table.count) * 1e-3
    answers, products = {}, {}
    for smooth in (False, True):
        calls = []

        class Counted:
            diagonal, E_star, geometry = op.diagonal, op.E_star, op.geometry

            def __call__(self, forces):
                calls.append(1)
                return op(forces)

        answers[smooth] = solve_contact_compliance(Counted(), slope, rhs, rtol=1e-3, smooth_preconditioner=smooth)
        products[smooth] = len(calls)
    assert products[True] <= products[False] - 2
    assert np.max(np.abs(answers[True] - answers[False])) < 3e-3 * np.max(np.abs(answers[False]))


def test_default_macro_tolerance_is_far_below_the_model_error():
    """The default ``macro_tol`` (1e-4), with Ewald products as accurate, against a 1e-13 solve: forces within
    1.5e-4 of the largest (1.02e-4 measured; 0.93e-4 with products at 1e-5: the Newton tolerance's share), where
    the point-load model itself is 0.5-1.1 % off (``benchmarks/RESULTS.md``)."""
    field = ts.random_asperity_field(300, coverage=0.4, nodes_per_spacing=8, seed=1)
    approach = float(field.max()) - 0.6 * float(np.mean(ts.asperity_table(field).summit_height))
    default = ts.solve(field, E=E, nu=NU, penetration=approach, scale="macro", fields=False)
    tight = ts.solve(field, E=E, nu=NU, penetration=approach, scale="macro", fields=False, macro_tol=1e-13)
    assert default.attrs["macro_tol"] == 1e-4 and default.attrs["macro_residual"] <= 1e-4
    assert default.attrs["ewald_accuracy"] == 1e-4 and tight.attrs["ewald_accuracy"] == 1e-7  # macro_tol, clipped
    assert np.max(np.abs(default.force.values - tight.force.values)) < 1.5e-4 * float(tight.force.max())


def test_two_scale_start_follows_the_outer_tolerance():
    """The macro step that starts the sweeps runs at 1e-2 of the outer tolerance (at most 1e-4): the
    sweeps' answer does not depend on it, so the forces match those from a 1e-12 start within a tenth of the
    ``force_tol`` of the solve, and a tight ``tol`` keeps the tight start."""
    field = ts.random_asperity_field(300, coverage=0.2, nodes_per_spacing=24, seed=0)
    approach = float(field.max()) - 0.6 * float(np.mean(ts.asperity_table(field).summit_height))
    loose = ts.solve(field, E=E, nu=NU, penetration=approach, force_tol=1e-2)
    tight = ts.solve(field, E=E, nu=NU, penetration=approach, force_tol=1e-2, macro_tol=1e-12)
    assert loose.attrs["macro_tol"] == 1e-4 and tight.attrs["macro_tol"] == 1e-12
    assert np.max(np.abs(loose.force.values - tight.force.values)) < 1e-3 * float(tight.force.max())  # 1.6e-5 measured
    assert ts.solve(field, E=E, nu=NU, penetration=approach, tol=1e-6, fields=False).attrs["macro_tol"] == 1e-8


def test_single_precision_window_products_agree_with_double(monkeypatch):
    """Loose local tolerances apply the window compliance in float32: each product within 2e-6 of the
    float64 one, and a two-scale solve at ``force_tol=1e-2`` (local solves at 1e-3) gives forces within
    1e-5 of the largest of the same solve in double precision (300 asperities, coverage 0.2)."""
    from contactlib.two_scale import micro
    from contactlib.two_scale.local import WindowStack

    pressure = np.random.default_rng(4).uniform(size=(7, 16, 16))
    double, single = WindowStack(16, 0.01, E_STAR), WindowStack(16, 0.01, E_STAR, single=True)
    assert single._dense.dtype == np.float32 and double._dense.dtype == np.float64
    exact = double(pressure)
    assert single(pressure).dtype == np.float64
    np.testing.assert_allclose(single(pressure), exact, rtol=0, atol=2e-6 * np.abs(exact).max())
    np.testing.assert_allclose(single(pressure[:3]), exact[:3], rtol=0, atol=2e-6 * np.abs(exact).max())

    field = ts.random_asperity_field(300, coverage=0.2, nodes_per_spacing=24, seed=0)
    approach = float(field.max()) - 0.6 * float(np.mean(ts.asperity_table(field).summit_height))
    fast = ts.solve(field, E=E, nu=NU, penetration=approach, force_tol=1e-2)
    assert 0.1 * 1e-2 >= micro.SINGLE_PRECISION_TOL  # the float32 path was the one taken
    monkeypatch.setattr(micro, "SINGLE_PRECISION_TOL", np.inf)
    slow = ts.solve(field, E=E, nu=NU, penetration=approach, force_tol=1e-2)
    assert fast.attrs["micro_iterations"] == slow.attrs["micro_iterations"]
    assert np.max(np.abs(fast.force.values - slow.force.values)) < 1e-5 * float(slow.force.max())


def test_frozen_windows_give_the_answer_of_immediate_removal(monkeypatch):
    """Done windows stay on the stack, frozen, until a quarter of it is done: the same pressures and
    iteration counts as dropping each the moment it is done (``COMPACT`` 0), and as keeping all to the
    end (``COMPACT`` 1)."""
    from contactlib.two_scale import local
    from contactlib.two_scale.local import WindowStack, solve_stack

    w, h = 16, 0.01
    stack = WindowStack(w, h, E_STAR)
    x = (np.arange(w) - w // 2) * h
    rng = np.random.default_rng(7)
    caps = [-((x[:, None] - c[0]) ** 2 + (x[None, :] - c[1]) ** 2) / (2 * (0.5 + rng.random()))
            for c in rng.random((40, 2)) * h]
    interference = np.array([c - c.max() for c in caps]) + 3e-4 * (1 + rng.random(40))[:, None, None]
    batched = solve_stack(stack, interference, tol=1e-7, max_iter=500)
    monkeypatch.setattr(local, "COMPACT", 0.0)
    at_once = solve_stack(stack, interference, tol=1e-7, max_iter=500)
    monkeypatch.setattr(local, "COMPACT", 1.0)
    kept = solve_stack(stack, interference, tol=1e-7, max_iter=500)
    assert len(set(batched[2])) > 1  # the windows finish at different iterations
    for other in (batched, kept):
        np.testing.assert_array_equal(other[2], at_once[2])
        np.testing.assert_allclose(other[0], at_once[0], rtol=0, atol=1e-12 * at_once[0].max())
        np.testing.assert_allclose(other[1], at_once[1], rtol=0, atol=1e-12 * np.abs(at_once[1]).max())


def test_known_initial_displacement_saves_a_product_and_nothing_else():
    """A warm start whose displacement the caller has (the sweeps' ``K_w p``): the same answer and
    iterations as computing it, one product fewer."""
    from contactlib.two_scale.local import WindowStack, solve_stack

    w, h = 16, 0.01
    stack = WindowStack(w, h, E_STAR)
    x = (np.arange(w) - w // 2) * h
    r2 = x[:, None] ** 2 + x[None, :] ** 2
    interference = np.array([3e-4 * k - r2 / (2 * 0.8) for k in (1.0, 1.5, 2.0)])
    start = np.maximum(interference, 0.0) * 0.5 / stack.self_compliance  # a rough warm start
    counted = []
    original = stack.__call__

    class Counting(WindowStack):
        def __call__(self, pressure):
            counted.append(pressure.shape[0])
            return original(pressure)

    stack.__class__ = Counting
    plain = solve_stack(stack, interference, tol=1e-8, max_iter=500, initial_pressure=start)
    products = len(counted)
    known = solve_stack(stack, interference, tol=1e-8, max_iter=500, initial_pressure=start,
                        initial_displacement=original(start))
    assert len(counted) - products == products - 1
    np.testing.assert_array_equal(known[2], plain[2])
    np.testing.assert_allclose(known[0], plain[0], rtol=0, atol=1e-12 * plain[0].max())


def test_pair_kernel_and_cached_pairs_match_a_fresh_query_and_the_sparse_matrix():
    """The Ewald short-range part by the numba pair kernel against a sparse matrix of the pairs from a fresh
    k-d tree query (not the table's cached one), and the cached narrower queries against fresh ones."""
    from scipy import sparse
    from scipy.spatial import cKDTree

    field = ts.random_asperity_field(400, coverage=0.3, nodes_per_spacing=4, seed=4)
    table = ts.asperity_table(field)  # its overlap check has cached the widest query
    op = ts.PointInteraction(table, E_STAR)
    cutoff = op.attrs["ewald_cutoff"]
    tree = cKDTree(table.centers, boxsize=table.length)
    for distance in (cutoff, 0.5 * cutoff):
        fresh = tree.query_pairs(distance, output_type="ndarray")
        k, l, _ = table.neighbour_pairs(distance)
        assert {tuple(p) for p in fresh.tolist()} == set(zip(k.tolist(), l.tolist()))
    fresh = tree.query_pairs(cutoff, output_type="ndarray")
    k, l = fresh[:, 0], fresh[:, 1]
    r = table.distance(k, l)
    w = np.array([math.erfc(op.attrs["ewald_alpha"] * v) for v in r]) / (math.pi * E_STAR * r)
    matrix = sparse.coo_matrix((np.r_[w, w], (np.r_[k, l], np.r_[l, k])), shape=(400, 400)).tocsr()
    forces = np.random.default_rng(1).uniform(0.0, 1.0, 400)
    out = np.zeros(400)
    interaction_module.add_pair_products(op._pair_k, op._pair_l, op._pair_w, forces, out)
    expected = matrix @ forces
    assert np.max(np.abs(out - expected)) < 1e-14 * np.max(np.abs(expected))


def test_finite_contact_size_halves_the_macro_error_of_a_dense_field():
    """The finite-size term of the interaction (:class:`contactlib.two_scale.macro.FiniteSize`) against the full
    solver at tol 1e-8, 200 asperities at coverage 0.4 (nearly touching): the largest asperity-force error
    1.2e-2 -> 4.4e-3 of the largest force, the total force's 1.3e-2 -> 1.1e-3 (measured; the near pairs alone
    gave 6.6e-3 and 4.1e-3)."""
    field = ts.random_asperity_field(200, coverage=0.4, nodes_per_spacing=22, seed=0)
    table = ts.asperity_table(field)
    approach = float(field.max()) - 0.6 * float(np.mean(table.summit_height))
    full = contactlib.solve(field, E=E, nu=NU, penetration=approach, tol=1e-8)
    reference = ts.asperity_forces(full.pressure, table)
    errors = {}
    for finite_size in (False, True):
        out = ts.solve(field, E=E, nu=NU, penetration=approach, scale="macro", fields=False, finite_size=finite_size)
        assert out.attrs["finite_size_correction"] == int(finite_size)
        errors[finite_size] = (np.max(np.abs(out.force.values - reference)) / reference.max(),
                               abs(out.force.values.sum() / reference.sum() - 1))
    assert errors[False][0] > 1e-2 and errors[True][0] < 5e-3
    assert errors[False][1] > 1e-2 and errors[True][1] < 2e-3


def test_finite_size_joins_the_interactions_own_pair_loop():
    """The finite-size term joins the Ewald operator's pair loop (one pair loop a product), for the accurate operator
    and its coarser copy alike, its weights formed in the loop or in an array, and the joined product equals the
    operator's plus the term's own pair sum."""
    from contactlib.two_scale.interaction import PointInteraction, add_pair_products
    from contactlib.two_scale.macro import FiniteSize

    field = ts.random_asperity_field(200, coverage=0.4, nodes_per_spacing=22, seed=0)
    table = ts.asperity_table(field)
    term = FiniteSize(table, E_STAR)
    rng = np.random.default_rng(2)
    forces, radius_squared = rng.uniform(0.5, 1.5, table.count), rng.uniform(0.5, 1.5, table.count) * 1e-4
    accurate = PointInteraction(table, E_STAR, accuracy=1e-5)
    for operator in (accurate, accurate.coarser(1e-3)):
        expected = operator(forces)
        k, l, _ = table.neighbour_pairs(table.neighbour_reach)
        add_pair_products(k, l, term.weights(radius_squared), forces, expected)
        for reused in (False, True):  # the weights formed in the pair loop, or once in an array
            joined = term.corrected(operator, radius_squared, reused=reused)
            assert isinstance(joined, PointInteraction)
            assert np.max(np.abs(joined(forces) - expected)) < 1e-13 * np.max(np.abs(expected))


def test_finite_size_far_pairs_mean_field_against_the_image_sum():
    """The finite-size term's pairs beyond the Ewald reach enter as a mean field (the continuum of summits):
    against the exact sum over those pairs and their periodic images (to 8 windows each side), for random
    forces and contact radii on 200 asperities: the mean within 4 %, the rms difference within 8 % of it
    (measured: 2.0 % and 4.8 %)."""
    from contactlib.two_scale.macro import FiniteSize

    field = ts.random_asperity_field(200, coverage=0.4, nodes_per_spacing=22, seed=0)
    table = ts.asperity_table(field)
    rng = np.random.default_rng(0)
    forces, radius_squared = rng.uniform(0.5, 1.5, table.count), rng.uniform(0.5, 1.5, table.count) * 1e-4
    term = FiniteSize(table, E_STAR)
    k, l, r = table.neighbour_pairs(table.neighbour_reach)
    weight = (2 / 15) / (math.pi * E_STAR * r**3) * (radius_squared[k] + radius_squared[l])
    near = np.zeros(table.count)
    np.add.at(near, k, weight * forces[l])
    np.add.at(near, l, weight * forces[k])
    mean_field = term(radius_squared, forces) - near
    L, reach, exact = table.length, table.neighbour_reach, np.zeros(table.count)
    for i in range(-8, 9):
        for j in range(-8, 9):
            d = np.sqrt((((table.centers[:, None, :] - table.centers[None, :, :] + [i * L, j * L])) ** 2).sum(-1))
            far = d >= reach
            w = np.where(far, (2 / 15) / (math.pi * E_STAR * np.where(far, d, 1.0) ** 3), 0.0)
            exact += (w * (radius_squared[:, None] + radius_squared[None, :]) * forces[None, :]).sum(1)
    assert abs(mean_field.mean() / exact.mean() - 1) < 0.04
    assert np.sqrt(np.mean((mean_field - exact) ** 2)) < 0.08 * exact.mean()


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_non_finite_heights_are_refused(bad):
    h = ts.random_asperity_field(20, coverage=0.2, nodes_per_spacing=6, seed=0)
    h.values[3, 4] = bad
    with pytest.raises(ValueError, match="heights contain NaN or infinite"):
        ts.asperity_table(h)


def test_coarser_products_for_the_newton_steps_leave_the_answer():
    """:meth:`PointInteraction.coarser`: its products within its accuracy (1e-3) of the accurate ones; the macro
    solve whose Newton steps use it converges in as many iterations to the answer of one that does not (both
    residuals measured with the accurate products), within the Newton tolerance."""
    from contactlib.two_scale import macro

    field = ts.random_asperity_field(500, coverage=0.4, nodes_per_spacing=8, seed=3)
    table = ts.asperity_table(field)
    op = ts.PointInteraction(table, E_STAR, accuracy=1e-5)
    coarse = op.coarser(1e-3)
    assert coarse.attrs is op.attrs and coarse._mesh < op._mesh and coarse._gx.shape[1] < op._gx.shape[1]
    assert op.coarser(1e-6) is op
    forces = np.random.default_rng(3).uniform(0.0, 1.0, table.count)
    exact = op(forces)
    assert np.max(np.abs(coarse(forces) - exact)) < 1e-3 * np.max(np.abs(exact))
    law = ts.HertzLaw(table.radius, E_STAR)
    approach = float(field.max()) - 0.6 * float(np.mean(table.summit_height))
    z_top = float(field.max())
    with_coarse = ts.solve_macro(table, op, law, penetration=approach, z_top=z_top, tol=1e-4)
    original = macro.JACOBIAN_ACCURACY
    try:
        macro.JACOBIAN_ACCURACY = 1.0  # never looser than the linear solve's tolerance: the accurate products
        without = ts.solve_macro(table, op, law, penetration=approach, z_top=z_top, tol=1e-4)
    finally:
        macro.JACOBIAN_ACCURACY = original
    assert with_coarse.converged and with_coarse.iterations == without.iterations
    assert np.max(np.abs(with_coarse.force - without.force)) < 1e-4 * float(without.force.max())


@pytest.mark.parametrize("count, reach, periodic, spread", [
    (1000, 0.079, True, 1.0), (1000, 0.079, False, 1.0), (30, 0.9, True, 1.0), (30, 0.4, True, 1.0),
    (200, 0.4, False, 1.0), (5, 0.0, True, 1.0), (400, 0.05, True, 0.1)])
def test_cell_list_pairs_match_a_kd_tree(count, reach, periodic, spread):
    """The neighbour pairs of the numba cell list against scipy's k-d tree (periodic or not, one cell or many,
    points on the window's edges, points clustered in a tenth of the window: 40x the room first allocated, walked
    again), and their distances against the nearest image's."""
    from scipy.spatial import cKDTree

    from contactlib.two_scale.asperities import cell_pairs

    rng = np.random.default_rng(count)
    centers = rng.uniform(0.0, spread, (count, 2))
    centers[0], centers[-1] = [0.0, 0.0], [1.0 - 1e-12, 0.5]
    k, l, r = cell_pairs(centers, 1.0, reach, periodic)
    fresh = cKDTree(centers, boxsize=1.0 if periodic else None).query_pairs(reach, output_type="ndarray")
    assert np.all(k < l) and {tuple(p) for p in fresh.tolist()} == set(zip(k.tolist(), l.tolist()))
    d = centers[k] - centers[l]
    if periodic:
        d -= np.rint(d)
    np.testing.assert_allclose(r, np.hypot(d[:, 0], d[:, 1]), rtol=1e-14, atol=1e-15)


def test_study_grid_is_a_fast_size_never_coarser():
    from contactlib.studies.two_scale import grid_points, nodes_per_spacing, smooth_size

    assert [smooth_size(n) for n in (696, 1929, 3100, 2200, 980, 1)] == [700, 1944, 3125, 2205, 980, 1]
    for count, coverage in ((1000, 0.4), (1000, 0.05), (10000, 0.2)):
        n = grid_points(count, coverage, 3.0)
        assert n >= round(nodes_per_spacing(coverage, 3.0) * math.sqrt(count))
    a = ts.asperity_table(ts.random_asperity_field(50, coverage=0.2, nodes_per_spacing=8, seed=0))
    b = ts.asperity_table(ts.random_asperity_field(50, coverage=0.2, nodes_per_spacing=8, seed=0, n=63))
    assert b.grid.shape == (63, 63) and np.array_equal(a.centers, b.centers)
    np.testing.assert_array_equal(a.summit_height, b.summit_height)


def test_heights_edited_after_the_table_are_refused():
    """The macro scale reads the asperity table, the micro scale the heights: a spheres DataArray whose heights were
    scaled afterwards was solved silently as two different surfaces. Heights above the highest summit are refused."""
    h = contactlib.surfaces.spheres(64, radius=0.5, lattice=4, summit_height=0.01, height_std=0.001)
    edited = h.copy()
    edited.values[:] *= 2
    with pytest.raises(ValueError, match="heights were changed after the table was made"):
        contactlib.two_scale.solve(edited, E=1.0, nu=0.5, mean_pressure=1e-4)
    with pytest.raises(ValueError, match="n must be a whole number"):
        contactlib.two_scale.solve(h, E=1.0, nu=0.5, mean_pressure=1e-4, n=64.7)
    assert contactlib.two_scale.solve(h, E=1.0, nu=0.5, mean_pressure=1e-4).attrs["converged"] == 1


def test_unconverged_steps_say_why():
    """Where an iteration fails on a scene past the method's reach, the ConvergenceError says which reach: a nearly
    touching field (coverage 0.5) pressed to 0.95 of its summit height, whose macro Newton iterate wanders past
    separate caps (an asperity pressed 3.6x its summit height); contacts a seventh of the grid spacing under load
    control, where the micro step's outer iteration does not settle."""
    field = ts.random_asperity_field(100, coverage=0.5, nodes_per_spacing=16, height_scatter=0.0, seed=0)
    z = float(np.mean(ts.asperity_table(field).summit_height))
    with pytest.raises(contactlib.ConvergenceError, match="past the method's assumption .* no longer separate caps"):
        ts.solve(field, E=1.0, nu=0.5, penetration=float(field.max()) - 0.05 * z, scale="macro", fields=False)
    field = ts.random_asperity_field(10, coverage=0.05, nodes_per_spacing=16, height_scatter=0.0, seed=0)
    z = float(np.mean(ts.asperity_table(field).summit_height))
    approach = float(field.max()) - 0.99 * z
    load = float(ts.solve(field, E=1.0, nu=0.5, penetration=approach, scale="macro", fields=False).mean_pressure)
    assert ts.solve(field, E=1.0, nu=0.5, penetration=approach).attrs["converged"] == 1
    with pytest.raises(contactlib.ConvergenceError, match="the micro scale does not resolve the contacts"):
        ts.solve(field, E=1.0, nu=0.5, mean_pressure=load, max_iter=50)


def test_short_range_weights_match_scipy_erfc():
    """The Ewald pair weights' series (``ewald_weights._erfcx_times``) against scipy's erfc over its whole reach, and
    scipy itself past it."""
    from scipy.special import erfc

    from contactlib.two_scale.ewald_weights import ERFC_SERIES_REACH, short_range_weights

    r = np.linspace(1e-9, 1.0, 200_001)
    for alpha in (0.5, ERFC_SERIES_REACH, 9.0):
        weights = short_range_weights(alpha, r, 1.3)
        exact = erfc(alpha * r) / (np.pi * 1.3 * r)
        assert np.abs(weights / exact - 1).max() <= 2e-13
    grid = r[: 200 * 1000].reshape(200, 1000)  # any shape, as scipy's
    np.testing.assert_allclose(short_range_weights(2.0, grid, 1.3), erfc(2.0 * grid) / (np.pi * 1.3 * grid), rtol=2e-13)
