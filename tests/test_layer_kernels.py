"""Layer Green's tensor: closed forms against an independent transfer-matrix solution, the seed's
eqs. (13)-(18), and the half-space limit."""

import numpy as np
import pytest
from scipy.linalg import expm

from contactlib.kernels.layer import halfspace_factors, layer_factors, zero_mode_compliance


def transfer_matrix_compliance(q, h, E, nu, base):
    """Surface compliance of one Fourier mode from Navier's equations written as a first-order system
    in depth, ``d/dz [U, W, S, T] = M [U, W, S, T]`` (displacements ``i U, W`` and stresses ``i S = s_xz``,
    ``T = s_zz`` of ``exp(i q x)``), integrated by a matrix exponential: no closed form used.
    Returns ``(Czz, c, Cxx)`` of ``u_z = Czz p - i c tau``, ``u_x = i c p + Cxx tau``."""
    mu = E / (2 * (1 + nu))
    lam = 2 * mu * nu / (1 - 2 * nu)
    M = np.zeros((4, 4))
    # U' = S/mu - q W ; W' = (T + lam q U)/(lam + 2 mu) ; S' = -q s_xx ; T' = q S, with u_x = iU, s_xz = iS
    M[0, 1], M[0, 2] = -q, 1 / mu
    M[1, 0], M[1, 3] = lam * q / (lam + 2 * mu), 1 / (lam + 2 * mu)
    # s_xx = (lam+2mu) du_x/dx + lam W' = -(lam+2mu) q U + lam W' -> S' = -q * s_xx... written for s_xx real
    M[2, 0] = (lam + 2 * mu) * q**2 - lam**2 * q**2 / (lam + 2 * mu)
    M[2, 3] = -lam * q / (lam + 2 * mu)
    M[3, 2] = q
    P = expm(M * h)
    out = []
    for p, t in ((1.0, 0.0), (0.0, 1.0)):
        # surface: s_zz(0) = -p, s_xz(0) = -tau = -i t -> S(0) = -t; unknown U(0), W(0)
        base_vec = np.array([0, 0, -t, -p], float)
        A = P[:, :2]
        b = P @ base_vec
        rows = (0, 1) if base == "confined" else (2, 3)
        U0, W0 = np.linalg.solve(A[rows, :], -b[list(rows)])
        out.append((U0, W0))
    (Up, Wp), (Ut, Wt) = out
    # tau = i t: u_z = Wp p + Wt t = Wp p - i Wt tau ; u_x = i Up p + i Ut t = i Up p + Ut tau
    return Wp, Wt, Up, Ut


@pytest.mark.parametrize("base", ["confined", "remote_pressure"])
@pytest.mark.parametrize("nu", [0.0, 0.3, 0.49])
@pytest.mark.parametrize("X", [0.05, 0.3, 1.0, 2.5, 6.0])
def test_closed_forms_match_transfer_matrix(base, nu, X):
    E, q = 2.0, 3.0
    h = X / q
    Czz, Cz_t, Cx_p, Cxx = transfer_matrix_compliance(q, h, E, nu, base)
    unit = 2 * (1 - nu**2) / (E * q)
    f = layer_factors(np.array([X]), nu, base)
    assert f["normal"][0] * unit == pytest.approx(Czz, rel=1e-9)
    assert f["inplane"][0] * unit == pytest.approx(Cxx, rel=1e-9)
    assert f["coupling"][0] * unit == pytest.approx(Cz_t, rel=1e-8, abs=1e-12 * unit)
    assert Cx_p == pytest.approx(Cz_t, rel=1e-8, abs=1e-12 * unit)  # reciprocity: u_x from p = i c


