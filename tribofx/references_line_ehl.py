"""The isoviscous-elastic line contact on an elastic half-space (NumPy; Herrebrugh's problem).

Re-exported by :mod:`tribofx.references` (units mm, N, s, MPa).  A cylinder of
radius R rolls and slides on a plane with the mean surface speed u_m; the
flooded film between them carries the load w per unit length.  The solids are
linear-elastic half-spaces in plane strain with the composite modulus
E* (1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂); the fluid is Newtonian, isoviscous and
incompressible; the film ruptures by the Swift–Stieber (Reynolds) condition.
This is the problem of Herrebrugh (1968, *J. Lubr. Technol.* 90, 262) and of the
soft-EHL line-contact literature (Hooke 1977; Snoeijer, Eggers & Venner 2013),
solved here numerically, independently of the finite-element code: a finite
volume Reynolds equation on a uniform grid, the half-space's exact influence
coefficients of piecewise-constant pressures, and one semismooth Newton system
for (p, h₀) with the load equation, continued in the speed from the rigid regime.

In Hertz units (X = x/a, P = p/p₀, H = hR/a², a = √(4wR/(πE*)), p₀ = 2w/(πa)):

    d/dX (H³ dP/dX − λ H) = 0,   λ = 12 μ u_m R²/(a³ p₀),
    H(X) = H₀ + X²/2 − (1/π) ∫ P(S) ln|X − S| dS,     ∫ P dX = π/2,

with P = 0 at X_in, X_out and the complementarity P ≥ 0, r ≤ 0, P r = 0 of the
discrete Reynolds rows r (the cavitated nodes carry no pressure).  λ → ∞ is the
rigid film (Martin: h₀ = 4.9 μ u_m R/w); λ ≪ 1 the soft regime, where the film
approaches h ∝ u_m^{0.6} (Herrebrugh's asymptote).  :func:`line_contact_film`
solves on two grids and reports their difference as its error (the film converges
at orders 1–3 in the spacing: the cavitation boundary moves node by node).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import numpy.typing as npt

__all__ = ["line_contact_film"]


def _influence(X: npt.NDArray[np.float64], d: float) -> npt.NDArray[np.float64]:
    """D[i, j] = −(1/π) ∫ ln|X_i − S| dS over the cell of width d centred at X_j."""

    def F(t: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(t == 0.0, 0.0, t * np.log(np.abs(t)) - t)

    t = X[:, None] - X[None, :]
    return -(F(t + 0.5 * d) - F(t - 0.5 * d)) / math.pi


def _solve(lam: float, X: npt.NDArray[np.float64], D: npt.NDArray[np.float64],
           P: npt.NDArray[np.float64], H0: float, elastic: bool = True,
           tol: float = 1e-11, max_it: int = 60) -> tuple[npt.NDArray[np.float64], float]:
    """Newton on (P interior, H₀): the complementarity rows min(P, −s r) and the load."""
    n, d = len(X), X[1] - X[0]
    inner = slice(1, n - 1)
    Dm = D if elastic else np.zeros_like(D)
    geom = 0.5 * X**2
    # the rows scaled like pressures: 1/|∂r_i/∂P_i| at the starting film
    H = H0 + geom + Dm @ P
    Hm0 = 0.5 * (H[1:] + H[:-1])
    s = d**2 / (Hm0[:-1] ** 3 + Hm0[1:] ** 3)

    def residual(P: npt.NDArray[np.float64], H0: float
                 ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        """Return the film at the cell faces and the Reynolds rows at the interior nodes."""
        H = H0 + geom + Dm @ P
        Hm = 0.5 * (H[1:] + H[:-1])
        q = Hm**3 * np.diff(P) / d - lam * Hm          # flux at the cell faces
        return Hm, np.diff(q) / d

    def rows(P: npt.NDArray[np.float64], r: npt.NDArray[np.float64]
             ) -> npt.NDArray[np.float64]:
        """Return the complementarity rows min(P, −s r) and the load row."""
        Pi = P[inner]
        return np.append(np.minimum(Pi, -s * r), d * Pi.sum() - 0.5 * math.pi)

    def system(P: npt.NDArray[np.float64], H0: float
               ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
        Hm, r = residual(P, H0)
        m = n - 2
        # ∂r/∂P (at fixed H): the tridiagonal flux differences
        A = Hm**3 / d**2
        JP = np.zeros((m, n))
        idx = np.arange(m)
        JP[idx, idx] += A[:-1]
        JP[idx, idx + 1] -= A[:-1] + A[1:]
        JP[idx, idx + 2] += A[1:]
        # ∂q_f/∂H at both nodes of face f, then ∂r/∂H
        dq = 0.5 * (3 * Hm**2 * np.diff(P) / d - lam)
        c0, c1, c2 = -dq[:-1] / d, (dq[1:] - dq[:-1]) / d, dq[1:] / d   # tridiagonal
        drdP = JP + c0[:, None] * Dm[:-2] + c1[:, None] * Dm[1:-1] + c2[:, None] * Dm[2:]
        drdH0 = c0 + c1 + c2
        film = P[inner] > -s * r                         # min(P, −s r): the film rows
        J = np.zeros((m + 1, m + 1))
        J[:m, :m] = np.where(film[:, None], -s[:, None] * drdP[:, inner], np.eye(m))
        J[:m, m] = np.where(film, -s * drdH0, 0.0)
        J[m, :m] = d                                     # ∫ P dX (P = 0 at the ends)
        return rows(P, r), J

    for _ in range(max_it):
        G, J = system(P, H0)
        norm = np.linalg.norm(G)
        if norm < tol:
            return P, H0
        step = np.linalg.solve(J, -G)
        t = 1.0
        while t > 1e-4:
            Pt = P.copy()
            Pt[inner] += t * step[:-1]
            Ht0 = H0 + t * step[-1]
            if np.linalg.norm(rows(Pt, residual(Pt, Ht0)[1])) < (1 - 1e-4 * t) * norm:
                P, H0 = Pt, Ht0
                break
            t *= 0.5
        else:
            raise RuntimeError(f"line_contact_film: Newton stalled at λ = {lam:.3g} "
                               f"(residual {norm:.2e})")
    raise RuntimeError(f"line_contact_film: no convergence at λ = {lam:.3g}")


def _film(lam: float, x_in: float, x_out: float, n: int, elastic: bool,
          start: dict[str, Any] | None = None) -> dict[str, Any]:
    """Solve the film on n cells; from ``start`` (a coarser grid's film) or by continuation."""
    X = np.linspace(x_in, x_out, n + 1)
    d = X[1] - X[0]
    D = _influence(X, d)
    if start is not None:
        lams = [lam]
        P, H0 = np.interp(X, start["X"], start["P"]), float(start["H0"])
    else:
        # continuation from the rigid regime (λ₀ ≥ 30: H₀ ≈ 0.26 λ ≫ the elastic
        # deflection) down to λ in steps of ×0.5, from a Hertz-shaped pressure (at
        # P = 0 the rows do not depend on H₀)
        lams = [lam]
        while lams[-1] < 30.0 and elastic:
            lams.append(lams[-1] / 0.5)
        P = np.sqrt(np.clip(1.0 - X**2, 0.0, None))
        H0 = 0.26 * lams[-1]
    for k, lk in enumerate(reversed(lams)):    # (the path's points to 1e-6 only)
        P, H0 = _solve(lk, X, D, P, H0, elastic, tol=1e-11 if k == len(lams) - 1 else 1e-6)
    H = H0 + 0.5 * X**2 + (D @ P if elastic else 0.0)
    return {"X": X, "P": P, "H": H, "H0": H0}


def line_contact_film(w: float, mu: float, u_m: float, R: float, E_star: float,
                      x_in: float = -4.0, x_out: float = 4.0, n: int = 800,
                      elastic: bool = True) -> dict[str, Any]:
    """Return the isoviscous-elastic film of a cylinder on a plane (half-space, plane strain).

    Args:
        w: load per unit length (N/mm).
        mu: viscosity (MPa·s).
        u_m: mean surface speed (U₁ + U₂)/2 (mm/s).
        R: radius of the cylinder, or R* of two (mm).
        E_star: composite plane-strain modulus E* (MPa).
        x_in: the film's inlet end in units of the Hertz half-width a (p = 0 there).
        x_out: its outlet end, likewise.
        n: cells of the grid (solved on n and on n/2).
        elastic: False gives the rigid film (Martin's problem, to test the solver).

    Returns: ``h_central`` (at x = 0), ``h_min``, ``p_max`` (mm, MPa), their
    discretisation errors ``err_*`` (the difference to the grid of n/2, a bound
    where the error falls with the grid), ``lam``, ``a`` and ``p0`` (Hertz), and the
    profiles ``x``, ``p``, ``h`` (mm, MPa, mm).
    """
    a = math.sqrt(4 * w * R / (math.pi * E_star))
    p0 = 2 * w / (math.pi * a)
    lam = 12 * mu * u_m * R**2 / (a**3 * p0)
    out: dict[str, Any] = {"lam": lam, "a": a, "p0": p0}
    coarse_film = _film(lam, x_in, x_out, n // 2, elastic)
    sols = [coarse_film, _film(lam, x_in, x_out, n, elastic, start=coarse_film)]

    def values(s: dict[str, Any]) -> dict[str, float]:
        X, H, P = s["X"], s["H"], s["P"]
        return {"h_central": float(np.interp(0.0, X, H)) * a**2 / R,
                "h_min": float(H.min()) * a**2 / R, "p_max": float(P.max()) * p0}

    coarse, fine = values(sols[0]), values(sols[1])
    for k, val in fine.items():
        out[k] = val
        out["err_" + k] = abs(val - coarse[k])
    s = sols[1]
    out.update(x=s["X"] * a, p=s["P"] * p0, h=s["H"] * a**2 / R)
    return out
