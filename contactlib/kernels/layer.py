"""Surface Green's tensor of an elastic layer of thickness h, relative to the half-space.

A traction ``(p, tau) exp(i q x)`` on the surface of an isotropic layer (plane strain along the
wavevector, Fourier mode ``q > 0``, thickness ``h``, ``X = q h``) gives the surface displacements

    u_z =  Czz p - i c tau,        u_x = i c p + Cxx tau,

with ``u_z`` positive into the body, ``p`` compressive and ``tau`` along ``+x`` (for ``q < 0`` the
coupling ``c`` changes sign: it is odd in ``q``). Each coefficient is the half-space's times a
dimensionless factor of ``X`` returned here:

* ``Czz = 2 / (E* q) * normal(X)``, ``Cxx = 2 / (E* q) * inplane(X)``,
* ``c = 2 / (E* q) * coupling(X)``; the half-space value is ``(1 - 2 nu) / (2 (1 - nu))``
  (Johnson, *Contact Mechanics*, eqs. 2.19-2.20: ``c = (1 - 2 nu)(1 + nu) / (E q)``),
* a shear traction across the wavevector (anti-plane) gives ``u = 2 (1 + nu) / (E q) * antiplane(X)``.

``confined``: the layer is bonded to a rigid base (``u = 0`` at depth ``h``)::

    D       = 5 + 2 X^2 - 4 nu (3 - 2 nu) + (3 - 4 nu) cosh 2X
    normal  = [(3 - 4 nu) sinh 2X - 2X] / D
    inplane = [(3 - 4 nu) sinh 2X + 2X] / D
    coupling = [(1 - 2 nu)(3 - 4 nu)(cosh 2X - 1) - 2 X^2] / (2 (1 - nu) D)
    antiplane = tanh X

These are seed 2's eqs. (15)-(18) (``normal = 1 - A``, ``inplane = 1 - B``, ``coupling =
[(1 - 2 nu) - C] / (2 (1 - nu))``) and Carbone & Mangialardi (2008), eq. (A.30).

``remote_pressure``: the back face is free of traction at every ``q != 0`` (it carries only the
uniform pressure that balances the load)::

    D'      = cosh 2X - 1 - 2 X^2                 (= 2 (sinh X - X)(sinh X + X))
    normal  = [sinh 2X + 2X] / D'                  (-> 6 / X^3: a plate, 1 / (D q^4))
    inplane = [sinh 2X - 2X] / D'
    coupling = [(1 - 2 nu)(cosh 2X - 1) + 2 X^2] / (2 (1 - nu) D')   (-> X / 2 times normal)
    antiplane = coth X

Both were derived from Navier's equations in the layer (general solution ``(a + b z) e^{+-qz}``,
four boundary conditions) and are checked in ``tests/test_layer_kernels.py`` against an
independent transfer-matrix (matrix exponential) solution of the same equations.

Evaluation: ``X <= 1`` in hyperbolic form (the differences ``sinh X - X`` by series, no
cancellation), ``X > 1`` divided through by ``e^{2X}``, so ``X -> infinity`` underflows to the
half-space values instead of overflowing.
"""

from __future__ import annotations

import numpy as np

BASES = ("confined", "remote_pressure")


def _sinh_minus(x: np.ndarray) -> np.ndarray:
    """``sinh x - x`` without cancellation for small ``x`` (series to x^11 below 1)."""
    x2 = x * x
    series = x * x2 / 6 * (1 + x2 / 20 * (1 + x2 / 42 * (1 + x2 / 72 * (1 + x2 / 110))))
    return np.where(np.abs(x) < 1.0, series, np.sinh(x) - x)


def halfspace_factors(nu: float) -> dict[str, float]:
    """The factors of an infinitely thick body: 1, and the material coupling ``(1 - 2 nu) / (2 (1 - nu))``."""
    return {"normal": 1.0, "inplane": 1.0, "coupling": (1 - 2 * nu) / (2 * (1 - nu)), "antiplane": 1.0}


