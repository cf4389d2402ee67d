"""Material parameters and their validation."""

from __future__ import annotations

import math


def contact_modulus(E: float, nu: float) -> float:
    """Plane-strain contact modulus ``E* = E / (1 - nu^2)`` of a body against a rigid surface.

    Raises ``ValueError`` naming ``E`` or ``nu`` when outside ``E > 0``, ``-1 < nu <= 0.5``.
    """
    if not isinstance(E, (int, float)) or not math.isfinite(E) or E <= 0:
        raise ValueError(f"E (Young's modulus) must be a finite number > 0, got {E!r}")
    if not isinstance(nu, (int, float)) or not math.isfinite(nu) or not (-1.0 < nu <= 0.5):
        raise ValueError(f"nu (Poisson ratio) must lie in (-1, 0.5], got {nu!r}")
    return float(E) / (1.0 - float(nu) ** 2)
