"""The resolution guard: every entry point measures its own grid resolution and warns where it is coarse.

Three measures, each with a rule measured against a known answer (``error = constant * resolution**-order``,
the fit itself, not a bound; :func:`predicted_error` takes the larger of the contact-area and pressure errors):

* ``points_per_wavelength``, a periodic surface: grid points per shortest wavelength of its heights' spectrum
  (:func:`contactlib.accuracy.grid_points_per_wavelength`); rule :data:`contactlib.accuracy.ROUGH_FITS`
  without its safety factor (self-affine surfaces; 1 % asks 62 points on the contact area, 40 on the pressure).
  Where the spectrum reaches the grid's Nyquist wavenumber (not band-limited: a periodic lattice of caps, a
  measured surface), the contact's patches decide instead (below, :func:`of_scene`).
* ``points_per_contact_radius``, an isolated contact (``periodic=False``): the typical radius of the solved
  contact's patches, ``2 A / P`` (area over perimeter, the radius of a disc), in grid spacings
  (:func:`points_per_contact_radius`); rule :data:`CONTACT_FITS` (Hertz's sphere; 1 % asks 25.5).
* ``process_zone_elements``, a cohesive law: grid elements across its process zone
  ``pi E* w / (4 sigma_0^2)`` (:func:`contactlib.model.adhesion.process_zone_length`); rule :data:`COHESIVE_FITS`
  (a Maugis sphere: 1 % asks 4.5 elements; exponential law 1.3), besides the contact's own measure.

Where the prediction exceeds :data:`THRESHOLD` (1 %), the call warns once with :class:`ResolutionWarning` (an
:class:`contactlib.accuracy.AccuracyWarning`), saying what it measured, the predicted error and what to change.
``target_error=`` asks for a guarantee instead: :func:`contactlib.solve` then checks the rule's safer bound against
that target (:func:`contactlib.accuracy.check_resolution`) and this guard only records. Every answer records in its
``attrs`` the measures (``points_per_wavelength``, ``points_per_contact_radius``, ``process_zone_elements``),
``predicted_resolution_error`` and ``resolution_rule`` (the measure that set the prediction).

A sweep of many solves records the prediction as data instead of printing a warning per point:
``with recording() as seen: ...`` keeps the warnings inside and lists every :class:`Resolution` measured;
:func:`contactlib.pipeline.sweep.evaluate_point` stores the largest as the point's ``predicted_resolution_error``, and
:func:`contactlib.pipeline.sweep.run_grid` logs one line for the whole sweep.
"""

from __future__ import annotations

import contextlib
import contextvars
import dataclasses
import math
import warnings

import numpy as np

from .accuracy import ROUGH_FITS, SAFETY, AccuracyWarning, grid_points_per_wavelength
from .model.adhesion import process_zone_length

THRESHOLD = 0.01
"""Predicted relative error (contact area or pressure) above which an entry point warns."""

CONTACT_FITS = {
    "contact_area": {"order": 1.353, "constant": 0.2573},
    "pressure": {"order": 0.779, "constant": 0.1249},
}
"""Measured ``error = constant * (points per contact radius)**-order`` of Hertz's sphere against
:mod:`contactlib.reference.hertz`: ``paraboloid(n, length=1, radius=1)``, ``E = 1, nu = 0.3``, non-periodic,
load control at tol 1e-10, ``n`` = 128 and 256, Hertz radius 3-77 spacings (38 solves, 2026-11-27), against the
guard's own measure (:func:`points_per_contact_radius` of the solved contact, 0.87-1.16x Hertz's radius over
it). Contact area: ``|A / (pi a^2) - 1|``, order 1.35, constant 0.257 (it jumps node by node: single solves up to
3.9x the fit); pressure: relative L2 error against Hertz's field at the nodes, order 0.78, constant 0.125 (at most
1.4x the fit). 1 % asks 11 spacings per radius on the area, 25.5 on the pressure. A cylinder (1D, half-width 2-300
spacings on 1024 points) erred less: 0.5 % area and 0.65 % pressure at 38 spacings."""

