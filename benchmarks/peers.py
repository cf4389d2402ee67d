"""The peer solvers the benchmarks compare with (tamaas, ContactMechanics) and contactlib behind the same interface:
one ``solve(heights, mean_pressure, tol, max_iter)`` each, timed by the caller."""

from __future__ import annotations

import contextlib
import io
import os
import sys
import tempfile
import time
import warnings
from dataclasses import dataclass

import numpy as np

import contactlib
from contactlib.core import fft as cfft

from .common import dist_version


@dataclass
class Solution:
    pressure: np.ndarray
    iterations: int
    seconds: float
    converged: bool = True  # False: stopped by the iteration cap (``max_iter``) before its tolerance


class Peer:
    """One solver under test: ``solve(heights, mean_pressure, tol) -> Solution``.

    ``heights`` live on the periodic unit square, higher points touch first; ``E``/``nu`` as in
    :func:`contactlib.solve`; the returned pressure is compressive-positive on the same grid.
    """

    name = "peer"
    tol_meaning = ""
    fft_pairs_per_iteration = 2  # a Polonsky-Keer iteration: K p and K t

    def __init__(self, E: float, nu: float, threads: int):
        self.E, self.nu, self.threads = E, nu, threads

    @staticmethod
    def available() -> bool:
        return True

    @staticmethod
    def version() -> str:
        return "?"

    def solve(self, heights: np.ndarray, mean_pressure: float, tol: float, *, max_iter: int = 100_000) -> Solution:
        raise NotImplementedError


class Contactlib(Peer):
    name = "contactlib"
    tol_meaning = "scale-free complementarity residual (contactlib.solvers.contact_residual)"
    fft_pairs_per_iteration = 2.5  # K p, the preconditioner P g, and the forward transform of t (load control)

    def __init__(self, E, nu, threads):
        super().__init__(E, nu, threads)
        cfft.set_fft_options(threads=threads)

    @staticmethod
    def version():
        return contactlib.__version__

    def _solve(self, heights, mean_pressure, tol, max_iter):
        try:
            out = contactlib.solve(heights, E=self.E, nu=self.nu, mean_pressure=mean_pressure, tol=tol, length=1.0,
                                   max_iter=max_iter)
        except contactlib.ConvergenceError as exc:
            return exc.dataset, False
        return out, True

    def solve(self, heights, mean_pressure, tol, *, max_iter=10_000):
        t0 = time.perf_counter()
        out, converged = self._solve(heights, mean_pressure, tol, max_iter)
        dt = time.perf_counter() - t0
        pressure = out["pressure"].transpose("x", ...).values  # indexed [ix, iy], as the bare heights
        return Solution(pressure, int(out["iterations"]), dt, converged)

    def reference(self, heights, mean_pressure, tol, *, max_iter=3000) -> tuple[Solution, float]:
        """The tightest solution reachable, and its residual (round-off can stall it above ``tol``)."""
        out, _ = self._solve(heights, mean_pressure, tol, max_iter)
        return Solution(out["pressure"].transpose("x", ...).values, int(out["iterations"]), 0.0), float(out["residual"])


