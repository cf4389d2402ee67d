"""The symmetry orbits of the energy method's contact discs (:mod:`contactlib.solvers.adhesive.energy`): the mirrors and
quarter turns of the grid about the apex that map the disc onto itself and leave the compliance unchanged, so the
family is solved with one unknown per orbit (an eighth of the points on a square window, half on a profile)."""

from __future__ import annotations

import numpy as np

from ...core._numba import jit


def _signed_permutations(dim: int) -> list[np.ndarray]:
    """The mirrors and quarter turns of the grid's axes about a point (integer matrices on index offsets)."""
    if dim == 1:
        return [np.array([[1]]), np.array([[-1]])]
    out = []
    for first, second in ((0, 1), (1, 0)):
        for s0 in (1, -1):
            for s1 in (1, -1):
                M = np.zeros((2, 2), dtype=int)
                M[0, first], M[1, second] = s0, s1
                out.append(M)
    return out


def symmetry_orbits(shape: tuple[int, ...], spacing: tuple[float, ...], order: np.ndarray, response: np.ndarray,
                    *, periodic: bool) -> tuple[np.ndarray, np.ndarray]:
    """``order`` regrouped so that each orbit of the problem's symmetries about the highest point is contiguous
    (the nested domains, unions of orbits, keep their elements), and the orbit of each.

    A symmetry is a mirror or quarter turn of the grid about the first element of ``order`` (the apex) that
    maps the elements of ``order`` onto themselves at the same distance (inside a non-periodic window) and
    leaves the compliance unchanged (``response``, the displacement due to a unit load on the work grid,
    compared at every offset between elements: a periodic window of unequal sides, or unequal spacings, has
    no quarter turn). They form a group; each element's orbit is named by its first element in ``order``.
    """
    dim = len(shape)
    dims = np.asarray(shape)[:, None]
    apex = np.array(np.unravel_index(int(order[0]), shape))[:, None]
    k = np.array(np.unravel_index(order, shape)) - apex
    if periodic:
        k = (k + dims // 2) % dims - dims // 2
    position = np.full(int(np.prod(shape)), -1)
    position[order] = np.arange(order.size)
    scale = np.asarray(spacing, dtype=float)[:, None]
    r2 = np.sum((k * scale) ** 2, axis=0)
    reach = 2 * int(np.abs(k).max()) if order.size > 1 else 0
    offsets = np.meshgrid(*[np.arange(-reach, reach + 1)] * dim, indexing="ij")
    work = response.shape

    def compliance(delta):
        return response[tuple(x % n for x, n in zip(delta, work))]

    base = compliance(offsets)
    floor = 1e-10 * float(np.abs(base).max())
    first = np.arange(order.size)
    for M in _signed_permutations(dim):
        image = M @ k
        index = apex + image
        if periodic:
            index = index % dims
        elif np.any((index < 0) | (index >= dims)):
            continue
        at = position[np.ravel_multi_index(tuple(index), shape)]
        if np.any(at < 0) or np.any(np.abs(np.sum((image * scale) ** 2, axis=0) - r2) > 1e-12 * max(r2.max(), 1)):
            continue
        moved = [sum(M[a, b] * offsets[b] for b in range(dim)) for a in range(dim)]
        if float(np.abs(compliance(moved) - base).max()) > floor:
            continue
        first = np.minimum(first, at)
    regroup = np.argsort(first, kind="stable")
    head = first[regroup]
    orbit = np.cumsum(np.r_[True, np.diff(head) > 0]) - 1
    return order[regroup], orbit


@jit
def orbit_compliance(table, heads, index, orbit, starts, counts, out):
    """``out[o, o'] = n_o sum_{j in o'} K[head_o, j]`` for ``o' <= o`` (the factorisation reads one triangle: as a
    Fortran array, the upper), ``K[i, j] = table[i - j]`` on the layout of :func:`energy_family`."""
    for o in range(heads.size):
        head = heads[o]
        row = out[o]
        for j in range(starts[o + 1]):
            row[orbit[j]] += table[head - index[j]]
        for k in range(o + 1):
            row[k] *= counts[o]
