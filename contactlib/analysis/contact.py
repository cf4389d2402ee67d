"""Contact area and contact clusters of a pressure field."""

from __future__ import annotations

import math
import numbers

import numpy as np
from scipy import ndimage

from ..inputs import real_values


def _pressure(pressure) -> np.ndarray:
    p = real_values(pressure, "pressure")
    if p.size == 0 or not np.all(np.isfinite(p)):
        raise ValueError("pressure must be a non-empty field of finite values (NaN would count as out of contact)")
    return p


def contact_area_fraction(pressure) -> float:
    """Fraction of elements carrying positive pressure [1]."""
    p = _pressure(pressure)
    return float(np.count_nonzero(p > 0)) / p.size


def contact_clusters(pressure, *, periodic: bool = True, element_area: float = 1.0):
    """Label connected contact patches (4/2-connectivity), merging across periodic edges.

    Returns
    -------
    labels : ndarray of int
        0 outside contact, 1..n for the clusters, numbered in order of first appearance.
    areas : ndarray of float
        Area of each cluster (element count times ``element_area``).
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
