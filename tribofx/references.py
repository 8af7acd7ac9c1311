"""Closed-form and quadrature references used to check tribofx results: each written once.

Every function here is pure (``math`` and NumPy only, no DOLFINx), documents its
formula, its source, its units and the range in which it is valid, and is
checked against an independent number in ``tests/test_references.py``.  The
cases, demos, benchmarks and tests import the references from this module.

Units are those of tribofx throughout: mm, N, s, MPa (so viscosity is MPa·s,
a load per unit length N/mm, a speed mm/s, an Archard coefficient
mm³/(N·mm)).

Contents:

* elastic contact (Hertz 1882): :func:`composite_modulus`, :func:`composite_radius`,
  :func:`hertz` (line and point contact of two bodies), :func:`hertz_reference`
  (the rigid-plane convenience);
* hydrodynamic lubrication of rigid surfaces: :func:`slider_pressure` and
  :func:`slider_reference` (inclined-pad slider bearing), :func:`cylinder_references`
  (cylinder near a plane: half-Sommerfeld and Swift–Stieber, by quadrature),
  :func:`rigid_clearance` (Martin 1916);
* soft EHL: :func:`hamrock_dowson` (isoviscous-elastic point contact, Hamrock and
  Dowson 1978), :func:`inverse_film` (inverse hydrodynamic theory, Blok 1963),
  :func:`line_contact_film` (the isoviscous-elastic line contact on a half-space,
  Herrebrugh's problem, solved numerically in :mod:`tribofx.references_line_ehl`);
* squeeze films (Reynolds 1886): :func:`squeeze_resistance`, :func:`squeeze_closed_form`,
  :func:`squeeze_film_under_load` (in :mod:`tribofx.references_squeeze`);
* Archard wear of a rigid ball: :func:`rigid_cap_depth`, :func:`rigid_cap_radius`
  (ball on a flat), :func:`rigid_groove_halfwidth` (ball on a track).

Not here, because they are not closed forms: the critical step of the explicit
wear scheme (chapter eq. 31 gives only the scaling Δt_cr ∼ h/E; tribofx measures
it by bisection, :func:`tribofx.studies.wear_stability.pin_critical_step` and
:func:`tribofx.studies.wear_stability.ball_critical_step`).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, NamedTuple, TypeVar, overload

import numpy as np

from .references_line_ehl import line_contact_film
from .references_squeeze import (
    squeeze_closed_form,
    squeeze_film_under_load,
    squeeze_resistance,
)

if TYPE_CHECKING:
    from collections.abc import Callable

    import numpy.typing as npt
    import ufl.core.expr

    #: a float or an array of them, the same type out as in
    FloatOrArray = TypeVar("FloatOrArray", float, npt.NDArray[np.float64])

__all__ = [
    "HertzContact",
    "barus_pressure",
    "composite_modulus",
    "composite_radius",
    "cylinder_references",
    "hamrock_dowson",
    "hertz",
    "hertz_reference",
    "inverse_film",
    "line_contact_film",
    "rigid_cap_depth",
    "rigid_cap_radius",
    "rigid_clearance",
    "rigid_groove_halfwidth",
    "slider_pressure",
    "slider_reference",
    "squeeze_closed_form",
    "squeeze_film_under_load",
    "squeeze_resistance",
]


# --------------------------------------------------------------------------- Hertz contact


def composite_modulus(E1: float, nu1: float, E2: float = math.inf, nu2: float = 0.0) -> float:
    """Contact (plane-strain composite) modulus E* of two elastic bodies, MPa.

    1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂  (Johnson, *Contact Mechanics*, 1985, §4.2).

    Args:
        E1: Young's modulus of body 1 (MPa).
        nu1: Poisson's ratio of body 1.
        E2: Young's modulus of body 2 (MPa); ``math.inf`` (the default) is a rigid
            body, for which ν₂ plays no role, so E* = E₁/(1 − ν₁²).
        nu2: Poisson's ratio of body 2.

    Valid for isotropic linear elastic bodies, −1 < ν < 1/2 (ν = 1/2 is allowed).
    """
    c = (1 - nu1**2) / E1 + (0.0 if math.isinf(E2) else (1 - nu2**2) / E2)
    if not c > 0:
        raise ValueError(f"composite compliance {c} <= 0: check the moduli and ratios")
    return 1.0 / c


def composite_radius(R1: float, R2: float = math.inf) -> float:
    """Relative (composite) radius of curvature R* of two surfaces in contact, mm.

    1/R* = 1/R₁ + 1/R₂ (Johnson 1985, §4.1).  Convention: a radius is positive for
    a convex surface, ``math.inf`` (the default) for a flat, negative for a concave
    surface (a ball in a groove or socket of radius |R₂| > R₁).  R = 0 is not a flat:
    it is rejected, as is a pair whose curvatures do not add up to a positive 1/R*.
    """
    if R1 == 0 or R2 == 0:
        raise ValueError("a radius of 0 has no curvature: use math.inf for a flat")
    k = (0.0 if math.isinf(R1) else 1 / R1) + (0.0 if math.isinf(R2) else 1 / R2)
    if not k > 0:
        raise ValueError(f"1/R* = {k} <= 0: the surfaces are not in non-conforming contact")
    return 1.0 / k


class HertzContact(NamedTuple):
    """Result of :func:`hertz` (mm, MPa)."""

    a: float        #: contact half-width (line) or radius (point), mm
    p0: float       #: peak pressure, MPa
    delta: float    #: mutual approach of distant points, mm (point contact; NaN for a line)
    E_star: float   #: composite modulus E*, MPa
    R_star: float   #: composite radius R*, mm

    def pressure(self, r: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Return p₀√(1 − r²/a²) (MPa, 0 outside) at r (mm) from the centre line/point."""
        return self.p0 * np.sqrt(np.maximum(0.0, 1.0 - np.asarray(r) ** 2 / self.a**2))


