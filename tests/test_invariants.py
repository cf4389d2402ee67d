"""Invariants in one place (issue 38): every entry point checks its result before returning it, a corrupted state
raises :class:`contactlib.invariants.InvariantError` (a ConvergenceError) and is never returned as converged."""

import dataclasses

import numpy as np
import pytest

import contactlib
from contactlib.problems import adhesive as adhesive_contact, problem, transient
from contactlib import invariants, surfaces
from contactlib.model.hereditary import PronyHistory
from contactlib.invariants import InvariantError

CONTACT = "load, sign, gap, complementarity, gap_definition"

# the scenes are coarse on purpose (fast); the resolution guard's warnings are another test's business
pytestmark = pytest.mark.filterwarnings("ignore::UserWarning")


@pytest.fixture(scope="module")
def rough():
    return surfaces.self_affine(32, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, seed=3)


def sls(E_inf=10.0, tau=1.0):
    return contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=E_inf, tau=tau, nu=0.5)


def corrupting(monkeypatch, corrupt):
    """Make every contact solve of :func:`contactlib.solve` return ``corrupt(state)``, still claiming convergence."""
    run = contactlib.Problem.run

    def corrupted(self, *args, **kwargs):
        state = run(self, *args, **kwargs)
        assert state.converged
        return corrupt(state)

    monkeypatch.setattr(contactlib.Problem, "run", corrupted)


def moved_pressure(state, source, target, amount):
    """The state with ``amount`` of pressure moved from point ``source`` to ``target`` (the load unchanged)."""
    p = state.pressure.copy()
    p.flat[source] -= amount
    p.flat[target] += amount
    return dataclasses.replace(state, pressure=p)


def open_point(state):
    """The open point with the largest gap (far from the contact)."""
    return int(np.argmax(np.where(state.pressure > 0, -np.inf, state.gap)))


def assert_refused(err, invariant):
    assert err.invariant == invariant
    assert err.violation > err.bound > 0
    assert isinstance(err, contactlib.ConvergenceError)
    assert err.dataset.attrs["converged"] == 0 and err.dataset.attrs["invariant_failed"] == invariant
    assert f"invariant '{invariant}' failed" in str(err)


# ---- the checks themselves ---------------------------------------------------------------------------------------

def test_checks_pass_within_and_fail_beyond_their_bound():
    assert invariants.check_load(1.0 + 5e-9, 1.0, tol=1e-8, scale=1.0).passed
    assert not invariants.check_load(1.0 + 2e-8, 1.0, tol=1e-8, scale=1.0).passed
    assert invariants.check_penetration(0.5, 0.5 + 1e-9, tol=1e-8, height_rms=1.0).passed
    assert not invariants.check_gap(-2e-5, tol=1e-8, height_rms=1.0).passed  # 2000 tol of one rms height
    assert invariants.check_gap(-5e-6, tol=1e-8, height_rms=1.0).passed
    assert not invariants.check_energy_balance(1.0 + 2e-8, 1.0, scale=1.0, tol=1e-8).passed
    assert invariants.check_energy_balance(1.0 + 5e-9, 1.0, scale=1.0, tol=1e-8).passed
    nan = invariants.check_load(float("nan"), 1.0, tol=1e-8, scale=1.0)
    assert not nan.passed  # a NaN never passes


def test_field_measures_match_the_solver_residual(rough):
    """The fused pass gives the residual's own terms: its complementarity term plus its interpenetration term is
    contact_residual of the returned fields, which the solve reported within RESIDUAL_MARGIN."""
    from contactlib.solvers.state import contact_residual, height_scale
    ds = contactlib.solve(rough, E=1.0, nu=0.5, mean_pressure=0.02, tol=1e-8)
    h = rough.values
    p, g, u = (ds[k].values for k in ("pressure", "gap", "displacement"))
    m = invariants.field_measures(p, g, u, h, float(ds.penetration))
    assert m.height_rms == pytest.approx(height_scale(h), rel=1e-12)
    comp = m.complementarity / (m.mean_pressure * m.height_rms)
    pen = float(np.mean(np.maximum(-g, 0.0))) / m.height_rms
    assert comp + pen == pytest.approx(contact_residual(p, g, height_scale(h)), rel=1e-9)
    assert comp + pen <= invariants.RESIDUAL_MARGIN * float(ds.residual)
    assert m.gap_definition / m.height_rms < 1e-12


