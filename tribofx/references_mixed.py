"""References of mixed lubrication: the Greenwood–Tripp integral and the rough flat punch.

* :func:`greenwood_tripp_f52` — F_{5/2}(H) = (2π)^{−½} ∫_H^∞ (s − H)^{5/2} e^{−s²/2} ds
  by quadrature (independent of the fit the forms use);
* :func:`flat_punch_separation` — the separation h of a rough flat under a
  uniform pressure p carried by the asperities alone, p = K E* F_{5/2}(h/σ),
  solved in closed form through the inverse of the fit of
  :data:`tribofx.forms.mixed.GT_FIT`;
* :func:`jgp_load_sharing` — the load-sharing estimate of Johnson, Greenwood
  & Poon (1972) for a line contact in the isoviscous-elastic regime.

Units: mm, MPa.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Callable

__all__ = ["flat_punch_separation", "greenwood_tripp_f52", "jgp_load_sharing"]


def greenwood_tripp_f52(H: float, n: int = 200_001, span: float = 12.0) -> float:
    """F_{5/2}(H) by the trapezoidal rule on [H, H + span] (relative error < 1e-8 for H ≥ −4)."""
    s = np.linspace(H, H + span, n)
    f = (s - H) ** 2.5 * np.exp(-0.5 * s**2) / np.sqrt(2 * np.pi)
    return float(np.trapezoid(f, s))


def flat_punch_separation(p: float, sigma: float, KE: float,
                          fit: tuple[float, float, float] = (4.4086e-5, 4.0, 6.804)) -> float:
    """Separation h (mm) at which K E* A (H_c − h/σ)^n equals the pressure p (MPa), p > 0.

    ``KE``: K E* (MPa); ``fit``: (A, H_c, n) of the F_{5/2} fit.
    """
    A, Hc, n = fit
    return sigma * (Hc - (p / (KE * A)) ** (1.0 / n))


def jgp_load_sharing(h_smooth: float, p0: float, p_a: Callable[[float], float],
                     exponents: tuple[float, float] = (-0.2, -0.4)) -> tuple[float, float]:
    """Return (film share 1/γ₁, central film h_c) of Johnson, Greenwood & Poon (1972).

    The film carries W/γ₁, the asperities W/γ₂ (1/γ₁ + 1/γ₂ = 1).  Each part acts
    as if alone on a contact of modulus E*/γ: the film is the smooth one of load
    W/γ₁ and modulus E*/γ₁, so with the smooth central film h ∝ W^a E*^b
    (isoviscous-elastic line contact, Herrebrugh: a = −0.2, b = −0.4)
    h_c = h_smooth γ₁^−(a+b); the asperities carry the Hertz pressure of W/γ₂ on
    E*/γ₂ at the centre, p_a(h_c) = p₀/γ₂.  Solved for γ₁ by bisection in log γ₁.

    Args:
        h_smooth: central film of the smooth surfaces at the same speed and load (mm).
        p0: Hertz peak pressure of W (MPa).
        p_a: the asperity pressure law p_a(h) (MPa), decreasing in h.
        exponents: (a, b) of the smooth film's load and modulus.
    """
    m = -(exponents[0] + exponents[1])
    lo, hi = 1.0, 1e8
    for _ in range(200):
        g = np.sqrt(lo * hi)
        if p_a(h_smooth * g**m) > p0 * (1 - 1 / g):
            lo = g
        else:
            hi = g
    g = np.sqrt(lo * hi)
    return 1 / g, h_smooth * g**m
