"""Central film thickness (Eq. 56): Hamrock-Dowson, in its dimensional form."""

from __future__ import annotations

import numpy as np

__all__ = ["central_film_thickness", "minimum_film_thickness", "SPEED_EXPONENT"]

#: Exponent of the entrainment speed in the central film thickness (``h ~ u_e^0.67``):
#: ``h(u_e) = h(1 m/s) |u_e|^0.67``, which the solvers use to keep the speed-independent
#: factor between iterations.
SPEED_EXPONENT = 0.67


def central_film_thickness(eta0, zeta, reduced_modulus, rx, entrainment_speed, load, ellipticity):
    """Hamrock-Dowson central film thickness of an elliptical EHL contact.

    ``H = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 exp(-0.73 k_e))``, ``h = H R_x``, with
    ``U = eta_0 u_e / (E' R_x)``, ``G = zeta E'``, ``W = F_N / (E' R_x^2)``. This is the
    paper's Eq. 56 written dimensionally (the equality is a test; docs/model.md §3).

    Parameters
    ----------
    eta0 : float
        Viscosity at atmospheric pressure [Pa s].
    zeta : float
        Pressure-viscosity coefficient [1/Pa].
    reduced_modulus : float
        ``E'`` [Pa].
    rx : array_like
        Equivalent radius in the rolling direction ``R_x`` [m].
    entrainment_speed : array_like
        Mean surface speed ``u_e`` [m/s].
    load : array_like
        Normal load ``F_N`` [N].
    ellipticity : array_like
        ``k_e = a_y / a_x`` [-].

    Returns
    -------
    ndarray
        Central film thickness ``h`` [m].
    """
    rx, u, g, w = _groups(eta0, zeta, reduced_modulus, rx, entrainment_speed, load)
    h_bar = (
        2.69 * u**SPEED_EXPONENT * g**0.53 * w**-0.067 * (1.0 - 0.61 * np.exp(-0.73 * ellipticity))
    )
    return h_bar * rx


def minimum_film_thickness(eta0, zeta, reduced_modulus, rx, entrainment_speed, load, ellipticity):
    """Hamrock-Dowson minimum film thickness of an elliptical EHL contact.

    ``H_min = 3.63 U^0.68 G^0.49 W^-0.073 (1 - exp(-0.68 k_e))``, ``h_min = H_min R_x``
    (Hamrock and Dowson, J. Lubr. Technol. 99 (1977) 264-276, Eq. 30; the same ``U``, ``G``,
    ``W`` as `central_film_thickness`). Used for the film thickness ratio
    ``Lambda = h_min / sigma`` of the validity warnings (docs/model.md §10).

    Parameters
    ----------
    eta0, zeta, reduced_modulus, rx, entrainment_speed, load, ellipticity
        As in `central_film_thickness` ([Pa s], [1/Pa], [Pa], [m], [m/s], [N], [-]).

    Returns
    -------
    ndarray
        Minimum film thickness ``h_min`` [m].
    """
    rx, u, g, w = _groups(eta0, zeta, reduced_modulus, rx, entrainment_speed, load)
    h_bar = 3.63 * u**0.68 * g**0.49 * w**-0.073 * (1.0 - np.exp(-0.68 * ellipticity))
    return h_bar * rx


def _groups(eta0, zeta, reduced_modulus, rx, entrainment_speed, load):
    """``R_x`` and the dimensionless speed, material and load parameters ``U, G, W``."""
    rx = np.asarray(rx, dtype=float)
    u = eta0 * np.abs(entrainment_speed) / (reduced_modulus * rx)
    w = np.asarray(load, dtype=float) / (reduced_modulus * rx**2)
    return rx, u, zeta * reduced_modulus, w
