"""contactlib's benchmarks: run each from the repository root as ``python -m benchmarks.<script> --help``.

Shared helpers live in :mod:`benchmarks.common`; results in ``RESULTS.md`` (the latest run of each benchmark) and
``history/<benchmark>.jsonl`` (the runs it superseded).
"""

import os

# Before any script imports numpy: no BLAS/OpenMP threads spinning against FFTW and the numba sweeps.
for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")