COHESIVE_FITS = {
    "maugis": {"mean_pressure": {"order": 1.929, "constant": 0.1815}},
    "exponential": {"mean_pressure": {"order": 2.516, "constant": 0.01823}},
}
"""Measured ``error = constant * (process zone elements)**-order`` of the load of a cohesive sphere at a fixed
approach, per law: ``paraboloid(n, length=1, radius=1)``, ``E = 1, nu = 0.3``, ``w = 1e-4``, non-periodic,
penetration 5e-4, tol 1e-8, ``n`` = 24-512 on the one window (2026-11-27). Maugis (range 2e-3, lambda = 1.1,
process zone ``pi E* w / (4 sigma_0^2)`` = 0.83-17.7 elements), against ``n`` = 768 (26.5 elements; 512 agrees to
3e-5): order 1.93, constant 0.18 over 1.66-13.3 elements (single solves up to 3.2x the fit: 12.5 % at 2.2
elements, 1.0-1.2 % at 3.3-4.4, 0.2-0.4 % at 6.6-8.8); 1 % asks 4.5 elements. Exponential (range 1e-3, 0.28-4.4
elements, against ``n`` = 512): order 2.52, constant 0.018 over 0.83-3.3 elements (1.6 % at 1.1, 0.2 % at 2.2);
1 % asks 1.3. The errors include the contact's own discretisation; its measure (:data:`CONTACT_FITS`, on the
repulsive area) applies besides, and the larger prediction speaks."""

MEASURES = ("points_per_wavelength", "points_per_contact_radius", "process_zone_elements")


class ResolutionWarning(AccuracyWarning):
    """The grid is coarser than the measured error rules ask for :data:`THRESHOLD` (1 %) in the contact area or
    pressure. ``measure``, ``value`` and ``predicted_error`` carry the numbers of the message.

    Parameters
    ----------
    message : str
        What was measured, the predicted error and what to change.
    resolution : Resolution, optional
        The measure behind the message.

    Attributes
    ----------
    resolution : Resolution or None
        The measure behind the message.
    measure : str or None
        Its name.
    value : float
        Its value (NaN without a measure).
    predicted_error : float
        The predicted relative error (NaN without a measure).
    """

    def __init__(self, message: str, resolution: "Resolution | None" = None):
        super().__init__(message)
        self.resolution = resolution
        self.measure = None if resolution is None else resolution.measure
        self.value = math.nan if resolution is None else resolution.value
        self.predicted_error = math.nan if resolution is None else resolution.predicted_error


@dataclasses.dataclass(frozen=True)
class Resolution:
    """One measured resolution: ``measure`` (one of :data:`MEASURES`), its ``value`` and the rules'
    ``predicted_error`` (relative, the larger of contact area and pressure), the grid side ``n`` it was
    measured on and the cohesive ``law`` (for the advice).

    Attributes
    ----------
    measure : str
        One of :data:`MEASURES`.
    value : float
        The measured resolution.
    predicted_error : float
        The rule's predicted relative error.
    n : int
        The grid side it was measured on.
    law : str, optional
        A cohesive law's name (:data:`COHESIVE_FITS`) for ``process_zone_elements``.
    """

    measure: str
    value: float
    predicted_error: float
    n: int = 0
    law: str | None = None


# --- the rules ---------------------------------------------------------------------------------------


def _rule(fits: dict, value: float) -> float:
    if not value > 0:
        return math.inf
    if math.isinf(value):
        return 0.0
    return max(f["constant"] * value ** -f["order"] for f in fits.values())


def _needed(fits: dict, target: float = THRESHOLD) -> float:
    """The resolution at which every fit of ``fits`` predicts ``target``."""
    return max((f["constant"] / target) ** (1.0 / f["order"]) for f in fits.values())


def _rough_fits() -> dict:
    """:data:`contactlib.accuracy.ROUGH_FITS` against the continuum (without the safety factor)."""
    return {k: {"order": f["order"], "constant": f["constant"] / SAFETY} for k, f in ROUGH_FITS.items()}


FITS = {"points_per_wavelength": _rough_fits, "points_per_contact_radius": lambda: CONTACT_FITS,
        "process_zone_elements": lambda: COHESIVE_FITS["maugis"]}
"""The rule of each measure; a cohesive law's own (:data:`COHESIVE_FITS`) where it has one, the Maugis law's (the
stricter) otherwise."""


def _fits(measure: str, law: str | None = None) -> dict:
    if measure not in FITS:
        raise ValueError(f"measure must be one of {MEASURES}, got {measure!r}")
    if measure == "process_zone_elements" and law in COHESIVE_FITS:
        return COHESIVE_FITS[law]
    return FITS[measure]()


