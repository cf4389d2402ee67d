"""Viscoelastic time stepping (contactlib.solve_transient, solve_reciprocating) against exact solutions,
the correspondence principle, the steady-sliding solver and tamaas' first step."""

import math
import re
import warnings

import numpy as np
import pytest

import contactlib
from contactlib import surfaces
from contactlib.model.hereditary import PronyHistory

NU = 0.3


def two_branch(nu=NU):
    return contactlib.Viscoelastic(E0=1.0, prony=[(2.0, 1.0), (5.0, 0.1)], nu=nu)


def sphere(n, *, length=1.0, radius=1.0):
    x = (np.arange(n) + 0.5) * length / n - length / 2
    X, Y = np.meshgrid(x, x, indexing="ij")
    return -(X**2 + Y**2) / (2 * radius)


def mode_error(pressure, heights, factor):
    """Relative L2 error of the pressure fluctuation against ``p_q = (|q|/2) h_q factor``, factor = E(t)/(1 - nu^2)."""
    grid = contactlib.Grid(heights.shape, (1.0,) * heights.ndim)
    hq = np.fft.rfftn(heights - heights.mean())
    exact = grid.wavenumber() / 2 * hq * factor
    pq = np.fft.rfftn(pressure - pressure.mean())
    return float(np.linalg.norm(pq - exact) / np.linalg.norm(exact))


# --- the exact cases ---------------------------------------------------------------------------------


def test_full_contact_relaxes_exactly_as_the_relaxation_modulus():
    """Beyond full contact the displacement is the surface, so every mode relaxes as E(t): at every step."""
    m = two_branch()
    h = surfaces.self_affine(32, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.05, seed=3)
    times = np.concatenate([[0.0], np.linspace(0.05, 5.0, 60)])  # 5 slowest relaxation times, dt = tau_fast / 1.2
    pm = 50 * float(np.ptp(h.values)) * 2 * np.pi * 8 * m.E_inf / (1 - NU**2)
    out = contactlib.solve_transient(h, material=m, times=times, mean_pressure=pm, save_fields=True)
    assert float(out.contact_area.min()) == 1.0
    errors = [mode_error(out.pressure.isel(saved_time=k).values, h.values, m.relaxation(t) / (1 - NU**2))
              for k, t in enumerate(out.saved_time.values)]
    assert max(errors) < 1e-3
    assert max(errors) < 1e-9  # the rule is exact at fixed displacement: solver tolerance, not a step error
    # and the last step is at the long-term modulus to 1e-2 of the relaxed/glassy gap
    assert m.relaxation(5.0) / m.E0 - 1 < 0.02


def test_full_contact_on_a_confined_layer_relaxes_exactly():
    """Layers compose: the same exact test with the confined layer's compliance."""
    m = two_branch(nu=0.4)
    h = surfaces.self_affine(32, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.05, seed=5)
    layer = contactlib.Layer(0.05, base="confined")
    times = np.linspace(0.0, 3.0, 31)
    pm = 100 * float(np.ptp(h.values)) * m.E_inf / 0.05
    out = contactlib.solve_transient(h, material=m, times=times, mean_pressure=pm, layer=layer, save_fields=True)
    assert "layer" in out.attrs["model"] and float(out.contact_area.min()) == 1.0
    from contactlib.kernels.tensor import surface_green_tensor
    grid = contactlib.Grid(h.shape, (1.0, 1.0))
    unit = surface_green_tensor(grid, 1.0, 0.4, 0.05, "confined").normal  # displacement per pressure at E = 1
    hq = np.fft.rfftn(h.values - h.values.mean())
    nonzero = grid.wavenumber() > 0
    for k, t in enumerate(out.saved_time.values):
        pq = np.fft.rfftn(out.pressure.isel(saved_time=k).values)
        exact = hq[nonzero] * m.relaxation(t) / unit[nonzero]
        assert np.linalg.norm(pq[nonzero] - exact) / np.linalg.norm(exact) < 1e-8