# ---- solve: a corrupted state raises -----------------------------------------------------------------------------

def test_solve_refuses_a_wrong_load(rough, monkeypatch):
    corrupting(monkeypatch, lambda s: dataclasses.replace(s, pressure=1.001 * s.pressure,
                                                          mean_pressure=1.001 * s.mean_pressure))
    with pytest.raises(InvariantError) as err:
        contactlib.solve(rough, E=1.0, nu=0.5, mean_pressure=0.02)
    assert_refused(err.value, "load")
    assert err.value.violation == pytest.approx(1e-3, rel=1e-6)


def test_solve_refuses_a_wrong_penetration(rough, monkeypatch):
    corrupting(monkeypatch, lambda s: dataclasses.replace(s, penetration=s.penetration * 1.001))
    with pytest.raises(InvariantError) as err:
        contactlib.solve(rough, E=1.0, nu=0.5, penetration=float(rough.std()))
    assert_refused(err.value, "penetration")


def test_solve_refuses_a_negative_pressure(rough, monkeypatch):
    def corrupt(s):  # tension at an open point, the load kept: only the sign is wrong there
        return moved_pressure(s, open_point(s), int(np.argmax(s.pressure)), 1e-3 * s.mean_pressure)

    corrupting(monkeypatch, corrupt)
    with pytest.raises(InvariantError) as err:
        contactlib.solve(rough, E=1.0, nu=0.5, mean_pressure=0.02)
    assert_refused(err.value, "sign")


def test_solve_refuses_interpenetration(rough, monkeypatch):
    def corrupt(s):  # one open point pushed into the rigid surface, gap and displacement together
        k, depth = open_point(s), s.gap.max() + 1e-3 * float(rough.std())
        gap, displacement = s.gap.copy(), s.displacement.copy()
        gap.flat[k] -= depth
        displacement.flat[k] -= depth
        return dataclasses.replace(s, gap=gap, displacement=displacement)

    corrupting(monkeypatch, corrupt)
    with pytest.raises(InvariantError) as err:
        contactlib.solve(rough, E=1.0, nu=0.5, mean_pressure=0.02)
    assert_refused(err.value, "gap")


def test_solve_refuses_broken_complementarity(rough, monkeypatch):
    def corrupt(s):  # a pressure on the most open point, taken from the contact: p > 0 where g > 0
        return moved_pressure(s, int(np.argmax(s.pressure)), open_point(s), 0.01 * s.mean_pressure)

    corrupting(monkeypatch, corrupt)
    with pytest.raises(InvariantError) as err:
        contactlib.solve(rough, E=1.0, nu=0.5, mean_pressure=0.02)
    assert_refused(err.value, "complementarity")


def test_solve_refuses_a_gap_that_is_not_the_displacement(rough, monkeypatch):
    corrupting(monkeypatch, lambda s: dataclasses.replace(s, displacement=s.displacement + 1e-4 * float(rough.std())
                                                          * np.cos(np.arange(s.gap.size)).reshape(s.gap.shape)))
    with pytest.raises(InvariantError) as err:
        contactlib.solve(rough, E=1.0, nu=0.5, mean_pressure=0.02)
    assert_refused(err.value, "gap_definition")