def hertz(load: float, R1: float, E1: float, nu1: float, R2: float = math.inf,
          E2: float = math.inf, nu2: float = 0.0, *, line: bool = False) -> HertzContact:
    """Hertz contact of two elastic bodies: size, peak pressure and approach.

    With E* = :func:`composite_modulus` (E₁, ν₁, E₂, ν₂) and R* =
    :func:`composite_radius` (R₁, R₂) (Hertz 1882; Johnson, *Contact Mechanics*,
    1985, §4.2):

    * point contact (spheres, or a sphere and a flat), load P in N:
      a = (3PR*/(4E*))^{1/3}, p₀ = 3P/(2πa²), δ = a²/R*  (Johnson eqs. 4.22–4.23);
      the pressure is p₀ (1 − r²/a²)^{1/2};
    * line contact (parallel cylinders, or a cylinder and a flat, plane strain),
      ``line=True``, load P per unit length in N/mm:
      a = (4PR*/(πE*))^{1/2}, p₀ = 2P/(πa) = (PE*/(πR*))^{1/2}; the pressure is
      p₀ (1 − x²/a²)^{1/2}.  The approach of a 2D contact depends on the size of the
      bodies (the half-plane displacement grows like ln r), so ``delta`` is NaN.

    Args:
        load: normal load P (N for a point contact, N/mm for a line contact).
        R1: radius of body 1 (mm).
        E1: Young's modulus of body 1 (MPa).
        nu1: Poisson's ratio of body 1.
        R2: radius of body 2 (mm); ``math.inf`` (the default) is a flat, R₂ < 0 a
            concave surface (see :func:`composite_radius`).
        E2: Young's modulus of body 2 (MPa); ``math.inf`` (the default) is rigid.
        nu2: Poisson's ratio of body 2.
        line: line contact (plane strain) instead of point contact.

    Valid for frictionless (or Dundurs β = 0) contact of linear elastic half-spaces:
    small strains, a ≪ R* (half-space and small-slope approximations, corrections of
    relative order a/R*), bodies large compared with a.  Returns a :class:`HertzContact`.
    """
    Es = composite_modulus(E1, nu1, E2, nu2)
    Rs = composite_radius(R1, R2)
    if line:
        a = math.sqrt(4 * load * Rs / (math.pi * Es))
        return HertzContact(a, 2 * load / (math.pi * a), math.nan, Es, Rs)
    a = (3 * load * Rs / (4 * Es)) ** (1 / 3)
    return HertzContact(a, 3 * load / (2 * math.pi * a * a), a * a / Rs, Es, Rs)