def test_relaxation_at_constant_penetration_follows_the_relaxation_modulus():
    """Lee and Radok: P(t) = 4/3 R^(1/2) d^(3/2) E(t) / (1 - nu^2) for a sphere held at penetration d."""
    n, radius, nu = 96, 1.0, 0.5
    m = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=4.0, tau=1.0, nu=nu)
    d = 0.2**2 / radius  # contact radius 0.2 of a unit window
    times = np.concatenate([[0.0], np.geomspace(0.01, 10.0, 12)])
    out = contactlib.solve_transient(sphere(n, radius=radius), material=m, times=times, penetration=d, length=1.0,
                                     periodic=False)
    load = out.mean_pressure.values  # total load over a unit window
    exact = 4 / 3 * math.sqrt(radius) * d**1.5 * m.relaxation(times) / (1 - nu**2)
    assert np.abs(load / exact - 1).max() < 0.01
    # the contact does not move at fixed penetration: the ratio to E(t) is constant to round-off
    ratio = load / m.relaxation(times)
    assert np.ptp(ratio) / ratio.mean() < 1e-6


def test_creep_under_constant_load_follows_lee_radok():
    """a(t)^3 = 3 P R (1 - nu^2) J(t) / 4 at every step (contact radius from the contact area)."""
    n, radius, nu = 128, 1.0, 0.5
    m = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=4.0, tau=1.0, nu=nu)
    load = 4 * m.E0 / (1 - nu**2) * 0.285**3 / (3 * radius)  # relaxed contact radius 0.285
    times = np.concatenate([[0.0], np.linspace(0.25, 20.0, 40)])  # to 5 creep times (tau E_inf / E0 = 4)
    out = contactlib.solve_transient(sphere(n, radius=radius), material=m, times=times, mean_pressure=load,
                                     length=1.0, periodic=False)
    a = np.sqrt(out.contact_area.values / math.pi)
    exact = (3 * load * radius * (1 - nu**2) * m.creep(times) / 4) ** (1 / 3)
    assert np.abs(a / exact - 1).max() < 0.01
    assert a[-1] / a[0] > 1.5  # it did creep: (E_inf/E0)^(1/3) = 1.59 at the end
    depth = exact**2 / radius
    assert np.abs(out.penetration.values / depth - 1).max() < 0.01


def test_time_step_convergence_is_second_order():
    """Creep of a sphere: the penetration's error against a fine-step run falls as dt^2."""
    n, nu = 64, 0.5
    m = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=4.0, tau=1.0, nu=nu)
    load = 4 / (1 - nu**2) * 0.28**3 / 3
    end = 4.0

    def run(steps):
        times = np.concatenate([[0.0], np.linspace(end / steps, end, steps)])
        out = contactlib.solve_transient(sphere(n), material=m, times=times, mean_pressure=load, length=1.0,
                                         periodic=False, tol=1e-12)
        return out.penetration.sel(time=[1.0, 2.0, 4.0], method="nearest").values

    reference = run(256)
    errors = [float(np.abs(run(s) - reference).max()) for s in (8, 16, 32)]
    orders = [math.log2(errors[i] / errors[i + 1]) for i in range(2)]
    assert min(orders) > 1.7, (errors, orders)


# --- motion ------------------------------------------------------------------------------------------