def test_solve_tolerances_checks_every_tolerance(rough, monkeypatch):
    out = contactlib.solve_tolerances(rough, [1e-4, 1e-8], E=1.0, nu=0.5, mean_pressure=0.02)
    assert [ds.attrs["invariants_checked"] for ds in out] == [CONTACT, CONTACT]
    monkeypatch.setattr(invariants, "RESIDUAL_MARGIN", 1e-12)  # no state meets that: each tolerance refused
    with pytest.raises(InvariantError) as err:
        contactlib.solve_tolerances(rough, [1e-4, 1e-8], E=1.0, nu=0.5, mean_pressure=0.02)
    assert [ds.attrs["converged"] for ds in err.value.datasets] == [0, 0]


def test_steady_sliding_energy_balance_is_checked(rough, monkeypatch):
    """Frictionless viscoelastic sliding: mu_a mean(p) V against the dissipated power, in attrs (they agree to
    round-off, mu_a taken from the deformed surface); a dissipated power off by 100 tol of its scale is refused."""
    ds = contactlib.solve(rough, material=sls(tau=0.05), sliding_velocity=(1.0, 0.0), mean_pressure=0.02)
    assert ds.attrs["invariants_checked"] == CONTACT + ", energy_balance"
    assert ds.attrs["energy_balance_bound"] == ds.attrs["tol"] == 1e-8
    assert abs(ds.attrs["energy_balance_scaled"]) < 1e-12  # the same spectral sum: round-off
    power = float(ds.friction_coefficient_interlocking) * float(ds.mean_pressure) * 1.0
    assert abs(power / float(ds.dissipated_power) - 1) < 1e-12 and abs(ds.attrs["energy_balance"]) < 1e-12
    traction_power = problem.traction_power
    slope = invariants.rms_slope_along(rough.values, (1.0, 1.0), 0.0)
    off = 1e-6 * 0.02 * 1.0 * slope  # 100 tol of mean(p) |V| s_rms
    monkeypatch.setattr(problem, "traction_power", lambda *a, **k: traction_power(*a, **k) + off)
    with pytest.raises(InvariantError) as err:
        contactlib.solve(rough, material=sls(tau=0.05), sliding_velocity=(1.0, 0.0), mean_pressure=0.02)
    assert_refused(err.value, "energy_balance")


def test_adhesive_solve_refuses_tension_beyond_the_law(monkeypatch):
    h = surfaces.paraboloid(64, length=1.0, radius=2.0)
    law = contactlib.Adhesion(work=1e-4, range=2e-3, model="exponential")
    ds = contactlib.solve(h, E=1.0, nu=0.5, periodic=False, adhesion=law, penetration=1e-3)
    assert ds.attrs["invariants_checked"] == "penetration, gap, closed_gap, tension"
    run = adhesive_contact.run

    def corrupted(setup, adhesion, **kwargs):  # a point ten ranges open (law: 5e-5 sigma_0) pulled at sigma_0
        s = run(setup, adhesion, **kwargs)
        p = s.pressure.copy()
        p.flat[int(np.argmin(np.where(s.gap > 10 * adhesion.range, s.gap, np.inf)))] = -adhesion.peak_stress
        return dataclasses.replace(s, pressure=p)

    monkeypatch.setattr(adhesive_contact, "run", corrupted)
    with pytest.raises(InvariantError) as err:
        contactlib.solve(h, E=1.0, nu=0.5, periodic=False, adhesion=law, penetration=1e-3)
    assert_refused(err.value, "tension")


def test_jkr_solve_holds_the_load_and_a_closed_gap():
    h = surfaces.paraboloid(64, length=4e-4, radius=1e-3)
    law = contactlib.Adhesion(work=0.05, model="jkr")
    for load in (0.0, 400.0):
        ds = contactlib.solve(h, E=1e6, nu=0.5, adhesion=law, periodic=False, mean_pressure=load)
        assert ds.attrs["invariants_checked"] == "load, gap, closed_gap, tension"
        assert float(ds.mean_pressure) == pytest.approx(load, abs=1e-6 * (load + 100.0))


# ---- time series -------------------------------------------------------------------------------------------------

