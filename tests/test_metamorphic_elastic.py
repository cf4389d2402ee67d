"""Metamorphic properties of frictionless elastic contact (contactlib.solve, solve_tolerances), on random scenes.

Each property relates two solves whose answers must agree exactly in the continuum and on the grid. They are
compared at the accuracy the solver promises, not at round-off. Every solve runs at ``TOL`` = 1e-10, the
scale-free residual (:func:`contactlib.solvers.contact_residual`): the mean gap on the contact relative to the
rms height. A gap error ``e h_rms`` in a mode of wavenumber ``q`` costs a pressure error ``E* q e h_rms / 2``.
The peak pressure is at least ``E* q_rms h_rms / 2``, so relative to it the pressure error is at most
``(q_max / q_rms) e``. That ratio is below the grid's ``n`` (at most 512 here). So ``PRESSURE_RTOL`` = 1e3 TOL
= 1e-7 of the peak bounds it with a margin of 2 or more, and ``GAP_RTOL`` = 1e-7 of the height range bounds
the gap. Measured on 24 scenes (1D 256, 2D 48^2 and 33^2): the scaling and shift relations hold to 1e-14
(the iterates are equivariant), and a solve at 1e-10 lies within 7e-10 of the peak from one at 1e-13. So the
bound leaves a margin of 100 over the solver's own error. A defect shows at 1e-4 or above (issue 38's broken
mirror symmetry was 4e-4).

The contact area compares the sets ``p > 0``. A point whose pressure is within the tolerance of zero may fall
either side, so only such points may differ (:func:`assert_same_contact`).
"""

import numpy as np
import pytest
from hypothesis import given, note, settings
from hypothesis import strategies as st

import contactlib
from contactlib import surfaces
from metamorphic import FAST, budget

# The resolution guard warns on coarse random scenes. The properties hold on any grid, so they are not
# about resolution and its warning is filtered here.
pytestmark = pytest.mark.filterwarnings(f"ignore::{contactlib.ResolutionWarning.__module__}.ResolutionWarning")

TOL = 1e-10
PRESSURE_RTOL = 1e3 * TOL  # of the peak pressure: (q_max / q_rms) TOL < n TOL, n <= 512 (module docstring)
GAP_RTOL = 1e3 * TOL  # of the height range


# --- scenes ----------------------------------------------------------------------------------------------


def bare(field) -> np.ndarray:
    """A labelled field or surface as the bare array the solvers take, indexed ``[ix, iy]`` (fields are on
    ``("y", "x")``): the transforms below act on those axes."""
    return field.transpose("x", ...).values


