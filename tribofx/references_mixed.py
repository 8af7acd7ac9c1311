"""References of mixed lubrication: the Greenwood–Tripp integral and the rough flat punch.

* :func:`greenwood_tripp_f52` — F_{5/2}(H) = (2π)^{−½} ∫_H^∞ (s − H)^{5/2} e^{−s²/2} ds
  by quadrature (independent of the fit the forms use);
* :func:`flat_punch_separation` — the separation h of a rough flat under a
  uniform pressure p carried by the asperities alone, p = K E* F_{5/2}(h/σ),
  solved in closed form through the inverse of the fit of
  :data:`tribofx.forms.mixed.GT_FIT`.

Units: mm, MPa.
"""

import numpy as np

__all__ = ["flat_punch_separation", "greenwood_tripp_f52"]


def greenwood_tripp_f52(H, n=200_001, span=12.0):
    """F_{5/2}(H) by the trapezoidal rule on [H, H + span] (relative error < 1e-8 for H ≥ −4)."""
    s = np.linspace(H, H + span, n)
    f = (s - H) ** 2.5 * np.exp(-0.5 * s**2) / np.sqrt(2 * np.pi)
    return float(np.trapezoid(f, s))


def flat_punch_separation(p, sigma, KE, fit=(4.4086e-5, 4.0, 6.804)):
    """Separation h (mm) at which K E* A (H_c − h/σ)^n equals the pressure p (MPa), p > 0.

    ``KE``: K E* (MPa); ``fit``: (A, H_c, n) of the F_{5/2} fit.
    """
    A, Hc, n = fit
    return sigma * (Hc - (p / (KE * A)) ** (1.0 / n))
