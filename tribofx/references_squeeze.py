"""Squeeze films between a rigid cylinder or sphere and a rigid plane (Reynolds 1886).

Re-exported by :mod:`tribofx.references` (pure functions, NumPy only, units mm,
N, s, MPa).  A rigid body of radius R approaches a plane at speed V = −dh/dt
through a flooded incompressible film, p = 0 where the film opens (|x| or r =
``extent``, the end of the lubricated arc or cap).  The flux through the
section at x (cylinder, per unit length) or r (sphere) carries the displaced
volume, q = V x and q = V r/2, so the pressure and the load follow by quadrature
of the exact gap h(x) = h₀ + R − √(R² − x²):

    cylinder  p(x) = 12μV ∫_x^L s/h³ ds,   W' = 24μV ∫_0^L x²/h³ dx   (N/mm, both halves)
    sphere    p(r) = 6μV ∫_r^L s/h³ ds,    F  = 6πμV ∫_0^L r³/h³ dr

(integration by parts, p(L) = 0).  For h₀ ≪ R and L ≫ √(2Rh₀) (parabolic gap,
infinite film) they reduce to the classical closed forms (e.g. Hamrock, Schmid
and Jacobson, *Fundamentals of Fluid Film Lubrication*, ch. 11):

    cylinder  W' = 3√2 π μ V (R/h₀)^{3/2},   p(0) = 6μVR/h₀²
    sphere    F  = 6π μ V R²/h₀,             p(0) = 3μVR/h₀²

with relative differences O(h₀/R) and O((2Rh₀)^{3/2}/L³).  Under a constant
load the film thins as dh/dt = −W/K(h), K = W/V the resistance above; closed
form for the sphere h(t) = h₀ exp(−F t/(6πμR²)) and for the cylinder
h(t)^{−1/2} = h₀^{−1/2} + W' t/(6√2 π μ R^{3/2}); :func:`squeeze_film_under_load`
integrates the exact-gap law by RK4.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from collections.abc import Callable

    import numpy.typing as npt

__all__ = ["squeeze_closed_form", "squeeze_film_under_load", "squeeze_resistance"]

_XG, _WG = np.polynomial.legendre.leggauss(20)


def _quad(f: Callable[[npt.NDArray[np.float64]], npt.NDArray[np.float64]], L: float,
          n: int = 200) -> float:
    """∫_0^L f dx, 20-point Gauss on [0, 1e-7 L] and n intervals of ratio 1.08 up to L.

    Each interval spans 8 % of its distance from 0, so every length scale of the
    integrand above 1e-7 L (here √(2Rh₀)) is resolved to round-off.
    """
    edges = np.concatenate([[0.0], np.geomspace(1e-7 * L, L, n)])
    a, b = edges[:-1, None], edges[1:, None]
    s = 0.5 * (b - a) * _XG + 0.5 * (b + a)
    return float(np.sum(0.5 * (b - a) * _WG * f(s)))


def squeeze_resistance(dim: int, R: float, mu: float, h0: float,
                       extent: float | None = None) -> float:
    """Resistance K = W/V of the rigid squeeze film with the exact gap (N·s/mm², N·s/mm).

    ``dim`` 2: cylinder, the load per unit length of both halves (W' = K V,
    N/mm); 3: sphere (F = K V, N).  ``extent``: the film's end L (default R,
    the lubricated half cylinder/hemisphere), p = 0 there.
    """
    L = R if extent is None else float(extent)
    if not 0 < L <= R:
        raise ValueError(f"extent {L} must lie in (0, R]")

    def h(x: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        # h₀ + R − √(R² − x²) without the cancellation near the axis
        return h0 + x * x / (R + np.sqrt(R * R - x * x))

    if dim == 2:
        return 24 * mu * _quad(lambda x: x * x / h(x) ** 3, L)
    if dim == 3:
        return 6 * math.pi * mu * _quad(lambda r: r**3 / h(r) ** 3, L)
    raise ValueError(f"dim must be 2 or 3, got {dim}")


def squeeze_closed_form(dim: int, R: float, mu: float, h0: float) -> tuple[float, float]:
    """Classical (parabolic-gap, infinite-film) resistance and centre pressure per unit speed.

    Returns (K, p0/V): cylinder K = 3√2 π μ (R/h₀)^{3/2}, p0/V = 6μR/h₀²;
    sphere K = 6πμR²/h₀, p0/V = 3μR/h₀².
    """
    if dim == 2:
        return 3 * math.sqrt(2) * math.pi * mu * (R / h0) ** 1.5, 6 * mu * R / h0**2
    if dim == 3:
        return 6 * math.pi * mu * R**2 / h0, 3 * mu * R / h0**2
    raise ValueError(f"dim must be 2 or 3, got {dim}")


def squeeze_film_under_load(dim: int, R: float, mu: float, W: float, h0: float,
                            times: npt.ArrayLike, extent: float | None = None,
                            steps: int = 2000) -> npt.NDArray[np.float64]:
    """Film thickness h(t) at ``times`` (s, ascending, ≥ 0) under a constant load W.

    dh/dt = −W/K(h) with K of :func:`squeeze_resistance`, integrated by
    classical RK4 with ``steps`` steps over [0, max(times)] (error O(Δt⁴),
    below 1e-9 relative for the default) and interpolated by the same RK4 to
    each time; W in N/mm (``dim`` 2) or N (3).
    """
    times = np.asarray(times, dtype=float)
    T = float(times.max(initial=0.0))
    out = np.empty_like(times)

    def f(h: float) -> float:
        return -W / squeeze_resistance(dim, R, mu, h, extent)

    grid = np.unique(np.concatenate([np.linspace(0.0, T, steps + 1), times]))
    h, t, values = h0, 0.0, {0.0: h0}
    for t_next in grid[1:]:
        dt = t_next - t
        k1 = f(h)
        k2 = f(h + 0.5 * dt * k1)
        k3 = f(h + 0.5 * dt * k2)
        k4 = f(h + dt * k3)
        h += dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        t = t_next
        values[t] = h
    for i, ti in enumerate(times):
        out[i] = values[float(ti)]
    return out
