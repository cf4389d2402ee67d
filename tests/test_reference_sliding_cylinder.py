"""Rigid cylinder sliding with friction on an elastic half-space (Johnson section 7.2)."""

import numpy as np
import pytest
from scipy.integrate import quad

from contactlib.reference import sliding_cylinder as sc

P, R, E = 1.3, 2.0, 3.0


def hertz(nu):
    E_star = E / (1 - nu**2)
    a = np.sqrt(4 * P * R / (np.pi * E_star))
    return a, lambda x: 2 * P / (np.pi * a**2) * np.sqrt(np.clip(a**2 - x**2, 0, None))


@pytest.mark.parametrize("nu, mu", [(0.3, 0.0), (0.0, 0.0), (0.5, 0.8), (0.5, 0.0)])
def test_hertz_limit(nu, mu):
    a, p_hertz = hertz(nu)
    c = sc.contact(P, R, E, nu, mu)
    assert sc.exponent(mu, nu) == 0.0
    assert c.a == pytest.approx(a, rel=1e-12)
    assert c.x_leading == pytest.approx(a, rel=1e-12)
    assert c.x_trailing == pytest.approx(-a, rel=1e-12)
    assert c.e == 0.0 and c.pressure_centroid == 0.0
    assert sc.interlocking_friction(P, R, E, nu, mu) == 0.0
    x = np.linspace(-1.2 * a, 1.2 * a, 241)
    x = x[np.abs(np.abs(x) - a) > 1e-3 * a]  # a^2 - x^2 in the Hertz formula cancels at the edges
    assert np.all(sc.pressure(np.array([-a, a]), P, R, E, nu, mu) == 0.0)
    np.testing.assert_allclose(sc.pressure(x, P, R, E, nu, mu), p_hertz(x), rtol=1e-12, atol=0)


@pytest.mark.parametrize("nu, mu", [(0.3, 0.5), (0.0, 1.0), (0.2, 3.0), (-0.5, 2.0)])
def test_load_moment_and_integral_equation(nu, mu):
    c = sc.contact(P, R, E, nu, mu)
    p = lambda x: sc.pressure(x, P, R, E, nu, mu)
    lo, hi = c.x_trailing, c.x_leading
    # QAGS copes with the algebraic edge singularities (exponents 1/2 -+ gamma)
    load = quad(p, lo, hi, epsabs=0, epsrel=1e-13, limit=200)[0]
    assert load == pytest.approx(P, rel=1e-8)
    moment = quad(lambda x: x * p(x), lo, hi, epsabs=1e-14, epsrel=1e-13, limit=200)[0]
    assert moment / P == pytest.approx(c.pressure_centroid, rel=1e-8)
    mu_a = -quad(lambda x: p(x) * (-x / R), lo, hi, epsabs=1e-14, epsrel=1e-13, limit=200)[0] / P
    assert sc.interlocking_friction(P, R, E, nu, mu) == pytest.approx(mu_a, rel=1e-8)
    assert p(np.array([lo - 1e-9, hi + 1e-9, lo, hi])).max() == 0.0
    # the singular integral equation mu beta p + (1/pi) PV int p(s)/(s-x) ds = -E* x/(2R), by Cauchy-weight quad
    E_star, beta = E / (1 - nu**2), (1 - 2 * nu) / (2 * (1 - nu))
    for x in lo + (hi - lo) * np.array([0.03, 0.3, 0.5, 0.77, 0.96]):
        pv = quad(p, lo, hi, weight="cauchy", wvar=x, epsabs=0, epsrel=1e-12, limit=200)[0]  # int p/(s-x)
        assert mu * beta * p(x) + pv / np.pi == pytest.approx(-E_star * x / (2 * R), rel=1e-7, abs=1e-9)


