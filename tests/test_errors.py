"""Bad input is refused with an error naming the parameter; non-convergence is never silent."""

import re
import subprocess
import sys

import numpy as np
import pytest

import contactlib


@pytest.fixture
def heights():
    return contactlib.surfaces.self_affine(32, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, seed=0)


@pytest.mark.parametrize("kwargs,match", [
    (dict(E=0.0), "E"),
    (dict(E=-1.0), "E"),
    (dict(E=float("nan")), "E"),
    (dict(nu=0.6), "nu"),
    (dict(nu=-1.0), "nu"),
    (dict(tol=0.0), "tol"),
    (dict(tol=-1e-8), "tol"),
    (dict(mean_pressure=-0.1), "mean_pressure"),
    (dict(mean_pressure=float("inf")), "mean_pressure"),
    (dict(mean_pressure=0.01, penetration=0.001), "exactly one"),
    (dict(mean_pressure=None), "exactly one"),
    (dict(kernel="boussinesq"), "kernel"),
    (dict(method="newton"), "method"),
    (dict(max_iter=0), "max_iter"),
    (dict(max_iter=2.5), "max_iter must be a whole number"),
    (dict(max_iter=float("nan")), "max_iter must be a whole number"),
    (dict(tol=1.0), "tol must be a number in \\(0, 1\\)"),  # the initial guess met it: "converged", 0 iterations
    (dict(tol=2.0), "tol must be a number in"),
    (dict(mean_pressure="0.01"), "mean_pressure must be a number"),
    (dict(initial_pressure=np.full((32, 32), np.nan)), "initial_pressure contains NaN"),  # was a ZeroDivisionError
    (dict(initial_pressure=np.zeros((32, 32)), method="active-set"), "initial_pressure: a warm start is for"),
    (dict(length=(1.0, 1.0, 1.0)), "length must be a number or one per axis"),
])
def test_bad_parameters(heights, kwargs, match):
    args = dict(E=1.0, nu=0.3, mean_pressure=0.01)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        contactlib.solve(heights, **args)


def test_coordinates_set_the_window_and_must_be_a_grid(heights):
    """A DataArray's window comes from its coordinates: a different ``length`` was used silently (area 0.70 instead
    of 0.22), and an uneven coordinate gave a window from its first step; both refused, naming the parameter."""
    with pytest.raises(ValueError, match="length 5.0 differs from the heights' window"):
        contactlib.solve(heights, E=1.0, nu=0.3, mean_pressure=0.01, length=5.0)
    same = contactlib.solve(heights, E=1.0, nu=0.3, mean_pressure=0.01, length=1.0)  # agreeing: accepted
    assert float(same.contact_area) == float(contactlib.solve(heights, E=1.0, nu=0.3, mean_pressure=0.01).contact_area)
    x = heights.x.values.copy()
    x[5] = 0.9
    with pytest.raises(ValueError, match="coordinate 'x' must be finite, increasing and evenly spaced"):
        contactlib.solve(heights.assign_coords(x=x), E=1.0, nu=0.3, mean_pressure=0.01)


def test_numpy_scalars_are_numbers(heights):
    """np.float32 values (not Python floats) were refused as "must be a finite number" for tol, friction, the
    layer's thickness and the adhesion law; np.float64 always passed."""
    f32 = np.float32
    out = contactlib.solve(heights, E=1.0, nu=f32(0.3), mean_pressure=f32(0.01), tol=f32(1e-6), friction=f32(0.3),
                           sliding_direction=f32(0.0), layer=contactlib.Layer(f32(0.2)))
    assert out.attrs["converged"] == 1
    assert contactlib.Adhesion(work=f32(1e-5), range=f32(1e-3)).work == pytest.approx(1e-5)


@pytest.mark.parametrize("bad", [np.nan, np.inf])
def test_non_finite_heights(heights, bad):
    values = heights.values.copy()
    values[3, 4] = bad
    with pytest.raises(ValueError, match="heights"):
        contactlib.solve(values, length=1.0, E=1.0, nu=0.3, mean_pressure=0.01)