def test_transient_refuses_a_corrupted_step_with_the_steps_before(rough, monkeypatch):
    calls = []
    solve = transient.constrained_solve

    def corrupted(*args, **kwargs):
        state = solve(*args, **kwargs)
        calls.append(1)
        if len(calls) == 3:  # the third step's load is off by 0.1 %
            return dataclasses.replace(state, pressure=1.001 * state.pressure,
                                       mean_pressure=1.001 * state.mean_pressure)
        return state

    monkeypatch.setattr(transient, "constrained_solve", corrupted)
    with pytest.raises(InvariantError) as err:
        contactlib.solve_transient(rough, material=sls(), times=np.linspace(0.0, 1.0, 5), mean_pressure=0.02)
    assert err.value.invariant == "load" and err.value.dataset.sizes["time"] == 2
    assert "not converged at step 2" in err.value.dataset.attrs["status"]


def test_transient_reaches_the_relaxed_limit_after_a_long_hold(rough):
    times = np.concatenate([[0.0], np.geomspace(0.01, 400.0, 60)])  # 40 creep times (tau E_inf / E0 = 10)
    ds = contactlib.solve_transient(rough, material=sls(), times=times, mean_pressure=0.02)
    assert ds.attrs["invariants_checked"] == CONTACT + " (every step), relaxed_limit"
    assert ds.attrs["relaxed_memory_left"] < invariants.RELAXED_MEMORY
    assert ds.attrs["relaxed_limit"] < ds.attrs["relaxed_limit_bound"] < 1e-4
    short = contactlib.solve_transient(rough, material=sls(), times=np.linspace(0.0, 5.0, 6), mean_pressure=0.02)
    assert short.attrs["invariants_checked"] == CONTACT + " (every step)"  # a hold of half a creep time: not checked


def test_transient_refuses_a_wrong_relaxed_limit(rough, monkeypatch):
    """Steps whose effective modulus is 1 % off converge to another limit than the relaxed elastic solve."""
    coefficients = PronyHistory.coefficients
    monkeypatch.setattr(PronyHistory, "coefficients",
                        lambda self, dt: (1.01 * coefficients(self, dt)[0],) + coefficients(self, dt)[1:])
    times = np.concatenate([[0.0], np.geomspace(0.01, 400.0, 60)])
    with pytest.raises(InvariantError) as err:
        contactlib.solve_transient(rough, material=sls(), times=times, mean_pressure=0.02)
    assert_refused(err.value, "relaxed_limit")
    assert err.value.dataset.attrs["status"] == err.value.dataset.attrs["convergence_message"]


def test_reciprocating_checks_every_step(monkeypatch):
    h = surfaces.self_affine(64, hurst=0.8, q_roll=1, q_cutoff=16, rms_slope=0.1, seed=0, dim=1)
    ds = contactlib.solve_reciprocating(h, E=1.0, nu=0.5, amplitude=0.1, frequency=1.0, mean_pressure=0.5)
    assert ds.attrs["invariants_checked"] == CONTACT + " (every step)"
    solve, calls = transient.constrained_solve, []

    def corrupted(*args, **kwargs):  # after the relaxed start, a step returns a NaN penetration
        calls.append(1)
        state = solve(*args, **kwargs)
        return dataclasses.replace(state, penetration=float("nan")) if len(calls) == 5 else state

    monkeypatch.setattr(transient, "constrained_solve", corrupted)
    with pytest.raises(InvariantError) as err:
        contactlib.solve_reciprocating(h, E=1.0, nu=0.5, amplitude=0.1, frequency=1.0, mean_pressure=0.5)
    assert err.value.invariant == "gap_definition" and "not converged in cycle 1" in str(err.value)
    assert err.value.dataset.sizes["time"] == 3 and err.value.dataset.attrs["converged"] == 0


# ---- paths and two scales ----------------------------------------------------------------------------------------

def test_speed_path_answers_are_checked(rough):
    out = contactlib.solve_speeds(rough, [(0.1, 0.0), (1.0, 0.0)], material=sls(tau=0.05), mean_pressure=0.02)
    assert all(ds.attrs["invariants_checked"] == CONTACT + ", energy_balance" for ds in out)


