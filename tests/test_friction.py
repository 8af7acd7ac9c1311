"""Coulomb friction on a block pressed onto a rigid plane: equilibrium of the solved state
(reaction of the clamped top from the bulk stresses against the force of the solved
multipliers), the Coulomb cone nodally, drag = μ × load in full sliding, a genuine
stick phase, and quadratic Newton convergence.

The reaction of the clamped top face is the internal virtual work ∫ P : Grad w dV
with w = e_i on the top dofs and 0 elsewhere (assembled here, not taken from the
library), i.e. the force the stresses of the solved body transmit to the clamp.  The
contact force is assembled from the solved multiplier fields λ_N, λ_T, not from
the traction formula of the contact law.

Error bounds used as tolerances (‖b‖: the final Newton residual 2-norm of the block
system, read from the Newton report; n_u, n_s: global numbers of displacement and
multiplier dofs).  With R_u(v) = I(v) + C(v) (internal + contact virtual work),
C(w_top) = 0 and I(e_i) = 0, the top reaction is I(w_top) = C(e_i) − Σ_free b_u,
and C(e_i) = −(force of the tractions T); the multipliers differ from the
tractions by λ − T = ρ b_λ / (nodal weight).  By Cauchy–Schwarz

    |reaction + force(λ)| ≤ (√n_u + (ρ_N + ρ_T) √n_s) ‖b‖ =: δ_eq,

and nodally |λ − T| ≤ ρ ‖b‖ / w_min (w_min the smallest lumped facet weight).
"""

import math
from types import SimpleNamespace

import numpy as np
import pytest
import ufl
from dolfinx import fem, la, mesh
from mpi4py import MPI
from tribofx.forms.hyperelastic import internal_virtual_work, lame_parameters

from tribofx.body import Body
from tribofx.interfaces import Contact
from tribofx.obstacles import rigid_plane
from tribofx.problem import Problem, convergence_orders

MU_F = 0.3
E, NU = 10.0, 0.3
TOP = 2


def _block(slip, gdim, friction=MU_F):
    comm = MPI.COMM_WORLD
    if gdim == 2:
        msh = mesh.create_rectangle(comm, [[0, 0], [2, 1]], [16, 8])
    else:
        msh = mesh.create_box(comm, [[0, 0, 0], [2, 1, 1]], [8, 4, 4])
    fdim = gdim - 1
    bot = mesh.locate_entities_boundary(msh, fdim, lambda x: np.isclose(x[gdim - 1], 0))
    top = mesh.locate_entities_boundary(msh, fdim, lambda x: np.isclose(x[gdim - 1], 1))
    idx = np.hstack([bot, top])
    val = np.hstack([np.full(len(bot), 1), np.full(len(top), TOP)]).astype(np.int32)
    order = np.argsort(idx)
    ft = mesh.meshtags(msh, fdim, idx[order], val[order])
    e = np.eye(gdim)
    mu, lmbda = lame_parameters(E, NU)
    body = Body(msh, ft, {"bottom": 1, "top": TOP}, "3d" if gdim == 3 else "plane_strain",
                ("neo-hookean", {"mu": mu, "lmbda": lmbda}),
                velocity=e[0] if slip == "eulerian" else None)
    top_u = body.add_dirichlet("top", np.zeros(gdim))
    contact = Contact(body, "bottom", rigid_plane(np.zeros(gdim), e[gdim - 1]),
                      rho_n=10.0 / 0.125, friction=friction, rho_t=10.0 / 0.125, slip=slip,
                      V_master=np.zeros(gdim), dtau=1.0)
    sim = SimpleNamespace(body=body, contact=contact,
                          problem=Problem([body, contact], name=f"friction_{slip}"))
    return sim, top_u


def _sum(form):
    return MPI.COMM_WORLD.allreduce(fem.assemble_scalar(fem.form(form)), op=MPI.SUM)