def predicted_error(measure: str, value: float, *, law: str | None = None) -> float:
    """Relative error (the larger of contact area and pressure) the rule of ``measure`` predicts at ``value``.


    Parameters
    ----------
    measure : str
        One of :data:`MEASURES`.
    value : float
        The measured resolution, > 0.
    law : str, optional
        A cohesive law's name (:data:`COHESIVE_FITS`) for ``process_zone_elements``.


    Returns
    -------
    float
        The predicted relative error.


    Raises
    ------
    ValueError
        Naming ``measure`` (not one of :data:`MEASURES`) or ``law`` (unknown).

    Examples
    --------
    >>> from contactlib import resolution
    >>> round(resolution.predicted_error("points_per_wavelength", 4.0), 3)   # q_cutoff 64 on 256 points
    0.153
    """
    return float(_rule(_fits(measure, law), float(value)))


def needed_resolution(measure: str, target: float = THRESHOLD, *, law: str | None = None) -> float:
    """The value of ``measure`` at which its rule predicts ``target`` (default :data:`THRESHOLD`); ``law``: a
    cohesive law's name (:data:`COHESIVE_FITS`).

    Parameters
    ----------
    measure : str
        One of :data:`MEASURES`.
    target : float
        The relative error asked.
    law : str, optional
        A cohesive law's name (:data:`COHESIVE_FITS`) for ``process_zone_elements``.

    Returns
    -------
    float
        The resolution the rule asks.
    """
    return float(_needed(_fits(measure, law), target))


# --- the measures ------------------------------------------------------------------------------------


def points_per_contact_radius(contact: np.ndarray, *, periodic: bool = False) -> float:
    """Typical radius of the contact patches of the boolean field ``contact``, in grid spacings: ``2 A / P``.

    ``A`` is the number of contact nodes and ``P`` the patches' perimeter in spacings: the node faces between
    contact and no contact (outside the array counts as no contact; ``periodic``: the array wraps), times pi / 4
    in 2D (a staircase around a disc is 4 / pi times its perimeter), so a disc of radius ``a`` spacings reads
    about ``a`` (2.6 at 3, 19.5 at 20: the staircase's corners); 1D: the half-width of the patches. ``inf`` in full
    contact, NaN with no contact. :data:`CONTACT_FITS` is measured against this measure.


    Parameters
    ----------
    contact : ndarray of bool
        The closed nodes, 1D or 2D.
    periodic : bool
        Whether the array wraps.


    Returns
    -------
    float
        ``2 A / P`` in grid spacings (inf for full contact, 0 for none).

    Examples
    --------
    >>> import numpy as np
    >>> x = np.arange(-50, 51)
    >>> disc = x[:, None] ** 2 + x[None, :] ** 2 <= 20.0 ** 2
    >>> round(points_per_contact_radius(disc), 1)
    19.5
    """
    c = np.asarray(contact, dtype=bool)
    nodes = int(c.sum())
    if nodes == 0:
        return math.nan
    if periodic:
        faces = sum(int(np.count_nonzero(c != np.roll(c, 1, axis=a))) for a in range(c.ndim))
    else:
        padded = np.pad(c, 1).astype(np.int8)
        faces = sum(int(np.abs(np.diff(padded, axis=a)).sum()) for a in range(c.ndim))
    if faces == 0:
        return math.inf
    perimeter = faces * (math.pi / 4 if c.ndim == 2 else 1.0)
    return float(c.ndim * nodes / perimeter)


def of_spectrum(values: np.ndarray, lengths) -> Resolution:
    """The periodic surface's points per shortest wavelength and the rough rule's prediction.

    Parameters
    ----------
    values : ndarray
        Periodic heights [length].
    lengths : sequence of float
        Window size per axis [length].

    Returns
    -------
    Resolution
        Points per shortest wavelength and its prediction.
    """
    ppw = grid_points_per_wavelength(values, length=list(lengths))
    return Resolution("points_per_wavelength", ppw, predicted_error("points_per_wavelength", ppw), max(values.shape))