def hertz_reference(dim: int, E: float, nu: float, R: float,
                    load: float) -> tuple[float, float]:
    """Hertz contact of an elastic cylinder (dim = 2) or sphere (dim = 3) on a rigid plane.

    The rigid-plane convenience of :func:`hertz`: returns ``(a, p_max)``, the contact
    half-width (2D, load per unit length in N/mm) or radius (3D, load in N) in mm and
    the peak pressure in MPa, for E* = E/(1 − ν²).  Same validity as :func:`hertz`.
    """
    h = hertz(load, R, E, nu, line=dim == 2)
    return h.a, h.p0


# --------------------------------------------------------------------------- rigid lubrication


@overload
def slider_pressure(x: float, K: float, L: float, h0: float, U: float, mu: float) -> float: ...


@overload
def slider_pressure(x: npt.NDArray[np.float64], K: float, L: float, h0: float, U: float,
                    mu: float) -> npt.NDArray[np.float64]: ...


@overload
def slider_pressure(x: ufl.core.expr.Expr, K: float, L: float, h0: float, U: float,
                    mu: float) -> ufl.core.expr.Expr: ...


def slider_pressure(x: float | npt.NDArray[np.float64] | ufl.core.expr.Expr, K: float, L: float,
                    h0: float, U: float,
                    mu: float) -> float | npt.NDArray[np.float64] | ufl.core.expr.Expr:
    """Pressure (MPa) of the plane inclined slider bearing at x (mm), 0 ≤ x ≤ L.

    Film h = h₀(1 + K − Kx/L) (outlet film h₀, inlet h₀(1 + K)), one surface sliding
    at U (mm/s) towards the narrowing gap, the other at rest (mean speed U/2), p = 0
    at both ends, viscosity μ (MPa·s); with s = x/L (Reynolds 1886; Cameron, *Basic
    Lubrication Theory*, 3rd ed. 1981, the plane inclined pad):

        p(x) = 6μUL K s(1 − s) / (h₀² (2 + K) (1 + K − Ks)²).

    Written with arithmetic operators only, so x may be a float, a NumPy array or
    any expression type that supports them (e.g. a UFL expression).  Valid for a
    rigid, infinitely wide pad (no side leakage), isoviscous incompressible
    Newtonian fluid, h ≪ L, K > −1.
    """
    s = x / L
    return 6 * mu * U * L / h0**2 * K * s * (1 - s) / ((2 + K) * (1 + K - K * s) ** 2)


@overload
def barus_pressure(p_iso: float, alpha: float,
                   log: Callable[[float], float] = math.log) -> float: ...


@overload
def barus_pressure(p_iso: npt.NDArray[np.float64], alpha: float,
                   log: Callable[[npt.NDArray[np.float64]], npt.NDArray[np.float64]]
                   ) -> npt.NDArray[np.float64]: ...


@overload
def barus_pressure(p_iso: ufl.core.expr.Expr, alpha: float,
                   log: Callable[[ufl.core.expr.Expr], ufl.core.expr.Expr]
                   ) -> ufl.core.expr.Expr: ...


