"""Axisymmetric soft EHL against a rigid rod (chapter §6.2–6.4, §7, example §8.1).

The film's Reynolds rows and fluid traction are those of :mod:`forms.ehl` and
:mod:`forms.reynolds` with the axisymmetric kinematics (``Film`` on a body of
kind ``axisymmetric``); this module holds what is particular to the seal: the
follower pressure of the sealed fluid and the axial flux (leakage).  The
geometry they rest on:

Coordinates of the meridian plane (r, z) = (X₀, X₁), rod axis = z axis.  The
countersurface is the rod cylinder r = r_rod; in the meridian plane it is the
straight line r = r_rod, so the closest-point projection of x = X + u is

    y = P(x) = (r_rod, x_z),  ν = e_r,  h = (x − y)·ν = x_r − r_rod,  ∂P/∂x = e_z⊗e_z   (36–37)

and the lubrication surface S = P(γ_l) is a part of the rod cylinder.  The seal
is at rest, the rod slides axially with speed U (U > 0: towards the air side,
+z), so the mean velocity is v̄ = ½(v_rod + v_seal) = ½ U e_z (41–42) and the
relative velocity of the seal w.r.t. the rod is v_seal − v_rod = −U e_z.

Reynolds equation on the surface of revolution S (49): for axisymmetric flow
the area element of S is ds = 2π r_S dl with r_S = r_rod on the rod and dl the
meridian length, dl = |det A| dS (A the tangent map of :mod:`forms.ehl`); grad_S
and div_S of axisymmetric fields without hoop components reduce to the
meridian operators.  The weak form is therefore the one of :mod:`forms.ehl`
multiplied by the constant 2π r_rod.

Fluid traction on the seal (46), nominal per reference area dA = 2πR dS: with
the 3×3 axisymmetric F (hoop stretch r/R), J F^{-T} N = (r/R) J₂ F₂^{-T} N and
da/dA = (r/R)|F₂ T|, so the axisymmetric nominal traction is the plane one of
:func:`forms.film_traction.fluid_traction` times the hoop stretch r/R.

Units: mm, N, s, MPa (viscosity MPa·s).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import ufl

from .kinematics import deformation_gradient, nanson_normal

if TYPE_CHECKING:
    from ufl.core.expr import Expr

    from .ehl import LubricationKinematics

__all__ = [
    "film_flux",
    "follower_pressure_traction",
]


def follower_pressure_traction(p: Expr | float, u: ufl.Coefficient, N: Expr) -> Expr:
    """Nominal traction −p J F^{-T} N (MPa per reference area 2πR dS) of a follower pressure.

    Axisymmetric Nanson formula (eq. 9) with the 3×3 F; returns the r–z components.
    """
    a = nanson_normal(deformation_gradient(u, "axisymmetric"), N, "axisymmetric")
    return -p * ufl.as_vector([a[0], a[1]])


def film_flux(
    kin: LubricationKinematics, p: Expr, mu: Expr | float,
    grad_gamma: Callable[[Expr], Expr], lam: Expr | None = None,
) -> Expr:
    """Axial volume flux per unit circumference q = θ(h v̄_z − h³/(12μ) ∂p/∂z) (mm²/s), eq. (48).

    θ = 1 − λ with the JFO void fraction ``lam`` (eq. 57; None: θ = 1).
    """
    gp = kin.grad(p, grad_gamma)
    theta = 1 if lam is None else 1 - lam
    return theta * (kin.h * kin.vbar[1] - kin.h**3 / (12 * mu) * gp[1])

