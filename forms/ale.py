"""Shape mapping Ψ of the worn body as an ALE field on the initial mesh (chapter §4.1, §4.4).

Three configurations (eq. 19): initial Ω̂ (the mesh, never moved), worn
undeformed Ω = Ψ(Ω̂) and deformed ω.  On the initial mesh

    X = Ψ(X̂) = X̂ + w,        x = X̂ + u,

i.e. the displacement ``u`` is measured from the *initial* configuration (so the
contact kinematics x = X̂ + u of ``forms/contact`` is unchanged and the contact
multiplier is a traction per unit initial area).  With G = I + Grad_X̂ w the
deformation gradient relative to the worn configuration and the measures are

    F = (I + Grad_X̂ u) G⁻¹,   dV = det G dV̂,   N dS = cof(G) N̂ dŜ   (Nanson).

The stress-free state of the worn body is u = w (F = I).  Only ``"3d"`` and
``"plane_strain"`` kinematics are supported here (the hoop stretch of an
axisymmetric worn body would need the worn radius).

The interior of Ψ is fixed by an auxiliary (linear) elasticity problem on Ω̂
driven by the normal component of the wear increment on Γ̂_c (eq. 28), with the
tangential component free there and zero normal motion on the rest of the
boundary (set by the driver as Dirichlet conditions on the normal component).
Lengths in mm.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

import ufl

from .hyperelastic import first_piola, strain_energy
from .kinematics import grad3

if TYPE_CHECKING:
    from ufl.core.expr import Expr

__all__ = [
    "aux_elasticity",
    "cofactor",
    "deformation_gradient_worn",
    "internal_virtual_work_worn",
    "nanson_vector",
    "shape_gradient",
    "shape_multiplier_work",
    "stored_energy_worn",
    "swept_nanson_vector",
    "traction_work_worn",
]


def _check(kind: str) -> None:
    if kind not in ("3d", "plane_strain"):
        raise ValueError(f"worn-body kinematics support '3d' and 'plane_strain', not {kind!r}")


def shape_gradient(w: Expr) -> Expr:
    """G = Grad_X̂ Ψ = I + Grad_X̂ w (gdim × gdim)."""
    return ufl.Identity(len(w)) + ufl.grad(w)


def cofactor(G: Expr) -> Expr:
    """Cofactor matrix cof G = det(G) G^{-T}, written polynomially (no division) in 2D/3D."""
    n = G.ufl_shape[0]
    if n == 2:
        return ufl.as_matrix([[G[1, 1], -G[1, 0]], [-G[0, 1], G[0, 0]]])
    return ufl.as_matrix([
        [G[(i + 1) % 3, (j + 1) % 3] * G[(i + 2) % 3, (j + 2) % 3]
         - G[(i + 1) % 3, (j + 2) % 3] * G[(i + 2) % 3, (j + 1) % 3] for j in range(3)]
        for i in range(3)])


def nanson_vector(w: Expr, N_hat: Expr) -> Expr:
    """Unnormalised worn normal a = cof(G) N̂ with |a| = dS/dŜ = j_w (Nanson's formula).

    On a boundary facet cof(G) N̂ depends on the tangential derivative of w only,
    so it is well defined for a continuous piecewise linear w.
    """
    return cofactor(shape_gradient(w)) * N_hat


def swept_nanson_vector(w: Expr, w_old: Expr, N_hat: Expr) -> Expr:
    """Time average over a step of the Nanson vector, ∫₀¹ cof(G(s)) N̂ ds, G(s) linear in s.

    For a P1 boundary facet whose vertices move linearly from w_n to w, the
    volume swept per unit initial area is (w − w_n)·∫₀¹ a(s) ds (eq. 28 with
    this ``a`` is then an exact discrete volume balance).  cof G is linear in G
    in 2D (the mid-step vector a(½) is exact) and quadratic in 3D, where
    Simpson's rule (a(0) + 4 a(½) + a(1))/6 is exact.
    """
    if len(w) == 2:
        return nanson_vector(0.5 * (w + w_old), N_hat)
    return (nanson_vector(w_old, N_hat) + 4 * nanson_vector(0.5 * (w + w_old), N_hat)
            + nanson_vector(w, N_hat)) / 6


def _G3(w: ufl.Coefficient, kind: str) -> Expr:
    _check(kind)
    return ufl.Identity(3) + grad3(w, kind)


def deformation_gradient_worn(u: ufl.Coefficient, w: ufl.Coefficient, kind: str) -> Expr:
    """F = (I + Grad_X̂ u)(I + Grad_X̂ w)⁻¹ (3×3; plane strain embeds F₃₃ = 1)."""
    return (ufl.Identity(3) + grad3(u, kind)) * ufl.inv(_G3(w, kind))


def internal_virtual_work_worn(
    u: ufl.Coefficient, w: ufl.Coefficient, du: ufl.Coefficient | ufl.Argument, kind: str,
    material: str, params: Mapping[str, Expr | float], dx: ufl.Measure,
) -> ufl.Form:
    """∫_Ω P(F) : Grad_X δu dV pulled back to Ω̂: ∫ P : (Grad_X̂ δu G⁻¹) det G dV̂."""
    G = _G3(w, kind)
    Ginv = ufl.inv(G)
    F = (ufl.Identity(3) + grad3(u, kind)) * Ginv
    P = first_piola(F, material, params)
    return ufl.inner(P, grad3(du, kind) * Ginv) * ufl.det(G) * dx


def stored_energy_worn(
    u: ufl.Coefficient, w: ufl.Coefficient, kind: str, material: str,
    params: Mapping[str, Expr | float], dx: ufl.Measure,
) -> ufl.Form:
    """Return the stored energy ∫_Ω ψ(F) dV pulled back to Ω̂: ∫ ψ(F) det G dV̂."""
    G = _G3(w, kind)
    F = (ufl.Identity(3) + grad3(u, kind)) * ufl.inv(G)
    return strain_energy(F, material, params) * ufl.det(G) * dx


def traction_work_worn(
    traction: Expr, w: Expr, du: Expr, N_hat: Expr, ds: ufl.Measure
) -> ufl.Form:
    """Work of a dead nominal traction T* given per unit *worn* area: ∫ T*·δu j_w dŜ."""
    a = nanson_vector(w, N_hat)
    return ufl.dot(traction, du) * ufl.sqrt(ufl.dot(a, a)) * ds


def aux_elasticity(
    w: Expr, dw: Expr, mu: Expr | float, lmbda: Expr | float, dx: ufl.Measure
) -> ufl.Form:
    """Auxiliary (mesh-motion) linear elasticity ∫ σ(w) : ε(δw) dV̂ on the initial mesh.

    ``mu``, ``lmbda`` are Lamé constants of the fictitious material (MPa); only
    their ratio matters for Ψ, their size scales the constraint multiplier.
    """
    eps = ufl.sym(ufl.grad(w))
    return (2 * mu * ufl.inner(eps, ufl.sym(ufl.grad(dw)))
            + lmbda * ufl.tr(eps) * ufl.div(dw)) * dx


def shape_multiplier_work(zeta: Expr, dw: Expr, a: Expr, ds: ufl.Measure) -> ufl.Form:
    """Work of the shape-update multiplier on the auxiliary problem, ∫ ζ δw·a dŜ (eq. 28).

    The discrete shape evolution law (28), (w − w_n)·a = −Δt Ẇ j_w on Γ̂_c, is
    imposed nodally (vertex quadrature ``ds``) by a multiplier ζ; its reaction
    on the auxiliary elasticity of w acts along ``a``, so the tangential component
    of w on Γ̂_c stays free (chapter §4.1, after eq. 20).  :class:`tribofx.interfaces.Wear`
    takes a = :func:`nanson_vector` of w, normal to the worn boundary at the step's
    end: the nodes' tangential positions are then a function of the worn shape
    alone (along the step average :func:`swept_nanson_vector` they depend on the
    step history by O(Δt)).

    Args:
        zeta: multiplier of the nodal constraint (on the contact submesh).
        dw: test function of the shape change w.
        a: the direction of the reaction, e.g. :func:`nanson_vector`.
        ds: (vertex-rule) measure over the initial contact boundary Γ̂_c.
    """
    return zeta * ufl.dot(dw, a) * ds