def barus_pressure(p_iso: float | npt.NDArray[np.float64] | ufl.core.expr.Expr, alpha: float,
                   log: Callable[[Any], Any] = math.log
                   ) -> float | npt.NDArray[np.float64] | ufl.core.expr.Expr:
    """Pressure of a Barus fluid μ₀ e^{αp} from the isoviscous one of the same film: p(x).

    With the reduced pressure q = (1 − e^{−αp})/α, h³/(12μ₀e^{αp}) ∇p = h³/(12μ₀) ∇q,
    so q solves the isoviscous Reynolds equation with the same p = q = 0 boundary
    conditions of a rigid film: q = p_iso, p = −ln(1 − α p_iso)/α, while α p_iso < 1
    (Barus 1893; the transform of Hamrock, Schmid & Jacobson 2004, §4.10).  ``log``:
    ``math.log``, ``numpy.log`` or ``ufl.ln`` for the argument's type.
    """
    return -log(1 - alpha * p_iso) / alpha


def slider_reference(K: float, L: float, h0: float, U: float, mu: float) -> dict[str, Any]:
    """Plane inclined slider bearing: pressure, load, peak pressure and its position.

    With :func:`slider_pressure` p(x) (same arguments and validity; K = h_in/h₀ − 1),
    the classical results (Cameron 1981; Hamrock, Schmid & Jacobson, *Fundamentals
    of Fluid Film Lubrication*, 2nd ed. 2004, fixed-incline slider bearing):

        W/B = ∫₀ᴸ p dx = (6μUL²/(K² h₀²)) (ln(1 + K) − 2K/(2 + K))   (N/mm),
        x_pmax = L (1 + K)/(2 + K),   p_max = 3μUL K / (2 h₀² (1 + K)(2 + K))   (MPa).

    Returns a dict with ``pressure`` (callable of x, NumPy), ``load`` (N/mm),
    ``p_max`` (MPa) and ``x_p_max`` (mm).
    """
    def pressure(x: npt.ArrayLike) -> npt.NDArray[np.float64]:
        return slider_pressure(np.asarray(x, dtype=float), K, L, h0, U, mu)

    if abs(K) < 1e-12:
        return {"pressure": pressure, "load": 0.0, "p_max": 0.0, "x_p_max": 0.5 * L}
    load = 6 * mu * U * L**2 / (K**2 * h0**2) * (math.log1p(K) - 2 * K / (2 + K))
    x_m = L * (1 + K) / (2 + K)
    return {"pressure": pressure, "load": load, "p_max": float(pressure(x_m)), "x_p_max": x_m}