def test_adhesion_curve_withdraws_a_state_off_its_load():
    h = surfaces.paraboloid(64, length=4e-4, radius=1e-3)
    law = contactlib.Adhesion(work=0.05, model="jkr")
    ds = contactlib.adhesion_curve(h, E=1e6, nu=0.5, adhesion=law, periodic=False, mean_pressures=[0.0, 400.0])
    assert ds.attrs["invariants_checked"] == "load (each state)" and ds.attrs["converged"] == 1
    assert ds.converged.values.tolist() == [1, 1, 1]
    np.testing.assert_allclose(ds.mean_pressure.values, [0.0, 400.0, 0.0], atol=1e-3)
    ds["mean_pressure"].values[1] = 496.0  # the snapped state of issue 38, item 1
    ds["converged"].values[:] = 1
    invariants.verify_path(ds, np.array([0.0, 400.0, 0.0]), h.values, law, load_control=True, tol=1e-6)
    assert ds.converged.values.tolist() == [1, 0, 1] and ds.attrs["converged"] == 0
    assert np.isnan(float(ds.pull_off_pressure)) and "invariant 'load' failed at steps [1]" in ds.attrs[
        "invariant_failures"]


def test_cohesive_path_takes_no_state_that_breaks_the_law(monkeypatch):
    """A cohesive path checks each state's fields: a state pulled beyond the law at one point is not accepted from any
    start, so the step is a failed one (converged 0, the path's scalars NaN), never a converged one."""
    h = surfaces.paraboloid(32, length=1.0, radius=2.0)
    law = contactlib.Adhesion(work=1e-4, range=2e-3, model="exponential")
    kwargs = dict(E=1.0, nu=0.5, adhesion=law, periodic=False, penetrations=[0.0, 1e-3])
    ds = contactlib.adhesion_curve(h, **kwargs)
    assert ds.attrs["invariants_checked"] == "penetration, gap, closed_gap, tension (each state)"
    assert ds.attrs["converged"] == 1 and ds.converged.values.tolist() == [1, 1, 1]
    run = adhesive_contact.run

    def corrupted(setup, adhesion, **kw):  # the deepest state: a point ten ranges open pulled at sigma_0
        s = run(setup, adhesion, **kw)
        if s.penetration < 0.9e-3:
            return s
        p = s.pressure.copy()
        p.flat[int(np.argmin(np.where(s.gap > 10 * adhesion.range, s.gap, np.inf)))] = -adhesion.peak_stress
        return dataclasses.replace(s, pressure=p)

    monkeypatch.setattr(adhesive_contact, "run", corrupted)
    ds = contactlib.adhesion_curve(h, **kwargs)
    assert ds.converged.values.tolist() == [1, 0, 1] and ds.attrs["converged"] == 0
    assert np.isnan(float(ds.pull_off_pressure))


def test_two_scale_answers_are_checked():
    h = surfaces.spheres(128, radius=0.5, lattice=2, summit_height=0.01, height_std=0.001)
    ds = contactlib.two_scale.solve(h, E=1.0, nu=0.5, mean_pressure=1e-4)
    assert ds.attrs["invariants_checked"] == "load, sign, gap, complementarity"
    macro = contactlib.two_scale.solve(h, E=1.0, nu=0.5, mean_pressure=1e-4, scale="macro")
    assert macro.attrs["invariants_checked"] == "load, sign"
    ds["force"].values[0] = -ds["force"].values[0]
    with pytest.raises(InvariantError) as err:
        invariants.verify_two_scale(ds, h.values, scale="two-scale", tol=1e-6, macro_tol=1e-4, mean_pressure=None,
                                    penetration=None)
    assert err.value.invariant == "sign"
    series = contactlib.two_scale.solve_transient(h, material=sls(), times=[0.0, 1.0], mean_pressure=1e-4,
                                                  scale="macro")
    assert series.attrs["invariants_checked"] == "load"
