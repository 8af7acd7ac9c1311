"""A film between two deformable bodies: its surface, its nodal data and its traction rows.

The lubrication surface of two deformable bodies is chosen as the slave's own
current boundary, S = γ_l (α = 1 of the chapter's S_α, Fig. 23): the one
surface whose points and tangent map are already unknowns of the slave, so
that the other body enters only through nodal data at the projections of the
slave nodes onto its current boundary (the C++ kernel of
``cpp_kernels/src/two_body_film.hpp``):

* the gap h, h_k = (x_k − x̄_k)·n⁽²⁾ (the master's outward normal at the closest
  point x̄_k, eq. 2), P1 between the nodes;
* the velocity w of the master's surface at x̄_k (its material moving along its
  own surface, eq. 26), whose part tangent to S enters v̄ and the Couette shear.

With x = X + u on Γ_l, F_t = F(I − N⊗N) and the Nanson vector
m = cof(F_t + N⊗N) N = |m| n (n the slave's current outward normal, |m| = ds/dS),

    A = F_t + n⊗N,   ds_S = |det A| dS,   v_layer = (I − n⊗n) F_t V⁽¹⁾,
    v_counter = (I − n⊗n) w,   v̄ = ½(v_layer + v_counter)   (eq. 41),

and ν = −n (the counter wall's normal into the film).  The Reynolds rows
(49)/(57) of :mod:`forms.ehl` are then unchanged, and the fluid traction (46) is
that of :mod:`forms.film_traction`.  h and w are unknowns of the film, tied to
the kernel's values node by node (:func:`nodal_equality`, the kernel adding
−c w_c g): the Jacobian's master columns come from the kernel, UFL's
derivative covers everything else.

The traction reaches both bodies through a nodal unknown t (MPa per reference
length): :func:`traction_collocation` makes t the traction (46) at the nodes
of Γ_l (the vertex rule of the bulk facets), and the kernel adds −w_k t_k to the
slave's rows and w_k N_m(ξ̄_k) t_k to the master's, so that the two forces
balance exactly.  The reaction on the master is the slave's reversed, −t at
x̄: the pressure along the slave's normal and the Couette shear reversed, which
equals the master's own wall traction up to the film's slope (lubrication
order), and keeps the film's momentum balance exact.

Units: mm, N, s, MPa.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import ufl

from .ehl import LubricationKinematics

if TYPE_CHECKING:
    from ufl.core.expr import Expr

__all__ = ["layer_surface_kinematics", "nodal_equality", "ring_traction_collocation",
           "traction_collocation"]


def layer_surface_kinematics(
    X: Expr, disp: Expr, grad_disp: Expr, N: Expr, h: Expr, V: Expr | None, w: Expr
) -> LubricationKinematics:
    """Kinematics of the lubrication surface S = γ_l (the slave's current boundary).

    Args:
        X: reference position on Γ_l (mm).
        disp: displacement at X (mm).
        grad_disp: displacement gradient whose action on tangents of Γ_l is exact
            (bulk Grad u, or the tangential gradient of the trace on the submesh).
        N: unit outer normal of Γ_l (reference).
        h: film thickness (mm), the nodal gap field.
        V: reference velocity of the slave's material along Γ_l (mm/s), UFL of X;
            None: at rest.
        w: velocity of the master's surface at the projection (mm/s), a field.
    """
    gdim = len(N)
    Id = ufl.Identity(gdim)
    Ft = (Id + grad_disp) * (Id - ufl.outer(N, N))
    M = Ft + ufl.outer(N, N)
    m = ufl.det(M) * ufl.inv(M).T * N             # Nanson on S: |m| = ds/dS
    n = m / ufl.sqrt(ufl.dot(m, m))
    A = Ft + ufl.outer(n, N)
    Pn = Id - ufl.outer(n, n)
    v_layer = Pn * (Ft * V) if V is not None else ufl.zero(gdim)
    v_counter = Pn * w
    return LubricationKinematics(h=h, nu=-n, y=X + disp, A=A, stretch=abs(ufl.det(A)),
                                 vbar=0.5 * (v_layer + v_counter), v_layer=v_layer,
                                 v_counter=v_counter)


def nodal_equality(f: Expr, df: Expr, c: Expr | float, nodal_dx: ufl.Measure) -> ufl.Form:
    """Linear half c ∫ f·δf of the nodal rows f_k = (kernel value)_k (vertex rule ``nodal_dx``).

    The kernel adds −c w_k (value)_k with w_k = ∫ φ_k ``nodal_dx``, so the row
    reads c w_k (f_k − value_k) = 0.
    """
    return c * ufl.inner(f, df) * nodal_dx


def traction_collocation(t: Expr, traction: Expr, dt: Expr, ds_vertex: ufl.Measure) -> ufl.Form:
    """Residual ∫_Γl (t − T)·δt dS with the vertex rule: t is the traction T at the nodes.

    ``traction`` is the nominal fluid traction (46) on the slave (bulk side:
    F from the bulk displacement), ``ds_vertex`` the vertex-rule measure of Γ_l on
    the bulk mesh; at a node T is the length-weighted mean of its facets' values.
    """
    return ufl.dot(t - traction, dt) * ds_vertex


def ring_traction_collocation(t: Expr, traction: Expr, dt: Expr, omega: Expr, u_r: Expr,
                              ds_vertex: ufl.Measure) -> ufl.Form:
    """Residual ∫ (ω t − (ω + 2π u_r) T)·δt dS (vertex rule): t, the ring traction (axisymmetric).

    ``omega``: the P1 field ω with ω_k ∫ φ_k dS = W_k = ∫ φ_k 2πR dS (the exact
    lumped area, positive on the axis, :class:`tribofx.interfaces.surface.Surface`);
    ``u_r`` the radial displacement.  At node k, W_k t_k = ℓ_k (ω_k + 2π u_r,k) T_k
    (ℓ_k = ∫ φ_k dS): the lumped ring force of T (46) on the current radius
    r = R + u_r, the lumped ∫ φ_k 2πr T dS to O(h²) and exact on the axis, where
    2πr vanishes at the node but its lumped area does not.  The kernel puts −W_k t_k
    on the slave and W_k N_m(ξ̄_k) t_k on the master at the projection.  (One rule for
    both terms: FFCx 0.10 cannot compile a facet form mixing the vertex rule with a
    Gauss rule when submesh coefficients enter.)
    """
    return ufl.dot(omega * (t - traction) - 2 * ufl.pi * u_r * traction, dt) * ds_vertex
