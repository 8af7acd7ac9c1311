"""Finite-deformation kinematics for 3D, plane-strain and axisymmetric bodies (chapter §2, §4.3).

Every body is described by a 3×3 deformation gradient so that one strain-energy
function serves all three kinematic kinds:

* ``"3d"``: F = I + Grad u.
* ``"plane_strain"``: the in-plane 2×2 block of I + Grad u, embedded with F₃₃ = 1.
* ``"axisymmetric"``: coordinates (R, Z) = (X₀, X₁); the in-plane block plus the hoop
  stretch F₃₃ = r/R = 1 + u_R/R, and the volume measure 2πR dR dZ.

Lengths in mm.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import ufl

if TYPE_CHECKING:
    from dolfinx.mesh import Mesh
    from ufl.core.expr import Expr

__all__ = [
    "AXIS_TOL",
    "KINDS",
    "axis_safe_hoop",
    "area_ratio",
    "deformation_gradient",
    "grad3",
    "nanson_normal",
    "reference_volume_factor",
    "spatial_position",
]

KINDS = ("3d", "plane_strain", "axisymmetric")


def _check(kind: str) -> None:
    if kind not in KINDS:
        raise ValueError(f"unknown kinematic kind {kind!r}; expected one of {KINDS}")


def grad3(v: ufl.Coefficient | ufl.Argument, kind: str) -> Expr:
    """Return the reference gradient of a displacement-like field ``v`` as a 3×3 tensor.

    For plane strain the third row/column vanish; for axisymmetry the (3,3)
    entry is the hoop term v_R / R.
    """
    _check(kind)
    g = ufl.grad(v)
    if kind == "3d":
        return g
    X = ufl.SpatialCoordinate(v.ufl_function_space().mesh)
    hoop = axis_safe_hoop(v, X) if kind == "axisymmetric" else 0
    return ufl.as_tensor(
        [[g[0, 0], g[0, 1], 0], [g[1, 0], g[1, 1], 0], [0, 0, hoop]]
    )


#: distance (mm) from the axis below which a point is on it (vertex-rule points, nodes)
AXIS_TOL = 1e-12


def axis_safe_hoop(v: ufl.Coefficient | ufl.Argument, X: Expr) -> Expr:
    """Hoop term v_R/R, by its limit ∂v_R/∂R on the axis (R = 0, where v_R = 0).

    A vertex-rule point on the axis (a contact node at r = 0) would otherwise give
    0/0; inside the cells (R > 0) this is v_R/R exactly.
    """
    # written linear in v with the switches as coefficients (FFCx compiles no test or
    # trial function inside a conditional)
    off_axis = ufl.gt(abs(X[0]), AXIS_TOL)
    inv_r = ufl.conditional(off_axis, 1 / X[0], 0.0)
    on_axis = ufl.conditional(off_axis, 0.0, 1.0)
    return v[0] * inv_r + on_axis * ufl.grad(v)[0, 0]


def deformation_gradient(u: ufl.Coefficient, kind: str) -> Expr:
    """Deformation gradient F = I + Grad u (3×3 for every ``kind``) — chapter eq. (1)."""
    return ufl.Identity(3) + grad3(u, kind)


def reference_volume_factor(mesh: Mesh, kind: str) -> Expr | float:
    """Factor multiplying dX in volume and surface integrals: 2πR for axisymmetry, else 1."""
    _check(kind)
    if kind == "axisymmetric":
        return 2 * ufl.pi * ufl.SpatialCoordinate(mesh)[0]
    return 1


def _embed_normal(N: Expr, kind: str) -> Expr:
    if kind == "3d":
        return N
    return ufl.as_vector([N[0], N[1], 0])


def nanson_normal(F: Expr, N: Expr, kind: str) -> Expr:
    """Nanson's formula: n da = J F^{-T} N dA; returns the (unnormalised) vector J F^{-T} N."""
    return ufl.det(F) * ufl.inv(F).T * _embed_normal(N, kind)


def area_ratio(F: Expr, N: Expr, kind: str) -> Expr:
    """Area ratio j = da/dA = J |F^{-T} N| of a boundary with reference normal N (eq. 9)."""
    a = nanson_normal(F, N, kind)
    return ufl.sqrt(ufl.dot(a, a))


def spatial_position(u: ufl.Coefficient) -> Expr:
    """Return the current position x = X + u (eq. 1)."""
    return ufl.SpatialCoordinate(u.ufl_function_space().mesh) + u


