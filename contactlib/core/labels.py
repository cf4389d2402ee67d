"""The single registry of variable labels (name -> units and long_name), and the labelling of a solver's
state as a Dataset.

Axis order: the solvers index a surface's arrays ``[ix, iy]`` (``SOLVER_AXES``); every 2D field contactlib returns
or writes is labelled on ``("y", "x")`` (``FIELD_AXES``: rows are y, the numpy and image convention), so that
xarray's ``.plot()`` puts x on the horizontal axis. :func:`field_variable` is the one place that turns the one into
the other (a transposed view, no copy); :func:`contactlib.core.inputs.solver_values` reads a field back by name.

Units are templates: ``{length}`` and ``{pressure}`` are filled with the units the caller
declares (SI by default), because the solvers themselves are unit-agnostic.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

VARIABLES: dict[str, dict[str, str]] = {
    "x": {"units": "{length}", "long_name": "position along x"},
    "y": {"units": "{length}", "long_name": "position along y"},
    "height": {"units": "{length}", "long_name": "rigid surface height"},
    "pressure": {"units": "{pressure}", "long_name": "contact pressure (compressive positive)"},
    "gap": {"units": "{length}", "long_name": "interfacial gap"},
    "displacement": {"units": "{length}", "long_name": "normal surface displacement (positive into the body)"},
    "contact_area": {"units": "1", "long_name": "contact area fraction"},
    "mean_pressure": {"units": "{pressure}", "long_name": "mean contact pressure over the window"},
    "penetration": {"units": "{length}", "long_name": "rigid approach from first contact"},
    "iterations": {"units": "1", "long_name": "solver iterations"},
    "outer_iterations": {"units": "1", "long_name": "outer (friction coupling) iterations of the solver"},
    "tangential_traction_x": {"units": "{pressure}", "long_name": "tangential traction on the body along x"},
    "tangential_traction_y": {"units": "{pressure}", "long_name": "tangential traction on the body along y"},
    "tangential_displacement_x": {"units": "{length}", "long_name": "tangential surface displacement along x"},
    "tangential_displacement_y": {"units": "{length}", "long_name": "tangential surface displacement along y"},
    "friction_coefficient_interlocking": {"units": "1",
                                          "long_name": "interlocking friction coefficient mu_a (pressure asymmetry)"},
    "friction_coefficient": {"units": "1", "long_name": "total friction coefficient mu_c + mu_a"},
    "dissipated_power": {"units": "{pressure} {length} s-1",
                         "long_name": "power dissipated in the body per unit area"},
    "residual": {"units": "1", "long_name": "scale-free contact residual"},
    "adhesive_pressure": {"units": "{pressure}", "long_name": "tensile (adhesive) part of the normal traction"},
    "interaction_area": {"units": "1",
                         "long_name": "area fraction where the cohesive stress acts (gap at most the range)"},
    "step": {"units": "1", "long_name": "step along the loading-unloading path"},
    "unloading": {"units": "1", "long_name": "1 on the unloading part of the path, 0 on loading"},
    "jump": {"units": "1", "long_name": "1 where the state jumped (left its branch) on arriving at this step"},
    "pull_off_pressure": {"units": "{pressure}", "long_name": "pull-off pressure (most tensile mean pressure)"},
    "pull_off_penetration": {"units": "{length}", "long_name": "penetration of the jump out of contact"},
    "jump_in_penetration": {"units": "{length}", "long_name": "penetration of the jump into contact"},
    "full_contact_penetration": {"units": "{length}",
                                 "long_name": "penetration of the jump into full contact (NaN if none)"},
    "full_contact_pressure": {"units": "{pressure}",
                              "long_name": "mean pressure of the jump into full contact (NaN if none)"},
    "hysteresis_energy": {"units": "{pressure} {length}",
                          "long_name": "energy lost per unit area over the loading-unloading cycle"},
    "position_x": {"units": "{length}", "long_name": "position of the rigid surface relative to the body along x"},
    "position_y": {"units": "{length}", "long_name": "position of the rigid surface relative to the body along y"},
    "tangential_force_x": {"units": "{pressure}",
                           "long_name": "tangential force per unit nominal area to move the rigid surface along +x "
                                        "(interlocking)"},
    "tangential_force_y": {"units": "{pressure}",
                           "long_name": "tangential force per unit nominal area to move the rigid surface along +y "
                                        "(interlocking)"},
    "cycle": {"units": "1", "long_name": "reciprocating cycle number"},
    "dissipated_energy": {"units": "{pressure} {length}",
                          "long_name": "energy dissipated in the body per unit area over the cycle"},
    "friction_work": {"units": "{pressure} {length}",
                      "long_name": "work of the tangential force per unit area over the cycle (loop area)"},
    "cycle_change": {"units": "1", "long_name": "relative change from the previous cycle"},
    "energy_balance": {"units": "1", "long_name": "friction work minus dissipated energy over the cycle's absolute "
                                                 "work"},
    "wavenumber": {"units": "rad {length}-1", "long_name": "wavenumber |q|"},
    "psd": {"units": "{length}4", "long_name": "radially averaged power spectral density"},
    "psd_1d": {"units": "{length}3", "long_name": "power spectral density of a profile"},
    "asperity": {"units": "1", "long_name": "asperity index"},
    "center_x": {"units": "{length}", "long_name": "asperity summit position along x"},
    "center_y": {"units": "{length}", "long_name": "asperity summit position along y"},
    "radius": {"units": "{length}", "long_name": "asperity sphere radius"},
    "summit_height": {"units": "{length}", "long_name": "asperity summit height above the base"},
    "force": {"units": "{pressure} {length}2", "long_name": "normal contact force on the asperity"},
    "macro_force": {"units": "{pressure} {length}2",
                    "long_name": "normal contact force on the asperity from the macro step (Hertz + point-load interaction)"},
    "contact_radius": {"units": "{length}",
                       "long_name": "area-equivalent contact radius sqrt(A / pi) (of the asperity, or of the window's "
                                    "contact)"},
    "mean_gap": {"units": "{length}", "long_name": "mean interfacial gap over the window"},
    "normal_force": {"units": "{pressure} {length}2",
                     "long_name": "normal force on the window (mean pressure times the window area)"},
    "line_load": {"units": "{pressure} {length}",
                  "long_name": "normal force per unit width on the profile (mean pressure times the window length)"},
    "contact_half_width": {"units": "{length}", "long_name": "half the contact length of the profile"},
    "target_contact_area": {"units": "1", "long_name": "contact area fraction asked of the solve"},
    "local_penetration": {"units": "{length}",
                          "long_name": "local penetration of the asperity from the macro step (negative: separated)"},
}


SOLVER_AXES = ("x", "y")
"""Axis names of a solver's 2D arrays, in their index order ``[ix, iy]``."""

