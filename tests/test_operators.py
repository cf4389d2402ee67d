"""The compliance operator: the Parseval quadratic form the CG step length relies on."""

import numpy as np
import pytest

from contactlib.grid import Grid
from contactlib.operators import Compliance


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
