"""Contact area and contact clusters of a pressure field."""

from __future__ import annotations

import math
import numbers

import numpy as np
from scipy import ndimage

from ..core.inputs import real_values


def _pressure(pressure) -> np.ndarray:
    p = real_values(pressure, "pressure")
    if p.size == 0 or not np.all(np.isfinite(p)):
        raise ValueError("pressure must be a non-empty field of finite values (NaN would count as out of contact)")
    return p


def contact_area_fraction(pressure) -> float:
    """Fraction of elements carrying positive pressure [1].

    Parameters
    ----------
    pressure : xarray.DataArray or ndarray
        Pressure field [pressure].

    Returns
    -------
    float
        The fraction of elements with ``p > 0``.

    Raises
    ------
    ValueError
        For an empty field or one with NaN or infinite values.

    Examples
    --------
    >>> import numpy as np
    >>> from contactlib import analysis
    >>> analysis.contact_area_fraction(np.array([0.0, 1.0, 2.0, 0.0]))
    0.5
    """
    p = _pressure(pressure)
    return float(np.count_nonzero(p > 0)) / p.size


def contact_clusters(pressure, *, periodic: bool = True, element_area: float = 1.0):
    """Label connected contact patches (4/2-connectivity), merging across periodic edges.


    Parameters
    ----------
    pressure : xarray.DataArray or ndarray
        1D or 2D pressure field [pressure].
    periodic : bool
        Merge patches that continue across the window's edges.
    element_area : float
        Area of one element [length^2] (1D: its length).

    Returns
    -------
    labels : ndarray of int
        0 outside contact, 1..n for the clusters, numbered in order of first appearance; on the axes of
        ``pressure`` as given (a DataArray's ``.values``: the labelling does not depend on which axis is x).
    areas : ndarray of float
        Area of each cluster (element count times ``element_area``).

    Raises
    ------
    ValueError
        For an empty field, NaN or infinite values, or ``element_area`` not finite and > 0.
    """
    if isinstance(element_area, bool) or not isinstance(element_area, numbers.Real) \
            or not (math.isfinite(element_area) and element_area > 0):
        raise ValueError(f"element_area must be finite and > 0, got {element_area!r}")
    mask = _pressure(pressure) > 0
    labels, n = ndimage.label(mask)
    if periodic and n > 1:
        parent = np.arange(n + 1)

        def find(a):
            while parent[a] != a:
                parent[a] = parent[parent[a]]
                a = parent[a]
            return a

        for axis in range(mask.ndim):
            first = np.take(labels, 0, axis=axis)
            last = np.take(labels, -1, axis=axis)
            for a, b in zip(np.ravel(first), np.ravel(last)):
                if a and b:
                    ra, rb = find(a), find(b)
                    if ra != rb:
                        parent[max(ra, rb)] = min(ra, rb)
        roots = np.array([find(i) for i in range(n + 1)])
        _, relabel = np.unique(roots, return_inverse=True)
        labels = relabel[labels]
        n = int(relabel.max())
    areas = np.bincount(labels.ravel(), minlength=n + 1)[1:] * element_area
    return labels, areas.astype(float)
