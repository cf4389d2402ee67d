"""The frozen-traction cohesive rounds inside one Polonsky-Keer solve (``contactlib.solvers.adhesive.cohesive_rounds``):
the moved heights against a direct convolution, the answer against the rounds that restart the solve each time
and against the semi-smooth Newton solver (an independent method), under load and displacement control."""

import numpy as np
import pytest

import contactlib
import contactlib.solvers.adhesive.cohesive as cohesive
import contactlib.solvers.adhesive.cohesive_frozen as cohesive_frozen
import contactlib.solvers.adhesive.cohesive_newton as cohesive_newton
from contactlib.core.grid import Grid
from contactlib.core.inputs import grid_of
from contactlib.model.operators import Compliance
from contactlib.solvers.adhesive.cohesive import solve_cohesive

WORK, RANGE = 4e-5, 4e-3  # sigma_0 = 0.01 (exponential): a process zone of a few elements on 64^2


def rough():
    return contactlib.surfaces.self_affine(64, hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=2)


@pytest.mark.parametrize("periodic", [True, False])
@pytest.mark.parametrize("shape", [(48, 40), (96,)])
def test_lower_offset_moves_the_heights(periodic, shape):
    """After ``lower_offset(f)`` the transforms' displacement is ``K p - (hp - K f)`` on the grid, and the field
    returned is ``K f``: against the operator's own convolution, periodic and zero-padded, 2D and 1D."""
    rng = np.random.default_rng(5)
    op = Compliance(Grid(shape, (1.0,) * len(shape)), E_star=2.0, periodic=periodic)
    p, hp, f = (rng.standard_normal(shape) for _ in range(3))
    with op.iteration_transforms(offset=hp) as transforms:
        transforms.pressure[...] = p
        np.testing.assert_allclose(transforms.displacement(1.0), op(p) - hp, atol=1e-12)
        np.testing.assert_allclose(transforms.lower_offset(f), op(f), atol=1e-12)
        np.testing.assert_allclose(transforms.displacement(0.5), op(p) - 0.5 * (hp - op(f)), atol=1e-12)
        transforms.lower_offset(-2.0 * f)  # the moves add up
        np.testing.assert_allclose(transforms.displacement(1.0), op(p) - (hp + op(f)), atol=1e-12)


def solve_both(monkeypatch, h, **scene):
    """The scene solved with the rounds inside one solve, and with a solve restarted each round."""
    inside = contactlib.solve(h, E=1.0, nu=0.0, tol=1e-10, **scene)
    monkeypatch.setattr(cohesive_frozen, "CONTINUED", False)
    restarted = contactlib.solve(h, E=1.0, nu=0.0, tol=1e-10, **scene)
    monkeypatch.setattr(cohesive_frozen, "CONTINUED", True)
    return inside, restarted


def check_against_newton(ds, h, law, *, periodic=True, start=None, **load):
    """The state is the cohesive contact of its traction: the gap by a fresh convolution of the traction is the
    solve's, its residual (mean interpenetration) is at the tolerance, and the semi-smooth Newton solver started
    from ``start`` (default: the non-adhesive state of the scene) lands on the same traction."""
    values, grid, _, _ = grid_of(h)
    op = Compliance(grid, E_star=1.0, periodic=periodic)
    p, delta = ds.pressure.transpose("x", "y").values, float(ds.penetration)  # [ix, iy], as values
    gap = op(p) + values.max() - values - delta
    scale = float(values.std())
    assert np.max(np.abs(gap - ds.gap.transpose("x", "y").values)) < 1e-9 * scale
    newton = cohesive_newton.CohesiveNewton(op, values, law, load.get("mean_pressure"), load.get("penetration"), 1e-10, 60)
    assert newton.residual_of(p, gap, largest=False)[-1] < 2e-10
    start = contactlib.solve(h, E=1.0, nu=0.0, periodic=periodic, **load) if start is None else start
    state, _ = solve_cohesive(op, values, adhesion=law, tol=1e-10,
                              initial_pressure=start.pressure.transpose("x", "y").values,
                              initial_penetration=float(start.penetration), **load)
    assert state.converged and state.solver.startswith("cohesive-newton")
    assert np.max(np.abs(state.pressure - p)) < 1e-5 * np.max(np.abs(p))
    assert np.count_nonzero(state.pressure > 0) == pytest.approx(np.count_nonzero(p > 0), abs=2)


@pytest.mark.parametrize("model", ["exponential", "maugis"])
def test_rounds_inside_one_solve_under_load(monkeypatch, model):
    h = rough()
    law = contactlib.Adhesion(work=WORK, range=RANGE, model=model)
    inside, restarted = solve_both(monkeypatch, h, mean_pressure=0.002, adhesion=law)
    for ds in (inside, restarted):
        assert ds.attrs["solver"].startswith("cohesive-frozen-traction") and ds.attrs["converged"] == 1
    # the same iterates, moved in place instead of set up anew, while each round runs its 3 CG iterations; in the
    # last rounds the inner tolerance ends some rounds earlier, and the continued solve measures it against the
    # heights it started from: within the tolerance's reach of each other (8e-9 of the peak stress at tol 1e-10)
    np.testing.assert_allclose(inside.pressure, restarted.pressure, rtol=0, atol=1e-7 * law.peak_stress)
    assert int(inside.outer_iterations) == int(restarted.outer_iterations)
    assert float(inside.mean_pressure) == pytest.approx(0.002, rel=1e-9)
    check_against_newton(inside, h, law, mean_pressure=0.002)


