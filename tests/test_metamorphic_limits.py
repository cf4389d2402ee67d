"""Limits and closed forms over random scenes: adhesion as its work vanishes (solve, adhesion_curve), one Prony term
stepped in time against its closed form and rescaled in time (solve_transient, solve_reciprocating), two-scale with
one asperity against Hertz (two_scale.solve), and the surface generators (contactlib.surfaces).

Each bound is stated where it is used, from the tolerance asked or the measured rule it rests on.
"""

import math

import numpy as np
import pytest
from hypothesis import given, note, settings
from hypothesis import strategies as st

import contactlib
import contactlib.two_scale as ts
from contactlib import resolution, surfaces
from contactlib.analysis import statistics
from contactlib.kernels.layer import zero_mode_compliance
from contactlib.kernels.tensor import surface_green_tensor
from contactlib.reference import hertz
from metamorphic import FAST, Scene, budget

pytestmark = [pytest.mark.filterwarnings(f"ignore::{contactlib.ResolutionWarning.__module__}.ResolutionWarning"),
              pytest.mark.filterwarnings("ignore::contactlib.TimeStepWarning")]


# --- adhesion as the work vanishes --------------------------------------------------------------------------

ADHESION_TOL = 1e-8
# The cohesive and energy solvers stop on the same scale-free residual as the plain solve. So, as in
# tests/test_metamorphic_elastic.py, their pressures agree to 1e3 times the looser tolerance, relative to the
# peak. The vanishing law adds its own traction, at most w / range, wherever the gap is within its range.
ADHESION_RTOL = 1e3 * ADHESION_TOL


@st.composite
def spheres_to_adhere(draw):
    """A sphere (2D) or cylinder (1D) pressed into a non-periodic half-space, contact 8-30 % of the window."""
    dim = draw(st.sampled_from([1, 2]))
    # even n: the energy method takes a surface symmetric about its highest point, which paraboloid's cell-centred
    # nodes give only on an even grid
    n = 2 * draw(st.integers(32, 128) if dim == 1 else st.integers(20, 32))
    length = 10 ** draw(st.floats(-4, 0))
    radius = length * 10 ** draw(st.floats(0, 1.5))
    E = 10 ** draw(st.floats(-2, 9))
    spacings = draw(st.floats(5.0, 0.15 * n))  # contact radius in grid spacings, at most 0.3 of the half-window
    a = spacings * length / n
    heights = surfaces.paraboloid(n, length=length, radius=radius, dim=dim)
    return Scene((heights, dict(E=E, nu=0.5, periodic=False), a**2 / radius, radius, spacings),
                 f"paraboloid(n={n}, length={length:.3g}, radius={radius:.3g}, dim={dim}) E={E:.3g} "
                 f"a={spacings:.3g} spacings")


def vanishing(draw, scene, model):
    """An Adhesion whose largest traction is 1e-12 to 1e-9 of E* (of the Hertz peak, 1e-10 to 1e-8 or so)."""
    heights, kw, depth, radius, _ = scene
    E_star = kw["E"] / (1 - kw["nu"] ** 2)
    stress = 10 ** draw(st.floats(-12, -9)) * E_star
    if model == "jkr":
        return contactlib.Adhesion(work=draw(st.sampled_from([0.0, stress * depth])), model="jkr"), 0.0
    reach = 10 ** draw(st.floats(-2, 0)) * depth  # range
    return contactlib.Adhesion(work=stress * reach, range=reach, model=model), stress


@settings(max_examples=budget(20), **FAST)
@given(scene=spheres_to_adhere(), model=st.sampled_from(["maugis", "exponential", "jkr"]),
       control=st.sampled_from(["penetration", "mean_pressure"]), data=st.data())