@pytest.mark.parametrize("call", [
    lambda h: contactlib.solve(h.astype(complex), E=1.0, nu=0.3, mean_pressure=0.01),
    lambda h: contactlib.solve(h.values.astype(complex), length=1.0, E=1.0, nu=0.3, mean_pressure=0.01),
    lambda h: contactlib.analysis.rms_slope(h.astype(complex)),
    lambda h: contactlib.analysis.contact_area_fraction(h.values + 0j),
    lambda h: contactlib.analysis.rms_height(h.values + 0j),
    lambda h: contactlib.analysis.directional_slope(h.values + 0j, lengths=1.0),
    lambda h: contactlib.analysis.interlocking_friction(h.values + 0j, h.values, lengths=1.0),
    lambda h: contactlib.solve(h, E=1.0, nu=0.3, mean_pressure=0.01, initial_pressure=np.ones(h.shape) + 0j),
])
def test_complex_fields_are_refused(heights, call):
    """Complex heights or fields (a spectrum passed for the field) were read as their real part with numpy's
    ComplexWarning; now refused by name."""
    with pytest.raises(ValueError, match="(heights|field|pressure|initial_pressure) must be real"):
        call(heights)


@pytest.mark.parametrize("shape", [(1,), (1, 16), (16, 1), (2, 2, 2)])
def test_grid_too_small_or_wrong_rank(shape):
    with pytest.raises(ValueError, match="heights|grid"):
        contactlib.solve(np.zeros(shape), length=1.0, E=1.0, nu=0.3, mean_pressure=0.01)


def test_bad_length():
    with pytest.raises(ValueError, match="length"):
        contactlib.solve(np.zeros((8, 8)), E=1.0, nu=0.3, mean_pressure=0.01, length=-1.0)


def test_round_off_floor_stalls_early_instead_of_running_to_max_iter(heights):
    """tol 1e-17 is below the round-off floor (~1e-15 here): the solve must say so, not spin."""
    with pytest.raises(contactlib.ConvergenceError, match="stalled") as info:
        contactlib.solve(heights, E=1.0, nu=0.3, mean_pressure=0.01, tol=1e-17, max_iter=1_000_000)
    from contactlib.solvers.symmetric.ccg import STALL_ITERATIONS
    assert int(info.value.dataset.iterations) < 3 * STALL_ITERATIONS
    assert 0 < info.value.residual < 1e-12


def test_non_convergence_raises_with_residual_and_partial_dataset(heights):
    with pytest.raises(contactlib.ConvergenceError) as info:
        contactlib.solve(heights, E=1.0, nu=0.3, mean_pressure=0.01, tol=1e-12, max_iter=3)
    err = info.value
    assert err.residual > 1e-12
    assert err.dataset.attrs["converged"] == 0
    assert int(err.dataset.iterations) == 3
    assert float(err.dataset.residual) == pytest.approx(err.residual)
    assert "residual" in str(err)


@pytest.mark.parametrize("call, match", [
    (lambda h: contactlib.analysis.contact_area_fraction(np.full((8, 8), np.nan)), "pressure must be"),
    (lambda h: contactlib.analysis.contact_clusters(np.ones((8, 8)), element_area=-1.0), "element_area"),
    (lambda h: contactlib.analysis.anisotropy_tensor(h.values, 0.1, 0.5, length=1.0), "holds no wavevector"),
    (lambda h: contactlib.analysis.anisotropy_tensor(h.values, 1.0, 4.0, n_theta=0, length=1.0), "n_theta"),
    (lambda h: contactlib.analysis.fit_hurst(h.values, q_min=8, q_max=2, length=1.0), "q_min < q_max"),
    (lambda h: contactlib.analysis.psd(h.values, bins=-1, length=1.0), "bins"),
    (lambda h: contactlib.analysis.rms_slope(np.full((8, 8), np.nan), length=1.0), "NaN"),
    (lambda h: contactlib.analysis.directional_slope(h.values, lengths=-1.0), "lengths"),
    (lambda h: contactlib.analysis.dissipated_power(h.values, material=1.0, sliding_velocity=(1.0, 0.0),
                                                    length=1.0), "material"),
    (lambda h: contactlib.analysis.dissipated_power(h.values, material=contactlib.Elastic(1.0, 0.3),
                                                    sliding_velocity=(1.0, 0.0, 0.0), length=1.0), "sliding_velocity"),
])
def test_bad_analysis_input_names_the_parameter(heights, call, match):
    """NaN pressures counted as out of contact (area 0), a band with no modes gave a plausible theta_d, negative
    lengths flipped a slope's sign; others failed with numpy's errors. Each now names the parameter."""
    with pytest.raises(ValueError, match=match):
        call(heights)


