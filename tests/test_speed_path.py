"""A path of speeds solved from predicted starts gives the cold solves' answers (contactlib.solve_speeds)."""

import numpy as np
import pytest

import contactlib

SLS = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)


def test_prediction_is_the_secant_in_log_speed_clipped_at_zero():
    a, b = np.array([1.0, 2.0, 0.5]), np.array([2.0, 1.0, 0.0])
    # pressure linear in log(speed): 1 -> a, 10 -> b, so 100 -> 2b - a (clipped), 10**1.5 -> (a + b) / 2 + (b - a)
    assert np.allclose(contactlib.predict_pressure([1.0, 10.0], [a, b], 100.0), [3.0, 0.0, 0.0])
    assert np.allclose(contactlib.predict_pressure([1.0, 10.0], [a, b], 10**1.5), [2.5, 0.5, 0.0])
    assert np.array_equal(contactlib.predict_pressure([3.0], [a], 5.0), a)
    assert contactlib.predict_pressure([], [], 1.0) is None
    with pytest.raises(ValueError, match="speed"):
        contactlib.predict_pressure([1.0, 10.0], [a, b], 0.0)


def test_prediction_from_speeds_a_round_off_apart_is_the_last_answer():
    """Two speeds 5e-16 apart in log(speed) made the secant's step 4.6e15 spacings long: the start overflowed to NaN
    and solve_speeds raised on its own warm start (found by the metamorphic suite's thorough profile)."""
    a, b = np.array([1.0, 2.0, 0.5]), np.array([1.0 + 1e-15, 2.0, 0.0])
    speeds = [1.0, 10**2.220446049250313e-16]
    assert np.array_equal(contactlib.predict_pressure(speeds, [a, b], 10.0), b)
    h = contactlib.surfaces.self_affine(48, hurst=1, q_roll=1, q_cutoff=2, rms_slope=0.1, seed=0, dim=1)
    v0 = 1 / (2 * np.pi)
    path = contactlib.solve_speeds(h, [v0, speeds[1] * v0, 10 * v0], material=SLS, mean_pressure=0.0125, tol=1e-10)
    alone = contactlib.solve(h, material=SLS, mean_pressure=0.0125, tol=1e-10, sliding_velocity=10 * v0)
    assert np.abs(path[-1].pressure.values - alone.pressure.values).max() <= 1e-7 * float(alone.pressure.max())


def test_prediction_from_three_speeds_extrapolates_geometric_changes():
    """Answers whose changes shrink (or grow) by a constant ratio per step in log speed are predicted exactly,
    one step or two ahead; unequal spacing falls back to the secant."""
    limit, change = np.array([1.0, 0.5, 2.0]), np.array([0.4, -0.05, 0.1])
    for ratio in (0.62, 1.5):
        speeds = [1.0, 10.0, 100.0]
        pressures = [limit + change * ratio**k for k in range(3)]
        for ahead in (1, 2):
            expected = limit + change * ratio ** (2 + ahead)
            assert np.allclose(contactlib.predict_pressure(speeds, pressures, 100.0 * 10**ahead), expected)
    pressures = [limit + change * 0.5**k for k in range(3)]
    secant = pressures[2] + (pressures[2] - pressures[1])
    assert np.allclose(contactlib.predict_pressure([1.0, 3.0, 100.0], pressures, 100.0 * 100 / 3), secant)


def test_path_answers_equal_cold_solves():
    h = contactlib.surfaces.self_affine(64, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, seed=3)
    velocities = [(zeta / (2 * np.pi), 0.0) for zeta in np.logspace(-2, 1, 5)]
    path = contactlib.solve_speeds(h, velocities, material=SLS, mean_pressure=0.02, tol=1e-8)
    areas = []
    for velocity, warm in zip(velocities, path):
        cold = contactlib.solve(h, material=SLS, mean_pressure=0.02, sliding_velocity=velocity, tol=1e-8)
        assert warm.residual <= 1e-8
        dp = np.linalg.norm(warm.pressure.values - cold.pressure.values) / np.linalg.norm(cold.pressure.values)
        assert dp < 1e-6
        assert float(warm.contact_area) == pytest.approx(float(cold.contact_area), abs=2 / h.size)
        assert float(warm.friction_coefficient_interlocking) == pytest.approx(
            float(cold.friction_coefficient_interlocking), rel=1e-6)
        areas.append(float(cold.contact_area))
    assert areas[0] > 1.3 * areas[-1]  # the path crosses the band: the glassy body touches less


def test_bad_path_arguments():
    h = np.zeros(32)
    with pytest.raises(ValueError, match="sliding_velocities"):
        contactlib.solve_speeds(h, [0.0], material=SLS, mean_pressure=0.1)
    with pytest.raises(ValueError, match="initial_pressure"):
        contactlib.solve_speeds(h, [1.0], material=SLS, mean_pressure=0.1, initial_pressure=np.ones(32))


def test_prediction_refuses_mismatched_or_non_finite_answers():
    """Fewer speeds than answers raised an IndexError; NaN answers gave a NaN start. Both named now."""
    p = np.ones((4, 4))
    with pytest.raises(ValueError, match="speeds: one per answer"):
        contactlib.predict_pressure([1.0], [p, p, p], 8.0)
    with pytest.raises(ValueError, match="pressures: the answers"):
        contactlib.predict_pressure([1.0, 2.0], [p, np.full((4, 4), np.nan)], 4.0)


@pytest.mark.parametrize("velocities, match", [(1.0, "must be a sequence"), ("ab", "must be a sequence"),
                                               ([], "is empty")])
def test_speed_path_refuses_what_is_not_a_path(velocities, match):
    """A bare number or a string failed deep in numpy, an empty path returned []: named now."""
    h = contactlib.surfaces.self_affine(16, hurst=0.8, q_roll=1, q_cutoff=4, rms_slope=0.1, seed=1)
    sls = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)
    with pytest.raises(ValueError, match=match):
        contactlib.solve_speeds(h, velocities, material=sls, mean_pressure=0.02)
    with pytest.raises(ValueError, match="heights must be a DataArray"):
        contactlib.surfaces.resample(h.values, 32)


def test_speed_path_with_the_active_set_method_gets_no_warm_start():
    """method="active-set" takes no initial_pressure: the path's predicted start made its second speed fail."""
    h = contactlib.surfaces.self_affine(16, hurst=0.8, q_roll=1, q_cutoff=4, rms_slope=0.1, seed=1)
    out = contactlib.solve_speeds(h, [(1.0, 0.0), (2.0, 0.0)], E=1.0, nu=0.5, mean_pressure=0.02, method="active-set")
    assert len(out) == 2 and all(o.attrs["converged"] == 1 for o in out)