def _cumtrapz(f: npt.NDArray[np.float64], x: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    out = np.zeros_like(f)
    out[1:] = np.cumsum(0.5 * (f[1:] + f[:-1]) * np.diff(x))
    return out


def _simpson(f: npt.NDArray[np.float64], x: npt.NDArray[np.float64]) -> float:
    n = len(x) - 1
    assert n % 2 == 0
    dx = (x[-1] - x[0]) / n
    return dx / 3 * (f[0] + f[-1] + 4 * f[1:-1:2].sum() + 2 * f[2:-1:2].sum())


def cylinder_references(R: float, h0: float, um: float, mu: float, x_in: float, x_out: float,
                        n: int = 200_000, inlet_void: float = 0.0) -> dict[str, dict[str, Any]]:
    """Half-Sommerfeld and Swift–Stieber solutions of the rigid cylinder–plane contact.

    Rigid cylinder of radius R (mm) near a rigid plane, parabolic gap
    h = h₀ + x²/(2R) on x_in ≤ x ≤ x_out (mm), mean entrainment speed u_m (mm/s),
    viscosity μ (MPa·s), p(x_in) = 0.  The steady 1D Reynolds equation integrates
    once to p' = 12μu_m (h − h*)/h³; then:

    * half-Sommerfeld (Gümbel 1914): the full Sommerfeld solution with
      p(x_in) = p(x_out) = 0 (h* = ∫h⁻² dx / ∫h⁻³ dx), negative pressures set to zero;
    * Swift–Stieber (Reynolds) conditions (Swift 1932, Stieber 1933):
      p = p' = 0 at the unknown rupture point x_r (so h* = h(x_r)), found by bisection.
      With ``inlet_void`` λ_in > 0 (starved inlet, JFO) the supplied flux
      Q = (1 − λ_in) h(x_in) u_m gives h* = Q/u_m, hence x_r (h(x_r) = h*), and the
      reformation point x_f where the film fills the gap and the pressure starts
      solves ∫_{x_f}^{x_r} (h − h*)/h³ dx = 0.

    Computed by NumPy quadrature with ``n`` intervals of width Δx: h* and x_r by
    composite Simpson (fourth order, ≲ 10⁻⁸ relative for n = 2·10⁵), the pressure and
    the load by the cumulative trapezoid rule (second order, ≈ (Δx/ℓ)² relative,
    ℓ = √(2Rh₀)).  For
    x_in → −∞ the loads tend to 4 μu_m R/h₀ (half-Sommerfeld, x_out → ∞) and to
    Martin's 4.9 μu_m R/h₀ (Swift–Stieber, :func:`rigid_clearance`).  Valid for
    rigid surfaces, h ≪ R, isoviscous incompressible Newtonian fluid, no side
    leakage (loads per unit length).

    Returns {"half_sommerfeld": d, "swift_stieber": d}, each d with ``x``, ``p`` (MPa)
    on a fine grid and ``load`` (N/mm), ``p_max`` (MPa), ``x_p_max``, ``x_rupture``
    (mm), ``h_star`` (mm, film thickness at which p' = 0) and ``flux`` = h* u_m
    (mm²/s); Swift–Stieber also ``x_reformation``, half-Sommerfeld ``p_full`` (the
    full Sommerfeld pressure), whose zero downstream of its maximum is its
    ``x_rupture``.  Raises ValueError if x_out lies upstream of the Swift–Stieber
    rupture point or if the starved film does not reform inside [x_in, x_out].
    """
    n += n % 2

    def gap(x: FloatOrArray) -> FloatOrArray:
        return h0 + x**2 / (2 * R)

    c = 12 * mu * um
    refs = {}
    # full Sommerfeld, p(x_in) = p(x_out) = 0
    x = np.linspace(x_in, x_out, n + 1)
    h = gap(x)
    hs = _simpson(h**-2, x) / _simpson(h**-3, x)
    p = c * _cumtrapz((h - hs) / h**3, x)
    i = int(np.argmax(p))
    neg = np.nonzero(p[i:] < 0)[0]
    if len(neg):
        j = i + neg[0]
        xr = x[j - 1] - p[j - 1] * (x[j] - x[j - 1]) / (p[j] - p[j - 1])
    else:
        xr = x_out
    pp = np.maximum(p, 0)
    refs["half_sommerfeld"] = {"x": x, "p": pp, "p_full": p, "load": _simpson(pp, x),
                               "p_max": p[i], "x_p_max": x[i], "x_rupture": xr,
                               "h_star": hs, "flux": hs * um}

    def G(xa: float, xb: float, hs: float) -> float:
        xs = np.linspace(xa, xb, n // 4 + 1)
        hh = gap(xs)
        return _simpson((hh - hs) / hh**3, xs)

    def bisect(f: Callable[[float], float], a: float, b: float) -> float:
        for _ in range(80):
            m = 0.5 * (a + b)
            a, b = (m, b) if f(m) > 0 else (a, m)
        return 0.5 * (a + b)

    if inlet_void == 0:
        # Swift–Stieber: bisection on the rupture point x_r, p(x_r)/c = G(x_in, x_r) = 0
        if G(x_in, x_out, gap(x_out)) > 0:
            raise ValueError(f"x_out = {x_out} mm lies upstream of the Swift–Stieber "
                             "rupture point")
        xr = bisect(lambda xr: G(x_in, xr, gap(xr)), 0.0, x_out)
        xf = x_in
    else:
        # starved inlet: h* from the supplied flux, x_f from G(x_f, x_r) = 0
        hs = (1 - inlet_void) * gap(x_in)
        if hs <= h0:
            raise ValueError(f"inlet_void = {inlet_void} starves the contact completely")
        xr = math.sqrt(2 * R * (hs - h0))
        if xr >= x_out or G(x_in, xr, hs) <= 0:
            raise ValueError(f"inlet_void = {inlet_void}: the supplied film does not reform "
                             "inside [x_in, x_out] (not starved, or x_out too small)")
        xf = bisect(lambda xf: G(xf, xr, hs), x_in, -xr)
    hs = gap(xr)
    x = np.linspace(x_in, x_out, n + 1)
    h = gap(x)
    p = np.zeros_like(x)
    full = (x >= xf) & (x < xr)
    p[full] = c * _cumtrapz((h[full] - hs) / h[full] ** 3, x[full])
    p = np.maximum(p, 0)
    i = int(np.argmax(p))
    refs["swift_stieber"] = {"x": x, "p": p, "load": _simpson(p, x), "p_max": p[i],
                             "x_p_max": x[i], "x_rupture": xr, "x_reformation": xf,
                             "h_star": hs, "flux": hs * um}
    return refs


def rigid_clearance(W: float, mu: float, U: float, R: float) -> float:
    """Minimum film h₀ (mm) of a rigid cylinder in pure sliding on a plane at load W.

    Martin (1916, *Engineering* 102, 119) with the Reynolds (Swift–Stieber) exit
    condition and a fully flooded inlet: W = 4.9 μ u_m R/h₀ with the mean speed
    u_m = U/2, i.e. h₀ = 2.45 μUR/W (rupture at x_r = 0.475 √(2Rh₀)).

    Args: W load per unit length (N/mm), μ viscosity (MPa·s), U sliding speed of one
    surface, the other at rest (mm/s), R cylinder radius (mm).  Valid for rigid
    surfaces, isoviscous Newtonian fluid, h₀ ≪ R, inlet far upstream (≳ 10 √(2Rh₀)).
    """
    return 2.45 * mu * U * R / W


# --------------------------------------------------------------------------- soft EHL


def hamrock_dowson(W: float, mu: float, U: float, R: float, E_star: float,
                   k: float = 1.0) -> tuple[float, float]:
    """Isoviscous-elastic (soft-EHL) central and minimum film (mm) of Hamrock & Dowson (1978).

    B.J. Hamrock, D. Dowson, "Elastohydrodynamic lubrication of elliptical contacts
    for materials of low elastic modulus I — fully flooded conjunction", ASME J.
    Lubr. Technol. 100 (1978) 236–245:

        Ĥ_c   = 7.32 (1 − 0.72 e^{−0.28k}) Û^0.64 Ŵ^−0.22,
        Ĥ_min = 7.43 (1 − 0.85 e^{−0.31k}) Û^0.65 Ŵ^−0.21,

    Ĥ = h/R_x, Û = μ u_m/(E' R_x), Ŵ = W/(E' R_x²), E' = 2E* (E* of
    :func:`composite_modulus`; for a rigid plane E' = 2E/(1 − ν²)).

    Args:
        W: normal load (N).
        mu: viscosity (MPa·s).
        U: mean entrainment speed u_m = (u₁ + u₂)/2 (mm/s; a ball at rest on a plane
            sliding at V has U = V/2).
        R: radius R_x in the entrainment direction (mm; a ball on a plane: its radius).
        E_star: composite modulus E* (MPa).
        k: ellipticity a_y/a_x (1: ball).

    Returns ``(h_c, h_min)``.  Valid in the isoviscous-elastic regime (no
    piezoviscous effect, elastic deformation large against the rigid film), fully
    flooded, isothermal, Newtonian, linear-elastic half-space (a ≪ R), k ≥ 1
    (the authors computed k = 1 to 12).
    """
    Ep = 2 * E_star
    Uh, Wh = mu * U / (Ep * R), W / (Ep * R * R)
    Hc = 7.32 * (1 - 0.72 * math.exp(-0.28 * k)) * Uh**0.64 * Wh**-0.22
    Hm = 7.43 * (1 - 0.85 * math.exp(-0.31 * k)) * Uh**0.65 * Wh**-0.21
    return Hc * R, Hm * R


def inverse_film(mu: float, U: float, w: float) -> float:
    """Film thickness h_c (mm) at the pressure maximum by the inverse hydrodynamic theory.

    Blok (1963, "Inverse problems in hydrodynamic lubrication and design directives
    for lubricated flexible surfaces", Proc. Int. Symp. Lubrication and Wear,
    Houston): in a steady 1D film the flux q = ½Uh − h³p'/(12μ) is constant, so
    p' = 6μU(h − h_c)/h³ with h_c = 2q/U the film where p' = 0 (the pressure
    maximum).  At the inlet point of maximum pressure gradient w (MPa/mm), where
    p'' = 0, the film is h* = 1.5 h_c = 3q/U and w = 2μU/h*², so

        h_c = 2q/U = √(8μ|U|/(9w)),   h* = 1.5 h_c.

    Args: μ viscosity (MPa·s); U = u₁ + u₂ the sum of the surface speeds (mm/s; a rod
    sliding under a seal at rest: the rod speed); w the largest inlet pressure
    gradient (MPa/mm).  Valid for an incompressible isoviscous Newtonian film,
    without cavitation between the inlet gradient maximum and the pressure maximum.
    """
    return math.sqrt(8 * mu * abs(U) / (9 * w))


# --------------------------------------------------------------------------- Archard wear


def rigid_cap_depth(k: float, F: float, R: float, s: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Worn depth h (mm) of a rigid ball sliding on a flat by Archard's law, h = √(kFs/(πR)).

    Archard (1953): worn volume k F s.  A rigid sphere worn flat to depth h loses
    the cap π h² (3R − h)/3 ≈ π R h² (h ≪ R), hence h² = kFs/(πR), whatever the
    pressure distribution.  Args: k Archard coefficient (mm³/(N·mm)), F normal load
    (N), R ball radius (mm), s sliding distance (mm; float or array).  Valid for
    h ≪ R (relative error ≈ h/(6R)) and a scar much larger than the Hertz contact
    (the elastic approach ∼ a_H²/R small against h), constant k.
    """
    return np.sqrt(k * F * np.asarray(s, dtype=float) / (math.pi * R))


def rigid_cap_radius(k: float, F: float, R: float, s: npt.ArrayLike) -> npt.NDArray[np.float64]:
    """Scar radius a (mm) of a rigid ball worn flat by Archard's law, a = (4kFRs/π)^{1/4}.

    The flat-scar radius a² ≈ 2Rh of :func:`rigid_cap_depth` (same arguments and
    validity; the relative error is ≈ h/(6R)); with the uniform wear rate of a
    flat scar, the pressure is uniform, F/(πa²) (chapter §5.2, Stupkiewicz 2013).
    """
    return (4 * k * F * R * np.asarray(s, dtype=float) / math.pi) ** 0.25


def rigid_groove_halfwidth(k: float, F: float, R: float, s: npt.ArrayLike,
                           L: float) -> npt.NDArray[np.float64]:
    """Half-width b (mm) of the groove worn by a rigid ball on a track by Archard's law.

    The ball (radius R, load F) slides the distance s over a closed track of length
    L (mm): the worn volume k F s spreads over the track, so the groove
    cross-section area is kFs/L.  A groove conforming to the ball has the depth
    b²/(2R) and the area 2b³/(3R) (parabolic profile, b ≪ R), so
    b = (3RkFs/(2L))^{1/3}.  Valid for b ≪ R, a groove much wider than the Hertz
    contact, wear spread uniformly along the track (many passes), constant k.
    """
    return (1.5 * R * k * F * np.asarray(s, dtype=float) / L) ** (1 / 3)
