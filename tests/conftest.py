import os

import numpy as np
import pytest
from hypothesis import settings

import contactlib

# Property-based tests (tests/test_metamorphic*.py). "ci", the default: the same examples on every run
# (derandomized, no example database), so CI is reproducible; each test's own max_examples is its budget at
# this profile's 100. "thorough" (HYPOTHESIS_PROFILE=thorough): ten times the examples, drawn afresh each run,
# to search hard; a failure prints the blob that replays it (@reproduce_failure).
settings.register_profile("ci", max_examples=100, derandomize=True, database=None, deadline=None, print_blob=True)
settings.register_profile("thorough", max_examples=1000, derandomize=False, database=None, deadline=None,
                          print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))


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
