"""The single FFT convention of contactlib.

Real-to-complex transforms over all axes (``rfftn`` layout). Forward transforms are
unnormalised; the ``1/N`` of the inverse is folded into the kernels by
:func:`convolution_multiplier`, so that one forward + one inverse FFT gives a convolution.

Plans are built once per (shape, threads) and per thread, with buffers reused across
iterations and across solves of the same shape. FFTW wisdom is cached on disk so
``FFTW_MEASURE`` planning is paid once per machine; :func:`export_wisdom` and
:func:`import_wisdom` let a sweep ship the same plans to every worker, which keeps
results bit-identical across workers and re-runs.
"""

from __future__ import annotations

import ctypes
import os
import threading
from pathlib import Path

import numpy as np
import pyfftw

_settings = {"threads": 1, "effort": "FFTW_MEASURE"}
_local = threading.local()
_wisdom_lock = threading.Lock()
_wisdom_loaded = False


def wisdom_path() -> Path:
    """On-disk FFTW wisdom cache (``$CONTACTLIB_WISDOM`` overrides)."""
    default = Path(os.environ.get("XDG_CACHE_HOME", Path.home() / ".cache")) / "contactlib" / "fftw-wisdom"
    return Path(os.environ.get("CONTACTLIB_WISDOM", default))


def set_fft_options(*, threads: int | None = None, effort: str | None = None) -> None:
    """Set the threads of a solve and the FFTW planner effort (``FFTW_ESTIMATE``/``MEASURE``/``PATIENT``).

    ``threads`` is FFTW's thread count per transform (its OpenMP team is sized to match, whatever
    ``OMP_NUM_THREADS`` says); above 1 the solvers' element-wise sweeps run on as many threads too on
    grids of 4096^2 points or more, equal to the serial sweeps to round-off (:mod:`contactlib.core._numba`)."""
    if threads is not None:
        if int(threads) < 1:
            raise ValueError(f"threads must be >= 1, got {threads}")
        _settings["threads"] = int(threads)
    if effort is not None:
        if effort not in ("FFTW_ESTIMATE", "FFTW_MEASURE", "FFTW_PATIENT", "FFTW_EXHAUSTIVE"):
            raise ValueError(f"unknown FFTW planner effort {effort!r}")
        _settings["effort"] = effort


def fft_options() -> dict:
    return dict(_settings)


def threads() -> int:
    """The thread count of :func:`set_fft_options` (read in every iteration: no copy)."""
    return _settings["threads"]


def _openmp_runtimes() -> list[ctypes.CDLL]:
    """The OpenMP runtimes (gomp, libomp) loaded in this process, with their ``omp_*`` calls (Linux;
    elsewhere none)."""
    try:
        maps = Path("/proc/self/maps").read_text().splitlines()
    except OSError:
        return []
    runtimes = []
    for path in sorted({line.split()[-1] for line in maps if "/lib" in line and ("gomp" in line or "libomp" in line)}):
        try:
            runtime = ctypes.CDLL(path)
            runtime.omp_set_num_threads  # a library that only mentions OpenMP in its name has none
        except (OSError, AttributeError):
            continue
        runtimes.append(runtime)
    return runtimes


def _match_openmp_threads(threads: int) -> None:
    """Give this thread's OpenMP teams ``threads`` threads, once per thread and count.

    pyFFTW's wheels build FFTW on OpenMP, whose transforms split into as many chunks as the plan's
    thread count but run them on the OpenMP team, sized by ``OMP_NUM_THREADS``: with it at 1 (usual
    on clusters, and set by benchmarks to pin BLAS) a 2-thread 512^2 FFT pair took 2.0 ms against
    1.7 on one thread and 0.9 with a team of 2. The setting is per thread, so it is made where the
    plans run."""
    if threads < 2 or getattr(_local, "openmp_threads", None) == threads:
        return
    global _openmp
    if _openmp is None:
        _openmp = _openmp_runtimes()
    for runtime in _openmp:
        runtime.omp_set_num_threads(threads)
    _local.openmp_threads = threads


