"""Random self-affine surfaces by filtering Gaussian white noise in Fourier space."""

from __future__ import annotations


import numpy as np
import xarray as xr

from ..core import fft
from .._version import __version__
from ..analysis import statistics
from ..core.grid import Grid
from ..core.inputs import check_whole, number
from ..core.labels import attrs_for, field_dims, field_values
from .spectra import self_affine_psd, stretched_wavenumber


def self_affine(
    n: int,
    *,
    length: float = 1.0,
    hurst: float,
    q_low: float = 1,
    q_roll: float,
    q_cutoff: float,
    rms_height: float | None = None,
    rms_slope: float | None = None,
    seed: int = 0,
    dim: int = 2,
    anisotropy: float = 1.0,
    angle: float = 0.0,
    synthesis: str = "filtered-noise",
    length_unit: str = "m",
) -> xr.DataArray:
    """Gaussian self-affine surface, periodic on ``length``.

    Parameters
    ----------
    n : int
        Points per side (``n x n`` in 2D, ``n`` in 1D).
    length : float
        Window size [length].
    hurst : float
        Hurst exponent H in (0, 1]: ``C(q) ~ q^-(2+2H)`` in 2D, ``q^-(1+2H)`` in 1D.
    q_low, q_roll, q_cutoff : float
        Band edges as multiples of ``q0 = 2 pi / length``: flat power on ``[q_low, q_roll)``,
        power law on ``[q_roll, q_cutoff]``, zero beyond. ``q_cutoff <= n/2`` (Nyquist). A mode on an
        edge is in the band for every ``length``; a band that holds no mode of the grid is refused
        (ValueError naming ``q_cutoff``), and so is ``rms_slope`` for a band of Nyquist modes only.
    rms_height, rms_slope : float
        Exactly one: the rms height [length] or rms gradient (spectral, exact for the band) [1].
    seed : int
        Seed of ``numpy.random.default_rng``: same seed, same surface, bit for bit.
    anisotropy : float
        Ratio gamma in (0, 1] of the eigenvalues of the slope tensor (seed 2, eq. 27); 1 is isotropic.
    angle : float
        Principal (steepest) direction of the slope tensor [rad] from the x axis.
    synthesis : {"filtered-noise", "random-phase"}
        ``filtered-noise``: Gaussian white noise filtered by ``sqrt(C)`` (Gaussian amplitudes, the
        PSD holds on average); ``random-phase``: every mode has exactly the amplitude ``sqrt(C)``
        and a random phase (the PSD and slope tensor hold for each realisation).

    dim : {1, 2}
        A profile (1D) or a surface (2D).
    length_unit : str
        udunits string written to the ``units`` attributes of the heights and coordinates.

    Returns
    -------
    xarray.DataArray ``height`` with dims ``("y", "x")`` (x last: ``.plot()`` draws it horizontally) or ``("x",)``;
    ``.transpose("x", "y").values`` is the bare array indexed ``[ix, iy]``.

    Raises
    ------
    ValueError
        Naming the parameter: ``n``, ``dim``, band edges out of order or beyond Nyquist (``q_cutoff``), not exactly one
        of ``rms_height`` and ``rms_slope``, an unknown ``synthesis``, anisotropy in 1D, or a band without modes.
    """
    n = check_whole(n, "n", 2)
    if isinstance(dim, bool) or dim not in (1, 2):
        raise ValueError(f"dim must be 1 or 2, got {dim!r}")
    hurst, q_low, q_roll, q_cutoff, target, anisotropy, angle, length = check_spectrum(
        n, hurst=hurst, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff, rms_height=rms_height, rms_slope=rms_slope,
        anisotropy=anisotropy, synthesis=synthesis, angle=angle, length=length)
    if dim == 1 and (anisotropy != 1 or angle != 0):
        raise ValueError("anisotropy and angle need dim=2")

    grid = Grid((n,) * dim, (float(length),) * dim)
    q0 = 2 * np.pi / length
    if dim == 2:
        qx, qy = grid.wavevectors()
        q = stretched_wavenumber(qx, qy, anisotropy=anisotropy, angle=angle)
    else:
        q = grid.wavenumber()
    psd = self_affine_psd(q, q0=q0, hurst=hurst, q_low=q_low, q_roll=q_roll, q_cutoff=q_cutoff, dim=dim)
    if not np.any(psd > 0):  # e.g. q_low = 1.2, q_cutoff = 1.5 in 1D: no mode between them
        raise ValueError(f"the band [q_low, q_cutoff] = [{q_low}, {q_cutoff}] (multiples of q0 = 2 pi / length) "
                         f"holds no mode of the {'x'.join(map(str, grid.shape))} grid"
                         + ("" if anisotropy == 1 else f" at anisotropy={anisotropy}, angle={angle}")
                         + ": raise q_cutoff or lower q_low")
    noise = np.random.default_rng(seed).standard_normal(grid.shape)
    spectrum = fft.rfftn(noise)
    if synthesis == "random-phase":  # unit modulus, phases of white noise (so Hermitian symmetry holds)
        modulus = np.abs(spectrum)
        spectrum = np.divide(spectrum, modulus, out=np.zeros_like(spectrum), where=modulus > 0)
    heights = fft.irfftn(spectrum * np.sqrt(psd), grid.shape)
    if rms_height is not None:
        current = statistics.rms_height(heights)
    else:
        current = statistics.rms_slope(heights, length=grid.lengths)
        if current == 0:  # the band holds only Nyquist modes, whose slope rms_slope leaves undefined
            raise ValueError(f"rms_slope cannot be met: the band [q_low, q_cutoff] = [{q_low}, {q_cutoff}] holds "
                             f"only Nyquist modes (n/2 = {n / 2}), which have no defined slope; give rms_height "
                             "or lower q_low")
    heights *= target / current

    dims = ("x", "y")[:dim]
    coords = {d: (d, c, attrs_for(d, length=length_unit)) for d, c in zip(dims, grid.coordinates())}
    attrs = attrs_for("height", length=length_unit)
    attrs.update(generator="contactlib.surfaces.self_affine", periodic=1, hurst=hurst, q_low=q_low, q_roll=q_roll,
                 q_cutoff=q_cutoff, seed=seed, anisotropy=anisotropy, angle=angle, length=float(length),
                 synthesis=synthesis,
                 normalised_by="rms_height" if rms_height is not None else "rms_slope", target=float(target),
                 contactlib_version=__version__)
    return xr.DataArray(field_values(dims, heights), dims=field_dims(dims), coords=coords, name="height", attrs=attrs)