def test_review_of_the_checks(heights):
    """What a review of the new checks found: float32 coordinates (rounded to 6e-8 of their size) are a grid; a 0-d
    array is a number; a 1D direction typed as 3.1416 is pi; the two-scale tolerances are relative (in (0, 1)); an
    infinite count is a ValueError, not an OverflowError."""
    h32 = heights.assign_coords(x=heights.x.values.astype(np.float32), y=heights.y.values.astype(np.float32))
    a = contactlib.solve(h32, E=1.0, nu=0.3, mean_pressure=0.01)
    b = contactlib.solve(heights, E=1.0, nu=0.3, mean_pressure=np.array(0.01))
    assert float(a.contact_area) == float(b.contact_area)
    x = np.arange(64) / 64
    profile = 0.01 * np.cos(2 * np.pi * x) + 0.002 * np.sin(6 * np.pi * x)
    typed = contactlib.solve(profile, length=1.0, E=1.0, nu=0.3, mean_pressure=0.01, friction=0.5,
                             sliding_direction=3.1416)
    exact = contactlib.solve(profile, length=1.0, E=1.0, nu=0.3, mean_pressure=0.01, friction=0.5,
                             sliding_direction=np.pi)
    assert np.array_equal(typed.pressure.values, exact.pressure.values)
    field = contactlib.surfaces.spheres(64, radius=0.5, lattice=4, summit_height=0.01, height_std=0.001)
    with pytest.raises(ValueError, match="tol must be a number in"):
        contactlib.two_scale.solve(field, E=1.0, nu=0.5, mean_pressure=1e-4, tol=2.0)
    for call, match in ((lambda: contactlib.analysis.psd(heights, bins=np.inf), "bins"),
                        (lambda: contactlib.analysis.anisotropy_tensor(heights, 1, 4, n_theta=np.inf), "n_theta"),
                        (lambda: contactlib.analysis.contact_clusters(np.ones((4, 4)), element_area=None),
                         "element_area"),
                        (lambda: contactlib.surfaces.wavy("8", amplitude=0.1), "n must be")):
        with pytest.raises(ValueError, match=match):
            call()


# --- one validation path: every entry point names the parameter, wrong types and shapes included (issue 38, 8) ------

def _scene():
    return contactlib.surfaces.self_affine(32, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, seed=0)


def _sls():
    return contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)


def _two_caps(**kwargs):
    return contactlib.surfaces.spheres(64, radius=0.01, centers=[[0.25, 0.25], [0.75, 0.75]], summit_height=1e-3,
                                       **kwargs)


def _solve(**kwargs):
    return contactlib.solve(_scene(), **{"E": 1.0, "nu": 0.3, "mean_pressure": 0.01, **kwargs})


def _transient(**kwargs):
    return contactlib.solve_transient(_scene(), **{"material": _sls(), "times": [0.0, 1.0], "mean_pressure": 0.01,
                                                   **kwargs})


def _reciprocating(**kwargs):
    return contactlib.solve_reciprocating(_scene(), **{"material": _sls(), "amplitude": 0.01, "frequency": 1.0,
                                                       "mean_pressure": 0.01, **kwargs})


def _curve(**kwargs):
    return contactlib.adhesion_curve(_scene(), **{"E": 1.0, "nu": 0.3, "penetrations": [0.0, 0.001],
                                                  "adhesion": contactlib.Adhesion(work=1e-4, range=1e-3), **kwargs})


def _two_scale(**kwargs):
    return contactlib.two_scale.solve(_two_caps(), **{"E": 1.0, "nu": 0.5, "mean_pressure": 1e-6, "scale": "macro",
                                                      **kwargs})


def _affine(**kwargs):
    return contactlib.surfaces.self_affine(16, **{"hurst": 0.8, "q_roll": 2, "q_cutoff": 4, "rms_slope": 0.1,
                                                  **kwargs})


RAGGED = [[0.0, 1.0], [2.0]]

