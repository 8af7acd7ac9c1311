"""Strain-energy functions and stresses of the solid (chapter §2, §7.1).

Each law maps a 3×3 deformation gradient to a strain-energy density ψ (MPa);
the first Piola–Kirchhoff stress is P = ∂ψ/∂F obtained with ``ufl.diff`` and
the tangent follows from ``ufl.derivative`` of the residual.  The geometrically
linear model is offered behind the same interface: ψ(F) = μ ε:ε + λ/2 (tr ε)²
with ε = sym(F − I), whose derivative is the small-strain stress σ(ε).

Mixed (u, p) form for nearly incompressible solids.  Every law is written

    ψ(F) = ψ_r(F) + K/2 g(J)²          (:func:`volumetric_split`)

with a volumetric measure g (J − 1 for Mooney–Rivlin, ln J for neo-Hookean,
tr ε for the linear law) and its modulus K (κ, λ, λ).  The perturbed-Lagrangian
energy of the displacement u and the volumetric stress p (MPa, tension positive)

    Π(u, p) = ∫ ψ_r(F) + p g(J) − p²/(2K) − β/2 |Grad p|² dV,   β = α h_K²/G   (M)

returns ψ on eliminating p = K g(J) (β = 0), so the continuous problem is
unchanged; its stationarity in (u, p) is the mixed residual
(:func:`mixed_virtual_work`) and its second derivative the (symmetric) tangent.
With equal-order P1 u and p the β term (Brezzi–Pitkäranta, O(h_K²) and so
without effect on the rates of P1 displacements) makes the pair inf–sup stable:
linear triangles and tetrahedra do not lock when K/G is large (the O-ring's
κ = 1000 G).  Locking is what makes the contact and film pressures on the
boundaries of a P1 displacement solid zig-zag node to node (a locked P1 surface
cannot take the smooth shape the film or the contact asks of it).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

import ufl

from .kinematics import deformation_gradient, grad3, nanson_normal, reference_volume_factor

if TYPE_CHECKING:
    from ufl.core.expr import Expr

__all__ = [
    "body_force_work",
    "MATERIALS",
    "external_virtual_work",
    "follower_pressure_work",
    "first_piola",
    "internal_virtual_work",
    "lame_parameters",
    "linear_elastic",
    "mixed_strain_energy",
    "mixed_virtual_work",
    "mooney_rivlin",
    "neo_hookean",
    "stored_energy",
    "strain_energy",
    "volumetric_split",
]

MATERIALS = ("neo-hookean", "mooney-rivlin", "linear")


def lame_parameters(E: float, nu: float) -> tuple[float, float]:
    """Lamé constants (μ, λ) from Young's modulus E (MPa) and Poisson's ratio ν."""
    return E / (2 * (1 + nu)), E * nu / ((1 + nu) * (1 - 2 * nu))


def _neo_hookean_parts(
    F: Expr, mu: Expr | float, lmbda: Expr | float
) -> tuple[Expr, Expr, Expr | float]:
    J = ufl.det(F)
    return mu / 2 * (ufl.tr(F.T * F) - 3 - 2 * ufl.ln(J)), ufl.ln(J), lmbda


def neo_hookean(F: Expr, mu: Expr | float, lmbda: Expr | float) -> Expr:
    """Compressible neo-Hookean ψ = μ/2 (I₁ − 3 − 2 ln J) + λ/2 (ln J)²."""
    psi, g, K = _neo_hookean_parts(F, mu, lmbda)
    return psi + K / 2 * g**2


def _mooney_rivlin_parts(
    F: Expr, mu1: Expr | float, mu2: Expr | float, kappa: Expr | float
) -> tuple[Expr, Expr, Expr | float]:
    J = ufl.det(F)
    C = F.T * F
    I1 = ufl.tr(C)
    I2 = (I1**2 - ufl.tr(C * C)) / 2
    return mu1 / 2 * (J ** (-2 / 3) * I1 - 3) + mu2 / 2 * (J ** (-4 / 3) * I2 - 3), J - 1, kappa


def mooney_rivlin(
    F: Expr, mu1: Expr | float, mu2: Expr | float, kappa: Expr | float
) -> Expr:
    """Nearly incompressible Mooney–Rivlin, ψ = μ₁/2 (Ī₁ − 3) + μ₂/2 (Ī₂ − 3) + κ/2 (J − 1)².

    Isochoric invariants Ī₁ = J^{-2/3} I₁, Ī₂ = J^{-4/3} I₂; small-strain shear
    modulus μ₁ + μ₂ and bulk modulus κ (all MPa).
    """
    psi, g, K = _mooney_rivlin_parts(F, mu1, mu2, kappa)
    return psi + K / 2 * g**2


def _linear_parts(
    F: Expr, mu: Expr | float, lmbda: Expr | float
) -> tuple[Expr, Expr, Expr | float]:
    eps = ufl.sym(F - ufl.Identity(3))
    return mu * ufl.inner(eps, eps), ufl.tr(eps), lmbda


def linear_elastic(F: Expr, mu: Expr | float, lmbda: Expr | float) -> Expr:
    """Geometrically linear (small-strain) Hooke law written as ψ(F) with ε = sym(F − I)."""
    psi, g, K = _linear_parts(F, mu, lmbda)
    return psi + K / 2 * g**2


def volumetric_split(
    F: Expr, material: str, params: Mapping[str, Expr | float]
) -> tuple[Expr, Expr, Expr | float]:
    """Return (ψ_r(F), g(J), K) with ψ = ψ_r + K/2 g² (see the module docstring)."""
    if material == "neo-hookean":
        return _neo_hookean_parts(F, params["mu"], params["lmbda"])
    if material == "linear":
        return _linear_parts(F, params["mu"], params["lmbda"])
    if material == "mooney-rivlin":
        return _mooney_rivlin_parts(F, params["mu1"], params["mu2"], params["kappa"])
    raise ValueError(f"unknown material {material!r}; expected one of {MATERIALS}")


def mixed_strain_energy(
    F: Expr, p: Expr, material: str, params: Mapping[str, Expr | float]
) -> Expr:
    """Mixed energy density ψ_r(F) + p g(J) − p²/(2K) of eq. (M) without the β term (MPa)."""
    psi, g, K = volumetric_split(F, material, params)
    return psi + p * g - p**2 / (2 * K)


def mixed_virtual_work(
    u: ufl.Coefficient, p: Expr, v: ufl.Coefficient | ufl.Argument, q: Expr, kind: str,
    material: str, params: Mapping[str, Expr | float], dx: ufl.Measure, beta: Expr | float,
) -> tuple[ufl.Form, ufl.Form]:
    """Residuals (R_u, R_p) of the mixed energy (M): its derivatives along (δu, δp) = (v, q).

        R_u = ∫ ∂ψ_m/∂F : Grad δu dV,   ψ_m = ψ_r(F) + p g(J) − p²/(2K),
        R_p = ∫ (g(J) − p/K) δp − β Grad p·Grad δp dV

    (2πR-weighted if axisymmetric); ``beta`` = α h_K²/G (mm²/MPa, UFL).  The
    u row is the internal work of eq. (7) with P = ∂ψ_m/∂F (``ufl.diff``).
    """
    F = ufl.variable(deformation_gradient(u, kind))
    psi, g, K = volumetric_split(F, material, params)
    P = ufl.diff(psi + p * g - p**2 / (2 * K), F)
    w = reference_volume_factor(u.ufl_function_space().mesh, kind)
    R_u = ufl.inner(P, grad3(v, kind)) * w * dx
    R_p = ((g - p / K) * q - beta * ufl.dot(ufl.grad(p), ufl.grad(q))) * w * dx
    return R_u, R_p


def strain_energy(F: Expr, material: str, params: Mapping[str, Expr | float]) -> Expr:
    """Dispatch on ``material`` in :data:`MATERIALS` with parameter dict ``params``.

    neo-hookean and linear take ``mu``, ``lmbda``; mooney-rivlin takes ``mu1``,
    ``mu2``, ``kappa``.
    """
    psi, g, K = volumetric_split(F, material, params)
    return psi + K / 2 * g**2


def first_piola(F: Expr, material: str, params: Mapping[str, Expr | float]) -> Expr:
    """First Piola–Kirchhoff stress P = ∂ψ/∂F (3×3) via ``ufl.variable``/``ufl.diff``."""
    F = ufl.variable(F)
    return ufl.diff(strain_energy(F, material, params), F)


def internal_virtual_work(
    u: ufl.Coefficient, v: ufl.Coefficient | ufl.Argument, kind: str, material: str,
    params: Mapping[str, Expr | float], dx: ufl.Measure,
) -> ufl.Form:
    """Return the internal virtual work ∫ P : Grad δφ dV of eq. (7), 2πR-weighted if axisym."""
    F = deformation_gradient(u, kind)
    P = first_piola(F, material, params)
    w = reference_volume_factor(u.ufl_function_space().mesh, kind)
    return ufl.inner(P, grad3(v, kind)) * w * dx


def stored_energy(
    u: ufl.Coefficient, kind: str, material: str, params: Mapping[str, Expr | float],
    dx: ufl.Measure,
) -> ufl.Form:
    """Return the stored energy ∫ ψ(F) dV (2πR-weighted if axisym), the potential of eq. (7)."""
    F = deformation_gradient(u, kind)
    w = reference_volume_factor(u.ufl_function_space().mesh, kind)
    return strain_energy(F, material, params) * w * dx


def external_virtual_work(
    traction: Expr, v: ufl.Coefficient | ufl.Argument, kind: str, ds: ufl.Measure
) -> ufl.Form:
    """Virtual work ∫ T*·δφ dS of a prescribed nominal traction T* (MPa), eq. (7)."""
    w = reference_volume_factor(v.ufl_function_space().mesh, kind)
    return ufl.dot(traction, v) * w * ds


def follower_pressure_work(
    pressure: Expr | float, u: ufl.Coefficient, v: ufl.Coefficient | ufl.Argument, kind: str,
    ds: ufl.Measure,
) -> ufl.Form:
    """Virtual work of a follower pressure p (MPa): T* = −p J F⁻ᵀ N (Nanson), eq. (7).

    ``u`` the displacement (F = I + Grad u, with the hoop stretch when
    axisymmetric), ``v`` its test function, ``ds`` the loaded boundary.
    """
    F = deformation_gradient(u, kind)
    t = -pressure * nanson_normal(F, ufl.FacetNormal(u.ufl_function_space().mesh), kind)
    t = ufl.as_vector([t[i] for i in range(v.ufl_shape[0])])
    return external_virtual_work(t, v, kind, ds)


def body_force_work(
    force: Expr, v: ufl.Coefficient | ufl.Argument, kind: str, dx: ufl.Measure
) -> ufl.Form:
    """Virtual work ∫ B·δφ dV of a dead body force B (N/mm³ per reference volume), eq. (7)."""
    w = reference_volume_factor(v.ufl_function_space().mesh, kind)
    return ufl.dot(force, v) * w * dx