def of_contact(contact: np.ndarray, *, periodic: bool = False) -> Resolution | None:
    """A contact's points per contact radius and the Hertz rule's prediction (None: no contact).

    Parameters
    ----------
    contact : ndarray of bool
        The closed nodes.
    periodic : bool
        Whether the array wraps.

    Returns
    -------
    Resolution or None
        The contact's measure, None without contact.
    """
    value = points_per_contact_radius(contact, periodic=periodic)
    if math.isnan(value):
        return None
    return Resolution("points_per_contact_radius", value, predicted_error("points_per_contact_radius", value),
                      max(np.shape(contact)))


def of_process_zone(elements: float, n: int, law: str | None = None) -> Resolution:
    """A cohesive law's process zone in grid elements and the cohesive rule's prediction.

    Parameters
    ----------
    elements : float
        Grid elements across the process zone.
    n : int
        The grid side.
    law : str, optional
        A cohesive law's name (:data:`COHESIVE_FITS`) for ``process_zone_elements``.

    Returns
    -------
    Resolution
        The process zone's measure.
    """
    return Resolution("process_zone_elements", float(elements),
                      predicted_error("process_zone_elements", elements, law=law), n, law)


NYQUIST_POINTS = 2.0
"""Points per shortest wavelength of a spectrum that reaches the grid's Nyquist wavenumber: it is not band-limited,
and says nothing of how well the grid resolves the surface."""


def of_scene(values: np.ndarray, lengths, *, periodic: bool, contact: np.ndarray | None,
             zone_elements: float | None = None, law: str | None = None) -> list[Resolution]:
    """Every measure that applies to a solved scene, the first entry the one that sets the contact's prediction,
    then the process zone of a cohesive law (``zone_elements``, its ``law``).

    Non-periodic: the ``contact`` (boolean field of the closed nodes). Periodic: the heights' spectrum, and the
    contact's patches (recorded too). The spectrum decides, unless it reaches the Nyquist wavenumber
    (:data:`NYQUIST_POINTS`): a surface that is not band-limited, such as a smooth periodic indenter whose kink at
    the window edge fills the spectrum (a lattice of caps), or a measured surface; the patches then decide. On
    self-affine surfaces at 4-64 points per wavelength the two predictions agree within a factor 2.3 (the patches'
    0.7-1.5x the spectrum's). In full contact the area is exact and a band-limited surface's pressure too, and with
    no contact there is nothing to resolve: the prediction is then 0.

    Parameters
    ----------
    values : ndarray
        The heights [length].
    lengths : sequence of float
        Window size per axis [length].
    periodic : bool
        Periodic window or isolated footprint.
    contact : ndarray of bool or None
        The closed nodes of the solved state.
    zone_elements : float, optional
        A cohesive law's process zone in elements.
    law : str, optional
        A cohesive law's name (:data:`COHESIVE_FITS`) for ``process_zone_elements``.

    Returns
    -------
    list of Resolution
        Every measure that applies, the deciding one first.
    """
    out = []
    closed = None if contact is None else np.asarray(contact, dtype=bool)
    if periodic:
        found = [of_spectrum(values, lengths)]
        patches = None if closed is None else of_contact(closed, periodic=True)
        if patches is not None and math.isfinite(patches.value):
            found.append(patches)
            if found[0].value <= NYQUIST_POINTS:
                found.reverse()
        if closed is not None and (closed.all() or not closed.any()):
            found[0] = dataclasses.replace(found[0], predicted_error=0.0)
        out.extend(found)
    elif closed is not None:
        r = of_contact(closed)
        if r is not None:
            out.append(r)
    if zone_elements is not None and math.isfinite(zone_elements):
        out.append(of_process_zone(zone_elements, max(np.shape(values)), law))
    return out


# --- reporting ---------------------------------------------------------------------------------------

_RECORDER: contextvars.ContextVar = contextvars.ContextVar("contactlib_resolution_recorder", default=None)


@contextlib.contextmanager
def recording():
    """Collect the resolutions that the entry points called inside measure, instead of warning.

    Yields the list they are appended to (one :class:`Resolution` per call, its worst measure). Nested: the
    innermost collects.


    Yields
    ------
    list of Resolution
        The resolutions measured inside the block.

    Examples
    --------
    >>> import contactlib
    >>> h = contactlib.surfaces.self_affine(64, hurst=0.8, q_roll=2, q_cutoff=16, rms_slope=0.1, seed=1)
    >>> with contactlib.resolution.recording() as seen:
    ...     out = contactlib.solve(h, E=1.0, nu=0.5, mean_pressure=0.01)
    >>> seen[0].measure, seen[0].value
    ('points_per_wavelength', 4.0)
    """
    seen: list[Resolution] = []
    token = _RECORDER.set(seen)
    try:
        yield seen
    finally:
        _RECORDER.reset(token)


