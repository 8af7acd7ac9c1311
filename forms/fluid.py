"""Lubricant laws: viscosity μ(p) and density ρ(p)/ρ₀ (UFL of the film pressure).

The chapter takes the fluid isoviscous and says the pressure dependence "can be
easily accounted for": a law here is a pure function ``law(p, **parameters)`` of
the (UFL) film pressure p in MPa returning μ in MPa·s.  A film takes the law once
(:class:`tribofx.laws.Law`) and uses the same expression in every place μ enters —
the Poiseuille conductance h³/(12μ) and the SUPG diffusivity of the Reynolds rows,
the Couette and Poiseuille shear of the fluid traction (eq. 46), the friction
post-processing — so they cannot disagree, and ``ufl.derivative`` keeps the
Newton tangent exact.

The pressure dependence acts on p⁺ = max(p, 0): a cavitated (p ≤ 0) film is at
ambient pressure, and Roelands' law is undefined below −p_R.

Units: p and the parameters in MPa, MPa·s and 1/MPa (2·10⁻⁸ Pa⁻¹ = 0.02 MPa⁻¹, a
mineral oil's pressure–viscosity coefficient).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import ufl

if TYPE_CHECKING:
    from ufl.core.expr import Expr

__all__ = [
    "DOWSON_HIGGINSON_A",
    "ROELANDS_P_R",
    "constant_density",
    "dowson_higginson_density",
    "barus_viscosity",
    "constant_viscosity",
    "roelands_index",
    "roelands_viscosity",
]

#: Roelands' reference pressure p_R = 1.96·10⁸ Pa (MPa)
ROELANDS_P_R = 196.0
#: ln of Roelands' μ_∞ = 6.31·10⁻⁵ Pa·s, in MPa·s: μ_∞ = 6.31·10⁻¹¹ MPa·s
_LN_MU_INF = -23.486  # ln(6.31e-11)


def constant_viscosity(p: Expr, mu0: Expr | float) -> Expr:
    """μ = μ₀ (the chapter's isoviscous fluid)."""
    return mu0 + 0 * p


def barus_viscosity(p: Expr, mu0: Expr | float, alpha: Expr | float) -> Expr:
    """Barus: μ = μ₀ exp(α p⁺) (α in 1/MPa)."""
    return mu0 * ufl.exp(alpha * ufl.max_value(p, 0))


def roelands_viscosity(p: Expr, mu0: Expr | float, z: Expr | float) -> Expr:
    """Roelands: μ = μ₀ exp{(ln μ₀ − ln μ_∞)[(1 + p⁺/p_R)^z − 1]}.

    μ_∞ = 6.31·10⁻⁵ Pa·s, p_R = 196 MPa, z the pressure–viscosity index (≈ 0.6 for
    mineral oils; :func:`roelands_index` gives the z of a Barus α).
    """
    return mu0 * ufl.exp((ufl.ln(mu0) - _LN_MU_INF)
                         * ((1 + ufl.max_value(p, 0) / ROELANDS_P_R) ** z - 1))


def roelands_index(mu0: float, alpha: float) -> float:
    """Return the z for which Roelands' law has Barus' slope α: α p_R/(ln μ₀ − ln μ_∞)."""
    return alpha * ROELANDS_P_R / (math.log(mu0) - _LN_MU_INF)


#: Dowson–Higginson's constants: ρ/ρ₀ = (A + B p)/(A + p), A = 5.9·10⁸ Pa (MPa), B = 1.34
DOWSON_HIGGINSON_A = 590.0


def constant_density(p: Expr, rho: Expr | float = 1.0) -> Expr:
    """ρ/ρ₀ = 1: the chapter's incompressible fluid."""
    return rho + 0 * p


def dowson_higginson_density(
    p: Expr, a: Expr | float = DOWSON_HIGGINSON_A, b: Expr | float = 1.34
) -> Expr:
    """Dowson–Higginson: ρ/ρ₀ = (a + b p⁺)/(a + p⁺), p and a in MPa (→ b for p → ∞)."""
    pp = ufl.max_value(p, 0)
    return (a + b * pp) / (a + pp)