def layer_factors(X: np.ndarray, nu: float, base: str) -> dict[str, np.ndarray]:
    """Dimensionless layer factors ``normal, inplane, coupling, antiplane`` at ``X = |q| h > 0``.

    Parameters
    ----------
    X : ndarray
        ``|q| h`` [1], positive (the ``q = 0`` mode is :func:`zero_mode_compliance`'s).
    nu : float
        Poisson ratio in [0, 0.5].
    base : {"confined", "remote_pressure"}

    Returns
    -------
    dict of ndarray
        Each factor multiplies the half-space coefficient (see the module docstring).
    """
    if base not in BASES:
        raise ValueError(f"base must be one of {BASES}, got {base!r}")
    X = np.asarray(X, dtype=float)
    small = X <= 1.0
    Xs = np.where(small, X, 1.0)  # each branch evaluated where it is accurate and finite
    Xl = np.where(small, 2.0, np.minimum(X, 400.0))  # e^{-800} is 0: the half-space, and X^2 stays finite
    k = 3 - 4 * nu
    if base == "confined":
        s2, c2m1 = np.sinh(2 * Xs), 2 * np.sinh(Xs) ** 2
        D = 5 + 2 * Xs**2 - 4 * nu * (3 - 2 * nu) + k * (c2m1 + 1)
        normal_s = (k * _sinh_minus(2 * Xs) + (k - 1) * 2 * Xs) / D  # k sinh 2X - 2X, both parts >= 0
        inplane_s = (k * s2 + 2 * Xs) / D
        coupling_s = ((1 - 2 * nu) * k * c2m1 - 2 * Xs**2) / (2 * (1 - nu) * D)
        t = np.exp(-2 * Xl)  # the same ratios times 2 e^{-2X}
        Dl = k * (1 + t * t) + 2 * (5 + 2 * Xl**2 - 4 * nu * (3 - 2 * nu)) * t
        normal_l = (k * (1 - t * t) - 4 * Xl * t) / Dl
        inplane_l = (k * (1 - t * t) + 4 * Xl * t) / Dl
        coupling_l = ((1 - 2 * nu) * k * (1 - t) ** 2 - 4 * Xl**2 * t) / (2 * (1 - nu) * Dl)
        antiplane = np.tanh(X)
    else:
        sm = _sinh_minus(Xs)
        D = 2 * sm * (np.sinh(Xs) + Xs)
        normal_s = (np.sinh(2 * Xs) + 2 * Xs) / D
        inplane_s = _sinh_minus(2 * Xs) / D
        coupling_s = ((1 - 2 * nu) * 2 * np.sinh(Xs) ** 2 + 2 * Xs**2) / (2 * (1 - nu) * D)
        t = np.exp(-2 * Xl)
        Dl = (1 - t) ** 2 - 4 * Xl**2 * t
        normal_l = (1 - t * t + 4 * Xl * t) / Dl
        inplane_l = (1 - t * t - 4 * Xl * t) / Dl
        coupling_l = ((1 - 2 * nu) * (1 - t) ** 2 + 4 * Xl**2 * t) / (2 * (1 - nu) * Dl)
        with np.errstate(divide="ignore"):
            antiplane = 1.0 / np.tanh(X)
    return {
        "normal": np.where(small, normal_s, normal_l),
        "inplane": np.where(small, inplane_s, inplane_l),
        "coupling": np.where(small, coupling_s, coupling_l),
        "antiplane": antiplane,
    }


def zero_mode_compliance(thickness: float, E: float, nu: float, base: str) -> dict[str, float]:
    """Surface compliance of the ``q = 0`` mode [length/pressure]: uniform traction on the layer.

    ``confined``: uniaxial strain of the layer on its rigid base, ``u_z = h (1 + nu)(1 - 2 nu) /
    (E (1 - nu)) p`` (0 at ``nu = 0.5``: an incompressible confined layer does not move) and
    ``u_t = 2 (1 + nu) h / E tau``; no coupling. A penetration is then measured from the undeformed
    surface. ``remote_pressure``: the layer is free to translate (a rigid-body mode), so the mean
    displacement is undetermined and set to zero, as for a periodic half-space: penetrations are
    measured against the mean deformed plane.
    """
    if base == "confined":
        return {"normal": thickness * (1 + nu) * (1 - 2 * nu) / (E * (1 - nu)),
                "tangential": 2 * (1 + nu) * thickness / E}
    return {"normal": 0.0, "tangential": 0.0}