@pytest.mark.parametrize("model", ["exponential", "maugis"])
def test_rounds_inside_one_solve_under_displacement_zero_padded(monkeypatch, model):
    """Zero-padded displacement control runs Polonsky-Keer too (a definite compliance): its heights move on
    the block of a padded grid. The rough surface sits on a sphere (radius 2) so that its edges drop out of the
    cohesive zone: a window whose edge is inside it is refused (the adhesion beyond it would be cut off)."""
    h = rough() + contactlib.surfaces.paraboloid(64, length=1.0, radius=2.0)  # added by name
    law = contactlib.Adhesion(work=WORK, range=RANGE, model=model)
    penetration = 0.3 * float(rough().std())
    inside, restarted = solve_both(monkeypatch, h, penetration=penetration, periodic=False, adhesion=law)
    assert inside.attrs["solver"].startswith("cohesive-frozen-traction") and inside.attrs["converged"] == 1
    np.testing.assert_allclose(inside.pressure, restarted.pressure, rtol=0, atol=1e-7 * law.peak_stress)
    assert float(inside.mean_pressure) < 0.0 < float(inside.contact_area)  # adhesion pulls more than it pushes
    check_against_newton(inside, h, law, periodic=False, penetration=penetration)


def test_tensile_load_from_a_warm_start():
    """Under a tensile mean traction (warm-started, as along a path) the repulsive solve carries
    ``P - mean(a) > 0`` and the rounds still converge to the Newton solver's state."""
    h = rough()
    law = contactlib.Adhesion(work=WORK, range=RANGE, model="maugis")
    warm = contactlib.solve(h, E=1.0, nu=0.0, mean_pressure=1e-4, tol=1e-10, adhesion=law)
    ds = contactlib.solve(h, E=1.0, nu=0.0, mean_pressure=-3e-4, tol=1e-10, adhesion=law,
                          initial_pressure=warm.pressure)  # a DataArray: read by name
    assert ds.attrs["solver"].startswith("cohesive-frozen-traction") and ds.attrs["converged"] == 1
    assert float(ds.mean_pressure) == pytest.approx(-3e-4, rel=1e-9)
    assert float(ds.contact_area) < float(warm.contact_area)
    check_against_newton(ds, h, law, start=warm, mean_pressure=-3e-4)


def test_work_continuation_never_returns_a_stage_short_of_the_work():
    """The continuation in the work of adhesion (``cohesive._continuation``) answers at the work asked: where its
    stages run out short of it, the state returned is a solve at ``w`` itself, converged or said not to be. The
    parent returned the last converged stage (0.97 w in the quick workflow's rough state) flagged converged."""
    calls = []

    def newton(law, p, delta):  # converges below 0.97 w only: the stages creep towards w and never reach it
        calls.append(law.work)
        ok = law.work < 0.97 * WORK
        return p, delta, None, None, 1, 1, 1e-9 if ok else 1e-3, ok

    from contactlib.solvers.adhesive.cohesive_law import grid_law

    op = Compliance(Grid((8, 8), (1.0, 1.0)), E_star=1.0, periodic=True)
    law = grid_law(contactlib.Adhesion(work=WORK, range=RANGE, model="exponential"), op)
    result = cohesive._continuation(newton, law, np.zeros(4), 0.0)
    assert calls[-1] == WORK and not result[-1] and result[-2] == 1e-3
    assert len(calls) == cohesive.STAGES + 1


def test_rough_state_of_the_quick_workflow_converges_on_its_law():
    """The quick workflow's ``adhesive_rough`` state that came back unconverged (rms slope 0.05, w 2e-4 over a
    3-element zone, seed 1, penetration -0.5 rms from the highest point): it converges, and every open point
    carries the law's traction at its gap to 1e-5 of the peak stress (measured 9e-7; the parent's answer, at 0.97 w,
    missed it by 2.7 % on 3,078 points and was refused by the tension invariant). Open: a gap above 1e-5 of the rms
    height (contact points keep gaps of the solve's tolerance, 1e-7 of it)."""
    from contactlib.studies._common import rough_surface
    from contactlib.studies.adhesive_rough import cohesive_law

    h = rough_surface(n=64, hurst=0.8, seed=1, q_low=1.0, q_roll=2.0, q_cutoff=16.0, rms_slope=0.05)
    law = cohesive_law(2e-4, E_star=4 / 3, spacing=1 / 64, process_zone_elements=3.0)
    ds = contactlib.solve(h, E=1.0, nu=0.5, adhesion=law, penetration=-0.5 * float(h.std()), tol=1e-6)
    assert ds.attrs["converged"] == 1
    p, gap = ds.pressure.values, ds.gap.values
    open_points = gap > 1e-5 * float(h.std())
    assert open_points.sum() > 3000 and np.max(np.abs(p - law.traction(gap))[open_points]) < 1e-5 * law.peak_stress