def _top_reaction(prob):
    """Force (N) the clamp exerts on the body: ∫ P : Grad w dV, w = e_i on the top dofs."""
    gdim = prob.body.mesh.geometry.dim
    fdim = prob.body.mesh.topology.dim - 1
    mu, lmbda = lame_parameters(E, NU)
    kind = "3d" if gdim == 3 else "plane_strain"
    out = np.zeros(gdim)
    for i in range(gdim):
        w = fem.Function(prob.body.V)
        dofs = fem.locate_dofs_topological(prob.body.V.sub(i), fdim, prob.body.facet_tags.find(TOP))
        w.x.array[dofs] = 1.0
        out[i] = _sum(internal_virtual_work(prob.body.u, w, kind, "neo-hookean",
                                            {"mu": mu, "lmbda": lmbda}, prob.body.dx))
    return out


def _multiplier_force(prob):
    """Force (N) of the plane on the body from the solved multipliers: −∫ (λ_N n + P_T λ_T) dS."""
    gdim = prob.body.mesh.geometry.dim
    n = ufl.as_vector(np.eye(gdim)[gdim - 1].tolist())
    lt = prob.contact.lam_t - ufl.dot(prob.contact.lam_t, n) * n
    f = -(prob.contact.lam_n * n + lt)
    return np.array([MPI.COMM_WORLD.allreduce(
        fem.assemble_scalar(fem.form(f[i] * prob.contact.dsc,
                                     entity_maps=[prob.contact.emap])), op=MPI.SUM)
        for i in range(gdim)])


def _nodal_multipliers(prob):
    """Owned nodal (λ_N, tangential λ_T, lumped weight) on the contact submesh, all ranks."""
    gdim = prob.body.mesh.geometry.dim
    n_own = prob.contact.Q.dofmap.index_map.size_local
    # Q and Vs are P1 on the same submesh: the blocked dofmap is the scalar one
    assert np.array_equal(prob.contact.Q.tabulate_dof_coordinates(),
                          prob.contact.Vs.tabulate_dof_coordinates())
    lam_n = prob.contact.lam_n.x.array[:n_own]
    lam_t = prob.contact.lam_t.x.array.reshape(-1, gdim)[:n_own, :gdim - 1]
    vec = fem.assemble_vector(fem.form(ufl.TestFunction(prob.contact.Q) * prob.contact.dsc,
                                       entity_maps=[prob.contact.emap]))
    vec.scatter_reverse(la.InsertMode.add)
    weight = vec.array[:n_own].copy()
    comm = MPI.COMM_WORLD
    return (np.concatenate(comm.allgather(lam_n)),
            np.concatenate(comm.allgather(lam_t)),
            np.concatenate(comm.allgather(weight)))


def _bounds(prob, r_final):
    """(δ_eq, nodal multiplier tolerance) from the final residual norm (module docstring)."""
    gdim = prob.body.mesh.geometry.dim
    s = prob.contact
    n_u = prob.body.V.dofmap.index_map.size_global * gdim
    n_s = prob.contact.Q.dofmap.index_map.size_global
    _, _, w = _nodal_multipliers(prob)
    d_eq = (math.sqrt(n_u) + (s.rho_n + s.rho_t) * math.sqrt(n_s)) * r_final
    d_nodal = (s.rho_t + MU_F * s.rho_n) * r_final / w[w > 0].min()
    return d_eq, d_nodal


def _check_equilibrium(prob, r_final):
    R, F = _top_reaction(prob), _multiplier_force(prob)
    d_eq, d_nodal = _bounds(prob, r_final)
    # assembly round-off: a sum of O(n) terms of the size of the force
    d_eq += 1e-12 * np.abs(F).max()
    print("top reaction", R, "multiplier force", F, "|R + F|", np.abs(R + F),
          "bound δ_eq", d_eq, "nodal bound", d_nodal)
    assert np.all(np.abs(R + F) <= d_eq)
    return R, F, d_eq, d_nodal