# (entry point and bad argument, the parameter the message must name, what else it must say: the type of a wrong type,
# the shape of a wrong shape). The parent (87c002a) raised TypeError from a comparison, numpy's own messages, or a
# ValueError naming the parameter without the type: each row fails there.
BAD_INPUT = [
    ("solve E str", lambda: _solve(E="1e7"), "E", "str"),
    ("solve nu str", lambda: _solve(nu="0.3"), "nu", "str"),
    ("solve E complex", lambda: _solve(E=1e7 + 0j), "E", "complex"),
    ("solve mean_pressure str", lambda: _solve(mean_pressure="0.01"), "mean_pressure", "str"),
    ("solve mean_pressure complex", lambda: _solve(mean_pressure=0.01j), "mean_pressure", "complex"),
    ("solve penetration list", lambda: _solve(mean_pressure=None, penetration=[1e-3]), "penetration", "list"),
    ("solve tol str", lambda: _solve(tol="1e-6"), "tol", "str"),
    ("solve max_iter str", lambda: _solve(max_iter="100"), "max_iter", "str"),
    ("solve heights str", lambda: contactlib.solve("0.1 0.2", length=1.0, E=1.0, nu=0.3, mean_pressure=0.01),
     "heights", "str"),
    ("solve heights ragged", lambda: contactlib.solve(RAGGED, length=1.0, E=1.0, nu=0.3, mean_pressure=0.01),
     "heights", "ragged"),
    ("solve heights None", lambda: contactlib.solve(None, length=1.0, E=1.0, nu=0.3, mean_pressure=0.01),
     "heights", "None"),
    ("solve length str", lambda: contactlib.solve(np.zeros((8, 8)), length="1", E=1.0, nu=0.3, mean_pressure=0.01),
     "length", "str"),
    ("solve periodic str", lambda: _solve(periodic="no"), "periodic", "str"),
    ("solve sliding_velocity str", lambda: _solve(sliding_velocity="fast"), "sliding_velocity", "str"),
    ("solve friction str", lambda: _solve(friction="0.3"), "friction", "str"),
    ("solve sliding_direction str", lambda: _solve(friction=0.3, sliding_direction="0"), "sliding_direction", "str"),
    ("solve adhesive mean_pressure str", lambda: _solve(mean_pressure="-0.01", adhesion=contactlib.Adhesion(
        work=1e-4, range=1e-3)), "mean_pressure", "str"),
    ("solve_tolerances tols str", lambda: contactlib.solve_tolerances(_scene(), "1e-6", E=1.0, nu=0.3,
                                                                      mean_pressure=0.01), "tols", "str"),
    ("solve_transient times str", lambda: _transient(times="0.1"), "times", "str"),
    ("solve_transient times number", lambda: _transient(times=0.1), "times", "single number"),
    ("solve_transient times ragged", lambda: _transient(times=RAGGED), "times", "ragged"),
    ("solve_transient mean_pressure str", lambda: _transient(mean_pressure="0.01"), "mean_pressure", "str"),
    ("solve_transient path str", lambda: _transient(path="left"), "path", "str"),
    ("solve_reciprocating amplitude str", lambda: _reciprocating(amplitude="0.01"), "amplitude", "str"),
    ("solve_reciprocating mean_pressure str", lambda: _reciprocating(mean_pressure="0.01"), "mean_pressure", "str"),
    ("solve_reciprocating max_cycles str", lambda: _reciprocating(max_cycles="5"), "max_cycles", "str"),
    ("solve_reciprocating direction str", lambda: _reciprocating(direction="0"), "direction", "str"),
    ("adhesion_curve penetrations str", lambda: _curve(penetrations="0 1e-3"), "penetrations", "str"),
    ("adhesion_curve penetrations ragged", lambda: _curve(penetrations=RAGGED), "penetrations", "ragged"),
    ("two_scale.solve mean_pressure str", lambda: _two_scale(mean_pressure="1e-6"), "mean_pressure", "str"),
    ("two_scale.solve penetration str", lambda: _two_scale(mean_pressure=None, penetration="1e-4"), "penetration",
     "str"),
    ("two_scale.solve_transient times str", lambda: contactlib.two_scale.solve_transient(
        _two_caps(), material=_sls(), times="0.1", mean_pressure=1e-6, scale="macro"), "times", "str"),
    ("self_affine hurst str", lambda: _affine(hurst="0.8"), "hurst", "str"),
    ("self_affine q_roll None", lambda: _affine(q_roll=None), "q_roll", "None"),
    ("self_affine rms_slope str", lambda: _affine(rms_slope="0.1"), "rms_slope", "str"),
    ("self_affine length str", lambda: _affine(length="1"), "length", "str"),
    ("self_affine angle str", lambda: _affine(angle="0"), "angle", "str"),
    ("wavy amplitude str", lambda: contactlib.surfaces.wavy(8, amplitude="0.1"), "amplitude", "str"),
    ("paraboloid radius str", lambda: contactlib.surfaces.paraboloid(8, radius="1"), "radius", "str"),
    ("spheres radius str", lambda: contactlib.surfaces.spheres(16, radius="0.1", lattice=2), "radius", "str"),
    ("spheres summit_height str", lambda: contactlib.surfaces.spheres(16, radius=0.1, lattice=2, summit_height="0.01"),
     "summit_height", "str"),
    ("spheres height_std str", lambda: contactlib.surfaces.spheres(16, radius=0.1, lattice=2, height_std="0"),
     "height_std", "str"),
    ("spheres centers str", lambda: contactlib.surfaces.spheres(16, radius=0.1, centers="middle"), "centers", "str"),
    ("Elastic E str", lambda: contactlib.Elastic("1e7", 0.3), "E", "str"),
    ("Elastic nu bool", lambda: contactlib.Elastic(1.0, True), "nu", "bool"),
    ("Viscoelastic E0 str", lambda: contactlib.Viscoelastic(E0="1", prony=[(1.0, 1.0)]), "E0", "str"),
    ("Viscoelastic tau_i str", lambda: contactlib.Viscoelastic(E0=1.0, prony=[(1.0, "1")]), "tau_i", "str"),
    ("Viscoelastic nu str", lambda: contactlib.Viscoelastic(E0=1.0, prony=[(1.0, 1.0)], nu="0.5"), "nu", "str"),
    ("Layer thickness str", lambda: contactlib.Layer("0.1"), "thickness", "str"),
    ("Adhesion work str", lambda: contactlib.Adhesion(work="1e-4", range=1e-3), "work", "str"),
    ("Adhesion range str", lambda: contactlib.Adhesion(work=1e-4, range="1e-3"), "range", "str"),
]


