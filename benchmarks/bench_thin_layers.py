"""Thin layers: displacement control of plates (semismooth Newton) and the thin confined viscoelastic layer with
Coulomb friction (non-monotone operator).

    python -m benchmarks.bench_thin_layers

(A) q0 h = 0.1 remote-pressure layer, nu = 0.3: load control, then displacement control at the penetration
found; wall times (median of 3, interleaved), CG iterations, the load and pressure agreement, and the dual
iteration's residual after 2000 iterations. (B) confined layer, SLS E_inf/E0 = 10, nu = 0.5, mu_c = 0.8 and 0,
1024 points, over V tau q0: whether the operator is monotone, solver, iterations, residual, wall time.
"""

import os

import numpy as np

import contactlib
from contactlib.model.bodies import body_model
from contactlib.core.grid import Grid
from contactlib.model.materials import Elastic
from contactlib.solvers import solve_periodic_displacement

from .common import timed


def plates():
    layer = contactlib.Layer(0.1 / (2 * np.pi), "remote_pressure")
    print("| scene | contact | load: s, CG it | penetration: s, CG it | mean p rel. err | pressure rel. err | dual residual after 2000 it |")
    print("|---|---|---|---|---|---|---|")
    for n, dim, P in ((4096, 1, 1e-3), (4096, 1, 1e-2), (4096, 1, 3e-2), (64, 2, 1e-3), (64, 2, 3e-3)):
        h = contactlib.surfaces.self_affine(n, hurst=0.8, q_roll=2, q_cutoff=n // (8 if dim == 1 else 4),
                                           rms_slope=0.1, seed=4, dim=dim)
        repeats = 3 if dim == 1 else 1
        tl, load = timed(lambda: contactlib.solve(h, E=1.0, nu=0.3, mean_pressure=P, layer=layer, tol=1e-10), repeats)
        d = float(load.penetration)
        tp, pen = timed(lambda: contactlib.solve(h, E=1.0, nu=0.3, penetration=d, layer=layer, tol=1e-10), repeats)
        body = body_model(Grid(h.shape, (1.0,) * dim), material=Elastic(1.0, 0.3), layer=layer, friction=0.0,
                          direction=0.0, tol=1e-10, kernel="spectral", periodic=True)
        dual = solve_periodic_displacement(body.compliance, h.values, penetration=d, tol=1e-10, max_iter=2000)
        err = np.linalg.norm(pen.pressure - load.pressure) / np.linalg.norm(load.pressure)
        print(f"| {'x'.join([str(n)] * dim)} | {float(load.contact_area):.3f} | {tl:.2f}, {int(load.iterations)} | "
              f"{tp:.2f}, {int(pen.iterations)} | {abs(float(pen.mean_pressure) / P - 1):.1e} | {err:.1e} | "
              f"{dual.residual:.1e}{' (converged)' if dual.converged else ''} |", flush=True)


def viscoelastic_layer():
    m = contactlib.Viscoelastic.standard_linear_solid(E0=1.0, E_inf=10.0, tau=1.0, nu=0.5)
    h = contactlib.surfaces.self_affine(1024, hurst=0.8, q_roll=1, q_cutoff=64, rms_slope=0.1, seed=3, dim=1)
    q0 = 2 * np.pi
    print("\n| q0 h | V tau q0 | mean p / E0 | monotone | solver | contact | it (outer) | residual | s (mu_c = 0.8) | s (mu_c = 0) |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for q0h in (0.5, 0.1):
        for zeta in (1e-2, 0.1, 0.3, 1.0, 100.0):
            for P in (0.05, 0.5):
                kw = dict(material=m, mean_pressure=P, sliding_velocity=zeta / q0, layer=contactlib.Layer(q0h / q0),
                          tol=1e-8)
                t8, out = timed(lambda: contactlib.solve(h, friction=0.8, **kw), 3)
                t0, _ = timed(lambda: contactlib.solve(h, friction=0.0, **kw), 3)
                print(f"| {q0h} | {zeta:g} | {P} | {out.attrs.get('monotone', 1)} | {out.attrs['solver']} | "
                      f"{float(out.contact_area):.3f} | {int(out.iterations)} ({int(out.get('outer_iterations', 0))}) | "
                      f"{float(out.residual):.1e} | {t8:.2f} | {t0:.2f} |", flush=True)


if __name__ == "__main__":
    print("load average before:", os.getloadavg())
    plates()
    viscoelastic_layer()
    print("load average after:", os.getloadavg())
