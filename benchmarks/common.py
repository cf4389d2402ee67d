"""What the benchmark scripts share: timing, the machine they ran on, shared scenes (the peer solvers are in :mod:`.peers`), and the one
gateway to contactlib's internals that some benchmarks time.

Run every script from the repository root as a module, ``python -m benchmarks.<script> --help``.
"""

from __future__ import annotations

import importlib.metadata
import json
import math
import os
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path
from types import SimpleNamespace

import numpy as np

import contactlib
from contactlib.core import fft as cfft

REPO = Path(__file__).resolve().parent.parent
"""The repository root: the working directory of the scripts' child processes."""


# --------------------------------------------------------------------------------------------------- timing

def timed(fn, repeats: int, warm: bool = False, setup=None):
    """``(median seconds, last output)`` of ``repeats`` calls of ``fn()``. ``warm``: one untimed call first
    (numba compilation, FFT plans, a peer's own caches); ``setup``: called untimed before each call."""
    if warm:
        fn()
    times, out = [], None
    for _ in range(repeats):
        if setup is not None:
            setup()
        start = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times), out


def ladder(start: float):
    """Half-decade tolerances from ``start`` downwards (a peer's tolerance tightened until it is as accurate)."""
    k = math.ceil(2 * math.log10(start) - 1e-9)
    while k > -30:
        yield 10 ** (k / 2)
        k -= 1


def rel_l2(a: np.ndarray, ref: np.ndarray) -> float:
    """Relative L2 difference of two fields."""
    return float(np.linalg.norm(a - ref) / np.linalg.norm(ref))


# ----------------------------------------------------------------------------------------------- the machine

def command_line() -> str:
    """How this process was started, as ``python -m benchmarks.<script> <arguments>``."""
    spec = getattr(sys.modules.get("__main__"), "__spec__", None)
    head = f"python -m {spec.name}" if spec is not None else Path(sys.argv[0]).name
    return " ".join([head] + sys.argv[1:])


def child_command(module: str, *arguments: str) -> list[str]:
    """The command that runs ``benchmarks.<module>`` in a fresh interpreter (run it with ``cwd=REPO``)."""
    return [sys.executable, "-m", f"benchmarks.{module}", *arguments]


def dist_version(name: str) -> str:
    """The installed distribution's version. (``ContactMechanics.__version__`` comes from DiscoverVersion, which
    reports the git revision of the *current directory* when it is a repository: here, contactlib's commit.)"""
    try:
        return importlib.metadata.version(name)
    except importlib.metadata.PackageNotFoundError:
        return "not installed"


def host_info() -> dict:
    """The machine and software a benchmark ran on: CPU, versions, git revision, date, command, load."""
    cpu = "?"
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next(ln.split(":", 1)[1].strip() for ln in f if ln.startswith("model name"))
    except (OSError, StopIteration):
        pass
    import pyfftw

    info = {
        "cpu": cpu, "logical_cpus": os.cpu_count(), "python": platform.python_version(), "numpy": np.__version__,
        "pyfftw": pyfftw.__version__, "contactlib": contactlib.__version__, "fftw_effort": cfft.fft_options()["effort"],
        "date": time.strftime("%Y-%m-%d %H:%M:%S"), "command": command_line(),
    }
    try:
        rev = subprocess.run(["git", "-C", str(REPO), "describe", "--always", "--dirty"], capture_output=True, text=True)
        info["contactlib_git"] = rev.stdout.strip() or "?"
    except OSError:
        pass
    try:
        import psutil

        info["memory_gib"] = round(psutil.virtual_memory().total / 2**30, 1)
    except ImportError:
        pass
    info["load_avg_1min"] = round(os.getloadavg()[0], 2)
    return info


def write_json(path: Path, payload: dict) -> None:
    """Write ``payload`` to ``path`` atomically (a killed run keeps the last complete file)."""
    tmp = Path(path).with_suffix(".tmp")
    tmp.write_text(json.dumps(payload, indent=1, default=str))
    os.replace(tmp, path)


# ------------------------------------------------------------------------------------------------ the scenes

def self_affine_surface(n: int, args, *, dim: int = 2):
    """The benchmarks' rough surface (a DataArray on the unit window): ``self_affine`` with ``args.hurst``,
    ``args.q_roll``, ``q_cutoff = args.cutoff_fraction * n``, ``args.rms_slope`` and ``args.seed``."""
    return contactlib.surfaces.self_affine(n, hurst=args.hurst, q_roll=args.q_roll, q_cutoff=n * args.cutoff_fraction,
                                           rms_slope=args.rms_slope, seed=args.seed, dim=dim)


def self_affine_array(n: int, args) -> np.ndarray:
    """:func:`self_affine_surface`'s 2D heights as a contiguous array (for the peers)."""
    return np.ascontiguousarray(self_affine_surface(n, args).transpose("x", "y").values)  # [ix, iy], as the peers'


def contact_fraction(pressure: np.ndarray) -> float:
    """Fraction of the nodes in contact (``p > 0``)."""
    return float(np.count_nonzero(pressure > 0)) / pressure.size


def calibrate_load(contact_area, target: float, first_guess: float, *, rtol: float = 0.02,
                   steps: int = 8) -> tuple[float, float]:
    """Mean pressure giving contact fraction ``target`` within ``rtol``: secant on log A against log p.

    ``contact_area(p)`` solves the scene at mean pressure ``p``; returns ``(p, its contact fraction)``."""
    p = first_guess
    area, slope = contact_area(p), 1.0
    for _ in range(steps):
        if abs(area / target - 1) <= rtol or area <= 0 or area >= 1:
            break
        previous = (p, area)
        p = math.exp(math.log(p) + (math.log(target) - math.log(area)) / slope)
        area = contact_area(p)
        if 0 < area < 1 and area != previous[1] and p != previous[0]:
            slope = min(max((math.log(area) - math.log(previous[1])) / (math.log(p) - math.log(previous[0])), 0.1),
                        2.0)
    return p, area


