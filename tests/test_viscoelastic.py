"""Viscoelastic materials and steady sliding: limits, sign, two independent routes, energy balance, hard cases."""

import math

import numpy as np
import pytest

import contactlib
from contactlib import Elastic, Layer, Viscoelastic
from contactlib.core.grid import Grid
from contactlib.kernels.elastic import halfspace_love_multiplier
from contactlib.kernels.viscoelastic import modulus_deviation, real_where_self_conjugate, sliding_factor
from contactlib.reference import viscoelastic_profile as vp

SLS = Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)


def profile(n=1024, seed=3, slope=0.1, cutoff=None):
    cutoff = min(64, n // 4) if cutoff is None else cutoff
    return contactlib.surfaces.self_affine(n, hurst=0.8, q_roll=1, q_cutoff=cutoff, rms_slope=slope, seed=seed, dim=1)


def q0_of(h):
    return 2 * np.pi / (float(h.x[1] - h.x[0]) * h.sizes["x"])


# ---- materials -------------------------------------------------------------------------------------

def test_standard_linear_solid_closed_forms():
    m = Viscoelastic.standard_linear_solid(E0=2.0, E_inf=22.0, tau=0.1, nu=0.3)
    t = np.array([0.0, 0.05, 0.1, 1.0, 10.0])
    assert np.allclose(m.relaxation(t), 2 + 20 * np.exp(-t / 0.1), rtol=1e-14)
    creep_time = 0.1 * 22 / 2  # the retardation time is tau E_inf / E0
    assert np.allclose(m.creep(t), 1 / 2 - (1 / 2 - 1 / 22) * np.exp(-t / creep_time), rtol=1e-12)
    w = 1 / 0.1
    assert m.complex_modulus(w) == pytest.approx(2 + 20 * 1j / (1 + 1j), rel=1e-14)
    assert m.complex_modulus(-w) == pytest.approx(np.conj(m.complex_modulus(w)), rel=1e-14)
    assert m.complex_modulus(w).imag > 0  # loss modulus positive for omega > 0


def test_prony_creep_is_the_inverse_of_the_relaxation():
    """A 3-branch series: the creep spectrum's complex compliance times the complex modulus is 1, and
    the creep function convolved with the relaxation rate gives t (int E(t - s) dJ(s) = 1 for t > 0)."""
    m = Viscoelastic(E0=2.0, prony=[(5.0, 0.01), (30.0, 1.0), (100.0, 1e-3)], nu=0.4)
    times, weights = m.retardation()
    assert np.all(times > 0) and np.all(weights > 0)
    assert weights.sum() == pytest.approx(1 / m.E0 - 1 / m.E_inf, rel=1e-12)
    w = np.logspace(-4, 5, 40)
    compliance = 1 / m.E_inf + sum(D / (1 + 1j * w * lam) for lam, D in zip(times, weights))
    assert np.abs(compliance * m.complex_modulus(w) - 1).max() < 1e-12
    # Volterra identity at t = 3: E(0) J(t) + int_0^t E'(t - s)... written as J(0) E(t) + int J'(s) E(t - s) ds = 1
    t = 3.0
    s = np.linspace(0, t, 200_001)
    integrand = m.creep_rate(s) * m.relaxation(t - s)
    value = float(m.creep(0.0)) * float(m.relaxation(t)) + np.trapezoid(integrand, s)
    assert value == pytest.approx(1.0, abs=1e-6)


@pytest.mark.parametrize("kwargs, name", [
    (dict(E0=1.0, E_inf=0.5, tau=1.0, nu=0.3), "E_inf"),
    (dict(E0=1.0, E_inf=2.0, tau=0.0, nu=0.3), "tau"),
    (dict(E0=1.0, E_inf=2.0, tau=-1.0, nu=0.3), "tau"),
    (dict(E0=0.0, E_inf=2.0, tau=1.0, nu=0.3), "E0"),
    (dict(E0=1.0, E_inf=2.0, tau=1.0, nu=0.6), "nu"),
])
def test_bad_standard_linear_solid(kwargs, name):
    with pytest.raises(ValueError, match=name):
        Viscoelastic.standard_linear_solid(**kwargs)


@pytest.mark.parametrize("prony, name", [
    ([], "empty"), ([(1.0, float("nan"))], "tau_i"), ([(float("inf"), 1.0)], "E_i"), ([(1.0, 0.0)], "tau_i"),
    ("abc", "prony"),
])
def test_bad_prony(prony, name):
    with pytest.raises(ValueError, match=name):
        Viscoelastic(E0=1.0, prony=prony, nu=0.3)


def test_bad_sliding_input():
    h = profile(64)
    with pytest.raises(ValueError, match="sliding_velocity must be finite"):
        contactlib.solve(h, material=SLS, mean_pressure=0.01, sliding_velocity=float("nan"))
    with pytest.raises(ValueError, match="sliding_velocity must have 1"):
        contactlib.solve(h, material=SLS, mean_pressure=0.01, sliding_velocity=(1.0, 0.0))
    with pytest.raises(ValueError, match="active-set"):
        contactlib.solve(h, material=SLS, mean_pressure=0.01, sliding_velocity=1.0, method="active-set")
    with pytest.raises(ValueError, match="periodic"):
        contactlib.solve(h, material=SLS, mean_pressure=0.01, sliding_velocity=1.0, periodic=False)
    with pytest.raises(ValueError, match="contradicts"):
        contactlib.solve(h, material=SLS, mean_pressure=0.01, sliding_velocity=1.0, sliding_direction=np.pi)
    with pytest.raises(ValueError, match="not both"):
        contactlib.solve(h, material=SLS, E=1.0, mean_pressure=0.01)
    with pytest.raises(ValueError, match="material"):
        contactlib.solve(h, mean_pressure=0.01)


def test_elastic_material_is_the_shorthand():
    h = profile(256)
    a = contactlib.solve(h, E=2.0, nu=0.3, mean_pressure=0.02)
    b = contactlib.solve(h, material=Elastic(2.0, 0.3), mean_pressure=0.02)
    np.testing.assert_array_equal(a.pressure.values, b.pressure.values)


# ---- limits and the reduced model ------------------------------------------------------------------

@pytest.mark.parametrize("zeta, modulus", [(1e-9, "E0"), (1e9, "E_inf")])
def test_speed_limits_are_the_elastic_solutions(zeta, modulus):
    """Far below and above the band the full viscoelastic model (forced by a tight tol) equals the elastic
    solution with E0 or E_inf to solver tolerance; at the default tol the reduced (elastic) model runs."""
    h = profile(1024)
    V = zeta / q0_of(h)
    E = getattr(SLS, modulus)
    elastic = contactlib.solve(h, E=E, nu=0.5, mean_pressure=0.02, tol=1e-11)
    full = contactlib.solve(h, material=SLS, mean_pressure=0.02, sliding_velocity=V, tol=1e-11)
    assert full.attrs["material_model"].startswith("viscoelastic")
    scale = float(np.abs(elastic.pressure).max())
    assert float(np.abs(full.pressure - elastic.pressure).max()) / scale < 1e-6
    assert float(full.contact_area) == pytest.approx(float(elastic.contact_area), abs=2 / h.size)
    reduced = contactlib.solve(h, material=SLS, mean_pressure=0.02, sliding_velocity=V * 1e-4 if zeta < 1 else V * 1e4,
                               tol=1e-8)
    assert reduced.attrs["material_model"].startswith(f"elastic, {'relaxed' if modulus == 'E0' else 'glassy'}")
    assert float(np.abs(reduced.pressure - elastic.pressure).max()) / scale < 1e-5


def test_reduction_rule_compares_the_complex_modulus():
    g = Grid((64,), (1.0,))
    V = 1e-7
    deviation = modulus_deviation(g, SLS, (V,), SLS.E0)
    # the loss modulus moves at first order: ~ (E_inf - E0) q_max V tau
    assert deviation == pytest.approx((SLS.E_inf - SLS.E0) * 2 * np.pi * 32 * V, rel=1e-3)


def test_compiled_factor_and_deviations_equal_the_materials_complex_modulus():
    """The compiled per-speed pass (:func:`sliding_factor_and_deviations`) sums the Prony series itself: against
    ``E0 / material.complex_modulus`` on the grid and the deviations from it, for a three-branch material on an odd
    and an even 2D grid at an oblique speed; on the Nyquist planes the mean over the signs of their component."""
    from contactlib.kernels.viscoelastic import sliding_factor_and_deviations, sliding_frequency

    material = Viscoelastic(E0=2.0, prony=[(5.0, 0.01), (30.0, 0.3), (100.0, 7.0)], nu=0.4)
    for shape in ((33, 20), (32, 48)):
        grid = Grid(shape, (1.0, 1.5))
        velocity = (0.7, -0.2)
        factor, deviations = sliding_factor_and_deviations(grid, material, velocity, (material.E0, material.E_inf))
        modulus = material.complex_modulus(sliding_frequency(grid, velocity))
        expected = material.E0 / modulus
        # a Nyquist row (an even first axis) or column (an even second one): the mean over the signs of its component
        qx, qy = (q.ravel() for q in grid.wavevectors())
        at = lambda qx, qy: material.E0 / material.complex_modulus(-(qx * velocity[0] + qy * velocity[1]))  # noqa: E731
        i, j = shape[0] // 2, shape[1] // 2
        if shape[0] % 2 == 0:
            expected[i, :] = (at(qx[i], qy) + at(-qx[i], qy)) / 2
        if shape[1] % 2 == 0:
            expected[:, j] = (at(qx, qy[j]) + at(qx, -qy[j])) / 2
        if shape[0] % 2 == 0 and shape[1] % 2 == 0:
            expected[i, j] = sum(at(a * qx[i], b * qy[j]) for a in (1, -1) for b in (1, -1)) / 4
        assert np.max(np.abs(factor - expected)) < 1e-14
        assert np.array_equal(factor, real_where_self_conjugate(grid, factor.copy()))  # real where self-conjugate
        rest = modulus.reshape(-1)[1:]  # every wavevector but q = 0
        for deviation, reference in zip(deviations, (material.E0, material.E_inf)):
            assert deviation == pytest.approx(float(np.abs(rest - reference).max()) / reference, rel=1e-13)


# ---- sign: the pressure leans to the leading edge -----------------------------------------------------

def cylinder(n=2048, length=1.0, radius=0.5):
    x = (np.arange(n) - n // 2) * length / n
    return x, -x**2 / (2 * radius)


@pytest.mark.parametrize("direction", [1.0, -1.0])
def test_cylinder_leans_to_the_leading_edge(direction):
    """A cylinder sliding in +x (or -x) on a standard linear solid: the contact moves ahead (shrinks at
    the trailing edge), the pressure centroid is ahead of the axis, mu_a > 0, and mu_a = x_c / R."""
    x, h = cylinder()
    radius, load = 0.5, 5e-4
    elastic = contactlib.solve(h, E=1.0, nu=0.5, mean_pressure=load, length=1.0)
    a0 = float(np.ptp(x[elastic.pressure.values > 0])) / 2
    V = direction * a0 / SLS.relaxation_times[0]  # V tau / a = 1: the middle of the band
    out = contactlib.solve(h, material=SLS, mean_pressure=load, sliding_velocity=V, length=1.0, tol=1e-10)
    p = out.pressure.values
    touching = x[p > 0]
    lead, trail = (touching.max(), -touching.min()) if direction > 0 else (-touching.min(), touching.max())
    assert lead > 1.2 * trail  # the trailing edge moved in
    centroid = float(np.sum(x * p) / np.sum(p))
    assert direction * centroid > 0.1 * a0
    mu_a = float(out.friction_coefficient_interlocking)
    assert mu_a > 0
    assert mu_a == pytest.approx(direction * centroid / radius, rel=1e-2)


# ---- two independent routes ---------------------------------------------------------------------------

def test_real_space_kernel_from_creep_equals_spectral_kernel():
    """Seed eq 25 integrated in time from J(t) on Love's elements equals the complex-modulus multiplier
    with each aliased image at its own frequency."""
    n, length = 256, 1.0
    g = Grid((n,), (length,))
    for zeta in (3e-3, 0.3, 30.0):
        V = zeta * length / (2 * np.pi)
        real_space = vp.steady_sliding_influence(n, length=length, material=SLS, velocity=V)
        love = halfspace_love_multiplier(g, 1 / (1 - SLS.nu**2), factor=lambda q: sliding_factor(SLS, (V,), q))
        spectral = np.fft.irfft(real_where_self_conjugate(g, love), n) / SLS.E0
        assert np.abs(real_space - spectral).max() < 1e-6 * np.abs(real_space).max()


def test_two_routes_agree_on_a_rough_profile():
    """Spectral complex-modulus kernel + constrained CG against the real-space eq 25 kernel + active set:
    pressure field, contact area and mu_a within 1 % (they agree far better)."""
    h = profile(512, cutoff=32)
    length = float(h.x[1] - h.x[0]) * h.size
    V = 1.0 / q0_of(h)  # V tau q0 = 1
    spectral = contactlib.solve(h, material=SLS, mean_pressure=0.1, sliding_velocity=V, kernel="love", tol=1e-11)
    real = vp.solve_profile(h.values, length=length, material=SLS, velocity=V, mean_pressure=0.1, tol=1e-11)
    p = spectral.pressure.values
    assert 0.1 < float(spectral.contact_area) < 0.9
    assert np.linalg.norm(p - real.pressure) / np.linalg.norm(real.pressure) < 1e-2
    assert float(spectral.contact_area) == pytest.approx(float((real.pressure > 0).mean()), rel=1e-2)
    mu_real = contactlib.analysis.interlocking_friction(real.pressure, h.values, lengths=(length,))
    assert float(spectral.friction_coefficient_interlocking) == pytest.approx(mu_real, rel=1e-2)
    assert mu_real > 0.01  # a real hysteretic friction, not a vanishing one


# ---- energy balance ------------------------------------------------------------------------------------

@pytest.mark.parametrize("dim", [1, 2])
def test_friction_power_equals_dissipation(dim):
    """mu_a p_m V (from the pressure on the slopes of the deformed surface) equals the dissipation from the loss
    modulus and the displacement spectrum to round-off: both are the discrete operator's ``p^T D M p``. (From the
    rigid slopes they differed by 0.2-1 % here, by 2 % at 8 points per shortest wavelength in 1D and up to 15 % at 4
    in 2D.)"""
    n = 2048 if dim == 1 else 128
    h = contactlib.surfaces.self_affine(n, hurst=0.8, q_roll=1, q_cutoff=n // (32 if dim == 1 else 8), rms_slope=0.1,
                                        seed=5, dim=dim)
    V = 1.0 / q0_of(h)
    velocity = (V,) if dim == 1 else (V * np.cos(0.3), V * np.sin(0.3))
    out = contactlib.solve(h, material=SLS, mean_pressure=0.03, sliding_velocity=velocity, tol=1e-10)
    friction_power = float(out.friction_coefficient_interlocking) * float(out.mean_pressure) * V
    dissipation = contactlib.analysis.dissipated_power(out.displacement, material=SLS, sliding_velocity=velocity)
    assert friction_power > 0
    assert dissipation == pytest.approx(friction_power, rel=1e-12)
    assert float(out.dissipated_power) == pytest.approx(dissipation, rel=1e-12)


# ---- hard cases -----------------------------------------------------------------------------------------

@pytest.mark.parametrize("zeta", [1e-4, 1e-2, 1.0, 1e2, 1e4])
@pytest.mark.parametrize("load", [2e-4, 0.02, 3.0])
def test_hard_speeds_and_loads_converge(zeta, load):
    """E_inf/E0 = 10, V tau q0 over 8 decades, contact from ~1 % to full: converged to tol 1e-8."""
    h = profile(1024)
    out = contactlib.solve(h, material=SLS, mean_pressure=load, sliding_velocity=zeta / q0_of(h), tol=1e-8)
    assert out.attrs["converged"] == 1 and float(out.residual) <= 1e-8
    area = float(out.contact_area)
    assert (area < 0.05) if load < 1e-3 else True
    if load == 3.0:
        assert area == 1.0
    # an elastic contact has mu_a = 0 up to discretisation (here |mu_a| ~ 5e-5 at the fast end)
    assert float(out.friction_coefficient_interlocking) >= -1e-3


def test_glassy_ratio_1000_converges_across_the_fast_band():
    m = Viscoelastic.standard_linear_solid(E0=1.0, E_inf=1000.0, tau=1.0, nu=0.5)
    h = profile(1024)
    for zeta in (1.0, 1e2, 1e4):
        out = contactlib.solve(h, material=m, mean_pressure=0.5, sliding_velocity=zeta / q0_of(h), tol=1e-8)
        assert out.attrs["converged"] == 1


@pytest.mark.parametrize("base", ["confined", "remote_pressure"])
def test_viscoelastic_layer_with_coupled_friction(base):
    """A confined (and a remote-pressure) layer, q0 h = 1.5, mu_c = 0.8, nu = 0.5, across the band: converges,
    the hysteresis adds to mu_a in the band, and (confined) the coupling keeps mu_a > 0 at both ends of the
    speed range (the remote-pressure layer's geometric coupling has the other sign at the fast end)."""
    h = profile(1024)
    q0 = q0_of(h)
    m = Viscoelastic.standard_linear_solid(E0=1.0, E_inf=11.0, tau=1.0, nu=0.5)
    layer = Layer(1.5 / q0, base)
    mus = []
    for zeta in (1e-4, 1.0, 1e4):
        out = contactlib.solve(h, material=m, mean_pressure=0.05, sliding_velocity=zeta / q0, layer=layer,
                               friction=0.8, tol=1e-8)
        assert out.attrs["converged"] == 1
        mus.append(float(out.friction_coefficient_interlocking))
    if base == "confined":
        assert min(mus) > 1e-4
    assert mus[1] > max(mus[0], mus[2]) + 5e-3  # the hysteresis adds to the coupling in the band


def test_non_monotone_frictional_layer_is_refused_where_ill_posed():
    """Thin confined layer, mu_c = 0.8, on elements longer than the layer is thick (16 points, q0 h = 0.3):
    the viscoelastic lag of the coupling makes an element's own compliance negative, so the operator is not a
    P-matrix; refused, naming friction (tests/test_viscoelastic_thin_layer.py: the two solutions, and the
    well-posed non-monotone scenes that are solved)."""
    h = profile(16)
    q0 = q0_of(h)
    m = Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)
    with pytest.raises(ValueError, match="friction"):
        contactlib.solve(h, material=m, mean_pressure=0.05, sliding_velocity=0.1 / q0, layer=Layer(0.3 / q0),
                         friction=0.8)


def test_two_dimensional_patches_stretch_across_the_sliding():
    """2D isotropic surface, V tau q0 in the band: the deformed surface's anisotropy tensor has its
    principal slope direction across the velocity (theta_d near pi/2) and gamma_d < 1."""
    h = contactlib.surfaces.self_affine(128, hurst=0.8, q_roll=1, q_cutoff=32, rms_slope=0.1, seed=2)
    q0 = q0_of(h)
    out = contactlib.solve(h, material=SLS, mean_pressure=0.05, sliding_velocity=(3.0 / q0, 0.0), tol=1e-8)
    band = contactlib.analysis.anisotropy_tensor(out.displacement, 4, 32)
    rigid = contactlib.analysis.anisotropy_tensor(h, 4, 32)
    assert float(band.gamma) < 0.9 * float(rigid.gamma)
    assert abs(float(band.theta_d) - math.pi / 2) < 0.3


def test_extreme_speed_keeps_the_glassy_answer():
    """omega tau past 1e154 overflowed x * x in the complex modulus, the modulus came out NaN and the scene was
    solved as the relaxed elastic one (area 0.337 against 0.068). In 1/x the answer at 1e200 is the one at 1e10."""
    h = contactlib.surfaces.self_affine(32, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, seed=0)
    sls = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)
    fast = contactlib.solve(h, material=sls, mean_pressure=0.02, sliding_velocity=(1e10, 0.0))
    extreme = contactlib.solve(h, material=sls, mean_pressure=0.02, sliding_velocity=(1e200, 0.0))
    np.testing.assert_allclose(extreme.pressure.values, fast.pressure.values, rtol=0,
                               atol=1e-8 * float(fast.pressure.max()))
