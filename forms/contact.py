"""Frictional contact with a rigid countersurface by the augmented Lagrangian method (chapter §2).

Kinematics (eqs. 2–3): the slave point x = X + u is projected onto the master
(rigid) surface; the projection x̄, the unit outer normal n of the master surface
and the signed normal gap g_N = (x − x̄)·n are returned as UFL expressions of x by
the countersurface functions below (analytic plane, cylinder, sphere, or a meshed
surface through the data of the C++ closest-point kernel).

Enforcement (eqs. 4–5, 8–9) follows Alart and Curnier: the nominal contact
tractions are unknown multipliers λ_N (scalar) and λ_T (vector) on the reference
slave surface Γ_c, with the augmented quantities

    λ̂_N = λ_N + ρ_N g_N,          T_N = min(λ̂_N, 0),
    λ̂_T = (I − n⊗n) λ_T + ρ_T s,  T_T = proj_{‖·‖ ≤ μ|T_N|}(λ̂_T),

where s is the slip increment (Lagrangian) or the slip velocity times a
pseudo-time scale (Eulerian steady sliding, eq. 26–27); the virtual work of the
friction traction is done on the variation δx̄ of the projection point (T_Tα δξ̄^α
of eq. 8).  The residual reads

    G_c = ∫_Γc (T_N δg_N + T_T·δx̄) dS
        − ∫_Γc (1/ρ_N)(λ_N − T_N) δλ_N dS − ∫_Γc (1/ρ_T)(λ_T − T_T)·δλ_T dS,

a nonsmooth but semismooth function of the unknowns; ``ufl.derivative`` of the
``conditional`` branches gives the exact generalised Jacobian.  Units: mm, MPa.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import ufl

if TYPE_CHECKING:
    from ufl.core.expr import Expr

__all__ = [
    "constant_friction",
    "pressure_dependent_friction",
    "multiplier_regularisation",
    "ContactGeometry",
    "augmented_lagrangian_contact",
    "contact_tractions",
    "cylinder_countersurface",
    "eulerian_slip",
    "lagrangian_slip",
    "meshed_countersurface",
    "plane_countersurface",
    "sphere_countersurface",
]


@dataclass(frozen=True)
class ContactGeometry:
    """UFL expressions of the closest-point projection of the slave point x (eq. 2).

    Attributes:
        gap: signed normal gap g_N = (x − x̄)·n (mm), positive when separated.
        normal: unit outer normal n of the master surface at x̄.
        projection: projection point x̄ on the master surface (mm).
    """

    gap: ufl.core.expr.Expr
    normal: ufl.core.expr.Expr
    projection: ufl.core.expr.Expr


def plane_countersurface(x: Expr, point: Expr, normal: Expr) -> ContactGeometry:
    """Rigid plane through ``point`` with unit outer normal ``normal`` (pointing to the body)."""
    g = ufl.dot(x - point, normal)
    return ContactGeometry(gap=g, normal=normal, projection=x - g * normal)


def _radial(x: Expr, center: Expr, axis: Expr | None) -> Expr:
    d = x - center
    if axis is not None:
        d = d - ufl.dot(d, axis) * axis
    return d


def cylinder_countersurface(
    x: Expr, center: Expr, radius: Expr | float, axis: Expr | None = None
) -> ContactGeometry:
    """Rigid cylinder (disc in 2D) of ``radius`` about ``center``; body outside it.

    In 3D ``axis`` is the unit axis of the cylinder; in 2D pass ``axis=None``.
    """
    d = _radial(x, center, axis)
    r = ufl.sqrt(ufl.dot(d, d))
    n = d / r
    return ContactGeometry(gap=r - radius, normal=n, projection=x - (r - radius) * n)


def sphere_countersurface(x: Expr, center: Expr, radius: Expr | float) -> ContactGeometry:
    """Rigid sphere of ``radius`` about ``center``; body outside it."""
    return cylinder_countersurface(x, center, radius, axis=None)


def meshed_countersurface(
    x: Expr, x0: Expr, gap0: Expr, normal0: Expr, dnormal_dx: Expr, xbar0: Expr,
    dxbar_dx: Expr, d2xbar_dx2: Expr | None = None,
) -> ContactGeometry:
    """Countersurface given as a mesh, through closest-point data at the expansion point x0.

    The C++ kernel returns, at the current slave positions x0, the gap g₀, the
    normal n₀, its derivative ∂n/∂x (= ∂²g/∂x²), the projection x̄₀ and ∂x̄/∂x.
    They enter as second-order Taylor expansions in d = x − x0,

        g(x) = g₀ + n₀·d + ½ d·(∂n/∂x) d,   n(x) = n₀ + (∂n/∂x) d,
        x̄(x) = x̄₀ + (∂x̄/∂x) d + ½ (∂²x̄/∂x²)[d, d],

    so that value, first and second derivatives of g_N and x̄ at x = x0 are exact
    and the Newton tangent is consistent, friction included (the data are
    refreshed at every iterate).  Without ``d2xbar_dx2`` (flat facets) the last
    term is dropped.
    """
    d = x - x0
    g = gap0 + ufl.dot(normal0, d) + 0.5 * ufl.dot(d, dnormal_dx * d)
    xbar = xbar0 + dxbar_dx * d
    if d2xbar_dx2 is not None:
        xbar += 0.5 * ufl.dot(ufl.dot(d2xbar_dx2, d), d)
    return ContactGeometry(gap=g, normal=normal0 + dnormal_dx * d, projection=xbar)


def lagrangian_slip(geometry: ContactGeometry, xbar_old: Expr) -> Expr:
    """Slip increment s = x̄(x) − x̄_old of the projection point over a load step (mm)."""
    return geometry.projection - xbar_old


def eulerian_slip(
    u: Expr, geometry: ContactGeometry, V: Expr, V_master: Expr, dtau: Expr | float
) -> Expr:
    """Steady sliding slip v_T Δτ with v = F V (eq. 26) and v_T its tangential part (eq. 27).

    ``V`` is the background velocity of the slave body in its reference frame,
    ``V_master`` the velocity of the rigid master surface (mm/s) and ``dtau`` a
    pseudo-time scale (s) that turns the velocity into a slip for the
    augmented Lagrangian.
    """
    n = geometry.normal
    F = ufl.Identity(len(u)) + ufl.grad(u)
    vrel = F * V - V_master
    return (vrel - ufl.dot(vrel, n) * n) * dtau


def contact_tractions(
    geometry: ContactGeometry, lam_n: Expr, rho_n: Expr | float, lam_t: Expr | None = None,
    rho_t: Expr | float | None = None, slip: Expr | None = None,
    mu: float | Callable[[Expr], Expr] | None = None,
) -> tuple[Expr, Expr | None]:
    """Nominal tractions (T_N, T_T) of the Alart–Curnier law as UFL expressions.

    T_N ≤ 0 is the nominal normal traction (eq. 9); T_T the frictional traction,
    inside the Coulomb cone ‖T_T‖ ≤ μ|T_N| (eq. 5).  Without friction T_T is None.
    ``mu``: the friction coefficient, a number or a friction law, a callable of the
    contact pressure −T_N (e.g. :func:`pressure_dependent_friction`).
    """
    lhat_n = lam_n + rho_n * geometry.gap
    t_n = ufl.conditional(ufl.lt(lhat_n, 0), lhat_n, 0)
    if lam_t is None:
        return t_n, None
    # friction gives lam_t with rho_t, slip and mu (the lines below raise on a None)
    assert rho_t is not None and slip is not None and mu is not None
    n = geometry.normal
    # tangential parts only: a Lagrangian slip is a chord of a curved countersurface
    lhat_t = lam_t - ufl.dot(lam_t, n) * n + rho_t * (slip - ufl.dot(slip, n) * n)
    radius = -(mu(-t_n) if callable(mu) else mu) * t_n
    norm = ufl.sqrt(ufl.dot(lhat_t, lhat_t) + 1e-24)
    t_t = ufl.conditional(ufl.lt(norm, radius), lhat_t, radius / norm * lhat_t)
    return t_n, t_t


def augmented_lagrangian_contact(
    u: ufl.Coefficient, v: Expr, geometry: ContactGeometry, lam_n: Expr, mu_n: Expr,
    rho_n: Expr | float, ds: ufl.Measure, lam_t: Expr | None = None,
    mu_t: Expr | None = None, rho_t: Expr | float | None = None,
    slip: Expr | None = None, mu: float | Callable[[Expr], Expr] | None = None,
    weight: Expr | float = 1,
) -> tuple[ufl.Form, ufl.Form, ufl.Form | None]:
    """Contact residual blocks (eq. 8 with the Alart–Curnier constraint equations).

    Args:
        u: displacement (bulk space).
        v: test function of the displacement.
        geometry: :class:`ContactGeometry` of the countersurface at x = X + u.
        lam_n: normal multiplier, the nominal normal traction (MPa).
        mu_n: test function of ``lam_n``.
        rho_n: normal augmentation parameter (MPa/mm).
        ds: measure over the reference slave surface Γ_c.
        lam_t: tangential multiplier (MPa); None for frictionless contact.
        mu_t: test function of ``lam_t``.
        rho_t: tangential augmentation (MPa per unit of ``slip``).
        slip: slip expression (Lagrangian increment or Eulerian v_T Δτ).
        mu: Coulomb friction coefficient.
        weight: reference measure factor of the virtual work (2πR for axisymmetric
            bodies, else 1).

    Returns:
        (R_u, R_n, R_t): contributions to the momentum residual and the normal and
        tangential constraint residuals (R_t is None without friction).
    """
    t_n, t_t = contact_tractions(geometry, lam_n, rho_n, lam_t, rho_t, slip, mu)
    R_u = t_n * ufl.derivative(geometry.gap, u, v) * weight * ds
    # the constraint rows hold pointwise (vertex rule): no 2πR weight, which would
    # make the rows of nodes on the axis of an axisymmetric body vanish
    R_n = -(1 / rho_n) * (lam_n - t_n) * mu_n * ds
    R_t = None
    if lam_t is not None:
        R_u += ufl.dot(t_t, ufl.derivative(geometry.projection, u, v)) * weight * ds
        assert rho_t is not None    # given with lam_t (1/None raises)
        R_t = -(1 / rho_t) * ufl.dot(lam_t - t_t, mu_t) * ds
    return R_u, R_n, R_t


def multiplier_regularisation(
    lam: Expr, mu: Expr, rho: Expr | float, ds: ufl.Measure
) -> ufl.Form:
    """Return the linear part −∫ (1/ρ) λ·δλ dS of the Alart–Curnier constraint rows.

    Of −(1/ρ)(λ − T(λ, g)): the part that stays when T is evaluated outside UFL
    (the two-body contact's kernel adds (1/ρ) T); scalar or vector ``lam``.
    """
    return -(1 / rho) * ufl.inner(lam, mu) * ds


def constant_friction(p: Expr, mu: Expr | float) -> Expr:
    """Coulomb's constant friction coefficient μ (the chapter's)."""
    return mu + 0 * p


def pressure_dependent_friction(
    p: Expr, mu0: Expr | float, p0: Expr | float, n: Expr | float
) -> Expr:
    """μ(p) = μ₀ (1 + p/p₀)^(−n): friction falling with the contact pressure p ≥ 0 (MPa).

    The form of rubber-like (real area of contact) friction, μ ∝ p^(−n) above p₀
    with n ≈ 1/3 (Schallamach 1952); μ₀ at vanishing pressure.
    """
    return mu0 * (1 + ufl.max_value(p, 0) / p0) ** (-n)