@pytest.mark.parametrize("call, name, says", [row[1:] for row in BAD_INPUT], ids=[row[0] for row in BAD_INPUT])
def test_every_entry_point_names_the_parameter_and_what_is_wrong(call, name, says):
    with pytest.raises(ValueError) as info:
        call()
    message = str(info.value)
    assert re.search(rf"(^|\W){re.escape(name)}\b", message), message
    assert says in message, message


def _bare(n=64, length=1e-4):
    """Micrometre heights on a 0.1 mm window, as a DataArray and as its bare array (indexed [ix, iy])."""
    h = contactlib.surfaces.self_affine(n, length=length, hurst=0.8, q_roll=2, q_cutoff=8, rms_height=1e-6, seed=1)
    return h, h.transpose("x", "y").values


@pytest.mark.parametrize("call", [
    lambda v: contactlib.solve(v, E=1e6, nu=0.5, mean_pressure=1e3),
    lambda v: contactlib.solve_tolerances(v, [1e-6], E=1e6, nu=0.5, mean_pressure=1e3),
    lambda v: contactlib.solve_speeds(v, [(1e-3, 0.0)], material=_sls(), mean_pressure=1e-3),
    lambda v: contactlib.solve_transient(v, material=_sls(), times=[0.0, 1.0], mean_pressure=1e-3),
    lambda v: contactlib.solve_reciprocating(v, material=_sls(), amplitude=1e-6, frequency=1.0, mean_pressure=1e-3),
    lambda v: contactlib.adhesion_curve(v, E=1e6, nu=0.5, penetrations=[0.0, 1e-7],
                                        adhesion=contactlib.Adhesion(work=1e-4, range=1e-8)),
], ids=["solve", "solve_tolerances", "solve_speeds", "solve_transient", "solve_reciprocating", "adhesion_curve"])
def test_a_bare_array_needs_its_window(call):
    """A bare array without ``length`` took a 1 m window: micrometre heights on a 0.1 mm window came back in full
    contact (64^2, rms height 1 um, E 1 MPa, 1 kPa: area 1.0, against 0.012 on their window). Now refused by name, at
    every entry point."""
    with pytest.raises(ValueError, match="length: heights given as a bare array"):
        call(_bare(16)[1])


