"""The invariants of a distributed solve, over the ranks: the checks of :func:`contactlib.invariants.contact_checks`
(the load or penetration asked, ``p >= 0``, no interpenetration, complementarity, the gap's definition) on sums and
extremes that each rank measures on its rows and MPI reduces, so every rank reaches the same verdict."""

from __future__ import annotations

import math

import numpy as np

from ..invariants import (FieldMeasures, check_complementarity, check_gap, check_gap_definition, check_load,
                          check_penetration, check_sign, verify)


def global_measures(comm, state, below_max: np.ndarray, height_max: float) -> FieldMeasures:
    """The :class:`contactlib.invariants.FieldMeasures` of a distributed state.

    Parameters
    ----------
    comm : mpi4py.MPI.Comm
        The ranks that share the grid.
    state : contactlib.distributed.ccg.LocalState
        This rank's rows of the solved state.
    below_max : ndarray
        This rank's heights minus their largest value over the grid (``h - max h <= 0``, what the solver
        subtracts from the gap) [length].
    height_max : float
        The largest height over the grid [length].

    Returns
    -------
    FieldMeasures
        The same measures the serial check takes from the whole fields, to round-off.
    """
    from mpi4py import MPI  # the distributed path only

    p, g, u, d = state.pressure, state.gap, state.displacement, float(state.penetration)
    def reduced(values, op):  # element-wise over the ranks, every rank getting the result
        out = np.empty(len(values))
        comm.Allreduce(np.asarray(values, dtype=float), out, op=op)
        return out

    n = comm.allreduce(p.size, op=MPI.SUM)
    psum, comp, hsum = reduced([p.sum(), np.sum(p * np.abs(g)), below_max.sum()], MPI.SUM)
    (variance,) = reduced([np.sum((below_max - hsum / n) ** 2)], MPI.SUM) / n
    pmin, gmin, hmin = reduced([p.min(), g.min(), below_max.min()], MPI.MIN)
    # the gap's definition g = u + max h - h - d, i.e. g - u + (h - max h) + d = 0
    definition, umax = reduced([np.max(np.abs(g - u + below_max + d)), np.max(np.abs(u))], MPI.MAX)
    rms = math.sqrt(variance) if variance > 0 else 1.0  # as contactlib.solvers.state.height_scale
    habs = max(abs(height_max), abs(height_max + float(hmin)))
    return FieldMeasures(mean_pressure=float(psum) / n, min_pressure=float(pmin), complementarity=float(comp) / n,
                         min_gap=float(gmin), height_rms=rms, gap_definition=float(definition),
                         round_off=float(umax) + habs + abs(d))


def verify_state(comm, state, below_max: np.ndarray, height_max: float, *, tol: float,
                 mean_pressure: float | None = None, penetration: float | None = None) -> str:
    """Check a converged distributed state against what must hold, as :func:`contactlib.solve` does.

    Parameters
    ----------
    comm : mpi4py.MPI.Comm
        The ranks that share the grid.
    state : contactlib.distributed.ccg.LocalState
        This rank's rows of the solved state.
    below_max : ndarray
        This rank's heights minus their largest value over the grid [length].
    height_max : float
        The largest height over the grid [length].
    tol : float
        The tolerance it was solved to.
    mean_pressure, penetration : float or None
        The load or approach asked (one of them).

    Returns
    -------
    str
        The invariants checked, comma-separated (``attrs['invariants_checked']`` of the serial answer).

    Raises
    ------
    contactlib.invariants.InvariantError
        On every rank, on the first invariant that failed.
    """
    m = global_measures(comm, state, below_max, height_max)
    checks = []
    if mean_pressure is not None:
        checks.append(check_load(state.mean_pressure, mean_pressure, tol=tol, scale=max(abs(mean_pressure), 1e-300)))
    if penetration is not None:
        checks.append(check_penetration(state.penetration, penetration, tol=tol, height_rms=m.height_rms))
    checks += [check_sign(m, tol=tol), check_gap(m.min_gap, tol=tol, height_rms=m.height_rms),
               check_complementarity(m, tol=tol), check_gap_definition(m, tol=tol)]
    verify(checks, where="distributed solve")
    return ", ".join(dict.fromkeys(c.invariant for c in checks))