def pressure_for_area(solver, heights: np.ndarray, target: float, args) -> tuple[float, float]:
    """Mean pressure giving contact fraction ``target`` within 2 % on ``solver`` (a :class:`Contactlib`) at
    ``args.calibration_tol``, from the small-contact estimate ``A ~ 2 p / (E* h'_rms)``."""
    E_star = args.E / (1 - args.nu**2)
    first = target * E_star * args.rms_slope / 2.0
    return calibrate_load(lambda p: contact_fraction(solver.solve(heights, p, args.calibration_tol).pressure),
                          target, first)


def sliding_surface(n: int, seed: int = 1):
    """The steady-sliding benchmarks' 2D surface: Hurst 0.8, rolloff 2, cutoff ``n / 8``, rms slope 0.1."""
    return contactlib.surfaces.self_affine(n, hurst=0.8, q_roll=2, q_cutoff=n // 8, rms_slope=0.1, seed=seed)


def load_for_contact(h, target: float) -> float:
    """Mean pressure [E0 units] giving ``target`` contact elastically (``E = 1``, ``nu = 0.5``; bisection on the
    log of the load, to 0.01 in the contact fraction)."""
    lo, hi = 1e-4, 1.0
    for _ in range(30):
        mid = np.sqrt(lo * hi)
        area = float(contactlib.solve(h, E=1.0, nu=0.5, mean_pressure=mid, tol=1e-6).contact_area)
        lo, hi = (mid, hi) if area < target else (lo, mid)
        if abs(area - target) < 0.01:
            break
    return float(mid)


# ------------------------------------------------------------ one solver of a prepared problem, timed alone

def prepared_problem(heights, *, material, mean_pressure=None, penetration=None, **options):
    """A validated scene with its operators (:func:`contactlib.prepare`) carrying one load, for the benchmarks that
    time one solver of a non-symmetric problem alone (:func:`nonsymmetric_solve`). ``options``: any other keyword of
    ``solve`` (``friction``, ``layer``, ``sliding_velocity``, ``tol``, ``max_iter``, ...)."""
    friction = options.get("friction", 0.0)
    options.setdefault("sliding_direction", 0.0 if friction else None)
    problem = contactlib.prepare(heights, material=material, **options)
    return problem.loaded(mean_pressure=mean_pressure, penetration=penetration)


def nonsymmetric_solve(problem, route: str, **kwargs):
    """One route of a loaded non-symmetric problem: ``"dispatch"`` (what ``solve`` runs), ``"krylov"``
    (semismooth GMRES; ``kwargs`` e.g. ``first_try=True``), ``"splitting"`` (Douglas-Rachford as the dispatch runs
    it), ``"coupled"`` (the fixed point on the skew part) or ``"douglas-rachford"`` (the bare splitting solver on
    :func:`complex_multiplier`, or on ``kwargs["multiplier"]``). Returns the solver's state."""
    from contactlib.solvers.nonsymmetric import choice as nonsymmetric_choice

    if route == "dispatch":
        return problem.run()
    if route == "krylov":
        return nonsymmetric_choice.solve_krylov(problem, **kwargs)
    if route == "splitting":
        return nonsymmetric_choice.solve_split(problem)
    if route == "coupled":
        from contactlib.solvers import solve_coupled

        return solve_coupled(problem.solve_symmetric, problem.body.coupling, problem.values, **problem.solver_args)
    if route == "douglas-rachford":
        from contactlib.solvers.nonsymmetric.splitting import solve_splitting

        multiplier = kwargs.get("multiplier")  # computed once by the caller, outside its timing
        multiplier = complex_multiplier(problem) if multiplier is None else multiplier
        return solve_splitting(multiplier, problem.values, mean_pressure=problem.solver_args["mean_pressure"],
                               tol=problem.solver_args["tol"])
    raise ValueError("route must be 'dispatch', 'krylov', 'splitting', 'coupled' or 'douglas-rachford', "
                     f"got {route!r}")


def complex_multiplier(problem) -> np.ndarray:
    """The Fourier multiplier of a prepared problem's body, its coupling included (complex where it is skew)."""
    from contactlib.solvers.nonsymmetric.splitting import fourier_multiplier

    return fourier_multiplier(problem.body.compliance, problem.body.coupling)


def iteration_internals(transforms, shape) -> SimpleNamespace:
    """The parts of one Polonsky-Keer iteration, for ``bench_iteration`` to time alone: the transforms' workspace
    and offset, the fused element-wise sweeps chosen for ``shape`` (serial or threaded) and the two compiled passes
    over a spectrum. These are implementation kernels with no public route: timing them alone is the point."""
    from contactlib.model import operators
    from contactlib.solvers.symmetric import fused

    sweeps = fused.select(shape)
    return SimpleNamespace(
        workspace=transforms.workspace, offset=transforms.offset_spectrum, sweeps=sweeps,
        threaded=sweeps is fused.THREADED,
        affine_pass=lambda rows: operators.spectrum_pass(operators.affine_spectrum, rows),
        scale_power_pass=lambda rows: operators.spectrum_pass(operators.scale_and_power_sum, rows))
