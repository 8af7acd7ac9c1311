"""Soft-EHL coupling: lubrication surface S = P(γ_l) on a rigid cylinder or plane (§6.2–6.4, §7).

Kinematics (plane, gdim = 2; all lengths mm).  A point X of the reference
lubricated boundary Γ_l (unit outer normal N, unit tangent T) is placed at
x = X + u.  Its closest point on the rigid cylinder (centre c, radius R) is

    y = P(x) = c + R ν,   ν = (x − c)/|x − c|,   h = (x − y)·ν = |x − c| − R   (36–37)

(ν points from the cylinder into the film).  Everything the Reynolds equation
needs depends only on the trace of x on Γ_l and on its tangential derivative
F_t = F (I − N⊗N):

    ∂P/∂x = (R/|x − c|)(I − ν⊗ν),    F_y = (∂P/∂x) F,
    A = F_y (I − N⊗N) + ν⊗N         (tangents of Γ_l → tangents of S, N → ν),
    ds_S = |det A| dS,  grad_S f = A^{-T} Grad_Γ f,  div_S w = tr(Grad_Γ w · A^{-1}).

Velocities (cylinder frame, the frame of the chapter's §8.2): the cylinder is at
rest, the layer material flows through the deformed mesh with v = F V (eq. 26),
V = U T the nominal sliding velocity.  The mean tangential velocity on S is
v̄ = ½ (I − ν⊗ν) F V (eq. 41–42) and the film is steady at fixed point of S, so
∂h/∂t = 0 in eq. (49).

Fluid traction on the layer (eq. 46), i = layer, countersurface at rest:

    t = −p n − (μ/h)(I − ν⊗ν) F V − (h/2) grad_S p,

as nominal traction T dS = t ds on Γ_l: −p J F^{-T} N (Nanson) for the pressure
and j = |F T| for the shear terms.  The Couette and Poiseuille shear terms are
switchable (``shear``).

The geometrically linear (classical EHL) variant (``model="linear"``) evaluates
the whole geometry at the undeformed configuration (u = 0): the lubrication
surface S0 = P(Γ_l), its operators A0, ds_S0, v̄0 = ½(I − ν0⊗ν0)V, and the
film thickness linearised in u, h = g(X) + ν0(X)·u (g, ν0 of the undeformed
point X); the traction acts on the reference surface, T = −p N − (μ/h) v0_T −
(h/2) grad_S0 p.  Both models coincide for u → 0, so their difference is of
higher order in the deformation.

Any countersurface (``surface=`` of :func:`lubrication_kinematics`).  A
countersurface given by its closest-point geometry x ↦ (g_N, n, x̄) — the
analytic plane, cylinder and sphere of :mod:`forms.contact`, or a surface mesh
through the data of the C++ kernel refreshed at the nodes of Γ_l before every
assembly (:func:`forms.contact.meshed_countersurface`: second-order Taylor
expansions about the expansion point x₀, so value, first and second derivative
of h and value and first derivative of ν and y are those of the kernel at x₀;
x₀ are the nodes, and the data are interpolated (P1) to quadrature points, so
away from the nodes the tangent is exact up to O(h κ) relative on a curved
countersurface — exact on flat facets and in vertex-rule terms)
— gives the lubrication projection by :func:`countersurface_projection`:

    h = g_N(x),  ν = n(x),  y = P(x) = x̄(x),  ∂P/∂x = ∂x̄/∂x      (36–37)

(∂P/∂x by ``ufl.diff`` of x̄, so the closed forms (R/|x − c|)(I − ν⊗ν) of the
cylinder and I − ν⊗ν of the plane follow, and the Newton tangent stays exact).

Three dimensions (the ball of §8.3).  The same expressions hold for gdim = 3
with a 2D lubricated surface: A maps the tangent plane of Γ_l to that of S and
N to ν, so |det A| is the area ratio ds_S/dS.  The countersurface may move: a
rigid plane z = z_p (y = x − (x_z − z_p) e_z, ν = e_z, h = x_z − z_p,
∂P/∂x = I − e_z⊗e_z) sliding with V_c gives v̄ = ½(v_layer + (I − ν⊗ν)V_c)
(eq. 41) and the Couette traction −(μ/h)(v_layer − v_c) (eq. 46; ``V_counter``
of :func:`lubrication_kinematics`).  The shear stretch is ds/dS = J|F⁻ᵀN|.
The reference normal N of a curved Γ_l varies: on the submesh it is the
outward normal of each flat cell (a DG0 field), on the bulk side the facet
normal (the same vector), and the tangential pressure gradient Grad_Γ p is a
vector DG0 field (:func:`tangential_gradient_constraint` with
:func:`tangential_gradient`).

Integration.  DOLFINx 0.11 does not differentiate a facet-submesh function in
an integral over facets of the bulk mesh, and does not evaluate bulk
coefficients in integrals over the submesh.  The Reynolds equation is therefore
written on the submesh in terms of the trace field u_s (same values as u on
Γ_l, imposed by :func:`trace_constraint`), and the solid sees the tangential
pressure gradient through a cellwise constant submesh field g = Grad_Γ p·T
(:func:`tangential_gradient_constraint`, exact for P1 pressure).

Units: mm, N, s, MPa (viscosity MPa·s, μU in N/mm).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import ufl

from . import reynolds as rf
from .reynolds import WeightedMeasure

if TYPE_CHECKING:
    from ufl.core.expr import Expr

    from .contact import ContactGeometry

__all__ = [
    "MODELS",
    "LubricationKinematics",
    "WeightedMeasure",
    "countersurface_projection",
    "cylinder_countersurface",
    "intermediate_surface",
    "lubrication_kinematics",
    "planar_kinematics",
    "reynolds_on_surface",
    "tangential_gradient",
    "tangential_gradient_constraint",
    "trace_constraint",
]

MODELS = ("finite", "linear")


@dataclass(frozen=True)
class LubricationKinematics:
    """UFL expressions of the lubrication surface at a point of Γ_l.

    Attributes:
        h: film thickness (mm).
        nu: unit normal ν of S at y, pointing into the film (towards the layer).
        y: projection point y = P(x) on the cylinder (mm).
        A: tangent map Γ_l → S (gdim × gdim).
        stretch: ds_S/dS = |det A|.
        vbar: mean tangential velocity v̄ (mm/s).
        v_layer: tangential (w.r.t. S) velocity of the layer surface (mm/s).
        v_counter: tangential velocity of the rigid countersurface at y (mm/s),
            None for a countersurface at rest.
    """

    h: ufl.core.expr.Expr
    nu: ufl.core.expr.Expr
    y: ufl.core.expr.Expr
    A: ufl.core.expr.Expr
    stretch: ufl.core.expr.Expr | float
    vbar: ufl.core.expr.Expr
    v_layer: ufl.core.expr.Expr
    v_counter: ufl.core.expr.Expr | None = None

    def grad(self, f: Expr, grad_gamma: Callable[[Expr], Expr] = ufl.grad) -> Expr:
        """Surface gradient grad_S f = A^{-T} Grad_Γ f of a scalar field on Γ_l."""
        return ufl.inv(self.A).T * grad_gamma(f)

    def div(self, w: Expr, grad_gamma: Callable[[Expr], Expr] = ufl.grad) -> Expr:
        """Surface divergence div_S w = tr(Grad_Γ w · A^{-1}) of a vector field on Γ_l."""
        return ufl.tr(grad_gamma(w) * ufl.inv(self.A))


def cylinder_countersurface(
    x: Expr, center: Expr, radius: Expr | float
) -> tuple[Expr, Expr, Expr, Expr]:
    """Closed-form projection onto the cylinder: (h, ν, y, ∂P/∂x) at the UFL position x."""
    d = x - center
    r = ufl.sqrt(ufl.dot(d, d))
    nu = d / r
    dP = (radius / r) * (ufl.Identity(len(x)) - ufl.outer(nu, nu))
    return r - radius, nu, center + radius * nu, dP


def tangential_gradient(N: Expr) -> Callable[[Expr], Expr]:
    """Return f ↦ Grad_Γ f, the gradient projected with (I − N⊗N) (N: reference normal).

    UFL's grad of an expression of the spatial coordinate on a facet submesh
    (a manifold) keeps the derivative along N (grad X = I); the projection
    removes it.  Vector fields: (Grad w)(I − N⊗N).
    """
    PN = ufl.Identity(len(N)) - ufl.outer(N, N)

    def grad_gamma(f: Expr) -> Expr:
        g = ufl.grad(f)
        return PN * g if len(g.ufl_shape) == 1 else g * PN

    return grad_gamma


def countersurface_projection(
    geometry: Callable[[Expr], ContactGeometry], x: Expr
) -> tuple[Expr, Expr, Expr, Expr]:
    """Lubrication projection (h, ν, y, ∂P/∂x) at x of a countersurface, eqs. (36–37).

    ``geometry`` maps a UFL position to the closest-point geometry
    (:class:`forms.contact.ContactGeometry`: gap g_N, normal n, projection x̄) of
    the countersurface — analytic or meshed.  Then h = g_N = (x − y)·ν, ν = n,
    y = x̄ and ∂P/∂x = ∂x̄/∂x (``ufl.diff`` with respect to x), all UFL of x.
    """
    xv = ufl.variable(x)
    g = geometry(xv)
    return g.gap, g.normal, g.projection, ufl.diff(g.projection, xv)


def lubrication_kinematics(
    X: Expr, disp: Expr, grad_disp: Expr, N: Expr, center: Expr | None,
    radius: Expr | float | None, V: Expr, model: str = "finite",
    surface: Callable[[Expr], tuple[Expr, Expr, Expr, Expr]] | None = None,
    alpha: Expr | float | None = None, V_counter: Expr | Callable[[Expr], Expr] | None = None,
) -> LubricationKinematics:
    """Lubrication surface S = P(γ_l) on a rigid cylinder, as UFL of the displacement.

    Args:
        X: reference position on Γ_l (mm).
        disp: displacement u at X (mm).
        grad_disp: displacement gradient whose action on tangents of Γ_l is exact
            (bulk Grad u, or the tangential gradient of the trace on the submesh).
        N: unit outer normal of Γ_l (reference; a constant, a facet normal or a
            cellwise constant field).
        center: cylinder centre c (mm).
        radius: cylinder radius R (mm).
        V: nominal sliding velocity of the layer in the cylinder frame (mm/s),
            tangent to Γ_l.
        model: "finite" (S = P(γ_l)) or "linear" (classical EHL, see module doc).
        surface: None (analytic cylinder ``center``, ``radius``) or a callable
            x ↦ (h, ν, y, ∂P/∂x), e.g. :func:`countersurface_projection` of a
            countersurface geometry (analytic or meshed); for ``model="linear"`` the
            data of a meshed countersurface must be expanded about the reference X.
        alpha: None (S = P(γ_l), closed form) or a scalar (UFL constant) α ∈ [0, 1]:
            the intermediate surface S_α = (1 − α) P(γ_l) + α γ_l of Fig. 23
            (see :func:`intermediate_surface`; α = 0 gives S = P(γ_l) to round-off).
        V_counter: None (countersurface at rest) or the velocity of the rigid
            countersurface at y (mm/s, e.g. 2U e_x of the plane of §8.3; a callable
            of y for a rolling countersurface); its
            tangential part (I − ν⊗ν) V_counter enters v̄ = ½(v_layer + v_counter)
            (eq. 41) and the Couette traction (46) (on S_α its part tangent to S_α).
            gdim = 2 or 3 (alpha: 2 only).
    """
    if model not in MODELS:
        raise ValueError(f"unknown model {model!r}; expected one of {MODELS}")
    gdim = len(N)
    Id = ufl.Identity(gdim)
    PN = Id - ufl.outer(N, N)
    if model == "linear":
        # all geometry at the reference configuration (u = 0): S0 = P(Γ_l); h linear in u
        k0 = lubrication_kinematics(X, ufl.zero(gdim), ufl.zero(gdim, gdim), N, center, radius,
                                    V, "finite", surface, alpha, V_counter)
        return LubricationKinematics(h=k0.h + ufl.dot(k0.nu, disp), nu=k0.nu, y=k0.y, A=k0.A,
                                     stretch=k0.stretch, vbar=k0.vbar, v_layer=k0.v_layer,
                                     v_counter=k0.v_counter)
    x = X + disp
    if surface is None:
        assert center is not None and radius is not None   # the analytic cylinder's
        h, nu, y, dP = cylinder_countersurface(x, center, radius)
    else:
        h, nu, y, dP = surface(x)
    if callable(V_counter):              # a field of the countersurface's points
        V_counter = V_counter(y)
    Ft = (Id + grad_disp) * PN           # F (I − N⊗N)
    if alpha is not None:
        return intermediate_surface(h, nu, y, dP, Ft, N, V, alpha, V_counter)
    Pnu = Id - ufl.outer(nu, nu)
    A = dP * Ft + ufl.outer(nu, N)
    v_layer = Pnu * (Ft * V)             # tangential part of v = F V (V ⊥ N)
    if V_counter is None:
        return LubricationKinematics(h=h, nu=nu, y=y, A=A, stretch=abs(ufl.det(A)),
                                     vbar=0.5 * v_layer, v_layer=v_layer)
    v_counter = Pnu * V_counter          # eq. (42) on the countersurface
    return LubricationKinematics(h=h, nu=nu, y=y, A=A, stretch=abs(ufl.det(A)),
                                 vbar=0.5 * (v_layer + v_counter), v_layer=v_layer,
                                 v_counter=v_counter)


def planar_kinematics(x: Expr, h: Expr, vbar: Expr) -> LubricationKinematics:
    """Kinematics of the traditional planar Reynolds equation (§6.6) between rigid surfaces.

    The lubrication surface is the reference line (plane) itself: A = I,
    ds_S = dS, grad_S = grad, div_S = div; ``h`` is the film thickness (UFL of the
    position ``x``, mm) and ``vbar`` the mean velocity (UFL vector, mm/s).  With it
    the Reynolds forms of this module (:func:`reynolds_on_surface`,
    :func:`forms.jfo.jfo_on_surface`) are those of :mod:`forms.reynolds` in the plane.
    """
    gdim = len(x)
    return LubricationKinematics(h=h, nu=ufl.as_vector([0.0] * (gdim - 1) + [1.0]), y=x,
                                 A=ufl.Identity(gdim), stretch=1, vbar=vbar, v_layer=vbar)


def intermediate_surface(
    h: Expr, nu: Expr, y: Expr, dP: Expr, Ft: Expr, N: Expr, V: Expr, alpha: Expr | float,
    V_counter: Expr | None = None,
) -> LubricationKinematics:
    """Kinematics on the intermediate lubrication surface S_α (Fig. 23), plane (gdim = 2).

    With y = P(x) the projection onto the countersurface and x the layer point,

        z = (1 − α) y + α x = y + α h ν                      (point of S_α)
        G = (1 − α) ∂P/∂x F + α F,  τ = G T                  (tangent of S_α, per dS)
        n_α = (τ_y, −τ_x)/|τ|                                (unit normal of S_α)
        A_α = G (I − N⊗N) + n_α⊗N,  ds_Sα = |τ| dS = |det A_α| dS,
        v̄ = ½ (I − n_α⊗n_α) F V,   h = (x − y)·ν             (film unchanged)

    so α = 0 is S = P(γ_l) (n_0 = ν: the tangent ∂P/∂x F T of the countersurface
    is ⊥ ν) and α = 1 is S = γ_l (G = F, v̄ = ½ F V, the tangent of the layer).  The
    film thickness is the gap between the physical surfaces along ν for every α;
    only the surface carrying the Reynolds equation (its metric, its operators
    grad_S, div_S and the tangential projection of the velocity) depends on α.
    Everything is UFL of the displacement, so the Newton tangent stays exact.
    A moving countersurface (``V_counter``) adds its part tangent to S_α,
    v̄ = ½ (I − n_α⊗n_α)(F V + V_counter) (α = 0: eq. 41).
    """
    G = (1 - alpha) * dP * Ft + alpha * Ft
    tau = G * ufl.as_vector([N[1], -N[0]])       # G T with T = (N_y, −N_x)
    jt = ufl.sqrt(ufl.dot(tau, tau))
    n_a = ufl.as_vector([tau[1], -tau[0]]) / jt
    A = G + ufl.outer(n_a, N)                    # G already annihilates N
    P_a = ufl.Identity(2) - ufl.outer(n_a, n_a)
    v_layer = P_a * (Ft * V)
    v_counter = None if V_counter is None else P_a * V_counter
    vbar = 0.5 * (v_layer if v_counter is None else v_layer + v_counter)
    return LubricationKinematics(h=h, nu=nu, y=y + alpha * h * nu, A=A, stretch=abs(ufl.det(A)),
                                 vbar=vbar, v_layer=v_layer, v_counter=v_counter)


def reynolds_on_surface(
    p: Expr, dp: Expr, kin: LubricationKinematics, mu: Expr | float,
    dx: ufl.Measure | WeightedMeasure, eps: Expr | float | None = None, supg: bool = False,
    p_c: Expr | float = 1.0, h_e: Expr | float | None = None,
    nodal_dx: ufl.Measure | WeightedMeasure | None = None,
    grad_gamma: Callable[[Expr], Expr] = ufl.grad, rho: Expr | float = 1,
    rate: Expr | None = None,
) -> ufl.Form:
    """Reynolds residual (49) on S pulled back to Γ_l (p = 0 on ∂S by Dirichlet).

    ``dx`` is the measure of Γ_l (the facet submesh), ``eps`` the penalty of
    cavitation (MPa·s/mm, None: no cavitation), ``supg`` adds the SUPG term with
    element size ``h_e`` (mm on Γ_l, scaled to S here) and pressure scale ``p_c``
    (MPa) in the Péclet number; ``nodal_dx`` is the vertex-quadrature measure for
    the penalty; ``rho`` the density ρ(p)/ρ₀ (1: incompressible; the compressible
    equation with a law of :mod:`forms.fluid`).

    ``rate``: the transient film (:mod:`forms.squeeze`), d(ρ h J_S w)/dt per unit
    reference measure (w the weight of a :class:`WeightedMeasure` ``dx``, else 1),
    with ``kin`` relative to the moving S; None: steady.
    """
    dS = WeightedMeasure(kin.stretch, dx)
    raw, w = (dx.measure, dx.weight) if isinstance(dx, WeightedMeasure) else (dx, 1)

    def grad(f: Expr) -> Expr:
        return kin.grad(f, grad_gamma)

    def div(w: Expr) -> Expr:
        return kin.div(w, grad_gamma)

    F = rf.reynolds_residual(p, dp, kin.h, kin.vbar, mu, dS, grad=grad, rho=rho)
    if rate is not None:
        F += rate * dp * raw
    if supg and not isinstance(kin.vbar, ufl.constantvalue.Zero):   # v̄ ≡ 0: no SUPG term
        D = kin.h**2 * p_c / (12 * mu)
        assert h_e is not None      # SUPG takes the element size
        tau = rf.supg_tau(h_e * kin.stretch, kin.vbar, D)
        # the strong residual per unit area of S: the rate over J_S w
        F += rf.supg_stabilisation(p, 0.0, dp, kin.h, kin.vbar, mu, tau, dS, grad=grad,
                                   div=div, rho=rho,
                                   rate=None if rate is None else rate / (kin.stretch * w))
    if eps is not None:
        F += rf.cavitation_penalty(p, dp, eps, WeightedMeasure(kin.stretch, nodal_dx or dx))
    return F


def trace_constraint(u_s: Expr, u: Expr, du_s: Expr, ds: ufl.Measure) -> ufl.Form:
    """Residual ∫_Γl (u_s − u)·δu_s dS that makes the submesh field u_s the trace of u.

    u_s and u have the same degree on Γ_l, so the L2 projection is the identity.
    """
    return ufl.dot(u_s - u, du_s) * ds


def tangential_gradient_constraint(
    g: Expr, p: Expr, dg: Expr, T: Expr | None, dx: ufl.Measure,
    grad_gamma: Callable[[Expr], Expr] | None = None,
) -> ufl.Form:
    """Residual ∫_Γl (g − Grad_Γ p·T) δg dS: g is the tangential pressure derivative.

    Vector g (DG0, any gdim): ∫_Γl (g − Grad_Γ p)·δg dS with ``grad_gamma`` the
    projected gradient (:func:`tangential_gradient`); exact for P1 p on affine cells.
    """
    if len(ufl.shape(g)) == 1:
        assert grad_gamma is not None   # a vector g takes the projected gradient
        return ufl.dot(g - grad_gamma(p), dg) * dx
    return (g - ufl.dot(ufl.grad(p), T)) * dg * dx