def test_sliding_from_rest_reaches_the_steady_sliding_solution():
    """A profile set sliding at constant speed from the relaxed static contact ends at the steady solver's answer."""
    n = 256
    h = surfaces.self_affine(n, hurst=0.8, q_roll=4, q_cutoff=32, rms_slope=0.1, seed=2, dim=1)
    m = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=3.0, tau=1.0, nu=0.5)
    speed, pm = 1 / (2 * np.pi * 4), 0.02  # V tau q0 = 1
    steady = contactlib.solve(h, material=m, mean_pressure=pm, sliding_velocity=speed)
    dt = 1 / n / 2 / speed  # half a grid spacing per step
    times = np.arange(801) * dt  # 39 relaxation times, 13 creep times
    out = contactlib.solve_transient(h, material=m, times=times, mean_pressure=pm, path=speed * times,
                                     initial="relaxed")
    shift = int(round(speed * times[-1] * n))  # a whole number of grid spacings: compare without interpolation
    pressure = np.roll(out.pressure.isel(saved_time=-1).values, -shift)
    reference = steady.pressure.values
    assert np.linalg.norm(pressure - reference) / np.linalg.norm(reference) < 0.01
    # the same estimator on both states (the transient's, from the rigid slopes: the indenter's work per slide);
    # the steady solver reports the deformed surface's, the operator's own dissipation, 2.3 % above it at 8 points
    # per shortest wavelength
    mu = float(out.friction_coefficient_interlocking[-1])
    steady_mu = contactlib.analysis.interlocking_friction(steady.pressure.values, h.values, lengths=1.0)
    assert mu == pytest.approx(steady_mu, rel=0.01)
    assert float(steady.friction_coefficient_interlocking) == pytest.approx(mu, rel=0.03)
    assert float(out.dissipated_power[-1]) == pytest.approx(float(steady.dissipated_power), rel=0.01)
    assert float(out.contact_area[0]) > 2 * float(out.contact_area[-1])  # it started relaxed, far from it


def test_path_is_a_translation():
    """An elastic body: the transient with a path is the static solve of the translated surface, at every step."""
    h = surfaces.self_affine(64, hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=7)
    times = np.arange(4.0)
    path = np.array([[0.0, 0.0], [0.25, 0.0], [0.25, 0.5], [-0.125, 0.375]])  # whole grid spacings
    out = contactlib.solve_transient(h, E=1.0, nu=0.3, times=times, mean_pressure=0.02, path=path, save_fields=True,
                                     tol=1e-10)
    for k in range(len(times)):
        shifted = np.roll(h.transpose("x", "y").values, tuple(int(round(c * 64)) for c in path[k]), axis=(0, 1))
        ref = contactlib.solve(shifted, length=1.0, E=1.0, nu=0.3, mean_pressure=0.02, tol=1e-10)
        p = out.pressure.isel(saved_time=k).values
        assert np.abs(p - ref.pressure.values).max() < 1e-6 * ref.pressure.values.max()
        assert float(out.contact_area[k]) == float(ref.contact_area)
    assert "position_y" in out and out.position_x.attrs["units"] == "m"


def test_reciprocating_dissipation_has_one_maximum_where_predicted():
    """Energy per cycle vanishes at low and high frequency, peaks once in between, at the frequency predicted
    from the steady sliding bell (quasi-steady: the speed sweeps 2 pi f A |cos|), and equals the loop's area."""
    n = 128
    x = np.arange(n) / n
    h = 0.01 * np.cos(2 * np.pi * x)
    m = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)
    pm, amplitude = 0.003, 0.1
    frequencies = np.geomspace(1e-3, 1.0, 7)
    energy = []
    for f in frequencies:
        out = contactlib.solve_reciprocating(h, material=m, amplitude=amplitude, frequency=float(f), mean_pressure=pm,
                                             length=1.0, steps_per_cycle=96, max_cycles=40)
        assert out.attrs["status"] == "settled", out.attrs["status"]
        assert float(out.friction_work_per_cycle) == pytest.approx(float(out.dissipated_energy_per_cycle), rel=0.02)
        energy.append(float(out.dissipated_energy_per_cycle))
    energy = np.array(energy)
    peak = int(np.argmax(energy))
    assert 0 < peak < len(frequencies) - 1
    assert np.all(np.diff(energy[: peak + 1]) > 0) and np.all(np.diff(energy[peak:]) < 0)  # one maximum
    assert energy[0] < 0.2 * energy[peak] and energy[-1] < 0.1 * energy[peak]  # tends to zero at both ends
    # measured peak: a parabola in log f through the three points around it
    logf = np.log(frequencies[peak - 1: peak + 2])
    c = np.polyfit(logf, np.log(energy[peak - 1: peak + 2]), 2)
    measured = math.exp(-c[1] / (2 * c[0]))
    # predicted: the steady bell mu(V) swept quasi-statically, E(f) = pm A int_0^2pi mu(2 pi f A |cos t|) |cos t| dt
    speeds = np.geomspace(1e-4, 1.0, 41)
    bell = np.array([float(contactlib.solve(h, material=m, mean_pressure=pm, length=1.0, sliding_velocity=float(v))
                           .friction_coefficient_interlocking) for v in speeds])
    theta = np.linspace(0, 2 * np.pi, 721)
    grid = np.geomspace(1e-3, 1.0, 121)
    predicted_energy = [pm * amplitude * np.trapezoid(np.interp(np.log(2 * np.pi * f * amplitude * np.abs(np.cos(theta))
                                                                   + 1e-30), np.log(speeds), bell)
                                                  * np.abs(np.cos(theta)), theta) for f in grid]
    predicted = grid[int(np.argmax(predicted_energy))]
    assert measured == pytest.approx(predicted, rel=0.35)