def _seed_coefficients(X, nu):
    """Seed 2 eqs. (16)-(18) as printed (their half-space limits 0, 0, 0 beyond X = 300, where they overflow)."""
    far = X > 300
    X = np.where(far, 1.0, X)
    D = 5 + 2 * X**2 - 4 * nu * (3 - 2 * nu) + (3 - 4 * nu) * np.cosh(2 * X)
    A = 1 + (2 * X - (3 - 4 * nu) * np.sinh(2 * X)) / D
    B = 1 - (2 * X + (3 - 4 * nu) * np.sinh(2 * X)) / D
    C = 4 * (1 - nu) * (2 + X**2 - 6 * nu + 4 * nu**2) / D
    return np.where(far, 0.0, A), np.where(far, 0.0, B), np.where(far, 0.0, C)


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.5])
def test_confined_factors_are_the_seed_coefficients(nu):
    X = np.linspace(0.01, 8.0, 400)
    A, B, C = _seed_coefficients(X, nu)
    f = layer_factors(X, nu, "confined")
    np.testing.assert_allclose(f["normal"], 1 - A, rtol=1e-9, atol=1e-14)
    np.testing.assert_allclose(f["inplane"], 1 - B, rtol=1e-9, atol=1e-14)
    np.testing.assert_allclose(f["coupling"], ((1 - 2 * nu) - C) / (2 * (1 - nu)), rtol=1e-9, atol=1e-14)


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.5])
def test_seed_real_space_series_equal_the_spectral_coefficients(nu):
    """Seed eqs. (13)-(15) summed in real space (1D periodic, lambda = 1) against the inverse transform
    of the spectral coefficients: the G_zz and G_xz kernels are the same functions."""
    lam, h, E, M = 1.0, 0.2, 1.0, 200_000
    q0 = 2 * np.pi / lam
    x = np.linspace(0.013, 0.987, 37) * lam
    m = np.arange(1, M + 1)[:, None]
    A, B, C = _seed_coefficients(m * q0 * h, nu)
    log2sin = np.log(np.abs(2 * np.sin(q0 * x / 2)))
    Gzz = -2 * (1 - nu**2) / np.pi * (log2sin + np.sum(A * np.cos(m * q0 * x) / m, axis=0)) / E
    Gxz = (1 + nu) / np.pi * ((1 - 2 * nu) / 2 * (np.sign(x) * np.pi - q0 * x)
                              - np.sum(C * np.sin(m * q0 * x) / m, axis=0)) / E
    # our multipliers: u_z(q_m) = Czz p(q_m) - i sgn(q) c tau(q_m): real-space kernels are
    # Kzz(x) = (1/lambda) sum_m 2 Czz cos(q_m x), Kzt(x) = (1/lambda) sum_m 2 c sin(q_m x)
    f = layer_factors(m * q0 * h, nu, "confined")
    unit = 2 * (1 - nu**2) / (E * m * q0)
    Kzz = np.sum(2 * f["normal"] * unit * np.cos(m * q0 * x), axis=0) / lam
    Kzt = np.sum(2 * f["coupling"] * unit * np.sin(m * q0 * x), axis=0) / lam
    np.testing.assert_allclose(Kzz, Gzz, atol=1e-4 * np.abs(Gzz).max())  # both truncated at M terms: error ~ 1/M
    np.testing.assert_allclose(Kzt, Gxz, atol=1e-4 * max(np.abs(Gxz).max(), 1e-3))


@pytest.mark.parametrize("base", ["confined", "remote_pressure"])
@pytest.mark.parametrize("nu", [0.0, 0.3, 0.5])
def test_thick_layer_is_the_halfspace_without_overflow(base, nu):
    X = np.array([10.0, 30.0, 300.0, 1e5, 1e300])
    with np.errstate(over="raise", invalid="raise", divide="raise"):  # underflow to the limit is the point
        f = layer_factors(X, nu, base)
    half = halfspace_factors(nu)
    for name in ("normal", "inplane", "coupling", "antiplane"):
        assert np.all(np.isfinite(f[name]))
        np.testing.assert_allclose(f[name][1:], half[name], rtol=1e-20, atol=1e-20)  # e^{-60} below round-off
        assert abs(f[name][0] - half[name]) < 1e-6


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.5])
def test_thin_layer_limits(nu):
    """Confined: stiffer as h falls (the normal factor vanishes); remote pressure: a Kirchhoff plate."""
    X = np.array([1e-3, 1e-2, 1e-1])
    conf = layer_factors(X, nu, "confined")["normal"]
    assert np.all(np.diff(conf) > 0) and conf[0] < 1e-2
    plate = layer_factors(X, nu, "remote_pressure")
    np.testing.assert_allclose(plate["normal"] * X**3, 6.0, rtol=2e-2)  # 1/(D q^4), D = E h^3 / (12 (1 - nu^2))
    np.testing.assert_allclose(plate["coupling"] / plate["normal"], X / 2, rtol=2e-2)  # friction's moment arm h/2


def test_zero_mode():
    conf = zero_mode_compliance(0.1, 2.0, 0.3, "confined")
    assert conf["normal"] == pytest.approx(0.1 * 1.3 * 0.4 / (2.0 * 0.7))
    assert zero_mode_compliance(0.1, 2.0, 0.5, "confined")["normal"] == 0.0
    assert zero_mode_compliance(0.1, 2.0, 0.3, "remote_pressure")["normal"] == 0.0
