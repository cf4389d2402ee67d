import numpy as np
import pytest

import contactlib


@pytest.fixture(scope="session")
def material():
    """Young's modulus, Poisson ratio and contact modulus E* used across tests."""
    E, nu = 2.0, 0.3
    return {"E": E, "nu": nu, "E_star": E / (1 - nu**2)}


@pytest.fixture(scope="session")
def rough64():
    return contactlib.surfaces.self_affine(64, hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=3)


@pytest.fixture
def rng():
    return np.random.default_rng(1234)