def worst(resolutions) -> Resolution | None:
    """The resolution with the largest predicted error (None for none).

    Parameters
    ----------
    resolutions : iterable of Resolution or None
        Measures (None entries are skipped).

    Returns
    -------
    Resolution or None
        The worst measure (None: nothing measured).
    """
    resolutions = [r for r in resolutions if r is not None]
    return max(resolutions, key=lambda r: r.predicted_error) if resolutions else None


def _deciding(resolutions) -> list[Resolution]:
    """The measures that decide: the first of the contact's (:func:`of_scene` puts it first) and the zone's."""
    contact = [r for r in resolutions if r.measure != "process_zone_elements"][:1]
    return contact + [r for r in resolutions if r.measure == "process_zone_elements"]


def record(attrs: dict, resolutions) -> Resolution | None:
    """Write the measures and the deciding prediction into ``attrs`` (in place); return it.

    Parameters
    ----------
    attrs : dict
        An answer's attributes, updated in place.
    resolutions : iterable of Resolution
        The measures.

    Returns
    -------
    Resolution or None
        The worst measure (None: nothing measured).
    """
    for r in resolutions:
        attrs[r.measure] = r.value
    w = worst(_deciding(resolutions))
    if w is not None:
        attrs["predicted_resolution_error"] = w.predicted_error
        attrs["resolution_rule"] = w.measure
    return w


def _advice(r: Resolution) -> str:
    need = needed_resolution(r.measure, law=r.law)
    factor = need / r.value if r.value > 0 else math.inf
    n = int(2 * math.ceil(r.n * factor / 2)) if r.n and math.isfinite(factor) else None
    if n and r.measure == "points_per_wavelength":
        n = 2 ** math.ceil(math.log2(n))
    grid = f"a grid of n >= {n} points per side over the same window" if n else "a finer grid"
    if r.measure == "points_per_wavelength":
        return (f"it asks {need:.3g}: generate the surface at n >= {n} with the same q_cutoff, or resample it "
                f"(contactlib.surfaces.resample(heights, {n}) keeps its modes)" if n else f"it asks {need:.3g}")
    if r.measure == "points_per_contact_radius":
        return f"it asks {need:.3g}: {grid}, or a larger load (a wider contact)"
    return f"it asks {need:.3g}: {grid}, or a longer range of the law (a wider zone)"


NAMES = {"points_per_wavelength": "grid points per shortest wavelength of the heights",
         "points_per_contact_radius": "grid spacings per contact radius",
         "process_zone_elements": "grid elements across the cohesive process zone"}


def report(resolutions, *, where: str, guarantee: bool = False, stacklevel: int = 3) -> Resolution | None:
    """Warn once (:class:`ResolutionWarning`) if the worst of ``resolutions`` predicts more than :data:`THRESHOLD`;
    inside :func:`recording`, list it there instead. ``guarantee``: the caller gave ``target_error``, which
    checked its own bound: nothing more is said. Returns the worst (of the measures that decide, as :func:`record`).

    Parameters
    ----------
    resolutions : iterable of Resolution
        The measures.
    where : str
        The entry point's name, for the message.
    stacklevel : int
        Passed to :func:`warnings.warn`, so the warning points at the user's call.
    guarantee : bool
        The caller gave ``target_error``: record only.

    Returns
    -------
    Resolution or None
        The worst measure (None: nothing measured).

    Warns
    -----
    ResolutionWarning
        When the worst measure predicts more than :data:`THRESHOLD`.
    """
    w = worst(_deciding(resolutions))
    if w is None:
        return None
    seen = _RECORDER.get()
    if seen is not None:
        seen.append(w)
        return w
    if guarantee or not w.predicted_error > THRESHOLD:
        return w
    message = (f"{where}: {w.value:.3g} {NAMES[w.measure]}; the measured rule (contactlib.resolution) predicts a "
               f"{w.predicted_error:.1%} error in the contact area or pressure, more than {THRESHOLD:.0%}; "
               f"{_advice(w)}. Give target_error= for a guaranteed bound; silence with "
               "warnings.filterwarnings('ignore', category=contactlib.ResolutionWarning)")
    warnings.warn(ResolutionWarning(message, w), stacklevel=stacklevel)
    return w