FIELD_AXES = ("y", "x")
"""Dimension order of every labelled 2D field contactlib returns or writes (x last: horizontal in ``.plot()``)."""


def field_dims(dims) -> tuple[str, ...]:
    """The labelled dims of a solver array on ``dims``: trailing ``("x", "y")`` become ``("y", "x")``; any other
    dims (a profile's ``("x",)``, leading ones such as ``saved_time``) are kept."""
    dims = tuple(dims)
    return dims[:-2] + FIELD_AXES if dims[-2:] == SOLVER_AXES else dims


def field_values(dims, values):
    """``values`` (a solver array on ``dims``) as :func:`field_dims` labels them: the last two axes swapped (a
    view) where they are ``("x", "y")``."""
    return np.swapaxes(values, -1, -2) if tuple(dims)[-2:] == SOLVER_AXES else values


def field_variable(dims, values, attrs=None) -> xr.Variable:
    """A solver array indexed ``[..., ix, iy]`` on ``dims`` as a labelled variable on :func:`field_dims`."""
    return xr.Variable(field_dims(dims), field_values(dims, values), attrs)


def attrs_for(name: str, *, length: str = "m", pressure: str = "Pa") -> dict[str, str]:
    """CF attributes of ``name`` with the declared units substituted."""
    entry = VARIABLES[name]
    return {"units": entry["units"].format(length=length, pressure=pressure), "long_name": entry["long_name"]}