def test_reciprocating_default_steps_resolve_the_slide():
    """By default a cycle has the steps that slide the surface at most a grid spacing each: a rough profile
    reciprocated at an amplitude of 0.3 of its window then dissipates what a 1024-step cycle does, where the old 64
    fixed steps (7.5 spacings a step) dissipated 41 % too little; given too few steps, it warns, and the energy
    balance shows the error."""
    h = surfaces.self_affine(256, hurst=0.8, q_roll=1, q_cutoff=32, rms_slope=0.1, seed=0, dim=1)
    m = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)
    args = dict(material=m, amplitude=0.3, frequency=1e-3, mean_pressure=0.5, length=1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", contactlib.TimeStepWarning)
        auto = contactlib.solve_reciprocating(h, **args)
        fine = contactlib.solve_reciprocating(h, steps_per_cycle=1024, **args)
    assert auto.attrs["steps_per_cycle"] == 484 and auto.attrs["slide_per_step"] <= 1.0
    reference = float(fine.dissipated_energy_per_cycle)
    assert float(auto.dissipated_energy_per_cycle) == pytest.approx(reference, rel=5e-3)  # 0.2 % measured
    assert float(auto.friction_work_per_cycle) == pytest.approx(reference, rel=0.02)
    assert abs(float(auto.energy_balance)) < 0.02 and auto.energy_balance.attrs["units"] == "1"
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        coarse = contactlib.solve_reciprocating(h, steps_per_cycle=64, **args)
    messages = [str(w.message) for w in caught if issubclass(w.category, contactlib.TimeStepWarning)]
    assert any(re.search("steps_per_cycle 64: .* 7.5.* takes 484", m) for m in messages)  # before the run
    assert any(m.startswith("energy_balance -0.77") for m in messages)  # after it
    assert float(coarse.dissipated_energy_per_cycle) < 0.7 * reference
    assert float(coarse.energy_balance) < -0.5


def test_reciprocating_warns_where_the_settled_cycle_does_not_balance():
    """Tiny contacts on a coarse map jump across a spacing a step: the default steps (64) leave the friction work
    a fifth of the absolute work short of the dissipated energy, which warns; four times the steps raise the
    energy by a fifth (it converges at first order there) and balance it within the bound."""
    h = surfaces.self_affine(32, hurst=0.8, q_roll=1, q_cutoff=4, rms_slope=0.1, seed=0)
    m = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=1000.0, tau=1.0, nu=0.5)
    args = dict(material=m, amplitude=0.3, frequency=1e-3, mean_pressure=0.005, length=1.0)
    with pytest.warns(contactlib.TimeStepWarning, match=r"energy_balance -0.2.* 64 steps a cycle do not resolve"):
        coarse = contactlib.solve_reciprocating(h, **args)
    assert coarse.attrs["status"] == "settled" and coarse.attrs["steps_per_cycle"] == 64
    assert coarse.attrs["slide_per_step"] <= 1.0  # the slide alone does not catch it
    with warnings.catch_warnings():
        warnings.simplefilter("error", contactlib.TimeStepWarning)
        finer = contactlib.solve_reciprocating(h, steps_per_cycle=256, **args)
    assert float(finer.dissipated_energy_per_cycle) > 1.15 * float(coarse.dissipated_energy_per_cycle)
    assert abs(float(finer.energy_balance)) < 0.05


