"""An independent reference for contact on any (non-symmetric) dense influence matrix: primal-dual active sets
with a direct (LU) solve on each set, under load control."""

import numpy as np


def dense_load_control(M, hp, mean_pressure, active, max_sets=300):
    """``p >= 0``, ``g = M p - hp - d >= 0``, ``p g = 0`` with ``mean(p)`` fixed (the approach ``d`` its
    multiplier), from the contact set ``active``; ``hp`` the flat heights measured down from their top.
    Returns the pressure, or None if the sets cycle."""
    n = hp.size
    for _ in range(max_sets):
        idx = np.flatnonzero(active)
        system = np.zeros((idx.size + 1, idx.size + 1))
        system[:-1, :-1] = M[np.ix_(idx, idx)]
        system[:-1, -1], system[-1, :-1] = -1.0, 1.0
        solution = np.linalg.solve(system, np.append(hp[idx], n * mean_pressure))
        p = np.zeros(n)
        p[idx] = solution[:-1]
        gap = M @ p - hp - solution[-1]
        following = np.where(active, p > 0, gap < 0)
        if np.array_equal(following, active):
            return p
        active = following
    return None