def window_variables(state, lengths, *, periodic: bool, length_unit: str = "m", pressure_unit: str = "Pa") -> dict:
    """The scalars of a solved window besides the solver's own: ``mean_gap``; for an isolated (non-periodic)
    footprint its load as a force and its size, ``normal_force`` and ``contact_radius`` (``sqrt(A / pi)``, ``A``
    the contact area) on a surface, ``line_load`` and ``contact_half_width`` (half the contact length) on a profile
    (name: variable). A periodic window's force and contact size depend on the window, so they are not given."""
    def variable(name, value):
        return xr.Variable((), float(value), attrs_for(name, length=length_unit, pressure=pressure_unit))

    out = {"mean_gap": variable("mean_gap", np.mean(state.gap))}
    if periodic:
        return out
    window_area = float(np.prod(lengths))
    contact = float(np.count_nonzero(state.pressure > 0)) / state.pressure.size * window_area
    if len(lengths) == 1:
        out["line_load"] = variable("line_load", state.mean_pressure * window_area)
        out["contact_half_width"] = variable("contact_half_width", contact / 2.0)
    else:
        out["normal_force"] = variable("normal_force", state.mean_pressure * window_area)
        out["contact_radius"] = variable("contact_radius", np.sqrt(contact / np.pi))
    return out


def to_dataset(state, *, dims, coords, length_unit="m", pressure_unit="Pa", extra=None) -> xr.Dataset:
    """Label a solver's :class:`contactlib.solvers.ContactState` as a CF-style Dataset: its fields (solver arrays on
    ``dims``) labelled on :func:`field_dims` (a surface's on ``("y", "x")``), its scalars, units and long names
    from :data:`VARIABLES`; ``extra`` (name: variable), the caller's variables after them, in the same
    construction (each later ``Dataset.update`` merges the whole dataset: about 1 ms at 512^2)."""
    def a(name):
        return attrs_for(name, length=length_unit, pressure=pressure_unit)

    fields = {name: field_variable(dims, getattr(state, name), a(name))
              for name in ("pressure", "gap", "displacement")}
    scalars = {
        "contact_area": float(np.count_nonzero(state.pressure > 0)) / state.pressure.size,
        "mean_pressure": state.mean_pressure,
        "penetration": state.penetration,
        "iterations": state.iterations,
        "residual": state.residual,
    }
    data = dict(fields)
    data.update({k: ((), v, a(k)) for k, v in scalars.items()})
    data.update(extra or {})
    ds = xr.Dataset(data, coords=coords)
    for d in dims:
        if not ds[d].attrs:
            ds[d].attrs.update(a(d))
    ds.attrs["Conventions"] = "CF-1.10"
    return ds


def _variable(dims, values, attrs) -> xr.Variable:
    """``xr.Variable(dims, values, attrs)``; for a plain numpy array or number of a numeric dtype (the labels'
    values) without the conversions other array types need (``fastpath``: the 14 variables of a two-scale result
    84 -> 59 us)."""
    if type(values) is np.ndarray or isinstance(values, (np.generic, float, int)):
        array = np.asarray(values)
        if array.dtype.kind in "biufc":
            return xr.Variable(dims, array, attrs, fastpath=True)
    return xr.Variable(dims, values, attrs)


def dataset(data: dict, coords: dict, attrs: dict | None = None) -> xr.Dataset:
    """``xr.Dataset(data, coords=coords, attrs=attrs)`` for ``name: (dims, values, attrs)`` entries whose shapes
    agree by construction, built directly from its variables and the dimension coordinates' indexes.

    The public constructor merges and aligns its arguments: 0.3 ms for the 14 variables of a two-scale result at
    10^3 asperities, where the whole macro step takes 2.3-3 ms; built directly, 0.09 ms. The same Dataset (tested
    with ``identical``); the dimensions are still checked for conflicts. Falls back to the constructor on an
    xarray without the direct path (a private method), and for names that clash (its own checks and errors)."""
    construct = getattr(xr.Dataset, "_construct_direct", None)
    dimensions = {d for entry in (*data.values(), *coords.values())
                  for d in ((entry[0],) if isinstance(entry[0], str) else entry[0])}
    if construct is None or set(data) & (set(coords) | dimensions):  # a clash: the constructor's checks and errors
        return xr.Dataset(data, coords=coords, attrs=attrs)
    variables, indexes = {}, {}
    for name, (dims, values, var_attrs) in data.items():
        variables[name] = _variable(dims, values, var_attrs)
    for name, (dims, values, var_attrs) in coords.items():
        if ((dims,) if isinstance(dims, str) else tuple(dims)) == (name,):  # a dimension coordinate: indexed
            variables[name] = xr.IndexVariable(name, values, var_attrs)
            indexes[name] = xr.indexes.PandasIndex(variables[name].to_index(), name)
        else:
            variables[name] = _variable(dims, values, var_attrs)
    try:
        return construct(variables, set(coords), attrs=dict(attrs or {}), indexes=indexes)
    except TypeError:  # the private method's signature changed
        return xr.Dataset(data, coords=coords, attrs=attrs)
