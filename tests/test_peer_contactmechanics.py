"""Cross-check against ContactMechanics' confined layer (its ``PeriodicFFTElasticHalfSpace(thickness=...)``,
Carbone and Mangialardi 2008, eq. A.30), an independent implementation of the same scene.

ContactMechanics is in the ``test`` extra (CI runs this), never a runtime dependency. Its conventions
(1.8.3): ``young`` is Young's modulus when ``poisson`` is given; ``external_force`` is the total
compressive force; ``jac`` is the compressive-positive force per node.
"""

import warnings

import numpy as np
import pytest

import contactlib

cm = pytest.importorskip("ContactMechanics", reason="ContactMechanics (the `test` extra) is not installed")
Topography = pytest.importorskip("SurfaceTopography", reason="SurfaceTopography (ContactMechanics' dependency)"
                                 ).Topography

N, E, NU = 512, 1.0, 0.3
THICKNESS = 1.0 / (2 * np.pi)  # q0 h = 1 on the unit window: the layer is 2-3x stiffer than the half-space


def _contactmechanics_pressure(h: np.ndarray, mean_pressure: float, tol: float) -> np.ndarray:
    node = 1.0 / h.size
    substrate = cm.PeriodicFFTElasticHalfSpace(h.shape, E, physical_sizes=(1.0, 1.0), thickness=THICKNESS,
                                               poisson=NU)
    system = cm.make_system(substrate=substrate, surface=Topography(h, physical_sizes=(1.0, 1.0), periodic=True))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sol = system.minimize_proxy(external_force=mean_pressure, pentol=tol * float(np.std(h)),
                                    forcetol=tol * mean_pressure * node, thermotol=tol, maxiter=5000)
    assert sol.success, sol.message
    return np.asarray(sol.jac).reshape(h.shape) / node


def test_confined_layer_contact_area_matches_contactmechanics():
    """512^2 self-affine surface at about 10 % contact: the same contact area within 1e-6 (here: the
    same contact nodes, one node being 3.8e-6 of the area) and the same pressure to 1e-6."""
    heights = contactlib.surfaces.self_affine(N, hurst=0.8, q_roll=2, q_cutoff=N // 8, rms_slope=0.1, seed=3)
    mean_pressure = 0.005  # about 10 % contact on this layer
    layer = contactlib.Layer(THICKNESS, base="confined")
    ours = contactlib.solve(heights, E=E, nu=NU, mean_pressure=mean_pressure, layer=layer, tol=1e-10)
    assert ours.attrs["body"] == "layer"
    theirs = _contactmechanics_pressure(np.ascontiguousarray(heights.values), mean_pressure, tol=1e-10)
    area_theirs = float(np.mean(theirs > 0))
    assert 0.05 < float(ours.contact_area) < 0.2
    assert abs(float(ours.contact_area) - area_theirs) <= 1e-6
    p = ours.pressure.values
    assert np.linalg.norm(p - theirs) / np.linalg.norm(theirs) < 1e-6
