"""Scenes chosen to break solvers. Each asserts convergence, physical sanity and a reference.

The scenes live in :mod:`contactlib.testing` (shared with ``benchmarks/bench_hard_cases.py``): to add a case,
append a :class:`contactlib.testing.HardCase` to ``HARD_CASES``.
"""

import numpy as np
import pytest

import contactlib
from contactlib.testing import HARD_CASE_E as E
from contactlib.testing import HARD_CASE_NU as NU
from contactlib.testing import HARD_CASES as SCENES

# two solves at tol 1e-8 agree to ~1e-7 in the pressure field on 2D grids (benchmarks/RESULTS.md), ~1e-5 on the
# 1000-scale profile
CROSS_CHECK_RTOL = 5e-5


@pytest.mark.parametrize("scene", SCENES, ids=[s.name for s in SCENES])
def test_hard_case(scene):
    heights = scene.surface()
    kwargs = {"tol": 1e-8, **scene.solve}
    out = contactlib.solve(heights, E=E, nu=NU, **kwargs)
    p, g = out.pressure.values, out.gap.values
    assert out.attrs["converged"] == 1 and float(out.residual) <= kwargs["tol"]
    assert p.min() >= 0
    scale = float(np.sqrt(np.mean((heights - heights.mean()).values ** 2))) or 1.0
    assert np.mean(np.maximum(-g, 0)) <= 10 * kwargs["tol"] * scale
    if "mean_pressure" in kwargs:
        assert p.mean() == pytest.approx(kwargs["mean_pressure"], rel=1e-10)
    if scene.check:
        scene.check(out)
    if scene.cross_check and "mean_pressure" in kwargs:
        # independent path: periodic displacement control solves the dual problem (the gap as unknown)
        other = contactlib.solve(heights, E=E, nu=NU, penetration=float(out.penetration),
                                 **{k: v for k, v in kwargs.items() if k != "mean_pressure"})
        assert float(other.mean_pressure) == pytest.approx(kwargs["mean_pressure"], rel=CROSS_CHECK_RTOL)
        assert np.linalg.norm(other.pressure.values - p) <= CROSS_CHECK_RTOL * np.linalg.norm(p)


def test_heights_from_1e_minus_9_to_1e3_same_dimensionless_answer():
    base = contactlib.surfaces.self_affine(64, hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=1)
    ref = contactlib.solve(base, E=E, nu=NU, mean_pressure=0.01, tol=1e-10)
    for s in (1e-9, 1e-3, 1e3):
        out = contactlib.solve(base * s, E=E, nu=NU, mean_pressure=0.01 * s, tol=1e-10)
        assert float(out.contact_area) == float(ref.contact_area)
        assert float(out.penetration) / s == pytest.approx(float(ref.penetration), rel=1e-8)


@pytest.mark.parametrize("modulus", [1e-6, 1e3, 2e11])
def test_moduli_from_1e_minus_6_to_2e11_pa_same_dimensionless_answer(modulus):
    """Pressures scale with E*: the iteration, re-entry included, must be blind to the unit system."""
    base = contactlib.surfaces.self_affine(128, hurst=0.8, q_roll=2, q_cutoff=32, rms_slope=0.1, seed=1)
    ref = contactlib.solve(base, E=E, nu=NU, mean_pressure=0.02 * E, tol=1e-9)
    for s in (1e-9, 1e3):
        out = contactlib.solve(base * s, E=modulus, nu=NU, mean_pressure=0.02 * modulus * s, tol=1e-9)
        assert int(out.iterations) == int(ref.iterations)
        assert float(out.contact_area) == float(ref.contact_area)
        assert float(out.penetration) / s == pytest.approx(float(ref.penetration), rel=1e-8)
        assert float(out.pressure.max()) / (modulus * s) == pytest.approx(float(ref.pressure.max()) / E, rel=1e-8)


@pytest.mark.parametrize("mean_pressure", [0.0175, 0.0275, 0.04])
def test_reentry_at_30_to_60_percent_contact_converges(mean_pressure):
    """Re-entered points get a pressure from the gap and a stiffness; too stiff a choice (an
    element's own, 1/self-compliance) diverged here at 46 % contact (residual 1.7 after 500 iterations)."""
    h = contactlib.surfaces.self_affine(512, hurst=0.8, q_roll=4, q_cutoff=64, rms_slope=0.1, seed=1)
    out = contactlib.solve(h, E=1.0, nu=0.3, mean_pressure=mean_pressure, tol=1e-10, max_iter=300)
    assert 0.3 < float(out.contact_area) < 0.65
    assert int(out.iterations) < 120  # 72-75 at the time of writing


def test_non_periodic_contact_reaching_the_window_edge_is_refused():
    h = contactlib.surfaces.paraboloid(64, radius=1.0)
    with pytest.raises(ValueError, match="edge of the window"):
        contactlib.solve(h, E=E, nu=NU, penetration=0.3, periodic=False)  # a = 0.55 > L/2