@pytest.mark.mpi
@pytest.mark.parametrize("gdim", [2, 3])
def test_steady_sliding_eulerian(gdim):
    prob, top_u = _block("eulerian", gdim)
    reports = []
    for k in range(1, 4):
        top_u.value[gdim - 1] = -0.02 * k
        reports.append(prob.problem.solve())
    r_final = reports[-1].residuals[-1]
    # (1) global equilibrium of the solved state: clamp reaction (bulk stresses) +
    # contact force (solved multipliers) = 0 within δ_eq (module docstring)
    R, F, d_eq, d_nodal = _check_equilibrium(prob, r_final)
    N = -R[gdim - 1]  # the load the clamp presses the block down with
    assert N > 0.1  # a real load: ≈ E* strain area = 11 × 0.06 × 2 ≈ 1.3 N
    # slip direction: the tangential part of F e_x (eq. 26-27), tilted from e_x by
    # θ with tan θ = |∂u_y/∂x| / (1 + ∂u_x/∂x) in 3D (0 in 2D); the vertex rule
    # evaluates it with Grad u of the cell behind each facet, so a node's λ_T is the
    # weighted mean of facet tractions of length μ|λ_N| at angles ≤ θ_max from e_x:
    # μ|λ_N| cos θ_max ≤ ‖λ_T‖ ≤ μ|λ_N|, cos θ ≥ 1 − tan²θ/2 (θ_max over all cells;
    # P1: Grad u is cellwise constant, interpolated exactly into DG0)
    if gdim == 2:
        tan2 = 0.0
    else:
        DG = fem.functionspace(prob.body.mesh, ("DG", 0, (gdim, gdim)))
        g = fem.Function(DG)
        g.interpolate(fem.Expression(ufl.grad(prob.body.u), DG.element.interpolation_points))
        G = g.x.array.reshape(-1, gdim, gdim)
        tan2 = MPI.COMM_WORLD.allreduce(
            float(np.max(G[:, 1, 0] ** 2 / (1 + G[:, 0, 0]) ** 2, initial=0.0)), op=MPI.MAX)
    lo = 1 - tan2 / 2
    # (2) Coulomb cone, nodally, for the solved multipliers: the augmented slip
    # ρ_T s = 80 MPa ≫ μ|λ_N| ≈ 0.2 MPa, so every active node slides and
    # ‖λ_T‖ ∈ [lo, 1] μ|λ_N| to the nodal bound, with the friction traction along the
    # slip (+x: the body moves at V = e_x over the plane at rest); a node that lifts
    # off (the trailing corner) carries no traction at all
    lam_n, lam_t, w = _nodal_multipliers(prob)
    on = w > 0
    act = on & (lam_n < -d_nodal)
    mag = np.linalg.norm(lam_t, axis=1)
    cone = MU_F * np.abs(lam_n)
    print("active", act.sum(), "of", on.sum(), "‖λ_T‖/μ|λ_N| in", (mag[act] / cone[act]).min(),
          (mag[act] / cone[act]).max(), "lower bound", lo, "nodal bound", d_nodal)
    assert act.sum() > 0.8 * on.sum()
    assert np.all(mag[on] <= cone[on] + d_nodal)
    assert np.all(mag[on] >= lo * cone[on] - d_nodal)
    assert np.all(lam_t[act, 0] > 0)
    # (3) drag = μ × load from the clamp reaction: R_x/(μ N) ∈ [lo, 1] (2D: lo = 1)
    # up to (1 + μ) δ_eq/N
    ratio = R[0] / N
    tol = (1 + MU_F) * d_eq / N
    print("R_x/N", ratio, "μ", MU_F, "tan²θ_max/2", tan2 / 2, "tol", tol)
    assert MU_F * lo - tol <= ratio <= MU_F + tol
    orders = convergence_orders(reports[-1].residuals)
    print("Newton residuals", reports[-1].residuals, "orders", orders)
    # quadratic convergence of the semismooth Newton: final order ≈ 2
    assert orders[-1] > 1.8


