"""Solving to a target contact area: ``solve(heights, ..., contact_area=A)``.

The contact area of a frictionless elastic (or steadily sliding) contact grows monotonically with the load, but on a
grid it is a count of elements: it rises in steps, as whole cells (a ring of them on a sphere) enter the contact. So
the load that gives an area is a bracket, not a root: :func:`run` brackets the target's element count by doubling or
halving the mean pressure from a first guess (Bush-Gibson-Thomas / Persson: ``A = 2 p / (E* h'_rms)``, so
``p = A E* h'_rms / 2``), then bisects the bracket in ``log p`` until it holds the target count, or until its two
loads are :data:`LOAD_RESOLUTION` apart (the count jumps over the target there: the grid's resolution in area). It
returns the state whose area is nearest the target. Every solve reuses one validated scene (its operators are built
once) and starts warm from the nearest solved state scaled to the new load.
"""

from __future__ import annotations

import math

import numpy as np

from ..core.inputs import real_values

LOAD_RESOLUTION = 1e-4
"""Relative width of the load bracket at which the search stops: the target area lies inside one jump of the count."""

MAX_SOLVES = 80
"""Bound on the solves of one search (doubling from the first guess covers 2^40 in load; the bisection ~14 more)."""


def check(contact_area, *, mean_pressure, penetration, adhesion) -> float:
    """Validate ``contact_area`` against the other load arguments of :func:`contactlib.solve`.

    Parameters
    ----------
    contact_area : float
        Target contact area fraction, in (0, 1).
    mean_pressure, penetration : float or None
        The load arguments of :func:`contactlib.solve`; both must be None (the area replaces the load).
    adhesion : contactlib.Adhesion or None
        Must be None: an adhesive contact's area is not monotone in the load.

    Returns
    -------
    float
        A provisional mean pressure (1.0) with which the scene is validated and built; :func:`search` replaces it.

    Raises
    ------
    ValueError
        Naming ``contact_area`` when it is not a number in (0, 1), or given with a load or with adhesion.
    """
    area = float(real_values(contact_area, "contact_area"))
    if not 0.0 < area < 1.0:
        raise ValueError(f"contact_area must be a fraction in (0, 1), got {contact_area!r}")
    if mean_pressure is not None or penetration is not None:
        raise ValueError("contact_area replaces the load: give contact_area or mean_pressure or penetration, "
                         "not several")
    if adhesion is not None:
        raise ValueError("contact_area: an adhesive contact's area is not monotone in the load (it jumps in and out "
                         "of contact); use contactlib.adhesion_curve and pick the state")
    return 1.0


def first_load(problem, contact_area: float) -> float:
    """The linear (Bush-Gibson-Thomas / Persson) load of ``contact_area``: ``A E* h'_rms / 2``."""
    slopes = np.gradient(problem.values, *problem.grid.spacing) if problem.grid.dim > 1 else \
        [np.gradient(problem.values, problem.grid.spacing[0])]
    rms_slope = math.sqrt(sum(float(np.mean(s**2)) for s in slopes))
    return contact_area * problem.attrs["E_star"] * max(rms_slope, 1e-12) / 2.0


def search(problem, contact_area: float):
    """The converged state of ``problem`` (a :class:`contactlib.Problem`, no adhesion) whose contact area is nearest
    ``contact_area``, under load control.

    Parameters
    ----------
    problem : contactlib.Problem
        The prepared scene; it is not changed.
    contact_area : float
        Target contact area fraction, in (0, 1).

    Returns
    -------
    loaded : contactlib.Problem
        The problem at the load found; its ``attrs`` gain ``target_contact_area`` and ``area_target_solves``.
    state : contactlib.solvers.ContactState
        The state nearest the target.

    Raises
    ------
    contactlib.ConvergenceError
        Where a solve of the search does not converge (from :meth:`contactlib.Problem.check`, with its partial state).
    ValueError
        Naming ``contact_area`` when no load reaches it (the count jumps from below it to above it at a single load,
        e.g. a flat-topped surface, or the target is below one grid element).
    """
    size = problem.values.size
    target = contact_area * size
    solved = {}  # load -> state

    def count_at(load):
        warm = min(solved, key=lambda p: abs(math.log(p / load)), default=None)
        loaded = problem.loaded(mean_pressure=load,
                                initial_pressure=None if warm is None else solved[warm].pressure * (load / warm))
        state = loaded.run()
        if not state.converged:
            loaded.check(state, loaded.label(state, 0.0))  # raises, with its state
        solved[load] = state
        return np.count_nonzero(state.pressure > 0)

    low = high = first_load(problem, contact_area)
    if count_at(low) < target:
        while count_of(solved, high) < target and len(solved) < MAX_SOLVES // 2:
            low, high = high, high * 2.0
            count_at(high)
    else:
        while count_of(solved, low) >= target and len(solved) < MAX_SOLVES // 2:
            high, low = low, low / 2.0
            count_at(low)
    if not count_of(solved, low) < target <= count_of(solved, high):
        raise ValueError(f"contact_area={contact_area!r}: no load found whose contact area brackets it (the area "
                         f"went from {count_of(solved, low) / size:.4g} to {count_of(solved, high) / size:.4g})")
    while high / low - 1.0 > LOAD_RESOLUTION and len(solved) < MAX_SOLVES:
        if min(abs(count_of(solved, p) - target) for p in (low, high)) <= 0.5:  # the nearest count is reached
            break
        middle = math.sqrt(low * high)
        if count_at(middle) < target:
            low = middle
        else:
            high = middle
    best = min((low, high), key=lambda p: abs(count_of(solved, p) - target))
    loaded = problem.loaded(mean_pressure=best)
    loaded.attrs.update(target_contact_area=contact_area, area_target_solves=len(solved))
    return loaded, solved[best]


def count_of(solved: dict, load: float) -> int:
    """Number of elements in contact in the solved state at ``load``."""
    return int(np.count_nonzero(solved[load].pressure > 0))
