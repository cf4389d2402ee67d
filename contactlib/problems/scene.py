"""A validated scene: everything :func:`contactlib.solve` takes except the load, checked once, on one path.

Every entry point reads its scene here: :func:`contactlib.prepare` (and so :func:`contactlib.solve`,
:func:`contactlib.solve_tolerances`, :func:`contactlib.solve_speeds`, :func:`contactlib.adhesion_curve`) and the
time-stepping drivers (:func:`contactlib.solve_transient`, :func:`contactlib.solve_reciprocating`), which add their
path (times, loads, positions) and never their own copy of these checks. The checks themselves are the vocabulary
of :mod:`contactlib.core.inputs`; each refuses with a ``ValueError`` naming the parameter, before anything is built.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from .. import accuracy
from . import adhesive
from ..model.bodies import Layer
from ..core.grid import Grid
from ..core.inputs import check_iterations, check_tolerance, grid_of, number, periodic_of, real_values
from ..model.materials import Elastic, Viscoelastic, material_of
from ..model.operators import KERNELS

METHODS = ("cg", "active-set")
"""The normal-contact methods a scene may ask for (:func:`contactlib.solve`'s ``method``)."""


@dataclasses.dataclass(frozen=True)
class Scene:
    """A validated scene (:func:`scene_of`): the heights on their grid, the body, the interface, the window and the
    solver options. Read-only; a path driver builds its problem or stepper on it."""

    values: np.ndarray
    """The rigid surface's heights [length] on :attr:`grid` (C-contiguous floats)."""
    grid: Grid
    dims: tuple
    """Dimension names of the solver's arrays, in their index order (``("x",)`` or ``("x", "y")``: ``[ix, iy]``);
    the answer labels a surface's fields on ``("y", "x")`` (:func:`contactlib.core.labels.field_dims`)."""
    coords: dict
    """Coordinates of the fields (the heights' own, or the grid's)."""
    material: Elastic | Viscoelastic
    layer: Layer | None
    periodic: bool
    tol: float
    max_iter: int
    kernel: str
    method: str
    friction: float
    sliding_direction: float
    """Direction [rad] in which the rigid surface moves (a profile: 0 or pi)."""
    velocity: tuple | None
    """Steady sliding velocity, one component per axis [length/time], or None."""
    adhesion: object = None
    target_error: float | None = None
    length_unit: str = "m"
    pressure_unit: str = "Pa"
    heights: object = None
    """The heights as given (a DataArray keeps its coordinates and attrs for a scene at another speed)."""
    length: object = None
    """``length`` as given."""
    sliding_direction_given: float | None = None
    """``sliding_direction`` as given (None: from the velocity), checked again against another speed's velocity."""


def scene_of(heights, *, E=None, nu=None, material=None, periodic=None, tol=None, max_iter=10_000,
             kernel="spectral", method="cg", length=None, target_error=None, layer=None, friction=0.0,
             sliding_direction=None, sliding_velocity=None, adhesion=None, length_unit="m", pressure_unit="Pa",
             default_tol=1e-8) -> Scene:
    """Validate a scene as :func:`contactlib.solve` documents its arguments; ``default_tol`` where ``tol`` and
    ``target_error`` are both None (an adhesive scene's is :data:`contactlib.problems.adhesive.DEFAULT_TOL`)."""
    periodic = periodic_of(heights, periodic)
    material = material_of(material, E, nu)
    values, grid, dims, coords = grid_of(heights, length)
    nu = material.nu
    if adhesion is not None:
        adhesive.check_scene(adhesion, values, spacing=grid.spacing, friction=friction, method=method)
    if target_error is not None:
        if tol is not None:
            raise ValueError("give tol or target_error, not both")
        tol = accuracy.tolerance_for(target_error)
        if periodic:
            accuracy.check_resolution(values, target_error, length=grid.lengths)
    tol = (default_tol if adhesion is None else adhesive.DEFAULT_TOL) if tol is None else tol
    check_tolerance(tol, "tol")
    check_iterations(max_iter)
    if kernel not in KERNELS:
        raise ValueError(f"kernel must be one of {KERNELS}, got {kernel!r}")
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    check_friction(layer, friction, sliding_direction, nu, method, kernel, periodic)
    given_direction = sliding_direction
    velocity, sliding_direction = check_velocity(sliding_velocity, sliding_direction, grid.dim, material, method,
                                                  periodic)
    if grid.dim == 1:
        if abs(math.sin(sliding_direction)) > 1e-4:  # pi to four decimals (3.1416) passes
            raise ValueError(f"sliding_direction must be 0 (+x) or pi (-x) for a profile (1D heights), got "
                             f"{sliding_direction!r}")
        sliding_direction = 0.0 if math.cos(sliding_direction) > 0 else math.pi  # 3.1416 from a command line: pi
    if adhesion is not None and velocity is not None and any(v != 0 for v in velocity):
        raise ValueError(f"sliding_velocity: adhesion is modelled at rest (a steady sliding adhesive contact is not "
                         f"supported), got sliding_velocity={sliding_velocity!r} with adhesion")
    return Scene(values, grid, dims, coords, material, layer, periodic, tol, int(max_iter), kernel, method,
                 float(friction), float(sliding_direction), velocity, adhesion,
                 None if target_error is None else float(target_error), length_unit, pressure_unit, heights, length,
                 given_direction)


def check_friction(layer, friction, sliding_direction, nu, method, kernel, periodic) -> None:
    """The scene's body and interface: refused with the parameter named, before anything is built."""
    sliding_direction = 0.0 if sliding_direction is None else sliding_direction
    if layer is not None:
        if not isinstance(layer, Layer):
            raise ValueError(f"layer must be a contactlib.Layer or None, got {layer!r}")
        if not 0.0 <= nu <= 0.5:
            raise ValueError(f"nu (Poisson ratio) must lie in [0, 0.5] for a layer, got {nu!r}")
        if not periodic and layer.base != "confined":
            raise ValueError(f"layer: a {layer.base!r} layer bends over the whole window (a plate), which a "
                             "non-periodic window cuts off: it is modelled on a periodic window only (periodic=True)")
    number("friction (Coulomb coefficient)", friction, lower=0.0)
    number("sliding_direction (angle [rad])", sliding_direction)
    if method == "active-set" and (layer is not None or friction > 0):
        raise ValueError("method='active-set' solves frictionless half-space contact only: use method='cg' "
                         "with a layer or friction")
    if kernel == "love" and (layer is not None or friction > 0):
        raise ValueError("kernel='love' is a half-space, frictionless kernel: use kernel='spectral' with a layer "
                         "or friction")


def check_velocity(sliding_velocity, sliding_direction, dim, material, method, periodic):
    """``(velocity, direction)``: the validated velocity (a tuple per axis, or None) and the sliding
    direction it sets; contradictions and unsupported scenes refused with the parameter named."""
    if sliding_velocity is None:
        return None, 0.0 if sliding_direction is None else sliding_direction
    velocity = np.atleast_1d(real_values(sliding_velocity, "sliding_velocity"))
    if velocity.shape != (dim,):
        raise ValueError(f"sliding_velocity must have {dim} component(s) (one per axis of the heights), "
                         f"got {sliding_velocity!r}")
    if not np.all(np.isfinite(velocity)):
        raise ValueError(f"sliding_velocity must be finite, got {sliding_velocity!r}")
    speed = float(np.hypot(*velocity)) if dim == 2 else abs(float(velocity[0]))
    direction = float(np.arctan2(velocity[-1], velocity[0])) if dim == 2 else (0.0 if velocity[0] >= 0 else np.pi)
    if speed == 0:
        direction = 0.0 if sliding_direction is None else sliding_direction
    elif sliding_direction is not None and not np.isclose(np.cos(sliding_direction - direction), 1.0, atol=1e-12):
        raise ValueError(f"sliding_direction {sliding_direction!r} contradicts sliding_velocity {sliding_velocity!r} "
                         f"(direction {direction:.6g} rad): give one of them")
    if isinstance(material, Viscoelastic) and speed > 0:
        if method == "active-set":
            raise ValueError("method='active-set' solves symmetric (elastic) problems only; a viscoelastic body in "
                             "steady sliding needs method='cg'")
        if not periodic:
            raise ValueError("sliding_velocity: steady viscoelastic sliding is modelled on a periodic window "
                             "(periodic=True); enlarge the window around an isolated indenter")
    return tuple(float(v) for v in velocity), direction
