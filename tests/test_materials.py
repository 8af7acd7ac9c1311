"""Strain-energy laws against closed forms written independently of forms/hyperelastic.py."""

import numpy as np
import pytest
import ufl
from dolfinx import fem, mesh
from mpi4py import MPI
from tribofx.forms import hyperelastic as hf

MSH = mesh.create_unit_square(MPI.COMM_WORLD, 1, 1)


def _evaluate(expr):
    """Value of a constant 3×3 UFL tensor, evaluated at one point of a local cell."""
    one = fem.Function(fem.functionspace(MSH, ("DG", 0)))  # ties the expression to MSH
    one.x.array[:] = 1.0
    e = fem.Expression(one * expr, np.array([[0.25, 0.25]]))
    return e.eval(MSH, np.array([0], dtype=np.int32)).reshape(3, 3)


F_FINITE = np.array([[1.2, 0.3, 0.0], [-0.1, 0.9, 0.05], [0.02, 0.0, 1.1]])


def test_neo_hookean_finite_strain():
    mu, lmbda = 1.3, 2.1
    P = _evaluate(hf.first_piola(ufl.as_matrix(F_FINITE.tolist()), "neo-hookean",
                                 {"mu": mu, "lmbda": lmbda}))
    J = np.linalg.det(F_FINITE)
    Finv_T = np.linalg.inv(F_FINITE).T
    # P = μ (F − F^{-T}) + λ ln J F^{-T} (the textbook form of the same energy)
    ref = mu * (F_FINITE - Finv_T) + lmbda * np.log(J) * Finv_T
    assert np.allclose(P, ref, rtol=1e-12, atol=1e-12)


def test_linear_law_is_hooke():
    mu, lmbda = 1.3, 2.1
    P = _evaluate(hf.first_piola(ufl.as_matrix(F_FINITE.tolist()), "linear",
                                 {"mu": mu, "lmbda": lmbda}))
    eps = 0.5 * (F_FINITE + F_FINITE.T) - np.eye(3)
    ref = 2 * mu * eps + lmbda * np.trace(eps) * np.eye(3)
    assert np.allclose(P, ref, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("material,params,G,K", [
    ("neo-hookean", {"mu": 1.3, "lmbda": 2.1}, 1.3, 2.1 + 2 * 1.3 / 3),
    # O-ring rubber of the chapter: μ1 + μ2 = 3.66 MPa, bulk modulus κ
    ("mooney-rivlin", {"mu1": 2.0, "mu2": 1.66, "kappa": 500.0}, 3.66, 500.0),
    ("linear", {"mu": 1.3, "lmbda": 2.1}, 1.3, 2.1 + 2 * 1.3 / 3),
])
def test_small_strain_moduli(material, params, G, K):
    gamma = 1e-6
    shear = np.eye(3)
    shear[0, 1] = gamma
    P = _evaluate(hf.first_piola(ufl.as_matrix(shear.tolist()), material, params))
    # simple shear: P_01 = G γ + O(γ²); the O(γ) relative error is 1e-6
    assert P[0, 1] / gamma == pytest.approx(G, rel=1e-5)
    eps = 1e-6
    P = _evaluate(hf.first_piola(ufl.as_matrix(((1 + eps) * np.eye(3)).tolist()),
                                 material, params))
    # uniform dilatation: mean stress = K tr ε = 3 K ε to O(ε)
    assert np.trace(P) / 3 / (3 * eps) == pytest.approx(K, rel=1e-5)
