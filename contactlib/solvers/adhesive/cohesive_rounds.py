"""The frozen-traction cohesive iteration as rounds inside one Polonsky-Keer solve.

:class:`contactlib.solvers.adhesive.cohesive_frozen.FrozenTraction` holds the adhesive traction ``a`` fixed, runs a few
constrained-CG iterations of the non-adhesive contact on the heights ``h - K a``, evaluates the law at the new
gap and mixes the next ``a``. Restarting the CG each round cost its set-up and finish every time (the offset
heights' transform, the evaluation at the warm start, the state's assembly: about 3.5 ms a round at 256^2, a
round's ``K a`` one FFT pair more). Here :class:`Rounds` moves the heights of one running solve
(``solve_polonsky_keer(..., rounds=)``): a round lowers them by ``K (a_new - a)``, whose transform updates the
offset's spectrum and, back in real space, gives the gap of the same pressure on the new heights: one FFT pair a
round and no evaluation. The pressure and the contact set carry over; the conjugacy restarts.
"""

from __future__ import annotations

import numpy as np

from . import sweeps
from ..symmetric.fused import as2d


class Rounds:
    """The ``rounds`` of :func:`contactlib.solvers.symmetric.ccg.solve_polonsky_keer` for a frozen-traction solve.

    Parameters
    ----------
    frozen : contactlib.solvers.adhesive.cohesive_frozen.FrozenTraction
        Judges each round (:meth:`~contactlib.solvers.adhesive.cohesive_frozen.FrozenTraction.judge`), mixes the next
        traction (``frozen.mix``) and keeps the law's traction at the last gap (``frozen.image``).
    a : ndarray
        The frozen traction the solve's heights start from [pressure] (the heights are ``h - K a``).
    load : float or None
        The solve's mean pressure, ``P - mean(a)`` [pressure]; None under displacement control.
    cap : int
        CG iterations a round, unless the solve's residual reaches ``frozen.inner_tol`` first.
    """

    def __init__(self, frozen, a: np.ndarray, load: float | None, cap: int):
        self.frozen, self.cap, self.load = frozen, int(cap), load
        self.a = np.array(a, dtype=float)  # our own: moved in place round by round
        self.total, self.gap = np.empty_like(self.a), np.empty_like(self.a)
        self.start = self.iteration = 0  # the iteration the current round began at, the current one
        self.unloaded = False  # stopped: the adhesive traction alone would carry the load

    def due(self, iteration: int, residual: float) -> bool:
        self.iteration = iteration
        return iteration - self.start >= self.cap or residual <= self.frozen.inner_tol

    def advance(self, q, factor, w, approach, hp, transforms):
        """Judge the state ``(factor q + a, factor w - approach)``; None to stop there, else move the heights to
        the next traction and return ``(mean_pressure, factor)`` of the solve."""
        frozen, a = self.frozen, self.a
        sweeps.frozen_state(q, factor, w, approach, as2d(a), as2d(self.total), as2d(self.gap))
        if not frozen.judge(self.total, self.gap):
            return None
        nxt = frozen.mix(a, frozen.image)
        load = new_factor = None
        if self.load is not None:
            load = frozen.load - float(nxt.mean())
            if load <= 0.0:  # the adhesive traction alone carries the load: no repulsive contact left
                self.unloaded = True
                return None
            new_factor = factor * load / self.load
        np.subtract(nxt, a, out=nxt)  # the change of the traction, which lowers the heights by K of it
        a += nxt
        sweeps.move_heights(w, hp, as2d(transforms.lower_offset(nxt)), factor,
                            factor if new_factor is None else new_factor)
        self.load, self.start = load, self.iteration
        return load, (1.0 if new_factor is None else new_factor)
