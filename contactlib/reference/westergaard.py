"""Periodic wavy surfaces on an elastic half-space (Westergaard 1939; Johnson section 13.2).

The rigid profile is ``h(x) = amplitude * cos(2 pi x / wavelength)``; ``E_star`` [pressure].
"""

from __future__ import annotations

import numpy as np


def full_contact_pressure(*, amplitude: float, wavelength: float, E_star: float,
                          wavelength_y: float | None = None) -> float:
    """Mean pressure at which the contact becomes complete: ``p* = E* |q| amplitude / 2``, where the
    full-contact field (:func:`full_contact_field`) first touches zero at the troughs.

    1D: ``p* = pi E* amplitude / wavelength``; 2D egg-box ``amplitude cos(qx x) cos(qy y)`` (give
    ``wavelength_y``, equal wavelengths: ``p* = sqrt(2) pi E* amplitude / wavelength``).

    Parameters
    ----------
    amplitude : float
        Amplitude of the sinusoid [length].
    wavelength : float
        Its wavelength (along x) [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].
    wavelength_y : float, optional
        The wavelength along y of a 2D egg-box; None for a 1D profile.

    Returns
    -------
    float
        The mean pressure p* of full contact [pressure].
    """
    q = 2 * np.pi / wavelength
    if wavelength_y is not None:
        q = np.hypot(q, 2 * np.pi / wavelength_y)
    return 0.5 * E_star * q * amplitude


def mean_pressure(contact_fraction, *, amplitude: float, wavelength: float, E_star: float):
    """Partial contact: p_mean = p* sin^2(pi a / wavelength), with contact fraction 2a/wavelength.

    Parameters
    ----------
    contact_fraction : float or array_like
        Contact fraction 2a / wavelength, in [0, 1].
    amplitude : float
        Amplitude of the sinusoid [length].
    wavelength : float
        Its wavelength [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].

    Returns
    -------
    float or ndarray
        The mean pressure [pressure].
    """
    p_star = full_contact_pressure(amplitude=amplitude, wavelength=wavelength, E_star=E_star)
    return p_star * np.sin(np.pi * np.asarray(contact_fraction) / 2.0) ** 2


def contact_fraction(mean_pressure, *, amplitude: float, wavelength: float, E_star: float):
    """Inverse of :func:`mean_pressure`: 2a/wavelength, 1 beyond full contact.

    Parameters
    ----------
    mean_pressure : float or array_like
        Mean pressure [pressure], >= 0.
    amplitude : float
        Amplitude of the sinusoid [length].
    wavelength : float
        Its wavelength [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].

    Returns
    -------
    float or ndarray
        The contact fraction 2a / wavelength (1 beyond full contact).

    Examples
    --------
    >>> from contactlib.reference import westergaard
    >>> p = westergaard.mean_pressure(0.5, amplitude=0.01, wavelength=1.0, E_star=1.0)
    >>> round(float(westergaard.contact_fraction(p, amplitude=0.01, wavelength=1.0, E_star=1.0)), 12)
    0.5
    """
    p_star = full_contact_pressure(amplitude=amplitude, wavelength=wavelength, E_star=E_star)
    ratio = np.clip(np.asarray(mean_pressure) / p_star, 0.0, 1.0)
    return 2.0 / np.pi * np.arcsin(np.sqrt(ratio))


def partial_contact_pressure(x, *, mean_pressure: float, amplitude: float, wavelength: float, E_star: float):
    """Pressure field in 1D partial contact, x measured from a crest (Johnson eq. 13.8).

    Parameters
    ----------
    x : array_like
        Positions from a crest [length].
    mean_pressure : float
        Mean pressure, below full contact [pressure].
    amplitude : float
        Amplitude of the sinusoid [length].
    wavelength : float
        Its wavelength [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].

    Returns
    -------
    ndarray
        The pressure at ``x`` [pressure], zero outside the contact.
    """
    p_star = full_contact_pressure(amplitude=amplitude, wavelength=wavelength, E_star=E_star)
    a = wavelength / np.pi * np.arcsin(np.sqrt(min(mean_pressure / p_star, 1.0)))
    xm = (np.asarray(x) + wavelength / 2) % wavelength - wavelength / 2
    s = np.sin(np.pi * a / wavelength)
    c = np.cos(np.pi * xm / wavelength)
    inside = np.abs(xm) < a
    with np.errstate(invalid="ignore"):
        p = 2 * p_star * c * np.sqrt(np.clip(s**2 - np.sin(np.pi * xm / wavelength) ** 2, 0.0, None))
    return np.where(inside, p, 0.0)


def full_contact_field(x, y=None, *, mean_pressure: float, amplitude: float, wavelength: float, E_star: float,
                       wavelength_y: float | None = None):
    """Full-contact pressure of ``amplitude cos(qx x)`` (1D) or ``amplitude cos(qx x) cos(qy y)`` (2D egg-box).

    Each Fourier mode ``q`` of a surface in full contact carries ``p_q = E* |q| h_q / 2``.

    Parameters
    ----------
    x : array_like
        Positions along x [length].
    y : array_like, optional
        Positions along y [length] of a 2D egg-box (None: a profile).
    mean_pressure : float
        Mean pressure, at or above full contact [pressure].
    amplitude : float
        Amplitude of the surface [length].
    wavelength : float
        Wavelength along x [length].
    E_star : float
        Contact modulus E* = E / (1 - nu^2) [pressure].
    wavelength_y : float, optional
        Wavelength along y of the egg-box (default: ``wavelength``).

    Returns
    -------
    ndarray
        The pressure field [pressure] on ``x`` (1D) or the ``(x, y)`` grid (2D).
    """
    qx = 2 * np.pi / wavelength
    if y is None:
        return mean_pressure + 0.5 * E_star * qx * amplitude * np.cos(qx * np.asarray(x))
    qy = 2 * np.pi / (wavelength_y or wavelength)
    q = np.hypot(qx, qy)
    return mean_pressure + 0.5 * E_star * q * amplitude * np.cos(qx * np.asarray(x)) * np.cos(qy * np.asarray(y))