@pytest.mark.mpi
def test_lagrangian_sliding_reaches_mu():
    gdim = 2
    prob, top_u = _block("lagrangian", gdim)
    top_u.value[1] = -0.05
    prob.problem.solve()
    prob.problem.commit()
    # translate the rigid plane tangentially in +x: stick first, then full sliding
    history, nodal = [], []
    for k in range(1, 11):
        prob.contact.counterpart.offset.value[0] = 0.03 * k
        rep = prob.problem.solve()
        R, F, d_eq, d_nodal = _check_equilibrium(prob, rep.residuals[-1])
        lam_n, lam_t, w = _nodal_multipliers(prob)
        on = w > 0
        mag = np.abs(lam_t[:, 0])
        cone = MU_F * np.abs(lam_n)
        # Coulomb cone, nodally, at every step (stick or slip): ‖λ_T‖ ≤ μ|λ_N|
        assert np.all(mag[on] <= cone[on] + d_nodal)
        act = on & (lam_n < -d_nodal)
        mag, cone = mag[act], cone[act]
        nodal.append((np.sum(mag < cone - d_nodal), np.abs(mag - cone).max(), d_nodal))
        history.append((R[0] / R[1], (1 + MU_F) * d_eq / abs(R[1])))
        prob.problem.commit()
        print(k, rep.iterations, "reaction", R, "R_x/R_y", R[0] / R[1],
              "sticking nodes", nodal[-1][0], "of", on.sum())
    # the clamp holds the block against the drag of the plane (+x on the body):
    # R_x < 0, and once every node slides R_x/R_y = μ (2D: slip along x at every
    # node) up to (1 + μ) δ_eq/|R_y|
    ratio, tol = history[-1]
    assert R[0] < 0 and R[1] < 0
    assert abs(ratio - MU_F) <= tol
    sticking, dev, d_nodal = nodal[-1]
    assert sticking == 0 and dev <= d_nodal
    # a genuine stick phase first: after the first 0.03 mm the tangential
    # displacement is partly carried elastically, nodes stick inside the cone and
    # the drag is well below μ N (measured ratio 0.149)
    assert nodal[0][0] > 0
    assert history[0][0] < 0.9 * MU_F


@pytest.mark.mpi
def test_sliding_follows_a_pressure_dependent_friction_law():
    """A friction law μ(p) = μ₀ (1 + p/p₀)^(−n) (forms.contact.pressure_dependent_friction;
    μ₀ = 0.6, p₀ = 0.1 MPa, n = 1/3: μ from 0.41 down to 0.23 over the active nodes)
    given to the Contact as a Law: once the plane has dragged the block into full
    sliding, every active node carries ‖λ_T‖ = μ(p) p with p = |λ_N|, to the nodal bound
    d of the solved multipliers: |λ_T − T_T| ≤ d and |d(μ p)/dp| ≤ μ₀, so (1 + μ₀) d."""
    from tribofx.forms.contact import pressure_dependent_friction

    from tribofx.laws import Law

    law = Law(pressure_dependent_friction, mu0=0.6, p0=0.1, n=1 / 3)
    prob, top_u = _block("lagrangian", 2, friction=law)
    top_u.value[1] = -0.05
    prob.problem.solve()
    prob.problem.commit()
    for k in range(1, 11):
        prob.contact.counterpart.offset.value[0] = 0.05 * k
        rep = prob.problem.solve()
        prob.problem.commit()
    R, F, d_eq, d_nodal = _check_equilibrium(prob, rep.residuals[-1])
    lam_n, lam_t, w = _nodal_multipliers(prob)
    act = (w > 0) & (lam_n < -d_nodal)
    p = np.abs(lam_n[act])
    mu_p = 0.6 * (1 + p / 0.1) ** (-1 / 3)
    dev = np.abs(np.abs(lam_t[act, 0]) - mu_p * p)
    print("active", act.sum(), "μ(p) from", mu_p.min(), "to", mu_p.max(), "max |‖λ_T‖ − μ(p)p|",
          dev.max(), "bound", d_nodal * (1 + 0.6))
    assert act.sum() > 4 and mu_p.max() - mu_p.min() > 0.05   # the law really varies
    assert np.all(dev <= d_nodal * (1 + 0.6))
