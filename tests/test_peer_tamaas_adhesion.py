"""Cross-check of the cohesive solver against tamaas 2.9's adhesion functional on its Polonsky-Keer-Rey
solver (:func:`contactlib.testing.solve_tamaas_adhesive`): a 2D periodic rough surface, 256^2, the exponential law, the
same work, range and mean pressure. tamaas is in the ``test`` extra, never a runtime dependency.

The Maugis law is not compared here: contactlib's is the Dugdale step as a narrow ramp
(:data:`contactlib.model.adhesion.MAUGIS_RAMP`), tamaas' the bare step, so their answers differ by more than
1e-3 by design (the benchmark prints both)."""

import numpy as np
import pytest

import contactlib

pytest.importorskip("tamaas", reason="tamaas (the `test` extra) is not installed")
from contactlib.testing import solve_tamaas_adhesive as solve_tamaas  # noqa: E402


def test_exponential_adhesion_matches_tamaas():
    h = contactlib.surfaces.self_affine(256, hurst=0.8, q_roll=4, q_cutoff=32, rms_slope=0.1, seed=1)
    work, range_, load = 1e-5, 1e-3, 0.01  # process zone 5 elements, sigma_0 = 1 x the load
    peer = solve_tamaas(h.values, E=1.0, nu=0.0, work=work, range_=range_, model="exponential",
                        mean_pressure=load, tol=1e-10)
    ds = contactlib.solve(h, E=1.0, nu=0.0, mean_pressure=load, tol=1e-8,
                          adhesion=contactlib.Adhesion(work=work, range=range_, model="exponential"))
    assert peer["mean_pressure"] == pytest.approx(load, rel=1e-5)
    assert float(ds.contact_area) == pytest.approx(peer["contact_area"], abs=1e-3)
    assert float(ds.gap.mean() - ds.gap.min()) == pytest.approx(peer["mean_gap"], rel=1e-3)
    assert ds.attrs["solver"].startswith("cohesive-frozen-traction")  # the fast method holds on this scene
    # adhesion matters in this scene: the non-adhesive area is clearly smaller
    plain = contactlib.solve(h, E=1.0, nu=0.0, mean_pressure=load)
    assert float(ds.contact_area) > float(plain.contact_area) + 0.02