def test_reciprocating_default_steps_follow_the_spacing_along_the_direction():
    """On a map with unequal spacings the default count follows the spacing along the sliding direction, and is
    the fewest: each step slides at most one spacing, yet more than 0.9 of one."""
    h = 1e-3 * surfaces.self_affine(64, hurst=0.8, q_roll=1, q_cutoff=8, rms_slope=0.1, seed=0).values[::2, :]
    m = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)
    expected = {0.0: 64, math.pi / 2: 124, math.pi / 4: 88, 3 * math.pi / 4: 88}  # 2 pi 0.3 (32 or 64 nodes)
    for direction, steps in expected.items():
        out = contactlib.solve_reciprocating(h, material=m, amplitude=0.3, frequency=1.0, mean_pressure=1e-4,
                                             length=1.0, direction=direction, max_cycles=2, min_cycles=2)
        assert out.attrs["steps_per_cycle"] == steps, direction
        assert 0.9 < out.attrs["slide_per_step"] <= 1.0 or steps == 64


def test_reciprocating_elastic_body_settles_at_once_without_a_balance():
    """An elastic body has no memory: 64 steps whatever the slide, no warning, its loop (1e-18 of the load, below
    the steps' error) counts as zero so the cycle settles at min_cycles, and the balance of nothing is NaN."""
    h = surfaces.self_affine(256, hurst=0.8, q_roll=1, q_cutoff=32, rms_slope=0.1, seed=0, dim=1)
    with warnings.catch_warnings():
        warnings.simplefilter("error", contactlib.TimeStepWarning)
        out = contactlib.solve_reciprocating(h, E=1.0, nu=0.5, amplitude=0.3, frequency=1e-3, mean_pressure=0.5,
                                             length=1.0)
    assert out.attrs["steps_per_cycle"] == 64 and out.attrs["status"] == "settled" and out.attrs["cycles"] == 3
    assert np.isnan(float(out.energy_balance))
    assert abs(float(out.dissipated_energy_per_cycle)) < 1e-12 and abs(float(out.friction_work_per_cycle)) < 1e-12


def test_transient_warns_where_a_viscoelastic_path_slides_past_a_grid_spacing():
    """The time stepper takes the pressure rate as constant over a step at each point of the body: a path that
    moves the surface two spacings a step is warned of on a viscoelastic body, not on an elastic one (no memory)."""
    n = 64
    h = 0.01 * np.cos(2 * np.pi * np.arange(n) / n)
    times = np.arange(4.0)
    path = times * 2.0 / n  # two grid spacings a step
    m = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)
    with pytest.warns(contactlib.TimeStepWarning, match="path: the surface slides up to 2 grid spacings"):
        contactlib.solve_transient(h, material=m, times=times, mean_pressure=0.003, path=path, length=1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", contactlib.TimeStepWarning)
        contactlib.solve_transient(h, material=m, times=times, mean_pressure=0.003, path=path / 2, length=1.0)
        contactlib.solve_transient(h, E=1.0, nu=0.5, times=times, mean_pressure=0.003, path=path, length=1.0)


def test_reciprocating_not_settled_returns_the_cycles_with_a_status():
    x = np.arange(64) / 64
    m = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)
    with pytest.warns(contactlib.TimeStepWarning, match="steps_per_cycle 16: the surface slides up to 2.45"):
        out = contactlib.solve_reciprocating(0.01 * np.cos(2 * np.pi * x), material=m, amplitude=0.1, frequency=1.0,
                                             mean_pressure=0.003, length=1.0, steps_per_cycle=16, max_cycles=3,
                                             accelerate=False)
    assert out.attrs["status"].startswith("not settled after 3 cycles")
    assert out.sizes["cycle"] == 3 and np.all(out.dissipated_energy > 0)
    assert out.sizes["time"] == 16 and out.tangential_force_x.attrs["units"] == "Pa"