@pytest.mark.parametrize("measure", [
    lambda v: contactlib.analysis.rms_slope(v),
    lambda v: contactlib.analysis.psd(v),
    lambda v: contactlib.analysis.fit_hurst(v, q_min=1, q_max=4),
    lambda v: contactlib.analysis.anisotropy_tensor(v, 1, 4),
    lambda v: contactlib.analysis.dissipated_power(v, material=contactlib.Elastic(1.0, 0.3),
                                                   sliding_velocity=(1.0, 0.0)),
])
def test_an_analysis_of_a_bare_array_needs_its_window(measure):
    """The analysis functions took a bare array on a 1 m window too: the rms slope of micrometre heights on a 0.1 mm
    window came out 1e4 times too small. Refused by name; with ``length`` it is the DataArray's."""
    h, values = _bare(16)
    with pytest.raises(ValueError, match="length: a field given as a bare array"):
        measure(values)
    assert contactlib.analysis.rms_slope(values, length=1e-4) == contactlib.analysis.rms_slope(h)


def test_a_bare_array_with_its_length_is_its_dataarray():
    h, values = _bare()
    labelled = contactlib.solve(h, E=1e6, nu=0.5, mean_pressure=1e3)
    bare = contactlib.solve(values, length=1e-4, E=1e6, nu=0.5, mean_pressure=1e3)
    assert np.array_equal(bare.pressure.values, labelled.pressure.values)
    assert float(bare.contact_area) == pytest.approx(0.0117, abs=1e-3)  # partial, not the 1 m window's full contact


def test_reference_modules_are_there_without_an_import():
    """``contactlib.reference.adhesive``, ``.sliding_cylinder`` and ``.hunter`` raised AttributeError until imported by
    hand (a fresh interpreter: in this one another test may have imported them)."""
    code = ("import contactlib; r = contactlib.reference; "
            "print(r.adhesive.jkr_pull_off(radius=1.0, work=1.0), callable(r.sliding_cylinder.contact), "
            "r.hunter.__name__, r.viscoelastic_profile.__name__, r.maugis.maugis_pull_off(1e3))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert float(out.stdout.split()[0]) == pytest.approx(-1.5 * np.pi, rel=1e-12)
    assert float(out.stdout.split()[-1]) == pytest.approx(-1.5, rel=1e-6)  # Maugis' pull-off: JKR's at lambda 1e3


def test_spheres_default_summit_height_works_without_scatter():
    """``summit_height=0.0`` by default always raised with ``height_std=0``; the default is now a tenth of each
    radius."""
    h = contactlib.surfaces.spheres(64, radius=0.1, lattice=2)
    assert np.allclose(h.attrs["asperity_summit_height"], 0.01, rtol=1e-15)
    assert float(h.max()) == pytest.approx(0.01, rel=1e-12)  # the summits sit on grid nodes
    mixed = contactlib.surfaces.spheres(64, radius=[0.1, 0.2], centers=[[0.25, 0.25], [0.75, 0.75]])
    assert np.allclose(mixed.attrs["asperity_summit_height"], [0.01, 0.02], rtol=1e-15)


def test_two_scale_names_the_load_at_which_separate_caps_end():
    """Two caps (radius 0.01, summit 1e-3, unit window) pressed by mean_pressure 10 pushed the body onto the base:
    the refusal said "no asperity in contact during the Newton iteration". Now it names the largest mean pressure the
    separate caps carry, and it is that load: just below it solves, just above it is refused."""
    with pytest.raises(ValueError, match="mean_pressure 10.0 is beyond what separate spherical caps carry") as info:
        contactlib.two_scale.solve(_two_caps(), E=1.0, nu=0.5, mean_pressure=10.0)
    message = str(info.value)
    assert "pressed by" in message and "summit height" in message  # where it happens: a cap pressed to its base
    limit = float(re.search(r"at most a mean pressure of about ([0-9.e+-]+)", message).group(1))
    below = contactlib.two_scale.solve(_two_caps(), E=1.0, nu=0.5, mean_pressure=0.99 * limit, scale="macro")
    assert float(below.local_penetration.max()) == pytest.approx(1e-3, rel=0.02)  # nearly at the summit height
    with pytest.raises(ValueError, match=f"at most a mean pressure of about {limit:.4g}"):
        contactlib.two_scale.solve(_two_caps(), E=1.0, nu=0.5, mean_pressure=1.01 * limit, scale="macro")