def test_vanishing_work_of_adhesion_is_no_adhesion(scene, model, control, data):
    """w -> 0: the adhesive solve is the plain one, under either control, for the cohesive laws and the energy
    method (whose ``work`` may be 0). The energy method's contact is a disc (or interval) of whole spacings, a
    discretisation of its own: it may differ from the plain solve by the measured resolution rule at the contact's
    radius (:func:`contactlib.resolution.predicted_error`)."""
    heights, kw, depth, radius, spacings = scene
    adhesion, stress = vanishing(data.draw, scene, model)
    note(f"{adhesion}")
    plain = contactlib.solve(heights, penetration=depth, tol=1e-10, **kw)
    asked = dict(penetration=depth) if control == "penetration" else dict(mean_pressure=float(plain.mean_pressure))
    sticky = contactlib.solve(heights, adhesion=adhesion, tol=ADHESION_TOL, **asked, **kw)
    peak = float(plain.pressure.max())
    grid_error = resolution.predicted_error("points_per_contact_radius", spacings) if model == "jkr" else 0.0
    bound = ADHESION_RTOL + 10 * stress / peak + grid_error
    error = float(np.abs(sticky.pressure.values - plain.pressure.values).max()) / peak
    assert error <= bound, f"pressure {error:.2e} of the peak off the plain solve (bound {bound:.2e})"
    assert float(sticky.mean_pressure) == pytest.approx(float(plain.mean_pressure), rel=bound)
    assert float(sticky.penetration) == pytest.approx(depth, rel=bound)


@settings(max_examples=budget(8), **FAST)
@given(scene=spheres_to_adhere().filter(lambda s: s[0].ndim == 2), model=st.sampled_from(["maugis", "jkr"]),
       data=st.data())
def test_vanishing_work_adhesion_curve_is_the_plain_path(scene, model, data):
    """w -> 0: a loading-unloading path retraces the plain solves without hysteresis, and its pull-off (at most
    2 pi w R, DMT's, over the window) vanishes with w. The path starts and ends out of contact, beyond the law's
    range (at most ``depth``): a path that stays compressive never reaches the turning point, and its pull-off is
    NaN with ``attrs['pull_off_status']`` (a cohesive law's comes from the sampled branch; JKR's from its
    equilibrium curve G = w, whatever the sampling)."""
    heights, kw, depth, radius, spacings = scene
    adhesion, stress = vanishing(data.draw, scene, model)
    note(f"{adhesion}")
    depths = depth * np.array([-2.0, 0.25, 0.5, 1.0])
    path = contactlib.adhesion_curve(heights, adhesion=adhesion, penetrations=depths, tol=ADHESION_TOL, **kw)
    plain = [float(contactlib.solve(heights, penetration=d, tol=1e-10, **kw).mean_pressure) for d in depths]
    assert plain[0] == 0.0  # out of contact
    expected = np.concatenate([plain, plain[-2::-1]])
    grid_error = resolution.predicted_error("points_per_contact_radius", spacings / 2) if model == "jkr" else 0.0
    # the vanishing law's traction, at most w / range, moves the mean pressure by at most that over the least load
    traction = 10 * stress / plain[1]
    np.testing.assert_allclose(path.mean_pressure.values, expected, rtol=ADHESION_RTOL + grid_error + traction,
                               atol=stress)
    length = float(heights.x[-1] - heights.x[0]) * heights.shape[0] / (heights.shape[0] - 1)
    pull_off = float(path.pull_off_pressure)
    plain = plain[1:]
    bound = 2 * math.pi * adhesion.work * radius / length**2 + ADHESION_RTOL * plain[0]
    assert math.isfinite(pull_off) and -bound <= pull_off <= 0, f"pull_off_pressure {pull_off!r}, bound {bound:.2e}"
    assert abs(float(path.hysteresis_energy)) <= ADHESION_RTOL * plain[-1] * depth


# --- one Prony term in time ---------------------------------------------------------------------------------

STEP_TOL = 1e-10  # each step's contact tolerance


@st.composite
def standard_linear_solids(draw):
    ratio = 10 ** draw(st.floats(0.1, 2.5))
    tau = 10 ** draw(st.floats(-3, 3))
    nu = draw(st.floats(0.0, 0.45))
    E0 = 10 ** draw(st.floats(-2, 9))
    return contactlib.Viscoelastic.standard_linear_solid(E0=E0, E_inf=ratio * E0, tau=tau, nu=nu)