# --- against tamaas ------------------------------------------------------------------------------------


def test_first_step_matches_tamaas_maxwell():
    """Same scene and material in both codes: tamaas' first step at dt = 1e-4 tau is an elastic solve at
    (nearly) the glassy modulus, as contactlib's instantaneous first step. tamaas' model.E is the long-term
    modulus and each branch a shear modulus G_i: E_i = 2 G_i (1 + nu)."""
    import tamaas as tm  # in the test extra
    tm.set_log_level(tm.LogLevel.error)
    n = 256
    h = surfaces.self_affine(n, hurst=0.8, q_roll=4, q_cutoff=64, rms_slope=0.1, seed=4)
    heights = np.ascontiguousarray(h.values)
    shear, taus = [2.0, 0.5], [1.0, 0.1]
    m = contactlib.Viscoelastic(E0=1.0, prony=[(2 * g * (1 + NU), t) for g, t in zip(shear, taus)], nu=NU)
    pm = 0.02 * m.E_inf
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], [n, n])
    model.E, model.nu = m.E0, NU
    tm.MaxwellViscoelastic(model, heights, 1e-12, 1e-4 * min(taus), shear, taus).solve(pm)
    theirs = np.array(model.traction).reshape(n, n)
    gap = np.array(model.displacement).reshape(n, n) - heights
    their_area = float(np.mean(gap - gap.min() <= 1e-7 * heights.std()))  # tamaas' traction is never exactly 0
    out = contactlib.solve_transient(h, material=m, times=[0.0], mean_pressure=pm, tol=1e-10)
    ours = out.pressure.isel(saved_time=0).values
    assert float(out.contact_area[0]) == pytest.approx(their_area, rel=1e-3)
    assert np.linalg.norm(ours - theirs) / np.linalg.norm(theirs) < 1e-3


# --- the memory, the records and the errors ----------------------------------------------------------------


def test_prony_history_step_of_zero_is_glassy_and_long_steps_relax():
    m = two_branch()
    hist = PronyHistory(m, (4,))
    assert hist.coefficients(0.0)[0] == pytest.approx(m.E_inf, rel=1e-15)
    assert hist.coefficients(1e6)[0] == pytest.approx(m.E0, rel=1e-5)
    assert contactlib.solve_transient(np.cos(2 * np.pi * np.arange(16) / 16), length=1.0, E=1.0, nu=0.3,
                                      times=[0.0, 1.0],
                                      mean_pressure=0.1).dissipated_power.max() == 0.0  # an elastic body


def test_save_fields_and_labels():
    h = surfaces.self_affine(32, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, seed=1)
    m = two_branch()
    times = np.linspace(0.0, 1.0, 6)
    args = dict(material=m, times=times, mean_pressure=0.05)
    assert contactlib.solve_transient(h, **args).sizes["saved_time"] == 1
    assert contactlib.solve_transient(h, **args, save_fields=True).sizes["saved_time"] == 6
    strided = contactlib.solve_transient(h, **args, save_fields=2)
    assert list(strided.saved_time.values) == pytest.approx([0.0, 0.4, 0.8, 1.0])
    chosen = contactlib.solve_transient(h, **args, save_fields=[0.2, 0.6])
    assert list(chosen.saved_time.values) == pytest.approx([0.2, 0.6])
    for name, var in chosen.data_vars.items():
        assert var.attrs.get("units") and var.attrs.get("long_name"), name
    assert chosen.attrs["status"] == "completed" and chosen.attrs["contactlib_version"]
    assert chosen.attrs["prony"] == [2.0, 1.0, 5.0, 0.1]
    assert np.all(np.diff(chosen.contact_area.values) > 0)  # creeping under a constant load
    with pytest.raises(ValueError, match="save_fields"):
        contactlib.solve_transient(h, **args, save_fields=[0.3])


