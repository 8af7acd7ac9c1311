"""The film on its walls: the fluid traction (eq. 46), its work, and its load of wear.

The traction on the layer and on the countersurface, its virtual work, and the
film as a load of Archard wear (chapter §6.4).

Every function takes the :class:`forms.ehl.LubricationKinematics` of the film
(evaluated with the bulk displacement for the layer's rows) and returns UFL.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import ufl

from .wear import WearLoad

if TYPE_CHECKING:
    from ufl.core.expr import Expr

    from .ehl import LubricationKinematics

__all__ = ["countersurface_traction", "film_virtual_work", "film_wear_load", "fluid_traction"]


def film_virtual_work(
    traction: Expr, v: Expr, ds: ufl.Measure, weight: Expr | float = 1
) -> ufl.Form:
    """Film term of the solid's virtual work (62): −∫_Γl T·δφ w dS.

    ``traction`` is the nominal fluid traction T (:func:`fluid_traction`, MPa),
    ``v`` the test function of the displacement, ``ds`` the measure of Γ_l and
    ``weight`` w the reference measure factor (2πR for axisymmetry, else 1).
    Equivalent to the spatial form (63) with t ds = T dS.
    """
    return -ufl.dot(traction, v) * weight * ds


def fluid_traction(
    p: Expr | float, dpdT: Expr, kin: LubricationKinematics, F: Expr, N: Expr, T: Expr | None,
    mu: Expr | float, shear: bool = True, model: str = "finite",
    factors: tuple[Expr, Expr] | None = None,
) -> Expr:
    """Nominal traction (MPa per reference length) of the film on the layer, eq. (46).

    Args:
        p: pressure (MPa).
        dpdT: tangential derivative Grad_Γ p · T of the pressure on Γ_l (MPa/mm), or
            (vector) the tangential gradient Grad_Γ p itself.
        kin: :class:`LubricationKinematics` evaluated with the bulk displacement.
        F: deformation gradient (gdim × gdim) of the bulk.
        N: unit outer normal of Γ_l (reference).
        T: unit tangent of Γ_l (reference, gdim = 2: the shear stretch |F T| and,
            for a scalar ``dpdT``, the direction of the gradient); None in 3D.
        mu: viscosity (MPa·s).
        model: "finite" (Nanson, current normal and stretch) or "linear" (reference surface).
        shear: include the Couette −(μ/h)(v_layer − v_counter) and Poiseuille
            −(h/2) grad_S p terms (v_counter = ``kin.v_counter``, 0 if None).
        factors: (c, d) in place of μ/h and h/2 (a rough film's shear-stress
            factors, :func:`forms.mixed.rough_shear_factors`), or None.
    """
    c, d = factors if factors is not None else (mu / kin.h, kin.h / 2)
    if len(ufl.shape(dpdT)) == 1:
        grad_gamma_p = dpdT                       # Grad_Γ p
    else:
        grad_gamma_p = dpdT * T                   # (Grad_Γ p·T) T (gdim = 2)
    v_rel = kin.v_layer if kin.v_counter is None else kin.v_layer - kin.v_counter
    if model == "linear":
        Tn = -p * N
        if shear:
            grad_S_p = ufl.inv(kin.A).T * grad_gamma_p
            Tn = Tn - c * v_rel - d * grad_S_p
        return Tn
    Tn = -p * ufl.det(F) * ufl.inv(F).T * N      # −p n ds/dS (Nanson)
    if shear:
        if len(N) == 2:
            FT = F * T
            j = ufl.sqrt(ufl.dot(FT, FT))         # ds/dS of γ_l
        else:
            nJ = ufl.det(F) * ufl.inv(F).T * N
            j = ufl.sqrt(ufl.dot(nJ, nJ))         # ds/dS = J|F⁻ᵀN| (Nanson)
        grad_S_p = ufl.inv(kin.A).T * grad_gamma_p
        Tn = Tn - j * (c * v_rel + d * grad_S_p)
    return Tn


def countersurface_traction(
    p: Expr, grad_gamma_p: Expr, kin: LubricationKinematics, mu: Expr | float,
    factors: tuple[Expr, Expr] | None = None,
) -> Expr:
    """Film traction on the countersurface per unit area of S (MPa): (46) at the other wall.

    −p ν + (μ/h)(v_layer − v_counter) − (h/2) grad_S p: the pressure along the
    countersurface's normal ν (into the film) and the wall shear stress of
    Reynolds' velocity profile at the countersurface (its Couette part
    reverses, its Poiseuille part keeps its sign against (46) on the layer).
    ``grad_gamma_p`` is Grad_Γ p on Γ_l, ``kin`` the :class:`LubricationKinematics`
    of S (the reference surface for the linear model); integrate with ds_S =
    ``kin.stretch`` dS.  The film's force on a rigid counterpart: the friction a
    rig measures on it.  ``factors``: (c, d) in place of μ/h and h/2 (a rough film's,
    :func:`forms.mixed.rough_shear_factors`).
    """
    c, d = factors if factors is not None else (mu / kin.h, kin.h / 2)
    v_rel = kin.v_layer if kin.v_counter is None else kin.v_layer - kin.v_counter
    grad_S_p = ufl.inv(kin.A).T * grad_gamma_p
    return -p * kin.nu + c * v_rel - d * grad_S_p


def film_wear_load(
    p: Expr, kin: LubricationKinematics, F: Expr, N: Expr, model: str = "finite"
) -> WearLoad:
    """Return the film as a driver of Archard wear of the layer (:class:`forms.wear.WearLoad`).

    The normal traction is the pressure part of (46) along the current normal,
    T_N = −p⁺ j per unit reference area (j = J|F⁻ᵀN| = ds/dS, Nanson; 1 in the
    geometrically linear model), and the sliding speed that of the layer against
    the countersurface, ‖v_layer − v_counter‖ (mm/s): the pressure form of
    Archard's law, k p j ‖v‖, for wear under the film's load (e.g. by the
    asperities the film does not separate, or erosive wear in a law k(p)).
    """
    v_rel = kin.v_layer if kin.v_counter is None else kin.v_layer - kin.v_counter
    p_plus = ufl.max_value(p, 0)
    if model == "linear":
        j = 1
    else:
        nJ = ufl.det(F) * ufl.inv(F).T * N
        j = ufl.sqrt(ufl.dot(nJ, nJ))
    return WearLoad(normal=-p_plus * j, slip_speed=ufl.sqrt(ufl.dot(v_rel, v_rel)))
