"""The ``reciprocating`` study: a 2D rough surface slid back and forth, ``X = A sin(2 pi f t)`` along +x, on a
standard linear solid under a constant load, each frequency run until the cycle repeats
(:func:`contactlib.solve_reciprocating`). Per frequency: the energy dissipated per cycle (and the loop's area,
its independent twin), and the last cycle's hysteresis loop (friction coefficient along +x against position)
and contact area, on ``phase`` (fraction of the cycle).
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from .. import analysis
from ..core.labels import attrs_for
from ..problems.reciprocating import solve_reciprocating
from ._common import rough_surface
from ._viscoelastic_scene import SCENE_VARIABLES, material, relaxed_contact_modulus

VARIABLES: dict[str, dict[str, str]] = {
    **{name: SCENE_VARIABLES[name] for name in ("glassy_ratio", "step_mean_pressure")},
    "frequency": {"units": "s-1", "long_name": "reciprocating frequency f"},
    "phase": {"units": "1", "long_name": "fraction of the cycle"},
    "dissipated_energy_per_cycle": {"units": "Pa m", "long_name": "energy dissipated per unit area per cycle"},
    "friction_work_per_cycle": {"units": "Pa m", "long_name": "loop area: work of the tangential force per cycle"},
    "energy_balance": attrs_for("energy_balance"),  # the library's own label, dimensionless
    "cycles": {"units": "1", "long_name": "cycles run"},
    "settled": {"units": "1", "long_name": "the cycle repeated to cycle_tol (1) or max_cycles was reached (0)"},
    "loop_position": {"units": "1", "long_name": "position over the amplitude X / A"},
    "loop_friction": {"units": "1", "long_name": "friction coefficient along +x over the last cycle"},
    "loop_contact_area": {"units": "1", "long_name": "contact area fraction over the last cycle"},
}


def reciprocating_point(*, frequency: float, glassy_ratio: float, seed: int, n: int, hurst: float, q_low: float,
                        q_roll: float, q_cutoff: float, rms_slope: float, reduced_pressure: float, amplitude: float,
                        steps_per_cycle: int | None, max_cycles: int, cycle_tol: float, E: float, tau: float, nu: float,
                        tol: float, max_iter: int, kernel: str) -> dict:
    """Energy per cycle and the last cycle's loop at ``frequency`` [1/s] (``amplitude`` [m], window 1 m)."""
    h = rough_surface(n=n, hurst=hurst, seed=seed, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff, rms_slope=rms_slope)
    m = material(E0=E, glassy_ratio=glassy_ratio, tau=tau, nu=nu)
    load = reduced_pressure * relaxed_contact_modulus(m) * analysis.rms_slope(h)
    out = solve_reciprocating(h, material=m, amplitude=amplitude, frequency=frequency, mean_pressure=load,
                              steps_per_cycle=None if steps_per_cycle is None else int(steps_per_cycle),
                              max_cycles=int(max_cycles), cycle_tol=cycle_tol, tol=tol, max_iter=max_iter)
    steps = int(out.attrs["steps_per_cycle"])  # None: the library's count by the slide a step
    phase = np.arange(1, steps + 1) / steps

    def loop(values, name):
        return xr.DataArray(np.asarray(values, dtype=float), dims=("phase",), coords={"phase": phase},
                            attrs=VARIABLES[name])

    return {"dissipated_energy_per_cycle": float(out.dissipated_energy_per_cycle),
            "friction_work_per_cycle": float(out.friction_work_per_cycle), "cycles": float(out.attrs["cycles"]),
            "energy_balance": float(out.energy_balance),
            "settled": float(out.attrs["status"] == "settled"),
            "loop_position": loop(out.position_x / amplitude, "loop_position"),
            "loop_friction": loop(out.tangential_force_x / out.mean_pressure, "loop_friction"),
            "loop_contact_area": loop(out.contact_area, "loop_contact_area"), "step_mean_pressure": load,
            "iterations": float(out.iterations.sum()), "residual": float(out.residual.max())}


def reciprocating_shapes(grid: dict, constants: dict) -> list[tuple[int, ...]]:
    return [(constants["n"], constants["n"])]


STUDY = {"point": reciprocating_point, "fft_shapes": reciprocating_shapes, "surface_keys": ("seed",)}
