"""The memory of a viscoelastic body in time stepping: Prony internal variables, advanced exactly.

A body with relaxation modulus ``E(t) = E0 + sum_i E_i exp(-t / tau_i)`` and a constant Poisson ratio
answers a surface displacement history ``u`` with the pressure

    p(t) = S [ E0 u(t) + sum_i E_i e_i(t) ],    de_i/dt = du/dt - e_i / tau_i,

where ``S`` is the body's surface stiffness at unit modulus (the inverse of its unit compliance ``C1``)
and ``e_i`` the elastic strain of branch ``i``. The state is kept in pressure-like fields that need no
inverse operator (so a zero-padded, non-periodic body works as a periodic one does):

* ``strain = S u``, the displacement as the pressure that would cause it at unit modulus [1];
* ``branch_stress[i] = E_i S e_i``, the stress carried by branch ``i`` [pressure].

**Integration rule.** Over a step ``dt`` the displacement (hence ``strain``) changes at a constant rate.
The branch equation is then integrated exactly::

    branch_stress_i(t + dt) = a_i branch_stress_i(t) + b_i E_i [strain(t + dt) - strain(t)],
    a_i = exp(-dt / tau_i),   b_i = tau_i (1 - a_i) / dt,

so the new pressure is ``p = E_eff strain(t + dt) - g`` with ``E_eff = E0 + sum_i b_i E_i`` and the
history pressure ``g = sum_i (b_i E_i strain(t) - a_i branch_stress_i(t))``: the step is an elastic
contact problem with modulus ``E_eff`` whose displacement is ``C1 (p + g) / E_eff``. The rule is second
order in ``dt`` (the trapezoidal rule's error on a smooth history) and exact for any displacement that
is piecewise linear in time, in particular a fixed one: a contact pressed beyond full contact relaxes
exactly as ``E(t)`` at any step. A step of ``dt = 0`` (``b_i = 1``) is the glassy response ``E_inf``.

The seed's rule (seed 1, eq 4) holds the pressure rate constant instead, with the creep function; it is
exact at fixed pressure on a fixed contact and second order otherwise. The displacement rule is kept
because its exact case is the one the transient tests pin down (full contact, constant penetration).

**Dissipation.** Branch ``i``'s dashpot dissipates twice its stored energy over ``tau_i``, so the power per
unit area is ``sum_i <branch_stress_i, C1 branch_stress_i> / (E_i tau_i) / A``.
"""

from __future__ import annotations

import numpy as np


class PronyHistory:
    """Internal variables of a body on a grid (``material``: :class:`contactlib.Elastic` has none).

    Parameters
    ----------
    material : contactlib.Elastic or contactlib.Viscoelastic
    shape : tuple of int
        The contact grid.
    relaxed_pressure : ndarray, optional
        Start from the body relaxed under this pressure [pressure] (held for ever: every branch
        unloaded); default the undeformed, unloaded body.
    """

    def __init__(self, material, shape, relaxed_pressure=None):
        self.E0 = float(material.E0)
        self.branches = tuple(getattr(material, "prony", ()))
        self.strain = np.zeros(shape) if relaxed_pressure is None else np.asarray(relaxed_pressure, float) / self.E0
        self.branch_stress = [np.zeros(shape) for _ in self.branches]

    def coefficients(self, dt: float) -> tuple[float, np.ndarray, np.ndarray]:
        """``(E_eff, a, b)`` of a step ``dt >= 0`` [time] (module docstring)."""
        taus = np.array([tau for _, tau in self.branches])
        a = np.exp(-dt / taus)
        b = np.ones_like(taus) if dt == 0 else -taus * np.expm1(-dt / taus) / dt
        moduli = np.array([E for E, _ in self.branches])
        return self.E0 + float(np.sum(b * moduli)), a, b

    def history_pressure(self, dt: float) -> np.ndarray | None:
        """``g`` [pressure]: the step's displacement is ``C1 (p + g) / E_eff``; None for an elastic body."""
        if not self.branches:
            return None
        _, a, b = self.coefficients(dt)
        g = np.zeros_like(self.strain)
        for (E, _), ai, bi, stress in zip(self.branches, a, b, self.branch_stress):
            g += bi * E * self.strain - ai * stress
        return g

    def advance(self, dt: float, pressure: np.ndarray, history: np.ndarray | None) -> None:
        """Close the step: ``pressure`` [pressure] is the step's solution, ``history`` its ``g``."""
        E_eff, a, b = self.coefficients(dt)
        strain = (pressure if history is None else pressure + history) / E_eff
        for i, ((E, _), ai, bi) in enumerate(zip(self.branches, a, b)):
            self.branch_stress[i] = ai * self.branch_stress[i] + bi * E * (strain - self.strain)
        self.strain = strain

    def state(self) -> list[np.ndarray]:
        """Copies of the internal variables (``strain`` first, then each branch stress)."""
        return [self.strain.copy()] + [stress.copy() for stress in self.branch_stress]

    def set_state(self, fields: list[np.ndarray]) -> None:
        self.strain, self.branch_stress = fields[0], list(fields[1:])

    def dissipated_power(self, quadratic_form) -> float:
        """Power dissipated per unit area [pressure length/time]: ``quadratic_form(field)`` must return
        ``mean(field * C1 field)`` [pressure length] for the body's unit compliance ``C1``."""
        return float(sum(quadratic_form(stress) / (E * tau)
                         for (E, tau), stress in zip(self.branches, self.branch_stress)))
