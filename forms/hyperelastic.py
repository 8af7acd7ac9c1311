"""Strain-energy functions and stresses of the solid (chapter §2, §7.1).

Each law maps a 3×3 deformation gradient to a strain-energy density ψ (MPa);
the first Piola–Kirchhoff stress is P = ∂ψ/∂F obtained with ``ufl.diff`` and
the tangent follows from ``ufl.derivative`` of the residual.  The geometrically
linear model is offered behind the same interface: ψ(F) = μ ε:ε + λ/2 (tr ε)²
with ε = sym(F − I), whose derivative is the small-strain stress σ(ε).
"""

import ufl

from .kinematics import deformation_gradient, grad3, reference_volume_factor

__all__ = [
    "body_force_work",
    "MATERIALS",
    "external_virtual_work",
    "first_piola",
    "internal_virtual_work",
    "lame_parameters",
    "linear_elastic",
    "mooney_rivlin",
    "neo_hookean",
    "stored_energy",
    "strain_energy",
]

MATERIALS = ("neo-hookean", "mooney-rivlin", "linear")


def lame_parameters(E, nu):
    """Lamé constants (μ, λ) from Young's modulus E (MPa) and Poisson's ratio ν."""
    return E / (2 * (1 + nu)), E * nu / ((1 + nu) * (1 - 2 * nu))


def neo_hookean(F, mu, lmbda):
    """Compressible neo-Hookean ψ = μ/2 (I₁ − 3 − 2 ln J) + λ/2 (ln J)²."""
    J = ufl.det(F)
    I1 = ufl.tr(F.T * F)
    return mu / 2 * (I1 - 3 - 2 * ufl.ln(J)) + lmbda / 2 * ufl.ln(J) ** 2


def mooney_rivlin(F, mu1, mu2, kappa):
    """Nearly incompressible Mooney–Rivlin, ψ = μ₁/2 (Ī₁ − 3) + μ₂/2 (Ī₂ − 3) + κ/2 (J − 1)².

    Isochoric invariants Ī₁ = J^{-2/3} I₁, Ī₂ = J^{-4/3} I₂; small-strain shear
    modulus μ₁ + μ₂ and bulk modulus κ (all MPa).
    """
    J = ufl.det(F)
    C = F.T * F
    I1 = ufl.tr(C)
    I2 = (I1**2 - ufl.tr(C * C)) / 2
    return (
        mu1 / 2 * (J ** (-2 / 3) * I1 - 3)
        + mu2 / 2 * (J ** (-4 / 3) * I2 - 3)
        + kappa / 2 * (J - 1) ** 2
    )


def linear_elastic(F, mu, lmbda):
    """Geometrically linear (small-strain) Hooke law written as ψ(F) with ε = sym(F − I)."""
    eps = ufl.sym(F - ufl.Identity(3))
    return mu * ufl.inner(eps, eps) + lmbda / 2 * ufl.tr(eps) ** 2


def strain_energy(F, material, params):
    """Dispatch on ``material`` in :data:`MATERIALS` with parameter dict ``params``.

    neo-hookean and linear take ``mu``, ``lmbda``; mooney-rivlin takes ``mu1``,
    ``mu2``, ``kappa``.
    """
    if material == "neo-hookean":
        return neo_hookean(F, params["mu"], params["lmbda"])
    if material == "linear":
        return linear_elastic(F, params["mu"], params["lmbda"])
    if material == "mooney-rivlin":
        return mooney_rivlin(F, params["mu1"], params["mu2"], params["kappa"])
    raise ValueError(f"unknown material {material!r}; expected one of {MATERIALS}")


def first_piola(F, material, params):
    """First Piola–Kirchhoff stress P = ∂ψ/∂F (3×3) via ``ufl.variable``/``ufl.diff``."""
    F = ufl.variable(F)
    return ufl.diff(strain_energy(F, material, params), F)


def internal_virtual_work(u, v, kind, material, params, dx):
    """Return the internal virtual work ∫ P : Grad δφ dV of eq. (7), 2πR-weighted if axisym."""
    F = deformation_gradient(u, kind)
    P = first_piola(F, material, params)
    w = reference_volume_factor(u.ufl_function_space().mesh, kind)
    return ufl.inner(P, grad3(v, kind)) * w * dx


def stored_energy(u, kind, material, params, dx):
    """Return the stored energy ∫ ψ(F) dV (2πR-weighted if axisym), the potential of eq. (7)."""
    F = deformation_gradient(u, kind)
    w = reference_volume_factor(u.ufl_function_space().mesh, kind)
    return strain_energy(F, material, params) * w * dx


def external_virtual_work(traction, v, kind, ds):
    """Virtual work ∫ T*·δφ dS of a prescribed nominal traction T* (MPa), eq. (7)."""
    w = reference_volume_factor(v.ufl_function_space().mesh, kind)
    return ufl.dot(traction, v) * w * ds


def body_force_work(force, v, kind, dx):
    """Virtual work ∫ B·δφ dV of a dead body force B (N/mm³ per reference volume), eq. (7)."""
    w = reference_volume_factor(v.ufl_function_space().mesh, kind)
    return ufl.dot(force, v) * w * dx
