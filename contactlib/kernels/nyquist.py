"""Kernels with an odd part on the rfft layout: made even on the Nyquist planes, so that mirrors stay mirrors.

On an axis of even length ``n`` the wavenumbers ``+n/2`` and ``-n/2`` are one mode: sampled at the nodes,
``exp(i pi m) = exp(-i pi m) = (-1)^m``. The layout stores it once, at the sign numpy gives it (``-n/2`` on an
``fftfreq`` axis, ``+n/2`` on the ``rfftfreq`` one). A kernel even in that component has one value there; one with
an odd part (the normal-tangential coupling ``c (q . s)/|q|``, the viscoelastic factor at ``q . V``, the in-plane
products ``q_x q_y / |q|^2``, the derivative ``i q . V``) has two, and taking numpy's sign picks one. The mirror
``x -> -x`` maps the Nyquist mode onto itself, so a kernel evaluated at one sign is not the mirror of the kernel
evaluated at the other: a 2D scene mirrored across the sliding direction (or along it, the sliding reversed) then
differed from the mirrored answer by 3-4e-4 of the peak pressure (issue 38, item 4; 2.8-2.9e-4 on the scenes
below). The only value that every mirror maps onto itself is the mean over the two signs,
:func:`even_on_nyquist`: an odd part is zero there (as :func:`contactlib.analysis.directional_slope` zeroes the
derivative), an even part unchanged. In 1D the Nyquist mode is its own conjugate, so the inverse real transform
already dropped the imaginary (odd) part; in 2D the Nyquist row of the ``fftfreq`` axis and column of the
``rfftfreq`` one carry modes that are not, and that is where the mirror broke. The last axis's Nyquist column
holds ``(i, n/2)`` and ``(-i, n/2)``, one mode and its conjugate: made even, the kernel gives them conjugate
values, as a real operator must (taken at numpy's sign it did not, and Douglas-Rachford stagnated at 2e-5 on a
viscoelastic slide off the grid's axes). Odd lengths have no Nyquist mode: nothing changes (the mirrors agreed there
to round-off before).

Measured (128^2, tol 1e-10; a confined layer h = 0.05, nu = 0.3, mu = 0.5, and a standard linear solid E_inf/E0 =
10 at V tau = 0.05): both mirrors from 2.8e-4 of the peak pressure to 2e-15 and 7e-15.

Kernels even in every component (every function of ``|q|``: the frictionless elastic and layer compliances) are
the same either way and are not passed through here: the frictionless path is unchanged, bit for bit.
"""

from __future__ import annotations

import itertools

import numpy as np

from ..core.grid import Grid


def nyquist_axes(grid: Grid) -> tuple[int, ...]:
    """The axes of ``grid`` with a Nyquist mode (even length)."""
    return tuple(axis for axis, n in enumerate(grid.shape) if n % 2 == 0)


def nyquist_planes(grid: Grid) -> np.ndarray:
    """A mask of the rfft layout: True on every Nyquist plane (index ``n // 2`` of an axis of even length)."""
    mask = np.zeros(grid.spectral_shape(), dtype=bool)
    for axis in nyquist_axes(grid):
        mask[tuple(grid.shape[a] // 2 if a == axis else slice(None) for a in range(grid.dim))] = True
    return mask


def even_on_nyquist(grid: Grid, evaluate, values: np.ndarray | None = None) -> np.ndarray:
    """``evaluate(*q)`` on the grid's rfft layout, its value on every Nyquist plane replaced by its mean over the
    signs of the Nyquist components there (module docstring).

    Parameters
    ----------
    grid : Grid
    evaluate : callable
        ``evaluate(*q)`` of the wavevector components [1/length], broadcastable arrays as
        :meth:`Grid.wavevectors` gives them (or slices of them), returns the kernel there (it may return a
        scalar or an array that broadcasts to them).
    values : ndarray, optional
        ``evaluate`` already taken on the whole layout (a compiled pass): only its Nyquist planes are rewritten,
        in place. Without it, the whole layout is evaluated.

    Returns
    -------
    ndarray
        ``values`` (or a new array) of the layout's shape.
    """
    q = grid.wavevectors()
    shape = grid.spectral_shape()
    if values is None:
        values = np.array(np.broadcast_to(evaluate(*q), shape))
    axes = nyquist_axes(grid)
    # single planes first, then their intersections (the corner), each over all signs of its Nyquist components
    for count in range(1, len(axes) + 1):
        for chosen in itertools.combinations(axes, count):
            plane = tuple(slice(grid.shape[a] // 2, grid.shape[a] // 2 + 1) if a in chosen else slice(None)
                          for a in range(grid.dim))
            on_plane = [c[tuple(plane[a] if c.shape[a] > 1 else slice(None) for a in range(grid.dim))] for c in q]
            total = 0.0
            for signs in itertools.product((1.0, -1.0), repeat=count):
                flipped = list(on_plane)
                for a, sign in zip(chosen, signs):
                    flipped[a] = sign * on_plane[a]
                total = total + evaluate(*flipped)
            values[plane] = np.broadcast_to(total / 2**count, values[plane].shape)
    return values


def wavevector_along(grid: Grid, vector) -> np.ndarray:
    """``q . v`` on the rfft layout, even on the Nyquist planes [1/length times v's unit]: the multiplier of the
    derivative ``v . grad`` is ``i q . v`` (an odd kernel; zero along a Nyquist component, as
    :func:`contactlib.analysis.directional_slope` takes it)."""
    components = [float(v) for v in vector]
    return even_on_nyquist(grid, lambda *q: sum(qi * vi for qi, vi in zip(q, components)))


def unit_projections(grid: Grid, names=("x", "y", "xx", "yy", "xy")) -> dict[str, np.ndarray]:
    """The direction cosines of ``n = q/|q|`` and their products on the rfft layout, each even on the Nyquist
    planes (0 at ``q = 0``) [1].

    1D: ``{"x": sgn q}``. 2D: those of ``names`` among ``{"x": n_x, "y": n_y, "xx": n_x^2, "yy": n_y^2, "xy": n_x
    n_y}``: the products are made even themselves (``n_x n_y`` is odd in both components; ``n_x^2`` even,
    unchanged), not formed from the made-even cosines (which would zero ``n_x^2`` on the Nyquist row). Formed on the
    whole layout once, then rewritten on the Nyquist planes alone.
    """
    if grid.dim == 1:
        return {"x": even_on_nyquist(grid, np.sign, np.sign(grid.wavevectors()[0]))}

    def cosines(qx, qy):
        k = np.sqrt(qx**2 + qy**2)
        safe = np.where(k > 0, k, 1.0)
        return np.where(k > 0, qx / safe, 0.0), np.where(k > 0, qy / safe, 0.0)

    products = {"x": lambda a, b: a, "y": lambda a, b: b, "xx": lambda a, b: a * a, "yy": lambda a, b: b * b,
                "xy": lambda a, b: a * b}
    nx, ny = cosines(*grid.wavevectors())
    out = {}
    for name in names:
        form = products[name]
        whole = np.array(np.broadcast_to(form(nx, ny), grid.spectral_shape()))
        out[name] = even_on_nyquist(grid, lambda qx, qy, form=form: form(*cosines(qx, qy)), whole)
    return out
