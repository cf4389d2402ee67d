"""A thin confined viscoelastic layer sliding with Coulomb friction mu_c = 0.8: where the normal operator
is not monotone (its symmetric part negative at the longest waves) but well posed, and where it is not."""

import re

import numpy as np
import pytest

import contactlib
from contactlib import Layer, Viscoelastic
from contactlib.model.bodies import MINOR_FLOOR, body_model, order_two_minors
from contactlib.core.grid import Grid
from contactlib.kernels.tensor import surface_green_tensor
from contactlib.kernels.viscoelastic import steady_sliding_factor
from dense_reference import dense_load_control

SLS = Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)
Q0 = 2 * np.pi  # window of length 1
MU = 0.8


def _profile(n, seed=3):
    return contactlib.surfaces.self_affine(n, hurst=0.8, q_roll=1, q_cutoff=min(64, n // 4), rms_slope=0.1,
                                           seed=seed, dim=1)


def _symbol(n, q0h, zeta):
    """The whole normal operator's transfer (G_zz + mu G_zt) E0 / E*(q.V) on the rfft layout, straight
    from the kernels (not through the body model's split)."""
    grid = Grid((n,), (1.0,))
    tensor = surface_green_tensor(grid, SLS.E0, SLS.nu, q0h / Q0, "confined")
    total = tensor.normal.astype(complex) + MU * tensor.coupling_multiplier(grid, 0.0)
    return grid, total * steady_sliding_factor(grid, SLS, (zeta / Q0,))


def _dense(n, q0h, zeta):
    """The real-space matrix of the operator: displacement at i due to a unit load on j."""
    grid, total = _symbol(n, q0h, zeta)
    column = np.fft.irfft(total, n)
    i = np.arange(n)
    return column[(i[:, None] - i[None, :]) % n]


@pytest.mark.parametrize("mean_pressure", [0.005, 0.05, 0.5])
def test_non_monotone_thin_layer_matches_the_dense_solve_from_every_start(mean_pressure):
    """q0 h = 0.5, mu_c = 0.8, E_inf/E0 = 10, V tau q0 = 0.3 (symmetric part negative at q0 and 2 q0: the
    operator's phase reaches 121 degrees), 256 points, 1 % to 40 % contact: converges, and the dense
    active set on the real-space matrix, from the highest points and from 8 random contact sets, finds one
    solution, the same pressure within 1e-6."""
    h = _profile(256)
    out = contactlib.solve(h, material=SLS, mean_pressure=mean_pressure, sliding_velocity=0.3 / Q0,
                           layer=Layer(0.5 / Q0), friction=MU, tol=1e-10)
    assert out.attrs["converged"] == 1 and out.attrs["monotone"] == 0
    assert "not monotone" in out.attrs["model"] and "uniqueness" in out.attrs["monotone_message"]
    M = _dense(256, 0.5, 0.3)
    hp = h.values - h.values.max()
    rng = np.random.default_rng(0)
    starts = [hp >= np.quantile(hp, 0.9)] + [rng.random(hp.size) < f for f in np.linspace(0.05, 0.9, 8)]
    solutions = [p for p in (dense_load_control(M, hp, mean_pressure, s) for s in starts) if p is not None]
    assert len(solutions) >= 6
    p = out.pressure.values
    for reference in solutions:
        assert np.linalg.norm(p - reference) / np.linalg.norm(reference) < 1e-6
    assert 0.005 < float(out.contact_area) < 0.6


@pytest.mark.parametrize("zeta", [1e-2, 0.1, 1.0, 100.0])
def test_thinnest_confined_layer_with_friction_converges_across_the_band(zeta):
    """The hard case: q0 h = 0.1, mu_c = 0.8, 1024 points, 4 % and 20 % contact, V tau q0 from 1e-2 to 1e2
    (not monotone at the first three), and the interlocking friction keeps its sign (resists sliding)."""
    h = _profile(1024)
    for mean_pressure in (0.05, 0.5):
        out = contactlib.solve(h, material=SLS, mean_pressure=mean_pressure, sliding_velocity=zeta / Q0,
                               layer=Layer(0.1 / Q0), friction=MU, tol=1e-8)
        assert out.attrs["converged"] == 1 and float(out.residual) <= 1e-8
        assert float(out.friction_coefficient_interlocking) > 0.005


def test_coarse_elements_make_two_solutions_and_are_refused():
    """16 points on q0 h = 0.3 at V tau q0 = 0.1: an element is longer than the layer is thick, so its own
    compliance is negative (an order-1 minor): the operator is not a P-matrix. From the eigenvector of that
    minor's negative eigenvalue, a load vector q is built for which p1 and p2 = two distinct pressures both
    solve ``p >= 0, M p + q >= 0, p (M p + q) = 0``; solve refuses the scene naming friction, the reason and
    the thinnest well-posed layer on that grid, which passes the same check (and a 2 % thinner one not)."""
    n, q0h, zeta = 16, 0.3, 0.1
    grid, total = _symbol(n, q0h, zeta)
    assert order_two_minors(grid, total) <= MINOR_FLOOR
    M = _dense(n, q0h, zeta)
    S = [0]
    values, vectors = np.linalg.eig(M[np.ix_(S, S)])
    assert values.real.min() < 0
    x = np.zeros(n)
    x[S] = vectors[:, np.argmin(values.real)].real
    y = M @ x  # x_i y_i <= 0 everywhere: the sign-reversing vector of a non-P matrix
    p1, p2 = np.maximum(x, 0.0), np.maximum(-x, 0.0)
    q = np.maximum(y, 0.0) - M @ p1
    for p in (p1, p2):
        w = M @ p + q
        assert w.min() >= -1e-14 * np.abs(q).max() and abs(p @ w) <= 1e-14 * np.abs(q).max() * np.abs(p).sum()
    assert np.linalg.norm(p1 - p2) > 0.5 * max(np.linalg.norm(p1), np.linalg.norm(p2))
    with pytest.raises(ValueError, match="friction.*not a P-matrix.*two distinct") as err:
        contactlib.solve(_profile(n), material=SLS, mean_pressure=0.05, sliding_velocity=zeta / Q0,
                         layer=Layer(q0h / Q0), friction=MU)
    thinnest = float(re.search(r"thinnest well-posed layer is q0 h = ([0-9.eE+-]+)", str(err.value)).group(1))
    assert q0h < thinnest < 10
    for scale, ok in ((1.01, True), (0.98, False)):
        grid, total = _symbol(n, thinnest * scale, zeta)
        assert (order_two_minors(grid, total) > MINOR_FLOOR) == ok
    body = body_model(grid, material=SLS, layer=Layer(thinnest * 1.01 / Q0), friction=MU, direction=0.0, tol=1e-8,
                      kernel="spectral", periodic=True, velocity=(zeta / Q0,))
    assert body.coupling is not None


def test_unconverged_non_monotone_scene_says_why():
    """A 64^2 thin confined layer (q0 h = 0.1, mu_c = 0.8) on a loss-dominated body (E_inf/E0 = 1000, V tau q0 =
    1e-3): the symmetric part is negative at 982 long waves, the order-2 minors pass, and no solver of the class
    converges (Douglas-Rachford 2e-3 after 40 000 iterations). The ConvergenceError says the operator is not
    monotone, not only that the residual is missed."""
    h = contactlib.surfaces.self_affine(64, hurst=0.8, q_roll=1, q_cutoff=8, rms_slope=0.1, seed=0, dim=2)
    q0 = 2 * np.pi / float(h.x[1] - h.x[0]) / 64
    m = Viscoelastic.standard_linear_solid(E0=1.0, E_inf=1000.0, tau=1.0, nu=0.5)
    with pytest.raises(contactlib.ConvergenceError, match="uniqueness is not implied by monotonicity") as err:
        contactlib.solve(h, material=m, mean_pressure=0.05, layer=Layer(0.1 / q0), friction=0.8,
                         sliding_velocity=(1e-3 / q0, 0.0), tol=1e-8, max_iter=500)
    assert err.value.residual > 1e-8 and err.value.dataset.attrs["monotone"] == 0