def check_spectrum(n: int, *, hurst, q_low, q_roll, q_cutoff, rms_height, rms_slope, anisotropy, synthesis, angle,
                   length) -> tuple:
    """The self-affine spectrum's arguments of :func:`self_affine` (and of its slab-wise twin in
    :mod:`contactlib.distributed.surfaces`), validated on ``n`` points a side.

    Returns
    -------
    tuple
        ``(hurst, q_low, q_roll, q_cutoff, target, anisotropy, angle, length)`` as floats, ``target`` the rms height or
        slope asked.

    Raises
    ------
    ValueError
        Naming the parameter: band edges out of order or beyond Nyquist (``q_cutoff``), not exactly one of
        ``rms_height`` and ``rms_slope``, an unknown ``synthesis``.
    """
    hurst = number("hurst", hurst, lower=0.0, upper=1.0, lower_open=True)
    q_low = number("q_low", q_low, lower=0.0, lower_open=True)
    q_roll = number("q_roll", q_roll, lower=0.0, lower_open=True)
    q_cutoff = number("q_cutoff", q_cutoff, lower=0.0, lower_open=True)
    if not (q_low <= q_roll <= q_cutoff):
        raise ValueError(f"need 0 < q_low <= q_roll <= q_cutoff, got {q_low}, {q_roll}, {q_cutoff}")
    if q_cutoff > n / 2:
        raise ValueError(f"q_cutoff={q_cutoff} exceeds the Nyquist wavenumber n/2={n / 2}")
    if (rms_height is None) == (rms_slope is None):
        raise ValueError("give exactly one of rms_height or rms_slope")
    target = number("rms_height" if rms_height is not None else "rms_slope",
                    rms_height if rms_height is not None else rms_slope, lower=0.0, lower_open=True)
    anisotropy = number("anisotropy", anisotropy, lower=0.0, upper=1.0, lower_open=True)
    if synthesis not in ("filtered-noise", "random-phase"):
        raise ValueError(f"synthesis must be 'filtered-noise' or 'random-phase', got {synthesis!r}")
    angle = number("angle (principal direction [rad])", angle)
    length = number("length", length, lower=0.0, lower_open=True)
    return hurst, q_low, q_roll, q_cutoff, target, anisotropy, angle, length
