"""Transient films: the squeeze term on a moving, deforming lubrication surface (past §6–§8).

The chapter's film is steady at fixed points of S (∂h/∂t = 0 in eq. 49).  A
transient film lives on S(t) = P(γ_l(t)), parametrised by the reference points
X of Γ_l: y(X, t) is the point of S carrying X (:attr:`LubricationKinematics.y`,
the projection P(x), or the point of S_α).  The fluid in a patch A(t) = y(A₀, t)
of S changes by what the relative flux carries across its moving edge,

    d/dt ∫_A(t) m ds_S = −∮ (q − m ẏ_t)·n dl,    m = ρ θ h,  θ = 1 − λ,

with q = ρθ(−h³/(12μ) grad_S p + h v̄) the flux of eq. (40) in the frame of the
velocities (v̄ = ½(v_layer + v_counter)) and ẏ_t = (I − ν⊗ν) ẏ the tangential
velocity of the parametrisation.  Pulled back to Γ_l (ds_S = J_S dS, the
``stretch``; w = 2π r_S on a surface of revolution) and tested by δp:

    ∫_Γl d(m J_S w)/dt|_X δp dS − ∫_S (q − m ẏ_t)·grad_S δp ds_S = 0.

So the transient rows are the steady ones (49)/(57) with v̄ replaced by the
relative mean velocity v̄ − ẏ_t (:func:`moving_surface`) plus the rate of the
fluid *content* c = ρ θ h J_S w per unit reference measure
(:func:`film_content`), whose time derivative is taken at fixed X by the
backward-difference formulas of the slow time (:func:`backward_difference`).
The layer's material velocity gains the rate of its displacement,
v_layer = (I − ν⊗ν)(F V + u̇), so that a layer stretching under the squeeze
drags the fluid (and enters the Couette traction (46)).

Reductions.  ∂/∂t = 0 (ẏ = 0, u̇ = 0, c constant): the chapter's steady form.
A rigid plane approaching a rigid body along its normal at speed V: ẏ_t = 0,
J_S constant and ∂h/∂t = −V, so the rows are the classical squeeze film
∫ (∂h/∂t δp + h³/(12μ) grad p·grad δp) = 0.  Small deformation (``model=
"linear"``): S is the reference projection, J_S and ẏ are fixed and
c = ρ θ (g + ν₀·u), the classical EHL squeeze term ∂(ρθh)/∂t.

Units: mm, s, MPa; c in mm (per unit reference length or area), rates mm/s.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

import ufl

if TYPE_CHECKING:
    from ufl.core.expr import Expr

    from .ehl import LubricationKinematics

__all__ = ["backward_difference", "film_content", "moving_surface", "surface_rate"]


def film_content(
    kin: LubricationKinematics, lam: Expr | None = None, rho: Expr | float = 1,
    weight: Expr | float = 1,
) -> Expr:
    """Fluid content c = ρ θ h J_S w per unit reference measure of Γ_l (mm).

    ``lam``: the JFO void fraction (θ = 1 − min(λ, 1); None: a full film,
    θ = 1, as in the penalty model); ``rho``: the density law's ρ(p)/ρ₀;
    ``weight``: 2π r_S of an axisymmetric film (1 in the plane and in 3D).
    """
    theta = 1 if lam is None else 1 - ufl.min_value(lam, 1.0)
    return rho * theta * kin.h * kin.stretch * weight


def backward_difference(
    f: Expr, f_n: Expr, f_nm1: Expr, inv_dt: Expr | float, c0: Expr | float, c1: Expr | float
) -> Expr:
    """Rate (c₀ (f − f_n) + c₁ (f_n − f_{n−1}))/Δt of a history (BDF1/BDF2, variable step).

    ``inv_dt`` = 1/Δt (0 between steps: the steady film); (c₀, c₁) = (1, 0) is
    backward Euler, the variable-step BDF2 weights are those of
    :func:`forms.wear.bdf2_coefficients`.
    """
    return inv_dt * (c0 * (f - f_n) + c1 * (f_n - f_nm1))


def moving_surface(
    kin: LubricationKinematics, layer_rate: Expr | None = None, surface_rate: Expr | None = None
) -> LubricationKinematics:
    """Kinematics of a transient film: the layer's displacement rate and S's motion.

    ``layer_rate`` u̇ (mm/s, at X): added to the layer velocity, v_layer += (I − ν⊗ν) u̇;
    ``surface_rate`` ẏ (mm/s): the velocity of the point of S carrying X; the
    mean velocity becomes the one relative to it, v̄ = ½(v_layer + v_counter) − (I − ν⊗ν) ẏ.
    The film thickness, the normal and the metric are unchanged.  Use the
    result with ``surface_rate`` for the Reynolds rows only; the tractions need
    the material velocities (``surface_rate=None``).
    """
    P = ufl.Identity(len(kin.nu)) - ufl.outer(kin.nu, kin.nu)
    v_layer, vbar = kin.v_layer, kin.vbar
    if layer_rate is not None:
        v_layer = v_layer + P * layer_rate
        vbar = vbar + 0.5 * (P * layer_rate)
    if surface_rate is not None:
        vbar = vbar - P * surface_rate
    return dataclasses.replace(kin, v_layer=v_layer, vbar=vbar)


def surface_rate(
    y: Expr, u: ufl.Coefficient, u_rate: Expr, c_rate: Expr | None = None
) -> Expr:
    """Velocity ẏ of the point of S carrying X, by the chain rule (mm/s).

    y is a UFL expression of the layer displacement ``u`` (through x = X + u) and
    of the countersurface's rigid translation c; a common translation d of x and
    c moves y by d (the projection, and S_α, are frame-indifferent), so

        ẏ = y'(u)[u̇ − ċ] + ċ,

    with the Gateaux derivative y'(u) of ``ufl.derivative``.  ``u_rate`` u̇ and
    ``c_rate`` ċ (None: a countersurface at rest) are the backward differences of
    the histories, so a steady state has ẏ = 0 exactly and the scheme's order is
    kept (y'(u_{n+1}) times a difference of order k is a rate of order k).
    """
    if c_rate is None:
        return ufl.derivative(y, u, u_rate)
    return ufl.derivative(y, u, u_rate - c_rate) + c_rate
