"""Two deformable bodies in 3D: a box pressed and slid on a box (C++ 3D kernel).

References: today's rigid-plane contact (a master held fixed must reproduce
it), the Taylor remainder of the assembled tangent (master columns included),
quadratic Newton convergence and Coulomb's law in sliding.
"""

import numpy as np
import pytest
from dolfinx import mesh
from mpi4py import MPI
from test_two_body import tagged_body

from tribofx.interfaces import Contact, TwoBodyContact
from tribofx.obstacles import rigid_plane
from tribofx.problem import Problem
from tribofx.testing import block_taylor_orders, exact_tangent, owned_arrays

COMM = MPI.COMM_WORLD
# every check is rank-independent: the suite runs them again on 2 processes (a rank's
# slave nodes project onto master facets owned by the other rank)
pytestmark = pytest.mark.mpi


def box(x0, x1, z0, z1, n, nz, name):
    """Box [x0, x1]² × [z0, z1] with boundaries "bottom" (z = z0) and "top" (z = z1)."""
    msh = mesh.create_box(COMM, [[x0, x0, z0], [x1, x1, z1]], [n, n, nz],
                          mesh.CellType.tetrahedron)
    return tagged_body(msh, z0, z1, "3d", name)


def two_boxes(friction, fixed_master, top=(0.01, 0.0, -0.02)):
    """Slave box [0, 1]² × [0, 0.5] (4 × 4 × 2) on a master [−0.5, 1.5]² × [−0.5, 0] (5 × 5 × 2)."""
    slave = box(0.0, 1.0, 0.0, 0.5, 4, 2, "slave")
    push = slave.add_dirichlet("top", np.asarray(top, float))
    master = box(-0.5, 1.5, -0.5, 0.0, 5, 2, "master")
    master.add_dirichlet("bottom", np.zeros(3))
    if fixed_master:
        master.add_dirichlet("top", np.zeros(3))
    contact = TwoBodyContact(slave, "bottom", master, "top", 10.0, friction=friction)
    return slave, master, contact, Problem([slave, master, contact], name="two_boxes"), push


@pytest.mark.parametrize("mu", [0.0, 0.3])
def test_fixed_master_is_the_rigid_plane_3d(mu):
    """A fixed flat master gives the rigid-plane contact: same iterates to round-off.

    As in 2D: the gap, normal, projection and slip of a flat fixed facet are
    those of the plane; the converged states differ by round-off of the
    assembly order only, ≤ 1e-9 max|u|.
    """
    slave, master, contact, problem, _ = two_boxes(mu, fixed_master=True)
    rep = problem.solve()
    rigid = box(0.0, 1.0, 0.0, 0.5, 4, 2, "rigid_slave")
    rigid.add_dirichlet("top", np.array([0.01, 0.0, -0.02]))
    plane = Contact(rigid, "bottom", rigid_plane([0.0, 0.0, 0.0], [0.0, 0.0, 1.0]), 10.0,
                    friction=mu)
    rep_rigid = Problem([rigid, plane], name="rigid_plane_3d").solve()
    scale = np.abs(rigid.u.x.array).max()
    assert rep.iterations == rep_rigid.iterations
    assert np.abs(slave.u.x.array - rigid.u.x.array).max() <= 1e-9 * scale
    on_slave, _ = contact.forces(problem)
    assert np.allclose(on_slave, plane.force(), rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("mu", [0.0, 0.3, 2.0])
def test_two_body_tangent_taylor_3d(mu):
    """Taylor remainder O(ε²) in every unknown, master displacements included (3D).

    A committed state, then a slide: μ = 0.3 slips, μ = 2 mostly sticks;
    directions of 1e-6 keep the active and stick sets.
    """
    slave, master, contact, problem, push = two_boxes(mu, fixed_master=False)
    problem.solve()
    problem.commit()
    push.value[:] = [0.04, 0.02, -0.025]
    problem.solve()
    rng = np.random.default_rng(7)
    dirs = [1e-6 * rng.standard_normal(len(f.x.array)) for f in problem.u]
    out = block_taylor_orders(problem, owned_arrays(problem, dirs), eps0=1.0)
    for name, (orders, rem, floor) in out.items():
        assert exact_tangent(orders, rem, floor), (name, orders, rem, floor)
    d = contact.nodal_data()
    assert COMM.allreduce(int(d["active"].sum()), op=MPI.SUM) > 0


def test_newton_quadratic_and_coulomb_3d():
    """Quadratic Newton (order ≥ 1.8), then sliding: |T_T| = μ|T_N| per node, equilibrium.

    After six committed sliding steps across master facets every contact node
    slips; the Coulomb cone holds to the constraint tolerance (1e-10 G/ρ_N of
    a slip, i.e. 1e-10 G of a traction against |T_N| ≈ 0.1 G: ≤ 1e-8 relative).
    """
    mu = 0.3
    slave, master, contact, problem, push = two_boxes(mu, fixed_master=False,
                                                      top=(0.0, 0.0, -0.02))
    rep = problem.solve()
    # corrections below 1e-9 of the first (2e-11 mm) are round-off of the linear solve
    # (condition number ~1e6 × ε × |u|), whose pivoting differs between 1 and 2 ranks
    orders = rep.increment_orders(slave.u.name, floor=1e-9)
    assert len(orders) >= 1 and orders[-1] > 1.8, rep.increments
    problem.commit()
    for k in range(1, 7):
        push.value[:] = [0.1 * k, 0.05 * k, -0.02]     # master facets are 0.4 mm wide
        problem.solve()
        problem.commit()
    d = contact.nodal_data()
    act = d["active"]
    tn, tt = np.abs(d["T_n"][act]), np.linalg.norm(d["T_t"][act], axis=1)
    assert COMM.allreduce(int(act.sum()), op=MPI.SUM) > 10
    t_max = COMM.allreduce(float(tn.max(initial=0.0)), op=MPI.MAX)
    assert np.all(np.abs(tt - mu * tn) <= 1e-8 * t_max)
    # equilibrium of the solved slave: the support of its top balances the contact
    # force, to the momentum tolerance summed over the rows (n_u · atol_u)
    on_slave, _ = contact.forces(problem)
    bound = slave.V.dofmap.index_map.size_global * 3 * slave.tolerances()[slave.u].atol
    for c in range(3):
        assert abs(slave.reaction("top", c) + on_slave[c]) <= bound