@contextlib.contextmanager
def _capture_output():
    """Capture what C++ code writes to file descriptors 1 and 2 (tamaas logs its iterations there)."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = {fd: os.dup(fd) for fd in (1, 2)}
    buf = io.StringIO()
    with tempfile.TemporaryFile(mode="w+") as tmp:
        for fd in (1, 2):
            os.dup2(tmp.fileno(), fd)
        try:
            with contextlib.redirect_stdout(buf), contextlib.redirect_stderr(buf):  # pybind11 redirects
                yield buf
        finally:
            sys.stdout.flush()
            sys.stderr.flush()
            for fd, old in saved.items():
                os.dup2(old, fd)
                os.close(old)
            tmp.seek(0)
            buf.write(tmp.read())


class Tamaas(Peer):
    name = "tamaas"
    tol_meaning = "tamaas PolonskyKeerRey.computeError (its own normalised complementarity)"

    def __init__(self, E, nu, threads):
        super().__init__(E, nu, threads)
        import tamaas as tm

        self.tm = tm
        tm.initialize(threads)  # the PyPI wheel is built with the cpp backend: single-threaded anyway

    @staticmethod
    def available():
        try:
            import tamaas  # noqa: F401
        except ImportError:
            return False
        return True

    @staticmethod
    def version():
        import tamaas as tm

        return f"{tm.__version__} (backend {tm.TamaasInfo.backend})"

    def solve(self, heights, mean_pressure, tol, *, max_iter=100_000):
        tm = self.tm
        n = heights.shape
        surface = np.ascontiguousarray(heights, dtype=float)
        t0 = time.perf_counter()
        model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, 1.0], list(n))
        model.E, model.nu = self.E, self.nu
        solver = tm.PolonskyKeerRey(model, surface, tol, tm.PolonskyKeerRey.pressure, tm.PolonskyKeerRey.pressure)
        solver.max_iter = max_iter
        solver.dump_freq = 10**9  # prints only the first and the last iteration
        with _capture_output() as log:
            error = solver.solve(mean_pressure)  # its final error: above tol when max_iter stopped it
        dt = time.perf_counter() - t0
        rows = [ln.split() for ln in log.getvalue().splitlines()]
        iters = [int(r[0]) for r in rows if r and r[0].isdigit()]
        return Solution(np.array(model.traction, copy=True).reshape(n), max(iters) if iters else -1, dt,
                        bool(error < tol))


def contactmechanics_solve(heights: np.ndarray, *, mean_pressure: float, E: float, nu: float, tol: float,
                           max_iter: int, thickness: float | None = None) -> dict:
    """ContactMechanics' Polonsky-Keer solver (``make_system(...).minimize_proxy``) under load control on the
    periodic unit square: a half-space, or with ``thickness`` its confined layer (Carbone & Mangialardi 2008, eq.
    A.30; 2D only, the 1D Green's function ignores ``thickness``).

    Its conventions, read from ``FFTElasticHalfSpace.py`` and ``ConstrainedConjugateGradients.py`` (1.8.3):
    ``young`` is Young's modulus when ``poisson`` is given (``contact_modulus = young / (1 - poisson**2)``);
    ``external_force`` is the total compressive force (mean pressure x area); ``jac`` is the compressive-positive
    force per node, so pressure = jac / node area. One tolerance drives its three criteria: ``pentol = tol h_rms``,
    ``forcetol = tol p A_node``, ``thermotol = tol``.
    """
    import ContactMechanics as cm
    from SurfaceTopography import Topography

    h = np.ascontiguousarray(heights, dtype=float)
    node = 1.0 / h.size
    t0 = time.perf_counter()
    substrate = cm.PeriodicFFTElasticHalfSpace(h.shape, E, physical_sizes=(1.0, 1.0), thickness=thickness, poisson=nu)
    system = cm.make_system(substrate=substrate, surface=Topography(h, physical_sizes=(1.0, 1.0), periodic=True))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sol = system.minimize_proxy(external_force=mean_pressure * 1.0, pentol=tol * float(np.std(h)),
                                    forcetol=tol * mean_pressure * node, thermotol=tol, maxiter=max_iter)
    dt = time.perf_counter() - t0
    return {"pressure": np.asarray(sol.jac).reshape(h.shape) / node, "iterations": int(sol.nit), "seconds": dt,
            "converged": bool(sol.success), "message": sol.message,
            "greens_function": np.asarray(substrate.greens_function)}


class ContactMechanicsPeer(Peer):
    """ContactMechanics' constrained_conjugate_gradients (Polonsky-Keer), :func:`contactmechanics_solve`."""

    name = "contactmechanics"
    tol_meaning = "pentol = tol*h_rms, forcetol = tol*p_mean*pixel area, thermotol = tol"

    @staticmethod
    def available():
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                import ContactMechanics  # noqa: F401
                import SurfaceTopography  # noqa: F401
        except Exception:
            return False
        return True

    @staticmethod
    def version():
        return dist_version("ContactMechanics")

    def solve(self, heights, mean_pressure, tol, *, max_iter=100_000):
        out = contactmechanics_solve(heights, mean_pressure=mean_pressure, E=self.E, nu=self.nu, tol=tol,
                                     max_iter=max_iter)
        if not out["converged"] and out["iterations"] < max_iter:
            raise RuntimeError(f"ContactMechanics did not converge: {out['message']}")
        return Solution(out["pressure"], out["iterations"], out["seconds"], out["converged"])


PEERS = {"contactlib": Contactlib, "tamaas": Tamaas, "contactmechanics": ContactMechanicsPeer}