def warn(message: str, *, stacklevel: int = 3) -> None:
    """A :class:`ResolutionWarning` of its own (no measure: e.g. a work of adhesion below the energy method's
    resolution), said as :func:`report` says one: not inside :func:`recording`, where the answer's attrs hold it.

    Parameters
    ----------
    message : str
        The warning's text.
    stacklevel : int
        Passed to :func:`warnings.warn`.

    Warns
    -----
    ResolutionWarning
        Always, outside :func:`recording`.
    """
    if _RECORDER.get() is None:
        warnings.warn(ResolutionWarning(message), stacklevel=stacklevel + 1)


def guard(ds, values: np.ndarray, lengths, *, periodic: bool, contact=None, where: str, guarantee: bool = False,
          stacklevel: int = 4) -> Resolution | None:
    """Measure a solved scene (:func:`of_scene`; a cohesive law's process zone from ``ds.attrs``, where
    :func:`contactlib.model.adhesion.scene_attrs` put it), record it in ``ds.attrs`` and :func:`report` it.

    Parameters
    ----------
    ds : xarray.Dataset
        The labelled answer; its ``attrs`` get the measures.
    values : ndarray
        The heights [length].
    lengths : sequence of float
        Window size per axis [length].
    periodic : bool
        Periodic window or isolated footprint.
    contact : ndarray of bool, optional
        The closed nodes.
    where : str
        The entry point's name, for the message.
    stacklevel : int
        Passed to :func:`warnings.warn`, so the warning points at the user's call.
    guarantee : bool
        The caller gave ``target_error``: record only.

    Returns
    -------
    Resolution or None
        The worst measure (None: nothing measured).

    Warns
    -----
    ResolutionWarning
        As :func:`report`.
    """
    zone = ds.attrs.get("process_zone_elements")
    found = of_scene(np.asarray(values), lengths, periodic=periodic, contact=contact, zone_elements=zone,
                     law=ds.attrs.get("adhesion_model"))
    record(ds.attrs, found)
    return report(found, where=where, guarantee=guarantee, stacklevel=stacklevel)


def guard_setup(setup, state, ds, *, where: str, guarantee: bool = False, quiet: bool = False,
                stacklevel: int = 5) -> Resolution | None:
    """:func:`guard` for a :func:`contactlib.solve` problem (its validated ``setup``) and its ``state``: the closed
    nodes are the adhesive state's repulsive ones, else those carrying pressure. ``quiet``: record in ``ds.attrs``
    only (the other answers of one call, which reports once).

    Parameters
    ----------
    setup : contactlib.Problem
        The validated problem.
    state : contactlib.solvers.ContactState
        Its solved state.
    ds : xarray.Dataset
        The labelled answer.
    where : str
        The entry point's name, for the message.
    stacklevel : int
        Passed to :func:`warnings.warn`, so the warning points at the user's call.
    guarantee : bool
        The caller gave ``target_error``: record only.
    quiet : bool
        Record only.

    Returns
    -------
    Resolution or None
        The worst measure (None: nothing measured).

    Warns
    -----
    ResolutionWarning
        As :func:`report`.
    """
    contact = getattr(state, "in_contact", None)
    contact = np.asarray(state.pressure) > 0 if contact is None else contact
    if quiet:
        zone = ds.attrs.get("process_zone_elements")
        found = of_scene(setup.values, setup.grid.lengths, periodic=bool(setup.attrs["periodic"]), contact=contact,
                         zone_elements=zone, law=ds.attrs.get("adhesion_model"))
        return record(ds.attrs, found)
    return guard(ds, setup.values, setup.grid.lengths, periodic=bool(setup.attrs["periodic"]), contact=contact,
                 where=where, guarantee=guarantee, stacklevel=stacklevel)


