"""Forms of the quasi-steady wear groove of a rigid ball sliding on a half-space (chapter §5.3).

The half-space is described in an Eulerian frame attached to the ball (§4.3):
the undeformed (worn) configuration moves rigidly with the background velocity
V = −V e_x, the deformation is Lagrangian, and the material velocity is
v = F V (eq. 26) with F relative to the worn configuration.  The groove is
uniform along x, so Ψ (the ALE field w, X = X̂ + w) has w_x = 0 and depends on
(y, z) only; then G = I + Grad w satisfies G e_x = e_x and
F V = (I + Grad u) G⁻¹ V = (I + Grad u) V: the slip velocity (27) is the
tangential part of (I + Grad u) V (see :func:`groove_slip_speed`).

Wear is averaged along the sliding path (§5.3, eqs. 22–23 with Δτ = L/V): one
revolution of the disk of track length L drags every point of the groove once
through the contact, so the groove depth rate at the cross-section position y is

    W̄̇(y) = (1/L) ∫ Ẇ(x, y) dx,

the normal rate of the 2D shape evolution law (28) on the cross-section.  The
algebraic (extrusion) form of that average is :func:`path_averaged_rate`.

Functionally graded layer (Fig. 10b): Young's modulus and the wear coefficient
increase linearly towards the surface over a layer of thickness h_L, from the
substrate value at depth h_L to (1 + α) times it at the initial surface.  The
property of a material point is that of its depth below the *initial* surface
in the worn configuration, d = −X·e_z = −(Ẑ + w_z) (material is removed, not
moved, by wear).  Units: mm, N, s, MPa.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import ufl

from .wear import archard_pressure_form

if TYPE_CHECKING:
    from ufl.core.expr import Expr

    from .contact import ContactGeometry

__all__ = [
    "nodal_rate_form",
    "graded_factor",
    "groove_rate_density",
    "groove_slip_speed",
    "material_depth",
    "path_averaged_rate",
]


def material_depth(X_hat: Expr, w: Expr) -> Expr:
    """Depth below the initial surface z = 0 of the worn point X = X̂ + w (eq. 19₁), mm."""
    return -(X_hat[2] + w[2]) if len(w) == 3 else -(X_hat[1] + w[1])


def graded_factor(depth: Expr, alpha: Expr | float, thickness: Expr | float) -> Expr:
    """FGM layer (Fig. 10b): 1 + α max(1 − d/h_L, 0) for d ≥ 0 (1 below the layer).

    Multiplies the substrate modulus E and the substrate wear coefficient k:
    linear rise towards the surface, (1 + α) at d = 0.
    """
    return 1 + alpha * ufl.max_value(1 - depth / thickness, 0)


def groove_slip_speed(u: Expr, geometry: ContactGeometry, V: Expr) -> Expr:
    """‖v_T‖ of the Eulerian slip velocity, v = F V (eq. 26), v_T its tangential part (eq. 27).

    ``V`` is the background velocity of the worn half-space in the ball frame
    (UFL vector, mm/s), ``geometry`` the ball's closest-point geometry (its
    normal n).  F V = (I + Grad u) V since the groove is uniform along V.
    """
    v = (ufl.Identity(len(u)) + ufl.grad(u)) * V
    vt = v - ufl.dot(v, geometry.normal) * geometry.normal
    return ufl.sqrt(ufl.dot(vt, vt))


def groove_rate_density(
    k: Expr | float, T_n: Expr, slip_speed: Expr | float, J: Expr | None = None
) -> Expr:
    """Nominal Archard rate per unit initial area, Ẇ j_w = k |T_N| ‖v_T‖ (eq. 14, pressure form).

    T_N is the contact multiplier (nominal traction per unit *initial* area, so
    the product is the worn volume per unit initial area and time); with ``J``
    the spatial law (15)–(16).  ``k`` may be a graded UFL expression.
    """
    return archard_pressure_form(k, T_n, slip_speed, J)


def path_averaged_rate(P_line: Any, rate_nodal: Any, L: float) -> Any:
    """Cross-section nodal wear rate of the path average (1/L) ∫ Ẇ dx (§5.3; eqs. 22–23).

    ``rate_nodal`` holds ∫_Γ̂c Ẇ j_w φ_i dŜ for the P1 basis functions φ_i of the
    3D contact surface (vertex rule), ``P_line`` the extrusion matrix of the
    contact line (3D surface node ← line node).  Since Σ over the x layers of
    φ_(x_l, y_j) is the 1D hat function φ_j(y), Pᵀ r = ∫∫ Ẇ φ_j(y) dx dy, and
    (1/L) Pᵀ r is the right-hand side of the lumped line form of (28):
    ∫ η_j (w − w_n)·a dŝ = −Δt (1/L) (Pᵀ r)_j.  Works on numpy/scipy arrays
    (vectors or Jacobian rows).
    """
    return (P_line.T @ rate_nodal) / L


def nodal_rate_form(rate_density: Expr, eta: Expr, ds: ufl.Measure) -> ufl.Form:
    """Return the form ∫ Ẇ j_w η dŜ of the nodal wear rates (mm³/s, vertex rule ``ds``).

    Assembled, it is the r of :func:`path_averaged_rate` (the right-hand side of the
    line form of eq. 28, eqs. 22–23).
    """
    return rate_density * eta * ds
