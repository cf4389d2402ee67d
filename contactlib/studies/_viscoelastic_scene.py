"""What the viscoelastic sliding studies share: the material, the scene of seed 2, section 4.1 (an
isotropic self-affine surface sliding on a standard-linear-solid half-space) and their labels.

Reading of the OCR (section 4.1): the window is the punch side ``lambda = L``, roughness from
``q0 = 2 pi / L`` over ``N`` scales to ``q_c = N q0`` (``q_cutoff = N`` in units of ``q0``), ``tau`` the
relaxation time (at constant strain), and the speed is given as ``V tau / lambda`` (``V tau / L``). The
text gives no roughness amplitude for this section: ``rms_slope`` is a constant of the study's config.
"""

from __future__ import annotations

import math

from ..core.labels import attrs_for
from ..model.materials import Viscoelastic, contact_modulus

SCENE_VARIABLES: dict[str, dict[str, str]] = {
    "zeta": {"units": "1", "long_name": "dimensionless sliding speed V tau q0"},
    "glassy_ratio": {"units": "1", "long_name": "E_inf / E0"},
    "friction_coefficient_interlocking": attrs_for("friction_coefficient_interlocking"),
    "dissipated_power": attrs_for("dissipated_power"),
    "outer_iterations": attrs_for("outer_iterations"),
    "viscoelastic_model": {"units": "1", "long_name": "viscoelastic kernel solved (1) or elastic shortcut (0)"},
    "step_mean_pressure": {"units": "Pa", "long_name": "the applied load (mean pressure)"},
}
"""Labels of the names the viscoelastic studies share."""


def material(*, E0: float, glassy_ratio: float, tau: float, nu: float) -> Viscoelastic:
    """The standard linear solid of a study: relaxed modulus ``E0`` [Pa] (the workflow's ``E``),
    ``E_inf = glassy_ratio E0``, relaxation time ``tau`` [s]."""
    return Viscoelastic.standard_linear_solid(E0=E0, E_inf=glassy_ratio * E0, tau=tau, nu=nu)


def relaxed_contact_modulus(m: Viscoelastic) -> float:
    return contact_modulus(m.E0, m.nu)


def speed(zeta: float, *, tau: float, length: float) -> float:
    """``V`` [m/s] of ``zeta = V tau q0`` on a window of ``length`` [m]."""
    return zeta * length / (2 * math.pi * tau)


def model_flag(out) -> float:
    """1.0 where the viscoelastic kernel was solved, 0.0 where the elastic shortcut ran."""
    return float(out.attrs.get("material_model", "").startswith("viscoelastic"))