def test_progress_callback_and_interrupt_keep_the_steps_done():
    h = surfaces.self_affine(32, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, seed=1)
    seen = []

    def progress(step, total, t, row):
        seen.append((step, total, t, row["contact_area"]))
        if step == 3:
            raise KeyboardInterrupt

    with pytest.raises(contactlib.TransientInterrupted) as err:
        contactlib.solve_transient(h, material=two_branch(), times=np.linspace(0, 1, 10), mean_pressure=0.05,
                                   progress=progress)
    ds = err.value.dataset
    assert ds.sizes["time"] == 4 and [s[0] for s in seen] == [0, 1, 2, 3] and seen[0][1] == 10
    assert ds.attrs["status"] == "interrupted after 4 of 10 steps"
    assert list(ds.contact_area.values) == [s[3] for s in seen]
    assert isinstance(err.value, KeyboardInterrupt)


def test_a_step_that_does_not_converge_raises_with_the_steps_done():
    h = surfaces.self_affine(32, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, seed=1)
    with pytest.raises(contactlib.ConvergenceError, match="not converged at step 0") as err:
        contactlib.solve_transient(h, material=two_branch(), times=np.linspace(0, 1, 5), mean_pressure=0.05,
                                   max_iter=1)
    assert err.value.residual > 1e-8 and err.value.dataset.sizes["time"] == 0


@pytest.mark.parametrize("kwargs, match", [
    (dict(times=[0.0, 1.0, 1.0]), "times must increase"),
    (dict(log_every=-1), "log_every must be a whole number"),
    (dict(log_every=0.5), "log_every must be a whole number"),
    (dict(times=[0.0, 2.0, 1.0]), "times must increase"),
    (dict(mean_pressure=[0.1, np.nan, 0.1]), "mean_pressure history holds a non-finite"),
    (dict(mean_pressure=[0.1, 0.1]), "mean_pressure has 2 values for 3 times"),
    (dict(path=[0.0, 0.1]), "path must hold one position"),
    (dict(mean_pressure=None, penetration=None), "exactly one of mean_pressure or penetration"),
    (dict(mean_pressure=-0.1), "mean_pressure must be >= 0"),
    (dict(initial="glassy"), "initial must be one of"),
    (dict(tol=0.0), "tol must be a number in"),
])
def test_bad_transient_input_names_the_parameter(kwargs, match):
    args = dict(material=two_branch(), times=[0.0, 1.0, 2.0], mean_pressure=0.1, length=1.0)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        contactlib.solve_transient(np.cos(2 * np.pi * np.arange(16) / 16), **args)


@pytest.mark.parametrize("kwargs, match", [
    (dict(amplitude=0.0), "amplitude must be a finite number > 0"),
    (dict(amplitude=-1.0), "amplitude must be a finite number > 0"),
    (dict(frequency=0.0), "frequency must be a finite number > 0"),
    (dict(frequency=float("nan")), "frequency must be a finite number > 0"),
    (dict(steps_per_cycle=2), "steps_per_cycle"),
    (dict(direction=0.5), "direction must be 0 or pi for a profile"),
    (dict(tol=1e-3), "tol 0.001 must be at most a tenth of cycle_tol"),
    (dict(tol=3e-5, cycle_tol=3e-4, direction=0.5), "direction must be 0 or pi"),  # a tenth exactly passes tol
    (dict(tol=1e-5, cycle_tol=5e-5), "at most a tenth of cycle_tol 5e-05"),
])
def test_bad_reciprocating_input_names_the_parameter(kwargs, match):
    args = dict(material=two_branch(), amplitude=0.1, frequency=1.0, mean_pressure=0.1, length=1.0)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        contactlib.solve_reciprocating(np.cos(2 * np.pi * np.arange(16) / 16), **args)
