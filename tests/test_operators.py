"""The compliance operator: the Parseval quadratic form the CG step length relies on."""

import numpy as np
import pytest

from contactlib.core.grid import Grid
from contactlib.model.operators import Compliance


@pytest.mark.parametrize("periodic", [True, False])
@pytest.mark.parametrize("kernel", ["spectral", "love"])
@pytest.mark.parametrize("shape", [(64, 64), (63, 50), (2, 3), (128,), (127,), (2,)])
def test_quadratic_form_equals_real_space_product(shape, kernel, periodic):
    """<t, K t> from the forward transform alone (Hermitian weights of the half spectrum: first
    column once, last column once for an even axis) equals sum(t * K t) in real space."""
    op = Compliance(Grid(shape, (1.0,) * len(shape)), E_star=1.3, kernel=kernel, periodic=periodic)
    t = np.random.default_rng(len(shape) * 100 + shape[-1]).standard_normal(shape)
    direct = float(np.sum(t * op(t)))
    op.load()[...] = t
    assert op.quadratic_form() == pytest.approx(direct, rel=1e-12)


@pytest.mark.parametrize("periodic", [True, False])
@pytest.mark.parametrize("shape", [(64, 64), (63, 50), (128,), (127,)])
def test_iteration_transforms_match_the_plain_operator(shape, periodic):
    """The solver's transforms on their own buffers: ``K p - s h`` with the heights' spectrum
    subtracted in Fourier space, the preconditioner with its Parseval sum ``<r, P r>``, and
    ``<t, K t>``, against the operator applied in real space."""
    op = Compliance(Grid(shape, (1.0,) * len(shape)), E_star=1.3, periodic=periodic)
    rng = np.random.default_rng(shape[-1] + periodic)
    p, h, r, t = (rng.standard_normal(shape) for _ in range(4))
    with op.iteration_transforms(offset=h) as tr:
        assert not tr.direction.any()  # starts at zero
        tr.pressure[...], tr.residual[...], tr.direction[...] = p, r, t
        scale = np.abs(op(p)).max()
        np.testing.assert_allclose(tr.displacement(0.7), op(p) - 0.7 * h, rtol=0, atol=1e-13 * scale)
        np.testing.assert_array_equal(tr.pressure, p)  # inputs survive their transforms
        preconditioned, power = tr.precondition()
        padded = np.zeros(op.work_shape)
        padded[op._block] = r
        spectrum = np.fft.rfftn(padded) * op.inverse_multiplier
        expected = np.fft.irfftn(spectrum, s=op.work_shape, axes=tuple(range(len(shape)))) * np.prod(op.work_shape)
        np.testing.assert_allclose(preconditioned, expected[op._block], rtol=0, atol=1e-12 * np.abs(expected).max())
        assert power == pytest.approx(float(np.sum(padded * expected)), rel=1e-11)
        assert tr.direction_energy() == pytest.approx(float(np.sum(t * op(t))), rel=1e-12)
        # a solve nested in this one gets buffers of its own
        with op.iteration_transforms() as inner:
            assert not np.shares_memory(inner.pressure, tr.pressure)
            inner.pressure[...] = 1.0
        np.testing.assert_array_equal(tr.pressure, p)
    with op.iteration_transforms() as again:  # the same buffers, lent again
        assert np.shares_memory(again.pressure, tr.pressure) or np.shares_memory(again.pressure, inner.pressure)


def test_taken_fields_leave_the_pool_working():
    """A solve hands its fields over at the end (periodic: the buffers themselves); the pool's plans are
    rebound to new buffers and give the same transforms in the next solve."""
    op = Compliance(Grid((32, 24), (1.0, 1.0)), E_star=2.0)
    p = np.random.default_rng(1).random((32, 24))
    with op.iteration_transforms() as tr:
        tr.pressure[...] = p
        first = tr.displacement().copy()
        taken = tr.take("pressure")
        np.testing.assert_array_equal(taken, p)
    with op.iteration_transforms() as tr:
        assert not np.shares_memory(tr.pressure, taken)
        tr.pressure[...] = p
        np.testing.assert_array_equal(tr.displacement(), first)
    np.testing.assert_array_equal(taken, p)  # the caller's array is left alone by the next solve
