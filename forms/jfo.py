"""JFO mass-conserving Reynolds rows (57) on the lubrication surface S, pulled back to Γ_l.

The transport and complementarity rows of a film with cavitation (§6.5) on S
(:class:`forms.ehl.LubricationKinematics`), their SUPG (Remark 3.2), the
Couette flux and the open end of a curve supplied with lubricant (the air end of
a reciprocating seal).  The Reynolds rows without cavitation and the
kinematics are in :mod:`forms.ehl`.  Units: mm, s, MPa.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import ufl

from . import reynolds as rf
from .reynolds import WeightedMeasure

if TYPE_CHECKING:
    from ufl.core.expr import Expr

    from .ehl import LubricationKinematics

__all__ = ["VERTEX_DELTA", "boundary_speed", "couette_flux", "jfo_inflow", "jfo_on_surface",
           "leak_conductance"]

# δ of the full-film fraction that switches the vertex-rule share of the Couette flux
# (p/p_c and λ): a transition over a few hundredths, where the iterates of a front at
# ambient pressure move (λ from −0.04 to 0.3, p/p_c below 0.01: the seal's instroke)
VERTEX_DELTA = 0.05


def jfo_on_surface(
    p: Expr, lam: Expr, dp: Expr, dlam: Expr, kin: LubricationKinematics, mu: Expr | float,
    dx: ufl.Measure, p_c: Expr | float, q_ref: Expr | float, h_e: Expr | float,
    nodal_dx: ufl.Measure, supg: bool = True, grad_gamma: Callable[[Expr], Expr] = ufl.grad,
    T: Expr | None = None, ds_ends: ufl.Measure | None = None, weight: Expr | float = 1,
    rate: Expr | None = None, lumped: bool = False,
    inflow: tuple[ufl.Measure, Expr | float] | None = None, vertex: Expr | float | None = None,
) -> tuple[ufl.Form, ufl.Form]:
    """JFO mass-conserving Reynolds equation (57) on S pulled back to Γ_l.

    Returns (transport, constraint): the transport residual

        ∫_S ( θ h³/(12μ) grad_S p·grad_S δp + div_S(θ h v̄) δp ) ds  (+ SUPG),  θ = 1 − min(λ, 1),

    (ds = ds_S, grad_S, div_S through A, continuous P1 λ so the jump term on Σ
    vanishes) and the nodal complementarity (52) ∫ (q_ref/h_e) min(p/p_c, λ) δλ dS
    with the vertex quadrature ``nodal_dx`` (C = 0 node by node; semismooth Newton
    through ``ufl.derivative`` of ``min_value``).  SUPG (Remark 3.2) uses the
    diffusivity D = s h² p_c/(12μ) blended by the full-film fraction s(p, λ)
    (:func:`forms.reynolds.jfo_diffusivity`), element size h_e scaled to S.
    ``ds_ends`` (the end points of Γ_l, with the reference tangent ``T``) adds
    the jumps of the Couette flux between elements (see the code), so that the
    discrete form is conservative node by node.  On a surface (gdim = 3, ``T``
    None) ``ds_ends`` is the boundary edges of Γ_l: the Couette part becomes
    −∫ θ h v̄·grad_S δp dS + ∮ θ h v_n δp dL (:func:`boundary_speed`), the same
    jumps by the divergence theorem on each triangle; the rows tested by δp = 1
    then sum to the Couette outflow through ∂S.  The ``vertex`` share is for curves.

    ``weight`` w: the area factor of a surface of revolution, ds_S = w dl with
    w = 2π r_S (1 in the plane).  ``dx``, ``nodal_dx`` and ``ds_ends`` are then
    unweighted: w multiplies the fluxes, and the divergence is the one of the
    surface of revolution, div_S q = (1/w) d(w q)/dl for a meridional q (the hoop
    term included), so that the balance stays exact when r_S varies.

    ``rate``: the transient film (:mod:`forms.squeeze`), d(θ h J_S w)/dt per unit
    reference measure ``dx``, with ``kin`` relative to the moving S; None: steady.
    ``lumped``: the rate of a starved film's content on the vertex rule
    ``nodal_dx`` (its history then lives at the nodes of each cell) and, in the
    SUPG residual, weighted by the full-film fraction s.  Where neither pressure
    nor Couette flow moves the fluid, each node then keeps its own content
    exactly (a consistent mass spreads it over its neighbours at O(h_e²)), and in
    the cavitated zone (s ≈ 0) the mass adds nothing off the diagonal: a steep
    starved front is not undershot by the mass terms.  In the full film s ≈ 1
    keeps SUPG consistent.

    ``vertex`` (None or a Constant ω ∈ [0, 1], with ``ds_ends``): the share ω of the
    Couette flux, whose divergence form with its jumps is −∫ w_t dδp/dX + [w_t δp]
    at the ends, integrated by the vertex rule (ω = 0: the form without it).  In
    the cavitated zone it then sees the interpolant of the content θh, not the
    Gauss-point product of θ and h, whose cross term −ΔθΔh/6 per element drains
    the cavitated node in front of a reformation (a starved inlet filling: the
    node is asked to dry, λ > 1); in the full film both rules are second order.
    At a rupture the vertex rule moves the O-ring's h_min at its outlet by 21 % at
    density 2: set ω = 1 only where films reform (the seal's instroke, whose
    outlet is flooded), 0 where they rupture.  In the full film the share is
    ω(1 − s), s the full-film fraction of :func:`~forms.reynolds.jfo_film_fraction`
    with δ = ``VERTEX_DELTA``: across a front where p and λ both vanish over
    several nodes (a film that empties at ambient pressure) s with its default δ
    = 1e-6 jumps between the rules and Newton cycles (the seal's instroke near
    its reversal, measured); the share ω alone (the full film on the vertex rule
    too) stalls the line search in the first instroke.

    ``inflow`` (ds_in, c_in): the open ends of :func:`jfo_inflow` (supply c_in, p = 0
    weakly) at the end points of ``ds_in``.
    """
    dS = WeightedMeasure(kin.stretch * weight, dx)

    def grad(f: Expr) -> Expr:
        return kin.grad(f, grad_gamma)

    def div(w: Expr) -> Expr:
        return kin.div(weight * w, grad_gamma) / weight

    lam_c = ufl.min_value(lam, 1.0)   # an iterate with λ > 1 cannot balance the fluxes
    F = rf.jfo_residual(p, lam_c, dp, kin.h, kin.vbar, mu, dS, grad=grad, div=div)
    if rate is not None:
        F += rate * dp * (nodal_dx if lumped else dx)
    if supg and not isinstance(kin.vbar, ufl.constantvalue.Zero):   # v̄ ≡ 0: no SUPG term
        D = rf.jfo_diffusivity(p, lam, kin.h, mu, p_c)
        tau = rf.supg_tau(h_e * kin.stretch, kin.vbar, D)
        r_supg = None if rate is None else rate / (kin.stretch * weight)
        if lumped and rate is not None:
            r_supg = rf.jfo_film_fraction(p, lam, p_c) * r_supg
        F += rf.supg_stabilisation(p, lam_c, dp, kin.h, kin.vbar, mu, tau, dS, grad=grad,
                                   div=div, rate=r_supg)
    if ds_ends is not None and T is None:
        # a surface S (gdim = 3): the jumps of the Couette flux θ h v̄ across the
        # edges, the same way as on a curve (below), but by the divergence theorem of
        # each triangle: −Σ_E [[w·ν_E]] δp = −Σ_e ∫_e div_S(w δp) dS + ∮_∂S w·ν δp dl,
        # so that the Couette part is −∫ w·grad_S δp dS + the outflow through ∂S
        w = (1 - lam_c) * kin.h * kin.vbar
        F -= div(w * dp) * dS
        F += boundary_speed(kin, ds_ends) * (1 - lam_c) * kin.h * dp * ds_ends
    elif ds_ends is not None:
        # v̄ = ½(I − ν⊗ν)FV is discontinuous between elements for a C⁰ displacement:
        # the element-wise divergence theorem leaves the jumps of the Couette flux
        # w_t = θ h v̄·t_S at the nodes, −Σ_F [[w_t]] δp (zero for the exact solution).
        # They are added element by element, without interior-facet integrals:
        # −Σ_F [[w_t]] δp = −Σ_e ∫_e d(w_t δp)/dX dX + [w_t δp] at the ends of Γ_l.
        # With them the discrete fluxes balance exactly (sum of the rows = end fluxes).
        assert T is not None    # given with ds_ends (the line below raises on None)
        w_t = weight * couette_flux(kin, lam_c, T)
        n = ufl.FacetNormal(ds_ends.ufl_domain())
        F -= ufl.dot(grad_gamma(w_t * dp), T) * dx
        F += w_t * ufl.dot(T, n) * dp * ds_ends
    if vertex is not None:
        # the divergence form with its jumps is −∫ w_t dδp/dX dX + [w_t δp] (above);
        # the share ω(1 − s) of its integral moves from the Gauss to the vertex rule
        assert T is not None    # given with vertex (the line below raises on None)
        w_t = weight * couette_flux(kin, lam_c, T)
        s = rf.jfo_film_fraction(p, lam, p_c, delta=VERTEX_DELTA)
        dw = vertex * (1 - s) * w_t * ufl.dot(grad_gamma(dp), T)
        F += dw * dx - dw * nodal_dx
    if inflow is not None:
        F += jfo_inflow(kin, lam_c, p, dp, inflow[1], T, inflow[0], mu, h_e, weight)
    C = rf.jfo_complementarity(p, lam, dlam, p_c, nodal_dx, weight=weight * q_ref / h_e)
    return F, C


def jfo_inflow(
    kin: LubricationKinematics, lam: Expr | float, p: Expr, dp: Expr, supply: Expr | float,
    T: Expr | None, ds_in: ufl.Measure, mu: Expr | float, h_e: Expr | float,
    weight: Expr | float = 1, leak: float = 1e3,
) -> ufl.Form:
    """Open end of Γ_l to a reservoir at p = 0 with a lubricant supply, JFO.

    The ends of a curve (gdim = 2, ``T`` its reference tangent) or the edges of a
    surface (gdim = 3, ``T`` None).  The divergence form of the transport rows
    carries the Couette flux w θ h v_n through an end (v_n of
    :func:`boundary_speed`, outward) with the end node's own content θh.  Where
    the flow enters (v_n < 0)

        ∫_ds_in w min(v_n, 0) (c_in − θ h) δp,   θ = 1 − λ,

    lets the supplied content c_in (mm; a layer of thickness t on a surface
    moving at 2v̄ brings c_in = 2t) enter in its place, an upwind inflow
    condition; where the flow leaves (v_n ≥ 0) it vanishes, a natural outlet.
    A film that arrives full at the end (p > 0 there: a pressure flow towards
    the reservoir) leaves through it,

        ∫_ds_in κ p δp,   κ = ``leak`` · w h³/(12μ h_e),

    a Robin condition for p = 0 with ``leak`` times the conductance of the end
    element (p at the end is then 1/leak of the last element's pressure drop);
    in a cavitated end p = 0 and the term vanishes.  One form serves both
    directions of a reciprocating film.  ``lam`` is the clamped λ, ``mu`` μ(p).
    """
    v_n = boundary_speed(kin, ds_in, T)
    kappa = leak_conductance(kin, mu, h_e, leak)
    return weight * (ufl.min_value(v_n, 0) * (supply - (1 - lam) * kin.h)
                     + kappa * p) * dp * ds_in


def leak_conductance(kin: LubricationKinematics, mu: Expr | float, h_e: Expr | float,
                     leak: float = 1e3) -> Expr:
    """Return κ = ``leak`` · h³/(12μ h_e J_S), the Robin conductance of an open end.

    The leak of :func:`jfo_inflow` (mm/(MPa·s) per unit length of the end).
    """
    return leak * rf.poiseuille_conductance(kin.h, mu) / (h_e * kin.stretch)


def boundary_speed(kin: LubricationKinematics, ds: ufl.Measure, T: Expr | None = None) -> Expr:
    """Outward speed v_n (mm/s) of the mean velocity v̄ through ∂S, per unit length of ∂Γ_l.

    The content θh times v_n is the Couette volume flux out of S through the end
    (mm²/s at an end of a curve; mm²/s per mm of reference edge on a surface).
    A curve (gdim = 2, ``T`` its reference tangent): v_n = v̄·t_S (T·n), n = ±1 the
    end's outward normal.  A surface (gdim = 3, ``T`` None): by Nanson's formula for
    the tangent map A (A N = ν), ν_∂ dl = J_S A⁻ᵀ n dL with n the outward conormal
    of the reference edge in the plane of Γ_l, so v_n = J_S (A⁻¹ v̄)·n.
    """
    n = ufl.FacetNormal(ds.ufl_domain())
    if T is not None:
        tS = kin.A * T
        return ufl.dot(kin.vbar, tS / ufl.sqrt(ufl.dot(tS, tS))) * ufl.dot(T, n)
    return kin.stretch * ufl.dot(ufl.inv(kin.A) * kin.vbar, n)


def couette_flux(kin: LubricationKinematics, lam: Expr | float, T: Expr) -> Expr:
    """Couette volume flux θ h v̄·t_S along S (mm²/s), θ = 1 − λ, gdim = 2 (eq. 40).

    t_S = A T/|A T| is the unit tangent of S in the direction of the reference
    tangent T of Γ_l; ``lam`` is the void fraction (0 without cavitation).
    """
    tS = kin.A * T
    return (1 - lam) * kin.h * ufl.dot(kin.vbar, tS / ufl.sqrt(ufl.dot(tS, tS)))
