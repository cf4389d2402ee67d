"""Rough surfaces: contact conditions, cross-checks between solvers and load modes, 1D and 2D."""

import numpy as np
import pytest

import contactlib
from contactlib.solvers import contact_residual


def check_contact_conditions(out, tol):
    p, g = out.pressure.values, out.gap.values
    scale = float(np.sqrt(np.mean((g - g.mean()) ** 2))) or 1.0
    assert p.min() >= 0.0
    h_rms = float(np.sqrt(np.mean((out.gap + 0).values ** 2)))
    assert h_rms > 0
    # interpenetration and complementarity, each bounded by the reported residual
    assert float(out.residual) <= tol
    assert np.mean(np.maximum(-g, 0)) <= 10 * tol * scale
    assert np.mean(p * np.abs(g)) <= 10 * tol * p.mean() * scale
    # force balance: the mean of the field is the prescribed/reported mean pressure
    assert p.mean() == pytest.approx(float(out.mean_pressure), rel=1e-12)
    # gap identity: g = u + (max h - h) - penetration, checked by the caller with the heights


@pytest.mark.parametrize("n", [64, 63, 48])
def test_rough_2d_contact_conditions(material, n):
    h = contactlib.surfaces.self_affine(n, hurst=0.7, q_roll=2, q_cutoff=n // 4, rms_slope=0.1, seed=7)
    out = contactlib.solve(h, E=material["E"], nu=material["nu"], mean_pressure=0.02, tol=1e-9)
    check_contact_conditions(out, 1e-9)
    assert 0.05 < float(out.contact_area) < 0.6
    lhs = out.displacement + (h.max() - h) - out.penetration
    np.testing.assert_allclose(out.gap.values, lhs.values, atol=1e-14 * float(h.max() - h.min()))
    assert float(out.mean_pressure) == pytest.approx(0.02, rel=1e-12)


def test_rough_1d_contact_conditions(material):
    h = contactlib.surfaces.self_affine(4096, hurst=0.5, q_roll=4, q_cutoff=1024, rms_slope=0.2, seed=11, dim=1)
    out = contactlib.solve(h, E=material["E"], nu=material["nu"], mean_pressure=0.05, tol=1e-9)
    check_contact_conditions(out, 1e-9)
    assert out.pressure.dims == ("x",)


@pytest.mark.parametrize("dim,n", [(2, 32), (1, 512)])
def test_cg_agrees_with_active_set(material, dim, n):
    h = contactlib.surfaces.self_affine(n, hurst=0.8, q_roll=2, q_cutoff=n // 4, rms_slope=0.1, seed=1, dim=dim)
    kwargs = dict(E=material["E"], nu=material["nu"], mean_pressure=0.02, tol=1e-10)
    cg = contactlib.solve(h, **kwargs)
    active = contactlib.solve(h, method="active-set", **kwargs)
    p_max = float(cg.pressure.max())
    assert np.max(np.abs(cg.pressure.values - active.pressure.values)) < 1e-6 * p_max
    assert float(active.penetration) == pytest.approx(float(cg.penetration), rel=1e-8)
    assert float(active.contact_area) == float(cg.contact_area)


def test_active_set_non_periodic_hertz_agrees(material):
    h = contactlib.surfaces.paraboloid(32, radius=1.0)
    kwargs = dict(E=material["E"], nu=material["nu"], penetration=0.005, periodic=False, tol=1e-10)
    cg = contactlib.solve(h, **kwargs)
    active = contactlib.solve(h, method="active-set", **kwargs)
    assert np.max(np.abs(cg.pressure.values - active.pressure.values)) < 1e-6 * float(cg.pressure.max())


@pytest.mark.parametrize("kernel", ["spectral", "love"])
@pytest.mark.parametrize("periodic", [True, False])
def test_load_and_displacement_control_same_state(material, rough64, kernel, periodic):
    kwargs = dict(E=material["E"], nu=material["nu"], kernel=kernel, periodic=periodic, tol=1e-11)
    # non-periodic: a rough sphere, so that the footprint stays inside the window
    heights = rough64 if periodic else rough64 * 0.05 + contactlib.surfaces.paraboloid(64, radius=0.5)
    by_load = contactlib.solve(heights, mean_pressure=0.01, **kwargs)
    by_depth = contactlib.solve(heights, penetration=float(by_load.penetration), **kwargs)
    assert float(by_depth.mean_pressure) == pytest.approx(0.01, rel=1e-7)
    p_max = float(by_load.pressure.max())
    assert np.max(np.abs(by_load.pressure.values - by_depth.pressure.values)) < 1e-6 * p_max
    assert float(by_load.contact_area) == float(by_depth.contact_area)


def test_warm_start_reaches_the_same_state_faster(material, rough64):
    kwargs = dict(E=material["E"], nu=material["nu"], tol=1e-10)
    first = contactlib.solve(rough64, mean_pressure=0.010, **kwargs)
    cold = contactlib.solve(rough64, mean_pressure=0.011, **kwargs)
    warm = contactlib.solve(rough64, mean_pressure=0.011, initial_pressure=first.pressure, **kwargs)
    assert int(warm.iterations) < int(cold.iterations)
    assert np.max(np.abs(cold.pressure - warm.pressure)) < 1e-7 * float(cold.pressure.max())


def test_residual_is_scale_free(material, rough64):
    """Heights x s and E x s give the same dimensionless answer (pressures x s^2 / s, ...)."""
    base = contactlib.solve(rough64, E=material["E"], nu=material["nu"], mean_pressure=0.01, tol=1e-10)
    for s in (1e-9, 1e3):
        scaled = contactlib.solve(rough64 * s, E=material["E"], nu=material["nu"], mean_pressure=0.01 * s, tol=1e-10)
        assert float(scaled.contact_area) == float(base.contact_area)
        np.testing.assert_allclose(scaled.pressure.values / s, base.pressure.values, rtol=0,
                                   atol=1e-7 * float(base.pressure.max()))
        assert float(scaled.penetration) / s == pytest.approx(float(base.penetration), rel=1e-7)


def test_residual_definition():
    p = np.array([1.0, 2.0, 0.0, 0.0])
    g = np.array([0.0, 0.1, 0.5, -0.2])
    # mean(p|g|) = 0.2/4 = 0.05; mean(p) = 0.75; mean(max(-g,0)) = 0.05
    expected = (0.05 + 0.75 * 0.05) / (0.75 * 2.0)
    assert contact_residual(p, g, 2.0) == pytest.approx(expected, rel=1e-15)


def test_flat_surface_is_full_contact(material):
    out = contactlib.solve(np.zeros((16, 16)), length=1.0, E=material["E"], nu=material["nu"], mean_pressure=0.3)
    assert float(out.contact_area) == 1.0
    np.testing.assert_allclose(out.pressure.values, 0.3, rtol=1e-14)


def test_penetration_beyond_full_contact_refused(material, rough64):
    too_deep = float(rough64.max() - rough64.mean()) * 1.01
    with pytest.raises(ValueError, match="penetration"):
        contactlib.solve(rough64, E=material["E"], nu=material["nu"], penetration=too_deep)


def test_negative_penetration_is_no_contact(material, rough64):
    out = contactlib.solve(rough64, E=material["E"], nu=material["nu"], penetration=-1e-3)
    assert float(out.contact_area) == 0.0 and float(out.mean_pressure) == 0.0
    assert float(out.gap.min()) == pytest.approx(1e-3)


def _compliance_and_heights(dim, n):
    from contactlib.core.grid import Grid
    from contactlib.model.operators import Compliance

    h = contactlib.surfaces.self_affine(n, hurst=0.8, q_roll=4, q_cutoff=n // 8, rms_slope=0.1, seed=1,
                                        dim=dim).values
    return Compliance(Grid(h.shape, (1.0,) * dim), E_star=1.0), h


def test_kept_directions_converge_sooner_to_the_same_answer():
    """The default restart rule (conjugacy kept through re-entries of under 1 % of the contact set)
    against Polonsky & Keer's (restart on every re-entry), 512^2 at 47 % contact: the same pressure
    field to the accuracy both promise, in at least 1.5x fewer iterations (1.9x here)."""
    from contactlib.solvers import solve_polonsky_keer

    op, h = _compliance_and_heights(2, 512)
    kept = solve_polonsky_keer(op, h, mean_pressure=0.03, tol=1e-10)
    restarted = solve_polonsky_keer(op, h, mean_pressure=0.03, tol=1e-10, restart_fraction=0.0)
    assert kept.converged and restarted.converged
    assert 0.3 < np.mean(kept.pressure > 0) < 0.7
    assert 1.5 * kept.iterations <= restarted.iterations
    assert np.linalg.norm(kept.pressure - restarted.pressure) <= 1e-8 * np.linalg.norm(restarted.pressure)
    assert kept.penetration == pytest.approx(restarted.penetration, rel=1e-9)


def test_kept_directions_converge_where_restarts_stall():
    """A 16384-point profile at 75 % contact: restarting on every re-entry stalls at residual ~5e-3;
    the default rule converges, and the dual solver (displacement control, another formulation) at
    its penetration gives back the load and the pressure field."""
    from contactlib.solvers import solve_polonsky_keer
    from contactlib.solvers.symmetric.dual import solve_periodic_displacement

    op, h = _compliance_and_heights(1, 16384)
    restarted = solve_polonsky_keer(op, h, mean_pressure=0.05, tol=1e-10, restart_fraction=0.0)
    assert not restarted.converged and restarted.residual > 1e-3
    kept = solve_polonsky_keer(op, h, mean_pressure=0.05, tol=1e-10)
    assert kept.converged and kept.residual <= 1e-10
    dual = solve_periodic_displacement(op, h, penetration=kept.penetration, tol=1e-10)
    assert dual.converged
    assert dual.mean_pressure == pytest.approx(0.05, rel=1e-7)
    assert np.linalg.norm(dual.pressure - kept.pressure) <= 1e-6 * np.linalg.norm(kept.pressure)