@st.composite
def rough_scenes(draw, dim=None, sizes=None):
    """A periodic self-affine surface within :func:`contactlib.surfaces.self_affine`'s documented limits, a
    material and a load that leaves it in partial contact (a fraction of ``E* rms_slope``)."""
    dim = draw(st.sampled_from([1, 2])) if dim is None else dim
    sizes = sizes or ((48, 512) if dim == 1 else (16, 64))
    n = draw(st.integers(*sizes))
    # a band of one wavenumber (q_cutoff = q_roll) included: its edge modes are kept at every window length
    # (test_surfaces.py::test_band_edge_modes_are_kept_whatever_the_window)
    q_roll = draw(st.integers(1, 3))
    q_cutoff = draw(st.integers(q_roll, max(q_roll + 1, n // 4)))
    heights = surfaces.self_affine(
        n, length=10 ** draw(st.floats(-6, 1)), hurst=draw(st.floats(0.3, 1.0)), q_roll=q_roll, q_cutoff=q_cutoff,
        rms_slope=10 ** draw(st.floats(-2.5, -0.5)), seed=draw(st.integers(0, 2**16)), dim=dim)
    E = 10 ** draw(st.floats(-3, 11))
    nu = draw(st.floats(-0.9, 0.5))
    load = draw(st.floats(0.003, 0.3)) * E / (1 - nu**2) * _rms_slope(heights)
    note(f"n={n} dim={dim} q_roll={q_roll} q_cutoff={q_cutoff} E={E:.3g} nu={nu:.3f} load={load:.3g}")
    return heights, dict(E=E, nu=nu, mean_pressure=load)


def _rms_slope(heights) -> float:
    """The rms gradient of the periodic heights, spectrally (as :func:`surfaces.self_affine` defines it)."""
    h = bare(heights)
    length = float(heights.x[1] - heights.x[0]) * h.shape[0]
    hq = np.fft.fftn(h) / h.size
    q2 = sum(k**2 for k in np.meshgrid(*[2 * np.pi * np.fft.fftfreq(s, length / s) for s in h.shape],
                                         indexing="ij"))
    return float(np.sqrt(np.sum(q2 * np.abs(hq) ** 2)))


@st.composite
def isolated_scenes(draw):
    """A paraboloid (sphere or cylinder) pressed into a non-periodic half-space, its contact 4-30 % of the
    window wide."""
    dim = draw(st.sampled_from([1, 2]))
    n = draw(st.integers(64, 256) if dim == 1 else st.integers(24, 48))
    length = 10 ** draw(st.floats(-5, 0))
    radius = length * 10 ** draw(st.floats(0, 2))
    E = 10 ** draw(st.floats(-3, 11))
    nu = draw(st.floats(-0.9, 0.5))
    E_star = E / (1 - nu**2)
    a = draw(st.floats(0.04, 0.3)) * length / 2  # contact half-width / radius
    # Hertz: the line load (1D) or total load (2D) that gives ``a``, over the window
    load = (np.pi * E_star * a**2 / (4 * radius)) / length if dim == 1 else \
        (4 * E_star * a**3 / (3 * radius)) / length**2
    heights = surfaces.paraboloid(n, length=length, radius=radius, dim=dim)
    note(f"n={n} dim={dim} length={length:.3g} radius={radius:.3g} E={E:.3g} nu={nu:.3f} a/L={a / length:.3f}")
    return heights, dict(E=E, nu=nu, mean_pressure=load, periodic=False)


scenes = st.one_of(rough_scenes(), isolated_scenes())


# --- comparisons -----------------------------------------------------------------------------------------


def assert_same_pressure(got: np.ndarray, expected: np.ndarray):
    peak = float(np.abs(expected).max())
    error = float(np.abs(got - expected).max()) / peak
    note(f"pressure difference {error:.2e} of the peak")
    assert error <= PRESSURE_RTOL, f"pressures differ by {error:.2e} of the peak (bound {PRESSURE_RTOL:.0e})"


def assert_same_contact(got: np.ndarray, expected: np.ndarray):
    """The contact sets ``p > 0`` agree except at points whose pressure is within the tolerance of zero."""
    peak = float(np.abs(expected).max())
    differ = (got > 0) != (expected > 0)
    ambiguous = np.maximum(np.abs(got), np.abs(expected)) <= PRESSURE_RTOL * peak
    assert np.all(ambiguous[differ]), f"{int(np.sum(differ & ~ambiguous))} points change contact"


def assert_same_field(got: np.ndarray, expected: np.ndarray, scale: float, name: str):
    error = float(np.abs(got - expected).max()) / scale
    assert error <= GAP_RTOL, f"{name} differs by {error:.2e} of the height range (bound {GAP_RTOL:.0e})"


def solve(heights, **kwargs):
    return contactlib.solve(heights, tol=TOL, **kwargs)


# --- properties ------------------------------------------------------------------------------------------


@settings(max_examples=budget(40), **FAST)
@given(scene=scenes, factor=st.floats(-3, 3))
def test_scaling_modulus_and_load_scales_the_pressure_only(scene, factor):
    """E -> s E, load -> s load: the same contact and displacement, the pressure s times (the problem is
    linear in E* and p for fixed displacements)."""
    heights, kw = scene
    s = 10.0**factor
    a = solve(heights, **kw)
    b = solve(heights, **{**kw, "E": s * kw["E"], "mean_pressure": s * kw["mean_pressure"]})
    assert_same_pressure(bare(b.pressure) / s, bare(a.pressure))
    assert_same_contact(bare(b.pressure), bare(a.pressure))
    scale = float(np.ptp(bare(heights)))
    assert_same_field(bare(b.displacement), bare(a.displacement), scale, "displacement")
    assert_same_field(bare(b.gap), bare(a.gap), scale, "gap")
    assert float(b.penetration) == pytest.approx(float(a.penetration), rel=GAP_RTOL, abs=GAP_RTOL * scale)


@settings(max_examples=budget(40), **FAST)
@given(scene=scenes, factor=st.floats(-3, 3))
def test_scaling_heights_and_load_scales_pressure_and_gap(scene, factor):
    """h -> s h, load -> s load: the same contact, pressure, gap and displacement s times."""
    heights, kw = scene
    s = 10.0**factor
    a = solve(heights, **kw)
    b = solve(heights * s, **{**kw, "mean_pressure": s * kw["mean_pressure"]})
    assert_same_pressure(bare(b.pressure) / s, bare(a.pressure))
    assert_same_contact(bare(b.pressure), bare(a.pressure))
    scale = float(np.ptp(bare(heights)))
    assert_same_field(bare(b.gap) / s, bare(a.gap), scale, "gap")
    assert_same_field(bare(b.displacement) / s, bare(a.displacement), scale, "displacement")
    assert float(b.penetration) / s == pytest.approx(float(a.penetration), rel=GAP_RTOL, abs=GAP_RTOL * scale)


@settings(max_examples=budget(60), **FAST)
@given(scene=rough_scenes(), data=st.data())
def test_periodic_shift_shifts_the_answer(scene, data):
    """np.roll of periodic heights by whole spacings rolls the pressure and gap, and keeps every scalar."""
    heights, kw = scene
    shift = tuple(data.draw(st.integers(0, s - 1), label=f"shift{k}") for k, s in enumerate(heights.shape))
    axes = tuple(range(heights.ndim))
    length = float(heights.x[1] - heights.x[0]) * heights.shape[0]
    a = solve(heights, **kw)
    b = solve(np.roll(bare(heights), shift, axis=axes), length=length, **kw)
    assert_same_pressure(bare(b.pressure), np.roll(bare(a.pressure), shift, axis=axes))
    assert_same_contact(bare(b.pressure), np.roll(bare(a.pressure), shift, axis=axes))
    assert_same_field(bare(b.gap), np.roll(bare(a.gap), shift, axis=axes), float(np.ptp(bare(heights))), "gap")
    assert float(b.penetration) == pytest.approx(float(a.penetration), rel=GAP_RTOL)


def mirror(field: np.ndarray, axis: int) -> np.ndarray:
    """``x -> -x`` along ``axis`` on a periodic grid: node ``i`` goes to ``-i mod n``."""
    return np.roll(np.flip(field, axis=axis), 1, axis=axis)


@settings(max_examples=budget(60), **FAST)
@given(scene=rough_scenes(dim=2), transform=st.sampled_from(["transpose", "mirror x", "mirror y", "rotate 180"]))
def test_transposition_and_mirrors_of_a_frictionless_surface(scene, transform):
    """Frictionless contact on an isotropic half-space has the symmetries of the square grid."""
    heights, kw = scene
    op = {"transpose": lambda f: f.T, "mirror x": lambda f: mirror(f, 0), "mirror y": lambda f: mirror(f, 1),
          "rotate 180": lambda f: mirror(mirror(f, 0), 1)}[transform]
    length = float(heights.x[1] - heights.x[0]) * heights.shape[0]
    a = solve(heights, **kw)
    b = solve(op(bare(heights)), length=length, **kw)
    assert_same_pressure(bare(b.pressure), op(bare(a.pressure)))
    assert_same_contact(bare(b.pressure), op(bare(a.pressure)))


@settings(max_examples=budget(60), **FAST)
@given(scene=st.one_of(rough_scenes(), isolated_scenes()), ratio=st.floats(1.05, 4.0))
def test_contact_area_grows_with_the_load(scene, ratio):
    """A frictionless half-space's contact set grows with the load (its discrete stiffness has no positive
    off-diagonal entry, so the solution is monotone in the load): the area at ``ratio`` times the load
    holds every point of the lighter contact, up to the points within the tolerance of zero pressure."""
    heights, kw = scene
    light = solve(heights, **kw)
    heavy = solve(heights, **{**kw, "mean_pressure": ratio * kw["mean_pressure"]})
    peak = float(heavy.pressure.max())
    lost = (bare(light.pressure) > PRESSURE_RTOL * peak) & (bare(heavy.pressure) <= 0)
    assert not lost.any(), f"{int(lost.sum())} points leave the contact as the load grows"
    assert float(heavy.contact_area) >= float(light.contact_area) - np.sum(
        (bare(light.pressure) > 0) & (bare(light.pressure) <= PRESSURE_RTOL * peak)) / heights.size
    assert float(heavy.penetration) > float(light.penetration)


@settings(max_examples=budget(30), **FAST)
@given(scene=st.one_of(rough_scenes(), isolated_scenes()),
       tols=st.lists(st.sampled_from([1e-5, 1e-6, 1e-7, 1e-8, 1e-9]), min_size=1, max_size=3, unique=True))
def test_solve_tolerances_is_each_separate_solve(scene, tols):
    """solve_tolerances documents its answers as bit for bit those of separate solves at each tolerance."""
    heights, kw = scene
    kw = dict(kw)
    E, nu = kw.pop("E"), kw.pop("nu")
    together = contactlib.solve_tolerances(heights, tols, E=E, nu=nu, **kw)
    for t, got in zip(tols, together):
        alone = contactlib.solve(heights, E=E, nu=nu, tol=t, **kw)
        np.testing.assert_array_equal(bare(got.pressure), bare(alone.pressure))
        assert int(got.iterations) == int(alone.iterations) and float(got.residual) == float(alone.residual)
        assert float(got.residual) <= t


@settings(max_examples=budget(40), **FAST)
@given(scene=rough_scenes(), q0h=st.floats(2.0, 40.0), base=st.sampled_from(["confined", "remote_pressure"]))
def test_thick_layer_is_the_half_space(scene, q0h, base):
    """A layer of thickness h answers as the half-space to within its compliance's largest relative deviation
    from it over the grid's wavevectors, ``eps = max_q |f(q h) - 1|`` (the solution of a linear problem moves at
    most in proportion); as thick as it gets (eps below the tolerance), the two agree to the tolerance."""
    from contactlib.kernels.layer import layer_factors

    heights, kw = scene
    kw = {**kw, "nu": min(abs(kw["nu"]), 0.5)}  # layers take 0 <= nu <= 0.5
    length = float(heights.x[1] - heights.x[0]) * heights.shape[0]
    thickness = q0h * length / (2 * np.pi)
    q = 2 * np.pi / length * np.arange(1, max(heights.shape) + 1)
    eps = float(np.abs(layer_factors(q * thickness, kw["nu"], base)["normal"] - 1).max())
    half = solve(heights, **kw)
    layer = solve(heights, layer=contactlib.Layer(thickness, base=base), **kw)
    note(f"h = {thickness / length:.3g} L, eps = {eps:.2e}, model {layer.attrs['model']!r}")
    peak = float(half.pressure.max())
    error = float(np.abs(bare(layer.pressure) - bare(half.pressure)).max()) / peak
    assert error <= 10 * eps + PRESSURE_RTOL, f"{error:.2e} of the peak against eps {eps:.2e}"
    if eps <= 1e-3 * TOL:  # far within the tolerance: the reduced model must be the half-space
        assert layer.attrs["model"].startswith("half-space")
