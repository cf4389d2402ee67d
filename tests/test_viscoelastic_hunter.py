"""Hunter (1961): a rigid cylinder sliding on a standard-linear-solid half-space, frictionless, plane strain.

The isolated problem is solved by :mod:`contactlib.reference.hunter` (closed-form steady-sliding Green's
function with the exponential integral, exact element integrals, dense active set, no periodic window, no
Fourier multiplier). contactlib's spectral solver runs it on a periodic window 256 contact half-widths long.
"""

import numpy as np
import pytest

import contactlib
from contactlib.reference import hunter

SLS = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)
N, PER_A0, RADIUS = 16384, 64, 1.0  # a0 = 64 elements: the relaxed Hertz half-width
H = 1.0 / N
A0 = PER_A0 * H
LOAD = np.pi * (SLS.E0 / (1 - SLS.nu**2)) * A0**2 / (4 * RADIUS)  # per unit length: Hertz a0 at E0


def reference(speed):
    return hunter.solve(radius=RADIUS, load=LOAD, material=SLS, speed=speed, half_span=1.5 * A0, n=3 * PER_A0)


@pytest.mark.parametrize("speed, modulus", [(1e-5 * A0, "E0"), (1e4 * A0, "E_inf")])
def test_reference_limits_are_hertz(speed, modulus):
    """Slow and fast limits of the reference: Hertz contact widths at E0 and E_inf, centred, no friction."""
    out = reference(speed)
    E_star = getattr(SLS, modulus) / (1 - SLS.nu**2)
    a = np.sqrt(4 * LOAD * RADIUS / (np.pi * E_star))
    assert out.width == pytest.approx(2 * a, rel=0.02)  # element edges: +-1 element of ~20-64
    assert abs(out.offset) <= H
    assert out.residual < 1e-10  # the set is stable: no tension, no interpenetration
    assert abs(out.friction_coefficient) < 1e-3 * a / RADIUS


def test_spectral_solver_reproduces_hunter_over_three_decades():
    """V tau / a0 = 0.003 ... 3: contact width, offset and friction coefficient within 3 % of the isolated
    reference (width and offset to within an element; mu to 1 %)."""
    x = (np.arange(N) - N // 2) * H
    mus = []
    for zeta in (0.003, 0.03, 0.3, 3.0):
        V = zeta * A0 / SLS.relaxation_times[0]
        ref = reference(V)
        out = contactlib.solve(-x**2 / (2 * RADIUS), material=SLS, mean_pressure=LOAD, sliding_velocity=V,
                               length=1.0, kernel="love", tol=1e-9)
        on = np.flatnonzero(out.pressure.values > 0)
        leading, trailing = x[on[-1]] + H / 2, x[on[0]] - H / 2
        assert leading - trailing == pytest.approx(ref.width, rel=0.03)
        assert abs(0.5 * (leading + trailing) - ref.offset) <= 0.03 * ref.width
        mu = float(out.friction_coefficient_interlocking)
        assert mu == pytest.approx(ref.friction_coefficient, rel=0.03)
        mus.append(ref.friction_coefficient)
    # the bell: the contact moves forward and mu peaks inside the band
    assert mus[2] > 3 * max(mus[0], mus[3])
