"""Materials of the deformable body: :class:`Elastic` and linearly :class:`Viscoelastic` (Prony series).

Both give the same three functions of the uniaxial response, so a solver asks a material, not a type:

* ``relaxation(t)``: the stress under a unit strain step, ``E(t)`` [pressure];
* ``creep(t)``: the strain under a unit stress step, ``J(t)`` [1/pressure] (seed 2, eq 20);
* ``complex_modulus(omega)``: ``E*(omega)`` [pressure] for a strain ``exp(i omega t)``, so the loss
  modulus ``Im E*`` is positive for ``omega > 0`` (the stress leads the strain).

The Poisson ratio is constant in time, so every Green's function of the body is the elastic one at
modulus 1 times the material's compliance (:mod:`contactlib.kernels.viscoelastic`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from ..core.inputs import number


def contact_modulus(E: float, nu: float) -> float:
    """Plane-strain contact modulus ``E* = E / (1 - nu^2)`` of a body against a rigid surface.

    Raises ``ValueError`` naming ``E`` or ``nu`` when outside ``E > 0``, ``-1 < nu <= 0.5``.
    """
    _check_positive(E, "E (Young's modulus)")
    _check_poisson(nu)
    return float(E) / (1.0 - float(nu) ** 2)


def _check_positive(value, name: str) -> None:
    number(name, value, lower=0.0, lower_open=True)


def _check_poisson(nu) -> None:
    number("nu (Poisson ratio)", nu, lower=-1.0, upper=0.5, lower_open=True)


@dataclass(frozen=True)
class Elastic:
    """A linearly elastic body: Young's modulus ``E`` [pressure], Poisson ratio ``nu``.

    Raises ``ValueError`` naming the parameter outside ``E > 0``, ``-1 < nu <= 0.5``.

    Parameters
    ----------
    E : float
        Young's modulus [pressure], > 0.
    nu : float
        Poisson ratio, ``-1 < nu <= 0.5``.

    Raises
    ------
    ValueError
        Naming ``E`` or ``nu`` out of range.

    Examples
    --------
    >>> import contactlib
    >>> contactlib.Elastic(E=2e11, nu=0.3)
    Elastic(E=200000000000.0, nu=0.3)
    """

    E: float
    nu: float

    def __post_init__(self):
        _check_positive(self.E, "E (Young's modulus)")
        _check_poisson(self.nu)

    @property
    def E0(self) -> float:
        """The relaxed modulus (``E``: nothing relaxes)."""
        return float(self.E)

    @property
    def E_inf(self) -> float:
        """The instantaneous modulus (``E``)."""
        return float(self.E)

    def relaxation(self, t):
        """``E(t) = E`` for ``t >= 0`` (0 before) [pressure]."""
        t = np.asarray(t, dtype=float)
        return np.where(t >= 0, float(self.E), 0.0)

    def creep(self, t):
        """``J(t) = 1/E`` for ``t >= 0`` (0 before) [1/pressure]."""
        t = np.asarray(t, dtype=float)
        return np.where(t >= 0, 1.0 / self.E, 0.0)

    def complex_modulus(self, omega):
        """``E`` at every angular frequency [pressure], complex."""
        return np.full(np.shape(omega), complex(self.E))


@dataclass(frozen=True)
class Viscoelastic:
    """A linearly viscoelastic body (generalised Maxwell / Wiechert model).

    ``E(t) = E0 + sum_i E_i exp(-t / tau_i)``: ``E0`` [pressure] is the relaxed (rubbery) modulus,
    ``E_inf = E0 + sum_i E_i`` the glassy (instantaneous) one, ``tau_i`` [time] relaxation times at
    constant strain. ``nu`` is the (constant) Poisson ratio.

    Parameters
    ----------
    E0 : float
        Relaxed modulus, > 0.
    prony : sequence of (E_i, tau_i)
        At least one branch; each ``E_i > 0``, ``tau_i > 0``, finite.
    nu : float
        Poisson ratio in (-1, 0.5].

    Examples
    --------
    >>> m = Viscoelastic.standard_linear_solid(E0=1e7, E_inf=1.1e8, tau=0.1, nu=0.5)
    >>> round(float(m.creep(0.0)) * m.E_inf, 12), round(float(m.creep(1e9)) * m.E0, 12)
    (1.0, 1.0)
    """

    E0: float
    prony: tuple = field(default=())
    nu: float = 0.5

    def __post_init__(self):
        _check_positive(self.E0, "E0 (relaxed modulus)")
        _check_poisson(self.nu)
        try:
            pairs = [tuple(branch) for branch in self.prony]
        except TypeError:
            raise ValueError(f"prony must be a sequence of (E_i, tau_i) pairs, got {self.prony!r}") from None
        if not pairs:
            raise ValueError("prony: the Prony series is empty; give at least one (E_i, tau_i) branch "
                             "(or use contactlib.Elastic)")
        branches = []
        for i, pair in enumerate(pairs):
            if len(pair) != 2:
                raise ValueError(f"prony[{i}] must be a pair (E_i, tau_i), got {pair!r}")
            branches.append((number(f"prony[{i}]: E_i", pair[0], lower=0.0, lower_open=True),
                             number(f"prony[{i}]: tau_i (relaxation time)", pair[1], lower=0.0, lower_open=True)))
        branches = tuple(branches)
        object.__setattr__(self, "prony", branches)

    @classmethod
    def standard_linear_solid(cls, *, E0: float, E_inf: float, tau: float, nu: float) -> Viscoelastic:
        """One Maxwell branch beside a spring: ``E(t) = E0 + (E_inf - E0) exp(-t / tau)``.

        ``tau`` [time] is the relaxation time at constant strain; the creep (retardation) time is
        ``tau E_inf / E0``. Raises ``ValueError`` on ``E_inf <= E0`` or ``tau <= 0``.
        """
        _check_positive(E0, "E0 (relaxed modulus)")
        _check_positive(E_inf, "E_inf (glassy modulus)")
        _check_positive(tau, "tau (relaxation time)")
        if E_inf <= E0:
            raise ValueError(f"E_inf (glassy modulus) must exceed E0 (relaxed modulus): got E_inf = {E_inf!r}, "
                             f"E0 = {E0!r}")
        return cls(E0=E0, prony=((E_inf - E0, tau),), nu=nu)

    @property
    def E_inf(self) -> float:
        """The glassy modulus ``E0 + sum E_i`` [pressure]."""
        return self.E0 + sum(E for E, _ in self.prony)

    @property
    def relaxation_times(self) -> np.ndarray:
        return np.array([tau for _, tau in self.prony])

    def relaxation(self, t):
        """``E(t)`` [pressure] (0 for ``t < 0``)."""
        t = np.asarray(t, dtype=float)
        value = self.E0 + sum(E * np.exp(-np.maximum(t, 0) / tau) for E, tau in self.prony)
        return np.where(t >= 0, value, 0.0)

    def complex_modulus(self, omega):
        """``E*(omega) = E0 + sum_i E_i i omega tau_i / (1 + i omega tau_i)`` [pressure], for a strain
        ``exp(i omega t)``; ``E*(-omega) = conj E*(omega)``."""
        w = np.asarray(omega, dtype=float)
        out = np.full(w.shape, complex(self.E0))
        for E, tau in self.prony:
            iwt = 1j * w * tau
            out = out + E * iwt / (1 + iwt)
        return out

    def retardation(self) -> tuple[np.ndarray, np.ndarray]:
        """The creep spectrum: ``(lambda_j, D_j)`` with ``J(t) = 1/E_inf + sum_j D_j (1 - exp(-t/lambda_j))``.

        The retardation rates ``1/lambda_j`` are the zeros of ``s E(s)`` (Laplace) on the negative axis,
        one below the slowest relaxation rate and one between each pair of consecutive rates; ``D_j > 0``
        is the residue there, so ``sum D_j = 1/E0 - 1/E_inf``.
        """
        taus = np.sort(self.relaxation_times)[::-1]  # slowest first: rates increasing
        rates = 1 / taus

        def carson(r):  # s E(s) at s = -r
            return self.E0 + sum(E * (-r * tau) / (1 - r * tau) for E, tau in self.prony)

        def slope(r):  # d(s E(s))/ds at s = -r
            return sum(E * tau / (1 - r * tau) ** 2 for E, tau in self.prony)

        roots = []
        edges = np.concatenate([[0.0], rates])
        for lo, hi in zip(edges[:-1], edges[1:]):
            if hi <= lo * (1 + 1e-14):  # repeated relaxation times: one retardation time between them
                continue
            eps = (hi - lo) * 1e-14
            roots.append(brentq(carson, lo + (eps if lo > 0 else 0.0), hi - eps, xtol=1e-300, rtol=1e-15,
                                maxiter=500))
        roots = np.array(roots)
        weights = np.array([1 / (r * slope(r)) for r in roots])
        return 1 / roots, weights

    def creep(self, t):
        """``J(t)`` [1/pressure] (seed 2, eq 20): ``1/E_inf`` at ``t = 0+``, ``1/E0`` as ``t -> inf``;
        0 for ``t < 0``."""
        t = np.asarray(t, dtype=float)
        times, weights = self.retardation()
        tt = np.maximum(t, 0)
        value = 1 / self.E_inf + sum(D * -np.expm1(-tt / lam) for lam, D in zip(times, weights))
        return np.where(t >= 0, value, 0.0)

    def creep_rate(self, t):
        """``dJ/dt`` [1/(pressure time)] for ``t > 0``."""
        t = np.asarray(t, dtype=float)
        times, weights = self.retardation()
        return sum(D / lam * np.exp(-np.maximum(t, 0) / lam) for lam, D in zip(times, weights))


Material = Elastic | Viscoelastic


def material_of(material, E, nu) -> Elastic | Viscoelastic:
    """The body of :func:`contactlib.solve`: ``material``, or ``Elastic(E, nu)`` from the shorthand.

    Raises ``ValueError`` when both or neither are given, or ``material`` is not a material.
    """
    if material is None:
        if E is None or nu is None:
            raise ValueError("give the body's material: material=contactlib.Elastic(E, nu) (or Viscoelastic), "
                             "or the elastic shorthand E=, nu=")
        return Elastic(E, nu)
    if E is not None or nu is not None:
        raise ValueError("give material= or E=, nu=, not both")
    if not isinstance(material, (Elastic, Viscoelastic)):
        raise ValueError(f"material must be a contactlib.Elastic or contactlib.Viscoelastic, got {material!r}")
    return material
