"""The error a solve raises when it does not converge: one class for every entry point (its subclass
:class:`contactlib.invariants.InvariantError` for a converged state that breaks what must hold)."""

from __future__ import annotations

import xarray as xr


class ConvergenceError(RuntimeError):
    """A solve did not reach its tolerance within ``max_iter``, or stalled before it (the CG
    residual stopped falling, e.g. at the round-off floor of a tolerance set too tight).

    Parameters
    ----------
    message : str
        What did not converge, with the residual and the tolerance.
    residual : float
        The residual reached.
    dataset : xarray.Dataset
        The partial state.

    Attributes
    ----------
    residual : float
        The residual reached.
    dataset : xarray.Dataset
        The partial (unconverged) state, labelled like a converged one, ``attrs['converged'] = 0``.
    datasets : list of xarray.Dataset or None
        From :func:`solve_tolerances`: the answer at every tolerance asked, reached or not.
    """

    def __init__(self, message: str, *, residual: float, dataset: xr.Dataset):
        super().__init__(message)
        self.residual = residual
        self.dataset = dataset
        self.datasets = None