def numerical_contact(nu, mu, n=2000, half_span=1.6):
    """Independent solution: piecewise-constant pressure on n elements over +-half_span Hertz widths, the
    log and sgn kernels integrated exactly over each element (collocation at the centres), and an
    active-set loop for p >= 0, gap >= 0 with the load P imposed. Uses nothing of the closed form."""
    E_star, k = E / (1 - nu**2), (1 - 2 * nu) * (1 + nu) / (2 * E)
    a_h = hertz(nu)[0]
    edges = np.linspace(-half_span * a_h, half_span * a_h, n + 1)
    h, xc = edges[1] - edges[0], 0.5 * (edges[:-1] + edges[1:])

    def F(u):  # antiderivative of ln|u|
        au = np.abs(u)
        return np.where(au > 0, u * np.log(np.where(au > 0, au, 1.0)) - u, 0.0)

    # u_z(x_i) = sum_j K_ij p_j:  int_elem ln|x - s| ds = F(x - s_left) - F(x - s_right)
    K = -2 / (np.pi * E_star) * (F(xc[:, None] - edges[None, :-1]) - F(xc[:, None] - edges[None, 1:]))
    K += k * mu * h * np.sign(xc[:, None] - xc[None, :])
    active = np.abs(xc) < a_h
    for _ in range(60):
        S = np.flatnonzero(active)
        m = S.size
        A = np.zeros((m + 1, m + 1))
        A[:m, :m], A[:m, m], A[m, :m] = K[np.ix_(S, S)], -1.0, h
        sol = np.linalg.solve(A, np.r_[-xc[S] ** 2 / (2 * R), P])  # u_z - d = -x^2/(2R) on S, sum p h = P
        p = np.zeros(n)
        p[S] = sol[:m]
        gap = K @ p - sol[m] + xc**2 / (2 * R)
        negative, penetrating = active & (p < 0), ~active & (gap < 0)
        if not negative.any() and not penetrating.any():
            break
        active = (active & ~negative) | penetrating
    else:
        raise RuntimeError("active set did not converge")
    S = np.flatnonzero(active)
    assert np.all(np.diff(S) == 1)  # one connected contact
    return dict(x_trailing=edges[S[0]], x_leading=edges[S[-1] + 1], x=xc, p=p, h=h)


@pytest.mark.parametrize("nu, mu", [(0.3, 0.5), (0.0, 1.0)])
def test_against_independent_numerics(nu, mu):
    c = sc.contact(P, R, E, nu, mu)
    num = numerical_contact(nu, mu)
    assert num["h"] < 0.002 * c.a
    # edges to within ~1.5 element (h ~ 0.0016 a)
    assert num["x_trailing"] == pytest.approx(c.x_trailing, abs=0.003 * c.a)
    assert num["x_leading"] == pytest.approx(c.x_leading, abs=0.003 * c.a)
    assert 0.5 * (num["x_leading"] - num["x_trailing"]) == pytest.approx(c.a, rel=0.003)
    e_num = 0.5 * (num["x_leading"] + num["x_trailing"])
    assert e_num == pytest.approx(c.e, rel=0.01)
    x, p = num["x"], num["p"]
    exact = sc.pressure(x, P, R, E, nu, mu)
    assert np.max(np.abs(p - exact)) < 0.01 * exact.max()
    centroid = np.sum(x * p) * num["h"] / P
    assert centroid == pytest.approx(c.pressure_centroid, rel=1e-4)
    assert x[np.argmax(p)] == pytest.approx(-4 * c.gamma * c.a, abs=0.02 * c.a)


def test_signs():
    """mu > 0, nu < 1/2: the surface behind the cylinder is lifted, so contact and pressure shift to
    the trailing side (-x) and the interlocking friction is negative (it aids sliding)."""
    nu, mu = 0.3, 0.5
    c = sc.contact(P, R, E, nu, mu)
    assert np.tan(np.pi * c.gamma) == pytest.approx(mu * (1 - 2 * nu) / (2 * (1 - nu)), rel=1e-14)
    assert c.gamma > 0 and c.e < 0 and c.pressure_centroid < c.e < 0
    assert -c.x_trailing > hertz(nu)[0] > c.x_leading > 0
    assert sc.interlocking_friction(P, R, E, nu, mu) == pytest.approx(-8 * c.gamma * c.a / (3 * R), rel=1e-14)
    assert sc.interlocking_friction(P, R, E, nu, mu) < 0
    # same sign from the independent numerics (coarser grid is enough for a sign)
    num = numerical_contact(nu, mu, n=600)
    assert num["x_trailing"] + num["x_leading"] < -0.1 * c.a
    assert np.sum(num["x"] * num["p"]) < 0
    # mirror symmetry: reversing the friction (sliding in -x) mirrors the solution
    x = np.linspace(-1.5 * c.a, 1.5 * c.a, 101)
    np.testing.assert_allclose(sc.pressure(x, P, R, E, nu, -mu), sc.pressure(-x, P, R, E, nu, mu), rtol=1e-13)
    assert sc.contact(P, R, E, nu, -mu).e == pytest.approx(-c.e, rel=1e-14)