@st.composite
def profiles(draw, sizes=(32, 128)):
    n = draw(st.integers(*sizes))
    q_cutoff = draw(st.integers(2, n // 4))
    slope, seed = 10 ** draw(st.floats(-2, -0.7)), draw(st.integers(0, 2**16))
    h = surfaces.self_affine(n, hurst=0.8, q_roll=1, q_cutoff=q_cutoff, rms_slope=slope, seed=seed, dim=1)
    return Scene((h,), f"self_affine({n}, hurst=0.8, q_roll=1, q_cutoff={q_cutoff}, rms_slope={slope:.3g}, "
                       f"seed={seed}, dim=1)")


@st.composite
def step_times(draw, scale, span, steps):
    """``steps + 1`` increasing instants from 0 over ``span`` times ``scale``, unevenly spaced (ratio up to 5)."""
    widths = np.array(draw(st.lists(st.floats(0.2, 1.0), min_size=steps, max_size=steps)))
    return np.concatenate([[0.0], np.cumsum(widths) / widths.sum() * span * scale])


@settings(max_examples=budget(25), **FAST)
@given(material=standard_linear_solids(), surface=profiles(), data=st.data())
def test_full_contact_on_a_confined_layer_relaxes_and_creeps_in_closed_form(material, surface, data):
    """A confined compressible layer pressed beyond full contact under a constant mean pressure ``p``: every
    Fourier mode of the pressure at q != 0 holds its displacement (the surface) and so relaxes as ``E(t)``. The
    stepping rule is exact at fixed displacement, so these match to the step tolerance times the grid's stiffness
    spread, 1e3 STEP_TOL. The mean mode carries ``p`` and creeps as the SLS closed form:
    ``penetration(t) - penetration(0) = p C0 (J(t) - J(0))``, ``C0`` the layer's uniaxial compliance at unit
    modulus. The rule is second order in ``dt``; its error, relative to the creep, scales as
    ``(E_inf / E0) (dt / tau_creep)^2`` (measured 0.026 times it at E_inf/E0 = 5 and 0.030 at 100, even steps),
    so the bound is 0.1 times it at the longest step."""
    (h,) = surface
    nu = material.nu
    tau = material.prony[0][1]
    creep_time = tau * material.E_inf / material.E0
    steps = data.draw(st.integers(15, 40), label="steps")
    times = data.draw(step_times(creep_time, data.draw(st.floats(0.5, 4.0), label="span"), steps), label="times")
    thickness = data.draw(st.floats(0.02, 0.3), label="thickness")
    grid = contactlib.Grid(h.shape, (1.0,))
    unit = surface_green_tensor(grid, 1.0, nu, thickness, "confined").normal  # displacement per pressure, E = 1
    hq = np.fft.rfft(h.values)
    nonzero = grid.wavenumber() > 0
    # twice the load that flattens the profile at the glassy modulus: E(t) <= E_inf keeps it in full contact
    flattening = hq * 0
    flattening[nonzero] = hq[nonzero] / unit[nonzero]
    pm = 2 * material.E_inf * float(-np.fft.irfft(flattening, h.shape[0]).min())
    out = contactlib.solve_transient(h, material=material, times=times, mean_pressure=pm, tol=STEP_TOL,
                                     layer=contactlib.Layer(thickness), save_fields=True)
    assert float(out.contact_area.min()) == 1.0
    for k, t in enumerate(out.saved_time.values):
        pq = np.fft.rfft(out.pressure.isel(saved_time=k).values)
        exact = hq[nonzero] * material.relaxation(t) / unit[nonzero]
        error = np.linalg.norm(pq[nonzero] - exact) / np.linalg.norm(exact)
        assert error <= 1e3 * STEP_TOL, f"step {k}: pressure modes off E(t) by {error:.2e}"
    C0 = zero_mode_compliance(thickness, 1.0, nu, "confined")["normal"]
    creep = pm * C0 * (material.creep(times) - material.creep(0.0))
    got = out.penetration.values - out.penetration.values[0]
    bound = 0.1 * material.E_inf / material.E0 * (float(np.diff(times).max()) / creep_time) ** 2
    error = float(np.abs(got - creep).max() / np.abs(creep).max())
    note(f"creep error {error:.2e}, bound {bound:.2e}")
    assert error <= bound + 1e3 * STEP_TOL


@settings(max_examples=budget(10), **FAST)
@given(material=standard_linear_solids(), surface=profiles(sizes=(32, 96)), factor=st.floats(-3, 3), data=st.data())
def test_rescaling_time_and_relaxation_time_changes_nothing(material, surface, factor, data):
    """``t -> s t``, ``tau -> s tau`` (and a path at speed ``V / s``): the same states at the same instants."""
    (h,) = surface
    s = 10.0**factor
    E1, tau = material.prony[0]
    slow = contactlib.Viscoelastic(E0=material.E0, prony=[(E1, s * tau)], nu=material.nu)
    times = data.draw(step_times(tau, 3.0, data.draw(st.integers(4, 12), label="steps")), label="times")
    path = times / tau / h.shape[0] * 0.5  # half a spacing per relaxation time
    pm = data.draw(st.floats(0.005, 0.1)) * material.E0 / (1 - material.nu**2) * 0.1
    a = contactlib.solve_transient(h, material=material, times=times, mean_pressure=pm, path=path, tol=STEP_TOL,
                                   initial="relaxed")
    b = contactlib.solve_transient(h, material=slow, times=s * times, mean_pressure=pm, path=path, tol=STEP_TOL,
                                   initial="relaxed")
    peak = float(a.pressure.max())
    assert float(np.abs(b.pressure.values - a.pressure.values).max()) <= 1e3 * STEP_TOL * peak
    np.testing.assert_allclose(b.penetration.values, a.penetration.values, rtol=1e3 * STEP_TOL)
    np.testing.assert_allclose(b.friction_coefficient_interlocking.values, a.friction_coefficient_interlocking.values,
                               rtol=1e-6, atol=1e3 * STEP_TOL)
    # the power is an energy per time: it scales as 1 / s
    np.testing.assert_allclose(s * b.dissipated_power.values, a.dissipated_power.values, rtol=1e-6,
                               atol=1e3 * STEP_TOL * float(np.abs(a.dissipated_power).max()))


@settings(max_examples=budget(4), **FAST)
@given(material=standard_linear_solids(), surface=profiles(sizes=(32, 64)), factor=st.floats(-2, 2),
       zeta=st.floats(-1, 1))
def test_reciprocating_cycle_depends_on_frequency_times_relaxation_time(material, surface, factor, zeta):
    """``f -> f / s``, ``tau -> s tau``: the same settled cycle, its energies per cycle unchanged."""
    (h,) = surface
    s = 10.0**factor
    E1, tau = material.prony[0]
    slow = contactlib.Viscoelastic(E0=material.E0, prony=[(E1, s * tau)], nu=material.nu)
    frequency = 10.0**zeta / tau
    pm = 0.02 * material.E0 / (1 - material.nu**2) * 0.1
    kw = dict(amplitude=0.1, mean_pressure=pm, length=1.0, tol=1e-9, max_cycles=8)
    a = contactlib.solve_reciprocating(h.values, material=material, frequency=frequency, **kw)
    b = contactlib.solve_reciprocating(h.values, material=slow, frequency=frequency / s, **kw)
    assert a.attrs["cycles"] == b.attrs["cycles"] and a.attrs["status"] == b.attrs["status"]
    scale = float(np.abs(a.dissipated_energy).max()) + 1e3 * 1e-9 * pm * 0.1
    np.testing.assert_allclose(b.dissipated_energy.values, a.dissipated_energy.values, rtol=1e-6, atol=1e-6 * scale)
    np.testing.assert_allclose(b.tangential_force_x.values, a.tangential_force_x.values, rtol=1e-6,
                               atol=1e-6 * float(np.abs(a.tangential_force_x).max()) + 1e-12 * pm)


# --- two-scale: one asperity is Hertz -------------------------------------------------------------------------


@settings(max_examples=budget(10), **FAST)
@given(n=st.integers(96, 160), radius=st.floats(0.3, 3.0), spacings=st.floats(12, 30),
       E=st.floats(-2, 9), nu=st.floats(0.0, 0.5), offset=st.tuples(st.floats(-0.5, 0.5), st.floats(-0.5, 0.5)))
def test_one_asperity_is_hertz(n, radius, spacings, E, nu, offset):
    """A lone, non-periodic sphere: the macro scale is Hertz's law exactly (1e-12), and the two-scale answer
    (the local FFT solve) is within the measured error rule of a contact ``spacings`` grid spacings in radius
    (:data:`contactlib.resolution.CONTACT_FITS`, the larger of area and pressure; the force, their integral, errs
    less)."""
    length = 0.25
    E = 10.0**E
    E_star = E / (1 - nu**2)
    a = spacings * length / n
    summit = 4 * a**2 / radius  # a summit well above the contact: the cap, not its base, touches
    centre = [0.125 + offset[0] * length / n, 0.125 + offset[1] * length / n]  # off the nodes
    h = surfaces.spheres(n, length=length, radius=radius, centers=[centre], summit_height=summit)
    h.attrs["periodic"] = 0
    depth = a**2 / radius - (summit - float(h.max()))  # counted from the highest node, as contactlib.solve does
    indentation = depth + summit - float(h.max())
    expected = hertz.sphere_load(indentation, radius=radius, E_star=E_star)
    macro = ts.solve(h, E=E, nu=nu, penetration=depth, scale="macro")
    assert float(macro.force[0]) == pytest.approx(expected, rel=1e-12)
    two = ts.solve(h, E=E, nu=nu, penetration=depth)
    bound = resolution.predicted_error("points_per_contact_radius", spacings)
    error = abs(float(two.force[0]) / expected - 1)
    note(f"two-scale force {error:.2e} off Hertz, rule {bound:.2e}")
    assert error <= bound


# --- surfaces ----------------------------------------------------------------------------------------------


@st.composite
def bands(draw, one_mode=True):
    dim = draw(st.sampled_from([1, 2]))
    n = draw(st.integers(8, 512) if dim == 1 else st.integers(8, 64))
    q_low = draw(st.integers(1, max(1, n // 8)))
    q_roll = draw(st.integers(q_low, max(q_low, n // 4)))
    q_cutoff = draw(st.integers(q_roll if one_mode else q_roll + 1, max(q_roll + 1, n // 2)))
    return dict(n=n, dim=dim, q_low=q_low, q_roll=q_roll, q_cutoff=min(q_cutoff, n // 2),
                length=10 ** draw(st.floats(-7, 3)), hurst=draw(st.floats(0.01, 1.0)), seed=draw(st.integers(0, 99)))


@settings(max_examples=budget(200), **FAST)
@given(band=bands(), slope=st.floats(-4, 0), use_height=st.booleans())
def test_self_affine_has_the_asked_rms_for_every_band(band, slope, use_height):
    """Any band the docstring allows (``0 < q_low <= q_roll <= q_cutoff <= n / 2``, whole multiples of q0 here, so
    each holds a mode of the grid) gives a surface with exactly the asked rms slope or rms height."""
    target = 10.0**slope * (band["length"] if use_height else 1.0)
    kw = dict(rms_height=target) if use_height else dict(rms_slope=target)
    h = surfaces.self_affine(**band, **kw)
    got = statistics.rms_height(h.values) if use_height else \
        statistics.rms_slope(h.values, length=(band["length"],) * band["dim"])
    assert got == pytest.approx(target, rel=1e-10)


@settings(max_examples=budget(100), **FAST)
@given(band=bands(one_mode=False), factor=st.floats(-3, 3))
def test_self_affine_scales_with_its_rms_and_its_window(band, factor):
    """Same seed: the heights are linear in the rms asked, and a window ``s`` times longer at the same rms height
    is the same surface on the new coordinates (the band is in multiples of ``q0``)."""
    s = 10.0**factor
    base = surfaces.self_affine(**band, rms_height=band["length"])
    scaled = surfaces.self_affine(**band | {"length": s * band["length"]}, rms_height=band["length"])
    np.testing.assert_allclose(scaled.values, base.values, rtol=0, atol=1e-12 * float(np.abs(base).max()))
    twice = surfaces.self_affine(**band, rms_height=2 * band["length"])
    np.testing.assert_allclose(twice.values, 2 * base.values, rtol=0, atol=1e-12 * float(np.abs(base).max()))


@settings(max_examples=budget(100), **FAST)
@given(band=bands(one_mode=False), up=st.integers(1, 3))
def test_resample_up_then_down_is_the_identity(band, up):
    """Refining keeps the nodes; coarsening back keeps every mode below the old Nyquist."""
    top = (band["n"] - 1) // 2  # below the Nyquist mode, which coarsening cannot keep
    q_cutoff = min(band["q_cutoff"], top)
    q_roll = min(band["q_roll"], q_cutoff)
    h = surfaces.self_affine(**band | dict(q_low=min(band["q_low"], q_roll), q_roll=q_roll, q_cutoff=q_cutoff),
                             rms_height=1.0)
    fine = surfaces.resample(h, band["n"] * 2**up)
    back = surfaces.resample(fine, band["n"])
    np.testing.assert_allclose(back.values, h.values, rtol=0, atol=1e-12)
    sl = (slice(None, None, 2**up),) * band["dim"]
    np.testing.assert_allclose(fine.values[sl], h.values, rtol=0, atol=1e-12)
