"""Coulomb friction: steady sliding carries exactly μ N; Newton converges quadratically."""

import numpy as np
import pytest
from dolfinx import mesh
from mpi4py import MPI
from tribofx.forms.hyperelastic import lame_parameters

from tribofx.contact_problem import ContactProblem, ContactSettings
from tribofx.newton import convergence_orders
from tribofx.obstacles import AnalyticObstacle

MU_F = 0.3


def _block(slip, gdim):
    comm = MPI.COMM_WORLD
    if gdim == 2:
        msh = mesh.create_rectangle(comm, [[0, 0], [2, 1]], [16, 8])
    else:
        msh = mesh.create_box(comm, [[0, 0, 0], [2, 1, 1]], [8, 4, 4])
    fdim = gdim - 1
    bot = mesh.locate_entities_boundary(msh, fdim, lambda x: np.isclose(x[gdim - 1], 0))
    top = mesh.locate_entities_boundary(msh, fdim, lambda x: np.isclose(x[gdim - 1], 1))
    idx = np.hstack([bot, top])
    val = np.hstack([np.full(len(bot), 1), np.full(len(top), 2)]).astype(np.int32)
    order = np.argsort(idx)
    ft = mesh.meshtags(msh, fdim, idx[order], val[order])
    e = np.eye(gdim)
    V = tuple(e[0]) if slip == "eulerian" else None
    settings = ContactSettings(rho_n=10.0 / 0.125, friction=MU_F, rho_t=10.0 / 0.125,
                               slip=slip, V=V, V_master=tuple(np.zeros(gdim)), dtau=1.0)
    mu, lmbda = lame_parameters(10.0, 0.3)
    prob = ContactProblem(
        msh, ft, 1, "3d" if gdim == 3 else "plane_strain", "neo-hookean",
        {"mu": mu, "lmbda": lmbda},
        lambda m, Vs: AnalyticObstacle(Vs.mesh, "plane", np.zeros(gdim), normal=e[gdim - 1]),
        settings)
    top_u = prob.add_dirichlet(2, np.zeros(gdim))
    prob.finalize()
    return prob, top_u


@pytest.mark.mpi
@pytest.mark.parametrize("gdim", [2, 3])
def test_steady_sliding_eulerian(gdim):
    prob, top_u = _block("eulerian", gdim)
    reports = []
    for k in range(1, 4):
        top_u.value[gdim - 1] = -0.02 * k
        reports.append(prob.solve())
    f = prob.contact_force()
    N, T = f[gdim - 1], f[0]
    Nmag, Tmag = prob.traction_magnitudes()
    print("N", N, "T", T, "T/N", T / N, "|T|/|N|", Tmag / Nmag)
    # every contact node slips, so ‖T_T‖ = μ|T_N| pointwise and the integrated
    # magnitudes are in the ratio μ to the Newton tolerance (1e-10 relative)
    assert N > 0 and Nmag == pytest.approx(N, rel=1e-12)
    assert Tmag / Nmag == pytest.approx(MU_F, rel=1e-8)
    # the slip direction is F V projected on the plane (eq. 26–27): along −x up to
    # the small in-plane shear ∂u_y/∂x of the 3D block, so the net drag is −μ N
    # exactly in 2D and to O(shear²) in 3D
    assert -T / N == pytest.approx(MU_F, rel=1e-8 if gdim == 2 else 1e-4)
    orders = convergence_orders(reports[-1].residuals)
    print("Newton residuals", reports[-1].residuals, "orders", orders)
    # quadratic convergence of the semismooth Newton: final order ≈ 2
    assert orders[-1] > 1.8


@pytest.mark.mpi
def test_lagrangian_sliding_reaches_mu():
    gdim = 2
    prob, top_u = _block("lagrangian", gdim)
    top_u.value[1] = -0.05
    prob.solve()
    prob.commit()
    # translate the rigid plane tangentially: stick first, then full sliding
    history = []
    for k in range(1, 11):
        prob.obstacle.offset.value[0] = 0.03 * k
        rep = prob.solve()
        prob.commit()
        f = prob.contact_force()
        history.append(f[0] / f[1])
        print(k, rep.iterations, f, f[0] / f[1])
    # the plane drags the body along +x; once everything slips T = μ N exactly
    assert history[-1] == pytest.approx(MU_F, rel=1e-8)
    # a genuine stick phase first: the first drag step is well inside the cone
    assert history[0] < 0.9 * MU_F