def guard_stepper(ds, stepper, *, where: str, stacklevel: int = 5) -> Resolution | None:
    """:func:`guard` for a time-stepping run (:class:`contactlib.problems.transient.Stepper`), its contact that of the
    last step.

    Parameters
    ----------
    ds : xarray.Dataset
        The labelled run.
    stepper : contactlib.problems.transient.Stepper
        The time stepper.
    where : str
        The entry point's name, for the message.
    stacklevel : int
        Passed to :func:`warnings.warn`, so the warning points at the user's call.

    Returns
    -------
    Resolution or None
        The worst measure (None: nothing measured).

    Warns
    -----
    ResolutionWarning
        As :func:`report`.
    """
    contact = None if stepper.pressure is None else np.asarray(stepper.pressure) > 0
    return guard(ds, stepper.values, stepper.grid.lengths, periodic=bool(stepper.periodic), contact=contact,
                 where=where, stacklevel=stacklevel)


def guard_path(ds, setup, *, where: str = "adhesion_curve", stacklevel: int = 5) -> Resolution | None:
    """:func:`guard` for a path of states (:func:`contactlib.adhesion_curve`), which keeps no fields: a
    non-periodic contact is measured as the disc (1D: the strip) of the closed area at the pull-off (the most
    tensile converged state in contact: the path's least resolved state that matters); a cohesive law's process
    zone as :func:`contactlib.model.adhesion.scene_attrs` measures it.

    Parameters
    ----------
    ds : xarray.Dataset
        The labelled path.
    setup : contactlib.Problem
        The validated problem.
    where : str
        The entry point's name, for the message.
    stacklevel : int
        Passed to :func:`warnings.warn`, so the warning points at the user's call.

    Returns
    -------
    Resolution or None
        The worst measure (None: nothing measured).

    Warns
    -----
    ResolutionWarning
        As :func:`report`.
    """
    law = setup.adhesion
    if law is not None and law.cohesive and law.work > 0 and "process_zone_elements" not in ds.attrs:
        ds.attrs["process_zone_elements"] = process_zone_length(law, setup.attrs["E_star"]) / max(setup.grid.spacing)
    contact = None
    if not setup.attrs["periodic"]:
        area, pressure = ds["contact_area"].values, ds["mean_pressure"].values
        ok = np.isfinite(area) & np.isfinite(pressure) & (area > 0)
        if ok.any():
            k = np.flatnonzero(ok)[int(np.argmin(pressure[ok]))]
            nodes = float(area[k]) * setup.values.size
            radius = nodes / 2 if setup.values.ndim == 1 else math.sqrt(nodes / math.pi)
            contact = _disc(radius, setup.values.ndim)
    return guard(ds, setup.values, setup.grid.lengths, periodic=bool(setup.attrs["periodic"]), contact=contact,
                 where=where, stacklevel=stacklevel)


def _disc(radius: float, dim: int) -> np.ndarray:
    """A disc (1D: a strip) of ``radius`` spacings on its own small grid: the contact a closed area stands for."""
    m = int(math.ceil(radius)) + 2
    x = np.arange(-m, m + 1)
    return (x**2 <= radius**2) if dim == 1 else (x[:, None] ** 2 + x[None, :] ** 2 <= radius**2)


def guard_asperities(ds, radii, spacing: float, n: int, *, where: str = "two_scale.solve",
                     stacklevel: int = 4) -> Resolution | None:
    """:func:`guard` for a field of separate contacts of known ``radii`` [length] on a grid of ``spacing``: the
    contact rule per asperity, weighted by its area (the total area's error), recorded as the rms radius in
    spacings.

    Parameters
    ----------
    ds : xarray.Dataset
        The labelled answer.
    radii : array_like
        Contact radii of the asperities [length].
    spacing : float
        Grid spacing [length].
    n : int
        The grid side.
    where : str
        The entry point's name, for the message.
    stacklevel : int
        Passed to :func:`warnings.warn`, so the warning points at the user's call.

    Returns
    -------
    Resolution or None
        The worst measure (None: nothing measured).

    Warns
    -----
    ResolutionWarning
        As :func:`report`.
    """
    a = np.asarray(radii, dtype=float)
    a = a[np.isfinite(a) & (a > 0)] / spacing
    if a.size == 0:
        return None
    errors = np.array([predicted_error("points_per_contact_radius", v) for v in a])
    found = [Resolution("points_per_contact_radius", float(np.sqrt(np.mean(a**2))),
                        float(np.sum(a**2 * errors) / np.sum(a**2)), n)]
    record(ds.attrs, found)
    return report(found, where=where, stacklevel=stacklevel)
