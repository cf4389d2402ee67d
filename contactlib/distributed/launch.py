"""Whether this process was started by ``mpirun``/``mpiexec`` with more than one rank: read from the launcher's
environment, so the serial command line never imports mpi4py."""

from __future__ import annotations

import os

# Open MPI (OMPI_COMM_WORLD_SIZE), MPICH and Intel MPI (PMI_SIZE), PMIx launchers (PMIX_SIZE? not always set)
_SIZE_VARIABLES = ("OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "MPI_LOCALNRANKS")


def launched_ranks() -> int:
    """The number of ranks the MPI launcher started (1 when not launched by one)."""
    for name in _SIZE_VARIABLES:
        value = os.environ.get(name)
        if value and value.isdigit():
            return int(value)
    return 1