_openmp = None


def export_wisdom() -> tuple[bytes, ...]:
    return pyfftw.export_wisdom()


def import_wisdom(wisdom: tuple[bytes, ...]) -> None:
    """Import FFTW wisdom (e.g. a parent's :func:`export_wisdom`) on top of the on-disk cache,
    which is read first so that the given plans are the last word."""
    load_wisdom_once()
    pyfftw.import_wisdom(wisdom)


def load_wisdom_once() -> None:
    global _wisdom_loaded
    with _wisdom_lock:
        if _wisdom_loaded:
            return
        _wisdom_loaded = True
        try:
            parts = wisdom_path().read_bytes().split(b"\n--contactlib--\n")
            if len(parts) == 3:
                pyfftw.import_wisdom(tuple(parts))
        except OSError:
            pass


def save_wisdom() -> None:
    path = wisdom_path()
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_suffix(f".{os.getpid()}.tmp")
        tmp.write_bytes(b"\n--contactlib--\n".join(pyfftw.export_wisdom()))
        os.replace(tmp, path)
    except OSError:  # a read-only home is no reason to fail a solve
        pass


class RealFFT:
    """Planned forward/inverse real FFT pair on aligned, reusable buffers.

    ``real`` and ``spectrum`` are the work buffers; ``forward()`` maps real -> spectrum,
    ``inverse()`` maps spectrum -> real (unnormalised, destroys ``spectrum``).
    """

    def __init__(self, shape: tuple[int, ...], threads: int, effort: str):
        load_wisdom_once()
        spectral = tuple(shape[:-1]) + (shape[-1] // 2 + 1,)
        self.shape = tuple(shape)
        self.real = pyfftw.empty_aligned(shape, dtype="float64")
        self.spectrum = pyfftw.empty_aligned(spectral, dtype="complex128")
        axes = tuple(range(len(shape)))
        self._fwd = pyfftw.FFTW(self.real, self.spectrum, axes=axes, flags=(effort,), threads=threads)
        self._inv = pyfftw.FFTW(
            self.spectrum, self.real, axes=axes, direction="FFTW_BACKWARD",
            flags=(effort, "FFTW_DESTROY_INPUT"), threads=threads,
        )
        if effort != "FFTW_ESTIMATE":
            save_wisdom()

    def forward(self) -> np.ndarray:
        self._fwd.execute()
        return self.spectrum

    def inverse(self) -> np.ndarray:
        self._inv.execute()
        return self.real


def get_fft(shape: tuple[int, ...], slot: str = "work") -> RealFFT:
    """The cached plan for ``shape`` in this thread (built on first use). Another ``slot`` gives a
    plan with buffers of its own, for a transform that must not disturb the work buffers."""
    cache = getattr(_local, "plans", None)
    if cache is None:
        cache = _local.plans = {}
    key = (tuple(shape), _settings["threads"], _settings["effort"], slot)
    _match_openmp_threads(_settings["threads"])
    plan = cache.get(key)
    if plan is None:
        plan = cache[key] = RealFFT(tuple(shape), _settings["threads"], _settings["effort"])
    return plan


class SharedSpectrum:
    """Named real buffers sharing one spectrum buffer, each with its own planned transforms.

    ``forward(name)`` maps buffer ``name`` to :attr:`spectrum`; ``inverse(name)`` maps the spectrum
    (destroying it) into buffer ``name``. Unlike :class:`RealFFT`, no transform writes over an input
    buffer: a field can stay in its buffer across iterations, and a zero padding stays zero. An
    output may share an input's buffer (``outputs={"result": "field"}``) where that input is spent.
    The buffers start zeroed (but for one replaced by :meth:`detach`); all plans are made at
    construction (FFTW_MEASURE scribbles on its arrays while planning).
    """

    def __init__(self, shape: tuple[int, ...], threads: int, effort: str, inputs: tuple[str, ...],
                 outputs: dict[str, str | None]):
        load_wisdom_once()
        self.shape = tuple(shape)
        spectral = self.shape[:-1] + (self.shape[-1] // 2 + 1,)
        self.spectrum = pyfftw.empty_aligned(spectral, dtype="complex128")
        axes = tuple(range(len(shape)))
        self.buffers = {name: pyfftw.empty_aligned(shape, dtype="float64") for name in inputs}
        for name, shared in outputs.items():
            self.buffers[name] = self.buffers[shared] if shared else pyfftw.empty_aligned(shape, dtype="float64")
        self._forward = {name: pyfftw.FFTW(self.buffers[name], self.spectrum, axes=axes, flags=(effort,),
                                           threads=threads) for name in inputs}
        self._inverse = {name: pyfftw.FFTW(self.spectrum, self.buffers[name], axes=axes, direction="FFTW_BACKWARD",
                                           flags=(effort, "FFTW_DESTROY_INPUT"), threads=threads)
                         for name in outputs}
        for buffer in self.buffers.values():
            buffer.fill(0.0)
        if effort != "FFTW_ESTIMATE":
            save_wisdom()

    def forward(self, name: str) -> np.ndarray:
        self._forward[name].execute()
        return self.spectrum

    def inverse(self, name: str) -> np.ndarray:
        self._inverse[name].execute()
        return self.buffers[name]

    def detach(self, name: str) -> np.ndarray:
        """Hand buffer ``name`` (and the names sharing it) over to the caller, and rebind its plans to a
        new, uninitialised buffer: a solve returns its fields without copying them, and the pool keeps
        its plans."""
        old = self.buffers[name]
        new = pyfftw.empty_aligned(self.shape, dtype="float64")
        for key in [key for key, buffer in self.buffers.items() if buffer is old]:
            self.buffers[key] = new
            if key in self._forward:
                self._forward[key].update_arrays(new, self.spectrum)
            if key in self._inverse:
                self._inverse[key].update_arrays(self.spectrum, new)
        return old


class _Pool:
    """Lends a thread's cached :class:`SharedSpectrum`; a nested borrower gets a new one."""

    def __init__(self, key, build):
        self.key, self.build = key, build

    def __enter__(self) -> SharedSpectrum:
        _match_openmp_threads(self.key[1])
        free = _free_workspaces().setdefault(self.key, [])
        self.workspace = free.pop() if free else self.build()
        return self.workspace

    def __exit__(self, *exc) -> None:
        _free_workspaces()[self.key].append(self.workspace)


def _free_workspaces() -> dict:
    free = getattr(_local, "workspaces", None)
    if free is None:
        free = _local.workspaces = {}
    return free


def shared_spectrum(shape: tuple[int, ...], inputs: tuple[str, ...], outputs: dict[str, str | None]) -> _Pool:
    """``with shared_spectrum(...) as workspace``: a :class:`SharedSpectrum` of this thread, kept for
    the next solve of this shape and layout (buffers and plans are reused, their contents are not
    reset); a solve nested inside another gets buffers of its own."""
    key = (tuple(shape), _settings["threads"], _settings["effort"], tuple(inputs), tuple(outputs.items()))
    return _Pool(key, lambda: SharedSpectrum(tuple(shape), _settings["threads"], _settings["effort"], inputs, outputs))


def convolution_multiplier(transfer: np.ndarray, shape: tuple[int, ...]) -> np.ndarray:
    """Fold the inverse-FFT normalisation into a real Fourier multiplier."""
    return np.ascontiguousarray(transfer / float(np.prod(shape)), dtype="float64")


def rfftn(field: np.ndarray) -> np.ndarray:
    """Forward real FFT (unnormalised), numpy's deterministic pocketfft: for setup, not loops."""
    return np.fft.rfftn(field)


def irfftn(spectrum: np.ndarray, shape: tuple[int, ...]) -> np.ndarray:
    """Inverse of :func:`rfftn` (normalised by 1/N)."""
    return np.fft.irfftn(spectrum, s=shape, axes=tuple(range(len(shape))))
