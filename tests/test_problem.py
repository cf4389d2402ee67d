"""A prepared problem (contactlib.prepare): the answers of contactlib.solve at every load and speed, bit for bit, the
same refusals, and its kernels and caches reused explicitly."""

import numpy as np
import pytest
import xarray as xr

import contactlib

SLS = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)


def rough(n=32, seed=1):
    return contactlib.surfaces.self_affine(n, hurst=0.8, q_roll=2, q_cutoff=8, rms_slope=0.1, seed=seed)


def identical(a: xr.Dataset, b: xr.Dataset) -> None:
    """Equal values, attrs and labels, the wall time aside."""
    a, b = a.copy(), b.copy()
    for ds in (a, b):
        ds.attrs.pop("wall_time")
    xr.testing.assert_identical(a, b)


@pytest.mark.filterwarnings("ignore::contactlib.ResolutionWarning")
@pytest.mark.parametrize("scene, loads", [
    (dict(E=1.0, nu=0.3), [dict(mean_pressure=0.01), dict(mean_pressure=0.03)]),
    (dict(E=1.0, nu=0.3), [dict(penetration=0.002), dict(penetration=0.004)]),
    (dict(E=1.0, nu=0.3, friction=0.4, layer=contactlib.Layer(0.1)), [dict(mean_pressure=0.01),
                                                                      dict(mean_pressure=0.03)]),
    (dict(material=SLS, sliding_velocity=(0.5, 0.2)), [dict(mean_pressure=0.01), dict(mean_pressure=0.03)]),
])
def test_a_load_sweep_on_one_problem_equals_separate_solves(scene, loads):
    h = rough()
    problem = contactlib.prepare(h, **scene)
    swept = [problem.solve(**load) for load in loads]
    assert float(swept[0].contact_area) < float(swept[1].contact_area)  # two different answers
    for load, ds in zip(loads, swept):
        identical(ds, contactlib.solve(h, **scene, **load))
    # the problem is unchanged by its solves: the first load again gives the first answer
    identical(problem.solve(**loads[0]), swept[0])
    assert problem.solver_args["mean_pressure"] is None and "load_control" not in problem.attrs


@pytest.mark.filterwarnings("ignore::contactlib.ResolutionWarning")
def test_a_speed_sweep_shares_the_kernels_and_gives_solves_answers():
    """at_speed builds the speed's body with the problem's caches: the half-space tensor is built once and read-only
    while kept; each speed's answer is solve's at that speed."""
    h = rough()
    problem = contactlib.prepare(h, material=SLS, friction=0.3, sliding_velocity=(0.5, 0.0))
    tensor = problem.kernels.tensor
    assert tensor is not None and not tensor.normal.flags.writeable
    faster = problem.at_speed((2.0, 0.0))
    assert faster.kernels is problem.kernels and faster.kernels.tensor is tensor
    identical(faster.solve(mean_pressure=0.02),
              contactlib.solve(h, material=SLS, friction=0.3, sliding_velocity=(2.0, 0.0), mean_pressure=0.02))
    assert faster.attrs["sliding_velocity"] == [2.0, 0.0] and problem.attrs["sliding_velocity"] == [0.5, 0.0]
    with pytest.raises(ValueError, match="sliding_direction"):  # the direction given is checked at every speed
        contactlib.prepare(h, material=SLS, sliding_velocity=(0.5, 0.0), sliding_direction=0.0).at_speed((0.0, 1.0))


BAD_SCENES = [
    ("E", dict(E=-1.0, nu=0.3)),
    ("nu", dict(E=1.0, nu=0.7)),
    ("tol", dict(E=1.0, nu=0.3, tol=2.0)),
    ("target_error", dict(E=1.0, nu=0.3, tol=1e-6, target_error=0.01)),
    ("max_iter", dict(E=1.0, nu=0.3, max_iter=0)),
    ("kernel", dict(E=1.0, nu=0.3, kernel="fem")),
    ("method", dict(E=1.0, nu=0.3, method="newton")),
    ("layer", dict(E=1.0, nu=0.3, layer=0.1)),
    ("friction", dict(E=1.0, nu=0.3, friction=-0.1)),
    ("sliding_velocity", dict(material=SLS, sliding_velocity=(1.0, 2.0, 3.0))),
    ("adhesion", dict(E=1.0, nu=0.3, adhesion="jkr")),
    ("periodic", dict(E=1.0, nu=0.3, periodic="no")),
    ("length", dict(E=1.0, nu=0.3, length=2.0)),
]


@pytest.mark.parametrize("name, scene", BAD_SCENES, ids=[name for name, _ in BAD_SCENES])
def test_a_bad_scene_is_refused_by_prepare_as_by_solve(name, scene):
    h = rough(16)
    with pytest.raises(ValueError) as by_prepare:
        contactlib.prepare(h, **scene)
    with pytest.raises(ValueError) as by_solve:
        contactlib.solve(h, mean_pressure=0.01, **scene)
    assert str(by_prepare.value) == str(by_solve.value)
    assert name.split("_")[0] in str(by_prepare.value)


def test_a_bad_load_is_refused_by_the_problems_solve():
    problem = contactlib.prepare(rough(16), E=1.0, nu=0.3)
    with pytest.raises(ValueError, match="exactly one of mean_pressure or penetration"):
        problem.solve()
    with pytest.raises(ValueError, match="mean_pressure"):
        problem.solve(mean_pressure=-1.0)
    with pytest.raises(ValueError, match="initial_pressure has shape"):
        problem.solve(mean_pressure=0.01, initial_pressure=np.zeros(3))
