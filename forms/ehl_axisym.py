"""Axisymmetric soft EHL against a rigid rod (chapter §6.2–6.4, §7, example §8.1).

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
:func:`forms.ehl.fluid_traction` times the hoop stretch r/R.

Units: mm, N, s, MPa (viscosity MPa·s).
"""

import dataclasses
import math

import ufl

from . import ehl as ef
from .kinematics import deformation_gradient, nanson_normal

__all__ = [
    "axisymmetric_fluid_traction",
    "film_flux",
    "follower_pressure_traction",
    "manifold_normal",
    "reynolds_on_rod",
    "rod_countersurface",
    "rod_kinematics",
]


def rod_countersurface(x, r_rod):
    """Projection onto the rod r = r_rod in the meridian plane: (h, ν, y, ∂P/∂x), eq. (36–37)."""
    nu = ufl.as_vector([1.0, 0.0])
    y = ufl.as_vector([r_rod, x[1]])
    dP = ufl.as_matrix([[0.0, 0.0], [0.0, 1.0]])
    return x[0] - r_rod, nu, y, dP


def rod_kinematics(X, disp, grad_disp, N, r_rod, U):
    """:class:`forms.ehl.LubricationKinematics` of S = P(γ_l) on the rod (eqs. 36–42).

    ``N`` is the unit outer normal of Γ_l (may vary from facet to facet), ``U``
    the axial rod speed (mm/s).  v̄ = ½ U e_z (seal at rest, eq. 41–42); the
    field ``v_layer`` holds the relative velocity v_seal − v_rod = −U e_z that
    drives the Couette shear of eq. (46).
    """
    zero = ufl.as_vector([0.0, 0.0])
    kin = ef.lubrication_kinematics(X, disp, grad_disp, N, None, None, zero,
                                    surface=lambda x: rod_countersurface(x, r_rod))
    return dataclasses.replace(kin, vbar=ufl.as_vector([0.0, 0.5 * U]),
                               v_layer=ufl.as_vector([0.0, -U]))


def reynolds_on_rod(p, dp, kin, mu, dx, r_rod, **kwargs):
    """Axisymmetric steady Reynolds residual (49) on the rod, weight ds = 2π r_rod dl.

    Keyword arguments are those of :func:`forms.ehl.reynolds_on_surface` (eps,
    supg, p_c, h_e, nodal_dx, grad_gamma).
    """
    return 2 * math.pi * r_rod * ef.reynolds_on_surface(p, dp, kin, mu, dx, **kwargs)


def axisymmetric_fluid_traction(p, dpdT, kin, u, N, T, mu, shear=True):
    """Nominal fluid traction (46) on the seal per reference area 2πR dS (MPa).

    Pressure by the axisymmetric Nanson formula (3×3 F, hoop stretch r/R), Couette
    −(μ/h)(v_seal − v_rod) and Poiseuille −(h/2) grad_S p shear in the r–z plane,
    both times the area ratio (r/R)|F₂T|.  ``u`` is the bulk displacement.
    """
    X = ufl.SpatialCoordinate(u.ufl_function_space().mesh)
    hoop = 1 + u[0] / X[0]
    F2 = ufl.Identity(2) + ufl.grad(u)
    return hoop * ef.fluid_traction(p, dpdT, kin, F2, N, T, mu, shear=shear)


def follower_pressure_traction(p, u, N):
    """Nominal traction −p J F^{-T} N (MPa per reference area 2πR dS) of a follower pressure.

    Axisymmetric Nanson formula (eq. 9) with the 3×3 F; returns the r–z components.
    """
    a = nanson_normal(deformation_gradient(u, "axisymmetric"), N, "axisymmetric")
    return -p * ufl.as_vector([a[0], a[1]])


def manifold_normal(mesh, outward):
    """Return the unit normal of the facets of a 1D manifold mesh in 2D, oriented along ``outward``.

    The facet tangent is the column of the cell Jacobian; ``outward`` (UFL vector)
    only fixes the sign, so the normal is the exact discrete facet normal.
    """
    J = ufl.Jacobian(mesh)
    t = ufl.as_vector([J[0, 0], J[1, 0]])
    t = t / ufl.sqrt(ufl.dot(t, t))
    n = ufl.as_vector([t[1], -t[0]])
    return ufl.sign(ufl.dot(n, outward)) * n


def film_flux(kin, p, mu, grad_gamma):
    """Axial volume flux per unit circumference q = h v̄_z − h³/(12μ) ∂p/∂z (mm²/s), eq. (48)."""
    gp = kin.grad(p, grad_gamma)
    return kin.h * kin.vbar[1] - kin.h**3 / (12 * mu) * gp[1]

