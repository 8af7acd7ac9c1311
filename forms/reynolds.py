"""Reynolds equation of thin-film lubrication with cavitation (chapter §6.3–6.6).

Flux (eq. 40), Poiseuille + Couette, with film thickness h (mm), mean
tangential velocity v̄ = (v⁽¹⁾ + v⁽²⁾)/2 (mm/s, eq. 41), viscosity μ (MPa·s)
and pressure p (MPa):

    q = −h³/(12μ) grad p + h v̄                                    (mm²/s)

Steady weak form without cavitation (eq. 49; Dirichlet p = p* on ∂_pS, flux
q·m = q* on ∂_qS):

    ∫_S (∂h/∂t δp − q·grad δp) ds + ∫_∂qS q* δp dl = 0            (49)

JFO mass-conserving cavitation (§6.5): with the void fraction λ = 1 − ϱ̄ as a
second continuous unknown (θ = ϱ̄ = 1 − λ), the weak form with the divergence
theorem applied only to the Poiseuille part (eq. 57, continuous λ so that the
jump term on Σ vanishes) reads

    ∫_S ( θ h³/(12μ) grad p·grad δp + (div(θ h v̄) + ∂(θh)/∂t) δp ) ds = 0,   (57)

and the complementarity conditions (52), p ≥ 0, λ ≥ 0, pλ = 0, are enforced by
the nonsmooth (semismooth) constraint function

    C(p, λ) = min(p/p_c, λ) = 0,        p_c > 0 a pressure scale (MPa),

tested by δλ and integrated with the vertex (nodal) quadrature so that C = 0
holds node by node.  ``ufl.derivative`` of ``min_value`` gives the generalised
Jacobian of the primal–dual active-set (semismooth Newton) method.

Penalty cavitation (an approximation of p ≥ 0 that is not mass conserving;
its solution converges to that of the variational inequality, i.e. to the
Swift–Stieber/Reynolds rupture conditions p = ∂p/∂m = 0) adds

    ∫_S ε⁻¹ min(p, 0) δp ds,        ε in MPa·s/mm,

so that ε⁻¹ min(p, 0) is a volume flux per area (mm/s) like div q.

SUPG (Remark 3.2, Brooks–Hughes) on the strong residual
R = div(θ h v̄) − div(θ h³/(12μ) grad p) + ∂(θh)/∂t (mm/s):

    ∫_S τ (v̄·grad δp) R ds,
    τ = h_e / √(4|v̄|² + (12 D/h_e)²)  = (h_e/(2|v̄|)) · Pe/√(Pe² + 9),
    Pe = |v̄| h_e/(2D)  (element Péclet number),

the doubly-asymptotic approximation (Shakib–Tezduyar) of the optimal
τ = (h_e/(2|v̄|))(coth Pe − 1/Pe): τ → h_e/(2|v̄|) for pure advection (D = 0,
cavitated zone) and τ → h_e²/(12 D) in the diffusive limit.  For the two-field
JFO problem D is the diffusivity of the single-field variable Φ (p = p_c Φ⁺,
λ = (−Φ)⁺): D = h² p_c/(12μ) (mm²/s) in the full film and D = 0 in the
cavitated zone, blended continuously by the full-film fraction s(p, λ) (see
:func:`jfo_diffusivity`; a jump of τ would make the residual discontinuous).

The planar/traditional form (§6.6) is obtained with ``grad = ufl.grad``,
``div = ufl.div`` and ``dx``; a lubrication surface S passes its tangential
operators grad_S, div_S and surface measure ds_S instead.  Units: mm, N, s, MPa.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import ufl

if TYPE_CHECKING:
    from ufl.core.expr import Expr


__all__ = [
    "WeightedMeasure",
    "cavitation_penalty",
    "jfo_complementarity",
    "jfo_diffusivity",
    "jfo_film_fraction",
    "jfo_residual",
    "poiseuille_conductance",
    "reynolds_flux",
    "reynolds_residual",
    "reynolds_strong_residual",
    "supg_stabilisation",
    "supg_tau",
]


class WeightedMeasure:
    """A measure times a weight, ``expr * WeightedMeasure(w, dx) == (expr * w) * dx``.

    Lets the Reynolds forms of this module (which take a measure) run on S pulled
    back to Γ_l (:mod:`forms.ehl`), with the weight w = ds_S/dS.
    """

    def __init__(self, weight: Expr | float, measure: ufl.Measure | WeightedMeasure) -> None:
        self.weight, self.measure = weight, measure

    def __rmul__(self, integrand: Expr) -> ufl.Form:
        return (integrand * self.weight) * self.measure

    def __call__(self, *args: object, **kwargs: object) -> WeightedMeasure:
        """Return the weighted measure with new subdomain data/metadata."""
        return WeightedMeasure(self.weight, self.measure(*args, **kwargs))


def poiseuille_conductance(h: Expr, mu: Expr | float) -> Expr:
    """Poiseuille flow factor h³/(12μ) (mm³/(MPa·s)) of eq. (40)."""
    return h**3 / (12 * mu)


def reynolds_flux(
    p: Expr, h: Expr, vbar: Expr, mu: Expr | float,
    grad: Callable[[Expr], Expr] = ufl.grad, rho: Expr | float = 1,
) -> Expr:
    """Flux per unit width q = ρ(−h³/(12μ) grad p + h v̄) (eq. 40; mm²/s).

    ``rho``: the density relative to the ambient one (1: the chapter's incompressible
    fluid, then q is the volume flux; a law ρ(p)/ρ₀ of :mod:`forms.fluid`: the
    compressible Reynolds equation div(ρ h³/(12μ) grad p) = div(ρ h v̄)).
    """
    return rho * (-poiseuille_conductance(h, mu) * grad(p) + h * vbar)


def reynolds_residual(
    p: Expr, dp: Expr, h: Expr, vbar: Expr, mu: Expr | float,
    dx: ufl.Measure | WeightedMeasure, grad: Callable[[Expr], Expr] = ufl.grad,
    dhdt: Expr | None = None, q_star: Expr | float | None = None, ds: ufl.Measure | None = None,
    rho: Expr | float = 1,
) -> ufl.Form:
    """Weak form (49) of the Reynolds equation (39)–(40), no cavitation.

    ∫ (∂h/∂t δp − q·grad δp) dx + ∫ q* δp ds; ``dhdt`` (mm/s) and the prescribed
    outward flux ``q_star`` (mm²/s) on ``ds`` are optional; ``rho`` as for
    :func:`reynolds_flux` (``dhdt`` is then ∂(ρh)/∂t).
    """
    q = reynolds_flux(p, h, vbar, mu, grad, rho)
    F = -ufl.inner(q, grad(dp)) * dx
    if dhdt is not None:
        F += dhdt * dp * dx
    if q_star is not None:
        F += q_star * dp * ds
    return F


def jfo_residual(
    p: Expr, lam: Expr | float, dp: Expr, h: Expr, vbar: Expr, mu: Expr | float,
    dx: ufl.Measure | WeightedMeasure, grad: Callable[[Expr], Expr] = ufl.grad,
    div: Callable[[Expr], Expr] = ufl.div, rate: Expr | None = None,
) -> ufl.Form:
    """Weak form (57) of the JFO mass-conserving Reynolds equation.

    ``lam`` is the void fraction λ = 1 − ϱ̄ (continuous field, so the jump term
    on the cavitation boundary Σ vanishes); ``rate`` is ∂(ϱ̄h)/∂t (mm/s),
    omitted in steady state.  With λ = 0 this is eq. (49) after integration by
    parts of the Couette part.
    """
    theta = 1 - lam
    F = theta * poiseuille_conductance(h, mu) * ufl.inner(grad(p), grad(dp)) * dx
    F += div(theta * h * vbar) * dp * dx
    if rate is not None:
        F += rate * dp * dx
    return F


def reynolds_strong_residual(
    p: Expr, lam: Expr | float, h: Expr, vbar: Expr, mu: Expr | float,
    grad: Callable[[Expr], Expr] = ufl.grad, div: Callable[[Expr], Expr] = ufl.div,
    rate: Expr | None = None, rho: Expr | float = 1,
) -> Expr:
    """Strong residual R = div(θρhv̄) − div(θρ h³/(12μ) grad p) + ∂(θρh)/∂t, θ = 1 − λ.

    Pass ``lam = 0`` for the model without (or with penalty) cavitation; ``rho`` as
    for :func:`reynolds_flux`.
    """
    theta = (1 - lam) * rho
    R = div(theta * h * vbar) - div(theta * poiseuille_conductance(h, mu) * grad(p))
    if rate is not None:
        R += rate
    return R


def supg_tau(h_e: Expr | float, vbar: Expr, diffusivity: Expr | float) -> Expr:
    """SUPG parameter τ = h_e/√(4|v̄|² + (12D/h_e)²) (s); see the module docstring.

    ``h_e`` is the element size (mm), ``diffusivity`` D (mm²/s).  Requires
    |v̄| > 0 or D > 0.
    """
    return h_e / ufl.sqrt(4 * ufl.inner(vbar, vbar) + (12 * diffusivity / h_e) ** 2)


def supg_stabilisation(
    p: Expr, lam: Expr | float, dp: Expr, h: Expr, vbar: Expr, mu: Expr | float, tau: Expr,
    dx: ufl.Measure | WeightedMeasure, grad: Callable[[Expr], Expr] = ufl.grad,
    div: Callable[[Expr], Expr] = ufl.div, rate: Expr | None = None, rho: Expr | float = 1,
) -> ufl.Form:
    """SUPG term ∫ τ (v̄·grad δp) R dx of Remark 3.2 (to be added to eq. 57 or 49).

    Consistent: it vanishes for the exact solution (R = 0).
    """
    R = reynolds_strong_residual(p, lam, h, vbar, mu, grad, div, rate, rho)
    return tau * ufl.inner(vbar, grad(dp)) * R * dx


def cavitation_penalty(
    p: Expr, dp: Expr, eps: Expr | float, dx: ufl.Measure | WeightedMeasure
) -> ufl.Form:
    """Penalty approximation of p ≥ 0: ∫ ε⁻¹ min(p, 0) δp dx, ε in MPa·s/mm."""
    return (1 / eps) * ufl.min_value(p, 0) * dp * dx


def jfo_complementarity(
    p: Expr, lam: Expr, dlam: Expr, p_c: Expr | float, dx: ufl.Measure,
    weight: Expr | float = 1,
) -> ufl.Form:
    """Constraint ∫ w min(p/p_c, λ) δλ dx enforcing (52): p ≥ 0, λ ≥ 0, pλ = 0.

    ``p_c`` (MPa) scales the pressure against the void fraction; ``weight`` w
    only scales the rows (a vertex-quadrature measure, so that the constraint holds
    at the nodes).
    """
    return weight * ufl.min_value(p / p_c, lam) * dlam * dx


def jfo_film_fraction(p: Expr, lam: Expr, p_c: Expr | float, delta: float = 1e-6) -> Expr:
    """Continuous full-film fraction s = (p⁺/p_c + δ)/(p⁺/p_c + λ⁺ + 2δ) ∈ (0, 1).

    s ≈ 1 in the full film (λ = 0, p > 0), s ≈ 0 in the cavitated zone (p = 0,
    λ ≫ δ).  Unlike an indicator of the cavitated zone it is continuous in
    (p, λ), so the SUPG residual built on it has no jumps when a node changes
    between the full film and the cavitated zone during Newton's iteration.
    """
    a = ufl.max_value(p, 0) / p_c + delta
    return a / (a + ufl.max_value(lam, 0) + delta)


def jfo_diffusivity(
    p: Expr, lam: Expr, h: Expr, mu: Expr | float, p_c: Expr | float, delta: float = 1e-6
) -> Expr:
    """Diffusivity D = s h² p_c/(12μ) (mm²/s) of the single-field JFO variable.

    s is the full-film fraction of :func:`jfo_film_fraction` (D = 0 in the
    cavitated zone, where the problem is pure advection); used for the element
    Péclet number of SUPG.
    """
    return jfo_film_fraction(p, lam, p_c, delta) * h**2 * p_c / (12 * mu)


