"""Two deformable bodies: the C++ two-body kernel, its tangent, and contact of two blocks.

References: the NumPy twin (brute-force search, complex-step tangent), today's
rigid-plane contact (a master held fixed must reproduce it), Coulomb's law
(sliding blocks: tangential force = μ × normal force) and the Hertz line
contact of two elastic cylinders.
"""

import math

import numpy as np
import pytest
from dolfinx import mesh
from mpi4py import MPI

from tribofx import two_body, two_body_ref
from tribofx.body import Body
from tribofx.interfaces import Contact, TwoBodyContact
from tribofx.obstacles import rigid_plane
from tribofx.problem import Problem
from tribofx.testing import block_taylor_orders, exact_tangent, owned_arrays

LAME = {"mu": 1.0, "lmbda": 1.5}


def _node_states(n, seed):
    """Random slave nodes near random segments, multipliers of both signs."""
    rng = np.random.default_rng(seed)
    q = np.zeros((n, 13))
    q[:, 2:4] = rng.uniform(-1, 1, (n, 2))
    q[:, 4:6] = q[:, 2:4] + rng.uniform(0.5, 1.5, (n, 1)) * np.c_[np.ones(n),
                                                                rng.uniform(-0.3, 0.3, n)]
    q[:, 0:2] = (q[:, 2:4] + rng.uniform(0, 1, (n, 1)) * (q[:, 4:6] - q[:, 2:4])
                 + rng.uniform(-0.05, 0.02, (n, 1)) * [[0.0, 1.0]])
    q[:, 6:10] = q[:, 2:6] + rng.uniform(-0.2, 0.2, (n, 4))
    q[:, 10] = rng.uniform(-1.0, 0.3, n)
    q[:, 11:13] = rng.uniform(-0.5, 0.5, (n, 2))
    return q, rng.uniform(0, 1, n), rng.uniform(0.5, 1, n), rng.uniform(0.5, 1, n)


@pytest.mark.parametrize("mu", [0.0, 0.3, 5.0])
def test_kernel_matches_numpy_twin(mu):
    """C++ residuals and dual-number tangents = NumPy twin with complex-step tangents.

    Both are exact to round-off on a smooth branch (μ = 5 puts most nodes in
    stick, 0.3 most in slip), so they agree to 1e-12 of the largest entry.
    """
    q, xi_old, w, w_c = _node_states(200, 1)
    r, J = two_body.node_residuals(q, xi_old, w, w_c, 10.0, 4.0, mu)
    r_ref, J_ref = two_body_ref.node_residuals(q, xi_old, w, w_c, 10.0, 4.0, mu)
    assert np.abs(r - r_ref).max() <= 1e-12 * np.abs(r_ref).max()
    assert np.abs(J - J_ref).max() <= 1e-12 * np.abs(J_ref).max()
    assert (q[:, 10] + 10.0 * 0.0 < 0).any() and np.abs(J[:, 0:6, 2:6]).max() > 0


def test_master_search_refit_matches_brute_force():
    """Nearest segment after a refit (moved nodes, same tree) = brute force over all segments."""
    rng = np.random.default_rng(3)
    s = np.linspace(0, 2 * math.pi, 201)[:-1]
    nodes = np.c_[np.cos(s), 0.5 * np.sin(s)]
    segments = np.c_[np.arange(200), (np.arange(200) + 1) % 200].astype(np.int32)
    master = two_body.MasterSurface(nodes, segments)
    pts = rng.uniform(-1.5, 1.5, (500, 2))
    for k in range(3):
        moved = nodes * (1 + 0.3 * k) + 0.05 * k * rng.standard_normal(nodes.shape)
        master.refit(np.ascontiguousarray(moved))
        got, ref = master.project(pts), two_body_ref.project(moved, segments, pts)
        assert np.array_equal(got["facet"], ref["facet"])
        assert np.allclose(got["xi"], ref["xi"], atol=1e-14)
        assert np.allclose(got["distance"], ref["distance"], atol=1e-14)


def tagged_body(msh, lo, hi, kind, name):
    """Body on ``msh`` with boundaries "bottom" (last coordinate = lo) and "top" (= hi)."""
    fdim, axis = msh.topology.dim - 1, msh.geometry.dim - 1
    ents, vals = [], []
    for tag, c in ((1, lo), (2, hi)):
        e = mesh.locate_entities_boundary(msh, fdim, lambda x, c=c: np.isclose(x[axis], c))
        ents.append(e)
        vals.append(np.full(len(e), tag, np.int32))
    e, v = np.concatenate(ents), np.concatenate(vals)
    order = np.argsort(e)
    tags = mesh.meshtags(msh, fdim, e[order], v[order])
    return Body(msh, tags, {"bottom": 1, "top": 2}, kind, ("neo-hookean", LAME), name=name)


def block(comm, x0, x1, y0, y1, nx, ny, name):
    """Rectangle body with boundaries "bottom" (y = y0) and "top" (y = y1)."""
    msh = mesh.create_rectangle(comm, [[x0, y0], [x1, y1]], [nx, ny],
                                diagonal=mesh.DiagonalType.left)
    return tagged_body(msh, y0, y1, "plane_strain", name)


def two_blocks(comm, friction, fixed_master, top=(0.02, -0.02), nx=(8, 11)):
    """Slave block [0, 1] × [0, 0.5] on a master block [−0.5, 1.5] × [−0.5, 0]."""
    slave = block(comm, 0.0, 1.0, 0.0, 0.5, nx[0], 4, "slave")
    push = slave.add_dirichlet("top", np.asarray(top, float))
    master = block(comm, -0.5, 1.5, -0.5, 0.0, nx[1], 3, "master")
    master.add_dirichlet("bottom", np.zeros(2))
    if fixed_master:
        master.add_dirichlet("top", np.zeros(2))
    contact = TwoBodyContact(slave, "bottom", master, "top", 10.0, friction=friction)
    return slave, master, contact, Problem([slave, master, contact], name="two_blocks"), push


@pytest.mark.parametrize("mu", [0.0, 0.3])
def test_fixed_master_is_the_rigid_plane(mu):
    """A master held fixed gives today's rigid-plane contact, iterate by iterate.

    The gap, normal, projection and slip of a flat fixed segment are those of the
    plane, so the Newton iterates are the same up to round-off of the assembly
    order: |Δu| ≤ 1e-9 max|u| (the residuals stop at 1e-10 of G·L and the last
    step is quadratic, so the converged states differ by round-off only).
    """
    comm = MPI.COMM_WORLD
    slave, master, contact, problem, _ = two_blocks(comm, mu, fixed_master=True)
    rep = problem.solve()
    rigid = block(comm, 0.0, 1.0, 0.0, 0.5, 8, 4, "rigid_slave")
    rigid.add_dirichlet("top", np.array([0.02, -0.02]))
    plane = Contact(rigid, "bottom", rigid_plane([0.0, 0.0], [0.0, 1.0]), 10.0, friction=mu)
    rep_rigid = Problem([rigid, plane], name="rigid_plane").solve()
    scale = np.abs(rigid.u.x.array).max()
    assert rep.iterations == rep_rigid.iterations
    assert np.abs(slave.u.x.array - rigid.u.x.array).max() <= 1e-9 * scale
    on_slave, _ = contact.forces(problem)
    assert np.allclose(on_slave, plane.force(), rtol=1e-9, atol=1e-12)


def _taylor_state(mu):
    slave, master, contact, problem, push = two_blocks(MPI.COMM_WORLD, mu, fixed_master=False)
    problem.solve()
    problem.commit()
    push.value[:] = [0.05, -0.025]      # slide on: the slip history is the committed state
    problem.solve()
    return slave, master, contact, problem


@pytest.mark.mpi
@pytest.mark.parametrize("mu", [0.0, 0.3, 2.0])
def test_two_body_tangent_taylor(mu):
    """Taylor remainder O(ε²) in each unknown's columns alone, master displacements included.

    μ = 0.3: the contact nodes slip, μ = 2: most stick; directions of 1e-6
    (positions, mm) and 1e-6 MPa keep the active and stick sets.  Per block
    (:func:`tribofx.testing.block_taylor_orders`): a wrong multiplier or master
    column cannot hide below the stiff slave block; serially and on 2 ranks (the
    master surface gathered across ranks).
    """
    _, master, contact, problem = _taylor_state(mu)
    rng = np.random.default_rng(7 + MPI.COMM_WORLD.rank)
    dirs = [1e-6 * rng.standard_normal(len(f.x.array)) for f in problem.u]
    out = block_taylor_orders(problem, owned_arrays(problem, dirs), eps0=1.0)
    for name, (orders, rem, floor) in out.items():
        assert exact_tangent(orders, rem, floor), (name, orders, rem, floor)
    # the master columns are there: the master row block reacts to the slave
    n = contact.nodal_data(problem)
    assert MPI.COMM_WORLD.allreduce(int(n["active"].sum()), op=MPI.SUM) > 0


def test_newton_quadratic():
    """Quadratic convergence on two deformable blocks: last correction order ≥ 1.8."""
    slave, _, _, problem, _ = two_blocks(MPI.COMM_WORLD, 0.3, fixed_master=False)
    rep = problem.solve()
    orders = rep.increment_orders(slave.u.name, floor=1e-12)
    assert len(orders) >= 1 and orders[-1] > 1.8, rep.increments


def test_sliding_blocks_tangential_force_is_mu_times_normal():
    """Large sliding (three master segments) on a deformable master: F_T = μ F_N.

    Then the Taylor test at that large-slip state.  Once every contact node
    slips the Coulomb cone holds node by node,
    |T_T| = μ|T_N| in the local frame of the (tilted, deformed) master, so the
    total magnitudes follow it to the tolerance of the constraint rows (1e-10
    G/ρ_N of a gap, i.e. 1e-10 G of a traction against |T_N| ≈ 0.1 G: ≤ 1e-8
    relative).  The x/y components of the force do not obey it exactly: the
    master surface tilts under the load.  The solved slave is in equilibrium:
    the support reaction of its top balances the contact force.
    """
    mu = 0.3
    _, _, contact, problem, push = two_blocks(MPI.COMM_WORLD, mu, fixed_master=False,
                                              top=(0.0, -0.02))
    problem.solve()
    problem.commit()
    for k in range(1, 7):
        push.value[:] = [0.1 * k, -0.02]    # segments of the master are 0.18 mm long
        problem.solve()
        problem.commit()
    on_slave, _ = contact.forces(problem)
    d = contact.nodal_data(problem)
    act = d["active"]
    tn, tt = np.abs(d["T_n"][act]), np.linalg.norm(d["T_t"][act], axis=1)
    comm = MPI.COMM_WORLD
    assert comm.allreduce(int(act.sum()), op=MPI.SUM) > 5
    t_max = comm.allreduce(float(tn.max(initial=0.0)), op=MPI.MAX)
    assert np.all(np.abs(tt - mu * tn) <= 1e-8 * t_max)        # every node slips
    F_t = comm.allreduce(float(np.sum(d["weight"][act] * tt)), op=MPI.SUM)
    F_n = comm.allreduce(float(np.sum(d["weight"][act] * tn)), op=MPI.SUM)
    assert abs(F_t - mu * F_n) <= 1e-8 * F_n
    # equilibrium of the solved slave: the support of its top balances the contact
    # force, to the momentum tolerance summed over the rows (n_u · atol_u)
    slave = contact.slave
    bound = slave.V.dofmap.index_map.size_global * 2 * slave.tolerances()[slave.u].atol
    for c in (0, 1):
        assert abs(slave.reaction("top", c) + on_slave[c]) <= bound
    assert on_slave[0] < 0            # friction opposes the sliding of the slave (+x)
    # large slip (six steps across three segments): the tangent is still exact one
    # step further (at a committed state the slip is zero and a slipping node sits
    # on the Coulomb cone, |λ̂_T| = μ|T_N|: a kink of the law, order 1 there)
    push.value[:] = [0.65, -0.02]
    problem.solve()
    rng = np.random.default_rng(11)
    dirs = [1e-6 * rng.standard_normal(len(f.x.array)) for f in problem.u]
    out = block_taylor_orders(problem, owned_arrays(problem, dirs), eps0=1.0)
    for name, (orders, rem, floor) in out.items():
        assert exact_tangent(orders, rem, floor), (name, orders, rem, floor)


@pytest.mark.mpi
def test_parallel_matches_serial():
    """Two sliding blocks on 1 and on all ranks: the same forces and displacement norm."""
    if MPI.COMM_WORLD.size < 2:
        pytest.skip("compares COMM_WORLD with COMM_SELF: run under mpiexec -n 2")
    out = []
    for comm in (MPI.COMM_SELF, MPI.COMM_WORLD):
        slave, _, contact, problem, push = two_blocks(comm, 0.3, fixed_master=False)
        problem.solve()
        problem.commit()
        push.value[:] = [0.1, -0.02]
        problem.solve()
        on_slave, _ = contact.forces(problem)
        unorm = comm.allreduce(float(np.sum(slave.u.x.array[
            :slave.V.dofmap.index_map.size_local * 2] ** 2)), op=MPI.SUM)
        out.append(np.r_[on_slave, unorm])
    assert np.allclose(out[0], out[1], rtol=1e-8, atol=1e-14), out


def test_hertz_two_cylinders(tmp_path):
    """Two elastic cylinders (E1 ≠ E2, ν1 ≠ ν2, R1 ≠ R2) against Hertz's line contact.

    Within 3 % in a and p0 (the Hertz theory is linear and half-space, here
    a/R* ≈ 0.07 with finite strain: model error O(a/R*) of a few per cent; the
    p0 error stays near 1 % under refinement), and the half-width error drops
    under refinement (a nodal measure: error ≤ one element a/(6·2^mesh)).
    The solved upper cylinder is in equilibrium: the reaction of its held face
    balances the contact force (bound: n_u · atol_u of the momentum rows).
    """
    from tribofx.runner import run_case

    errors = []
    for level in (1, 2):
        s = run_case("contact-two-cylinders", {"mesh": str(level), "E2": "20", "nu2": "0.2",
                                               "R2": "15"},
                     out=MPI.COMM_WORLD.bcast(str(tmp_path / f"m{level}"), root=0),
                     progress=False)
        assert s["status"] == "ok", s["status"]
        res = {k: x["value"] for k, x in s["results"].items()}
        errors.append((abs(res["contact_half_width_rel_error"]), abs(res["p_max_rel_error"])))
        assert res["equilibrium_error"] < res["equilibrium_bound"]
    assert all(e[0] < 0.03 and e[1] < 0.03 for e in errors), errors
    assert errors[1][0] < errors[0][0], errors


def test_cylinder_on_elastic_block(tmp_path):
    """R2 = 0: a cylinder on a flat elastic block [0, 20] × [−20, 0] mm against Hertz (R2 = ∞).

    The block is 40 a wide and deep, so the half-plane assumption of Hertz holds
    to O(a/L) (≈ 2.5 %, with a/R1 ≈ 0.05 of finite strain): within 3 % on
    mesh 2 (elements a/24).
    """
    from tribofx.runner import run_case

    s = run_case("contact-two-cylinders", {"mesh": "2", "R2": "0", "E2": "40"},
                 out=MPI.COMM_WORLD.bcast(str(tmp_path / "block"), root=0), progress=False)
    assert s["status"] == "ok", s["status"]
    res = {k: x["value"] for k, x in s["results"].items()}
    assert abs(res["contact_half_width_rel_error"]) < 0.03, res
    assert abs(res["p_max_rel_error"]) < 0.03, res


@pytest.mark.parametrize("ratio", [1.0, 2.0, 0.5, 1.5])
def test_patch_test(tmp_path, ratio):
    """Contact patch test of the single-pass node-to-segment scheme (case contact-patch).

    Analysis (module docstring of :mod:`tribofx.cases.contact_patch`): the
    homogeneous state is a discrete solution iff the slave nodes' trapezoidal
    rule integrates the master hat functions exactly, i.e. iff every master node
    is a slave node.  Nested meshes with the slave as fine or finer (ratio 1,
    2) must then transmit the pressure exactly: deviation ≤ the constraint
    tolerance, 1e-10 G of a traction against p = 0.1 MPa with G = 3.8 MPa, i.e.
    ≤ 1e-8 relative.  A coarser slave (0.5: the master nodes between slave nodes
    receive no force) or non-nested meshes (1.5) cannot: their deviation must
    exceed that tolerance by orders of magnitude (measured: 2.6 % and 9 %).
    """
    from tribofx.runner import run_case

    s = run_case("contact-patch", {"mesh_ratio": str(ratio)},
                 out=MPI.COMM_WORLD.bcast(str(tmp_path / "patch"), root=0), progress=False)
    assert s["status"] == "ok", s["status"]
    dev = s["results"]["pressure_max_deviation"]["value"]
    mean = s["results"]["pressure_mean"]["value"]
    if ratio in (1.0, 2.0):
        assert dev <= 1e-8 and abs(mean - 0.1) <= 1e-8 * 0.1, (dev, mean)
    else:
        assert dev > 1e-4, dev


def test_ironing_slides_through_segment_changes(tmp_path):
    """Ironing (case contact-ironing, coarse): a stiff die slid 1.5 mm over 5 of its segments.

    Newton converges at every step while the slab's nodes pass from one die
    segment to the next; the solved die is in equilibrium (its support reaction
    balances the contact force, bound n_u · atol_u); once sliding, the die is
    held back against its motion (F_x < 0) and pressed up (F_y > 0), with a
    finite drag ratio 0 < |F_x|/F_y < 1 (weak bounds: friction plus ploughing).
    """
    from tribofx.runner import run_case

    s = run_case("contact-ironing", {"n": "30", "depth": "0.3", "slide": "1.5",
                                     "press_steps": "3", "slide_steps": "6"},
                 out=MPI.COMM_WORLD.bcast(str(tmp_path / "iron"), root=0), progress=False)
    assert s["status"] == "ok", s["status"]
    res = {k: x["value"] for k, x in s["results"].items()}
    assert max(res["equilibrium_error"]) <= res["equilibrium_bound"], res
    F = np.array(res["reaction_force"])
    assert np.all(F[3:, 0] < 0) and np.all(F[:, 1] > 0)
    assert 0 < res["force_ratio_sliding"] < 1


def test_petsc_block_insertion_matches_petsc4py():
    """The C++ MatSetValues/VecSetValues loop equals one petsc4py setValues per block.

    Random 13 × 13 blocks with unused (−1) slots, repeated indices across blocks
    (ADD_VALUES sums them); exact equality (same additions in the same order).
    """
    from petsc4py import PETSc

    from tribofx.petsc_insert import (
        add_matrix_blocks,
        add_matrix_blocks_ref,
        add_vector_blocks,
        add_vector_blocks_ref,
    )

    rng = np.random.default_rng(5)
    n, m = 40, 30
    rows = rng.integers(-1, m, size=(n, 13))
    cols = rng.integers(-1, m, size=(n, 13))
    vals = rng.standard_normal((n, 13, 13))
    out = []
    for add_m, add_v in ((add_matrix_blocks, add_vector_blocks),
                         (add_matrix_blocks_ref, add_vector_blocks_ref)):
        A = PETSc.Mat().createAIJ([m, m], nnz=m, comm=PETSc.COMM_SELF)
        b = PETSc.Vec().createSeq(m, comm=PETSc.COMM_SELF)
        add_m(A, rows, cols, vals)
        add_v(b, rows, vals[:, 0, :])
        A.assemble()
        b.assemble()
        out.append((A.convert("dense").getDenseArray().copy(), b.getArray().copy()))
        A.destroy()
        b.destroy()
    assert np.abs(out[0][0]).max() > 0
    assert np.array_equal(out[0][0], out[1][0]) and np.array_equal(out[0][1], out[1][1])


def _node_states_3d(n, seed):
    """Random 3D slave nodes near random triangles, multipliers of both signs."""
    rng = np.random.default_rng(seed)
    q = np.zeros((n, 25))
    a = rng.uniform(-1, 1, (n, 3))
    q[:, 3:6] = a
    q[:, 6:9] = a + [1.0, 0.0, 0.0] + rng.uniform(-0.2, 0.2, (n, 3))
    q[:, 9:12] = a + [0.2, 1.0, 0.0] + rng.uniform(-0.2, 0.2, (n, 3))
    xi = rng.dirichlet([2, 2, 2], n)
    q[:, 0:3] = (xi[:, :1] * q[:, 3:6] + xi[:, 1:2] * q[:, 6:9] + xi[:, 2:] * q[:, 9:12]
                 + rng.uniform(-0.05, 0.02, (n, 1)) * [[0.0, 0.0, 1.0]])
    q[:, 12:21] = q[:, 3:12] + rng.uniform(-0.2, 0.2, (n, 9))
    q[:, 21] = rng.uniform(-1.0, 0.3, n)
    q[:, 22:25] = rng.uniform(-0.5, 0.5, (n, 3))
    return q, rng.uniform(0, 0.5, (n, 2)), rng.uniform(0.5, 1, n), rng.uniform(0.5, 1, n)


@pytest.mark.parametrize("mu", [0.0, 0.3, 5.0])
def test_kernel_3d_matches_numpy_twin(mu):
    """3D: C++ residuals and dual-number tangents = NumPy twin with complex-step tangents."""
    q, xi_old, w, w_c = _node_states_3d(100, 2)
    r, J = two_body.node_residuals(q, xi_old, w, w_c, 10.0, 4.0, mu)
    r_ref, J_ref = two_body_ref.node_residuals(q, xi_old, w, w_c, 10.0, 4.0, mu)
    assert r.shape == (100, 25) and J.shape == (100, 25, 25)
    assert np.abs(r - r_ref).max() <= 1e-12 * np.abs(r_ref).max()
    assert np.abs(J - J_ref).max() <= 1e-12 * np.abs(J_ref).max()
    assert np.abs(J[:, 0:12, 3:12]).max() > 0


def test_kernel_3d_virtual_work_is_the_variation_of_gap_and_xi():
    """Rows 0–11 = w (T_N ∂g/∂q + T_a ∂ξ^a/∂q), g and ξ differentiated by complex step.

    An independent check of the hand-derived first variations of the header
    (dg, dξ^a of a flat facet): g(q) and ξ(q) are written out from their
    definitions (plane projection) and differentiated numerically, exact to
    round-off.
    """
    q, xi_old, w, w_c = _node_states_3d(20, 4)
    mu, rho = 0.3, 10.0
    r, _ = two_body.node_residuals(q, xi_old, w, w_c, rho, rho, mu)

    def gap_xi(qc):
        x, a, b, c = qc[0:3], qc[3:6], qc[6:9], qc[9:12]
        t1, t2 = b - a, c - a
        m = np.array([[t1 @ t1, t1 @ t2], [t1 @ t2, t2 @ t2]])
        xi = np.linalg.solve(m, np.array([(x - a) @ t1, (x - a) @ t2]))
        nr = np.cross(t1, t2)
        n = nr / np.sqrt(nr @ nr)
        return np.r_[(x - a - xi[0] * t1 - xi[1] * t2) @ n, xi], t1, t2, n

    for i in range(len(q)):
        grads = np.zeros((3, 12))
        for k in range(12):
            qc = q[i].astype(complex)
            qc[k] += 1e-30j
            grads[:, k] = gap_xi(qc)[0].imag / 1e-30
        _, t1, t2, n = gap_xi(q[i].astype(complex))
        T_n = r[i, 21] * rho / w_c[i]
        T_t = r[i, 22:25] * rho / w_c[i]
        T_a = np.array([T_t @ t1.real, T_t @ t2.real])
        expect = w[i] * (T_n * grads[0] + T_a @ grads[1:])
        assert np.abs(r[i, :12] - expect).max() <= 1e-12 * max(np.abs(expect).max(), 1e-300)


def test_master_search_3d_refit_matches_brute_force():
    """Nearest triangle of a moved (refitted) closed surface = brute force over all triangles."""
    rng = np.random.default_rng(8)
    th, ph = np.meshgrid(np.linspace(0.2, math.pi - 0.2, 8), np.linspace(0, 2 * math.pi, 13)[:-1])
    nodes = np.c_[np.sin(th.ravel()) * np.cos(ph.ravel()), np.sin(th.ravel()) * np.sin(ph.ravel()),
                  np.cos(th.ravel())]
    tris = []
    for j in range(12):
        for i in range(7):
            jn = 8 * ((j + 1) % 12)
            p, r_, s, t = 8 * j + i, jn + i, 8 * j + i + 1, jn + i + 1
            tris += [[p, r_, t], [p, t, s]]
    tris = np.array(tris, np.int32)
    master = two_body.MasterSurface3(np.ascontiguousarray(nodes), tris)
    for step in range(3):
        nodes = nodes * (1 + 0.1 * step) + rng.uniform(-0.05, 0.05, nodes.shape)
        master.refit(np.ascontiguousarray(nodes))
        pts = rng.uniform(-1.5, 1.5, (60, 3))
        got = master.project(np.ascontiguousarray(pts))
        ref = two_body_ref.project_3d(nodes, tris, pts)
        assert np.allclose(got["distance"], ref["distance"], atol=1e-13)
        # a nearest point on a shared edge or vertex ties between facets: compare points
        def point(p):
            a, b, c = (nodes[tris[p["facet"], k]] for k in range(3))
            return a + p["xi"][:, :1] * (b - a) + p["xi"][:, 1:] * (c - a)

        assert np.allclose(point(got), point(ref), atol=1e-12)


@pytest.mark.parametrize("dim", [2, 3])
def test_kernel_eulerian_matches_numpy_twin(dim):
    """Eulerian slip s = c^a t_a: C++ residuals and tangents = the NumPy twin."""
    q, c, w, w_c = _node_states(50, 6) if dim == 2 else _node_states_3d(30, 6)
    r, J = two_body.node_residuals(q, c, w, w_c, 10.0, 4.0, 0.3, eulerian=True)
    r_ref, J_ref = two_body_ref.node_residuals(q, c, w, w_c, 10.0, 4.0, 0.3, eulerian=True)
    assert np.abs(r - r_ref).max() <= 1e-12 * np.abs(r_ref).max()
    assert np.abs(J - J_ref).max() <= 1e-12 * np.abs(J_ref).max()
    L = q.shape[1]
    d = 2 if L == 13 else 3
    assert np.abs(J[:, :, d + d * d:L - 1 - d]).max() == 0      # the y slots are unused


def test_eulerian_fixed_master_is_the_rigid_plane():
    """Steady sliding (eq. 27) on a fixed master = the rigid plane moving at V (Eulerian).

    With the master fixed, F⁽²⁾ = I and the slip −Δτ F⁽²⁾V is the rigid case's
    v Δτ = (F V_body − V_plane) Δτ for a slave at rest: the same iterates.
    """
    comm = MPI.COMM_WORLD
    V = np.array([3.0, 0.0])
    slave = block(comm, 0.0, 1.0, 0.0, 0.5, 8, 4, "slave")
    slave.add_dirichlet("top", np.array([0.0, -0.02]))
    master = block(comm, -0.5, 1.5, -0.5, 0.0, 11, 3, "master")
    master.add_dirichlet("bottom", np.zeros(2))
    master.add_dirichlet("top", np.zeros(2))
    contact = TwoBodyContact(slave, "bottom", master, "top", 10.0, friction=0.3,
                             slip="eulerian", V_master=V, dtau=0.01)
    problem = Problem([slave, master, contact], name="eulerian_blocks")
    rep = problem.solve()
    rigid = Body(slave.mesh, slave.facet_tags, {"bottom": 1, "top": 2}, "plane_strain",
                 ("neo-hookean", LAME), name="rigid_slave", velocity=(0.0, 0.0))
    rigid.add_dirichlet("top", np.array([0.0, -0.02]))
    plane = Contact(rigid, "bottom", rigid_plane([0.0, 0.0], [0.0, 1.0]), 10.0, friction=0.3,
                    slip="eulerian", V_master=V, dtau=0.01)
    rep_rigid = Problem([rigid, plane], name="eulerian_plane").solve()
    scale = np.abs(rigid.u.x.array).max()
    assert rep.iterations == rep_rigid.iterations
    assert np.abs(slave.u.x.array - rigid.u.x.array).max() <= 1e-9 * scale
    assert np.allclose(contact.forces()[0], plane.force(), rtol=1e-9, atol=1e-12)
    assert contact.forces()[0][0] > 0          # the moving master drags the slave along +x


def test_eulerian_deformable_master_taylor_and_coulomb():
    """Eulerian slip on a deformable master: exact tangent, every node on the Coulomb cone.

    The slip −Δτ F⁽²⁾V depends on the current master facet (F⁽²⁾ maps the
    reference edge onto the current one): the Taylor test covers those
    columns.  In steady sliding |T_T| = μ|T_N| node by node (the constraint
    tolerance, 1e-8 relative, as for Lagrangian sliding).
    """
    comm = MPI.COMM_WORLD
    slave = block(comm, 0.0, 1.0, 0.0, 0.5, 8, 4, "slave")
    slave.add_dirichlet("top", np.array([0.0, -0.02]))
    master = block(comm, -0.5, 1.5, -0.5, 0.0, 11, 3, "master")
    master.add_dirichlet("bottom", np.zeros(2))
    contact = TwoBodyContact(slave, "bottom", master, "top", 10.0, friction=0.3,
                             slip="eulerian", V_master=(3.0, 0.0), dtau=0.01)
    problem = Problem([slave, master, contact], name="eulerian_deformable")
    problem.solve()
    d = contact.nodal_data()
    act = d["active"]
    tn, tt = np.abs(d["T_n"][act]), np.linalg.norm(d["T_t"][act], axis=1)
    t_max = comm.allreduce(float(tn.max(initial=0.0)), op=MPI.MAX)
    assert comm.allreduce(int(act.sum()), op=MPI.SUM) > 5
    assert np.all(np.abs(tt - 0.3 * tn) <= 1e-8 * t_max)
    rng = np.random.default_rng(9)
    dirs = [1e-6 * rng.standard_normal(len(f.x.array)) for f in problem.u]
    out = block_taylor_orders(problem, owned_arrays(problem, dirs), eps0=1.0)
    for name, (orders, rem, floor) in out.items():
        assert exact_tangent(orders, rem, floor), (name, orders, rem, floor)


def test_pairing_depends_on_state_and_committed_history_only():
    """The residual at a state is the same whatever was evaluated before it.

    A slave node is put 2 % of a master facet to the left of a master vertex (inside
    the hysteresis band of the right facet, STICKY = 5 %), then 30 % into the right
    facet (a line-search trial, a Taylor perturbation), then back: the residual at the
    first state, and after restore(), must be bit-identical — the facet the hysteresis
    keeps is the committed one, not that of the last evaluation.
    """
    slave, master, contact, problem, _ = two_blocks(MPI.COMM_WORLD, 0.3, fixed_master=False)
    problem.solve()
    problem.commit()
    d, h_m = 2, 2.0 / 11
    i = int(np.argmin(np.abs(contact._X[:, 0] - 0.75)))        # slave node near x = 0.75
    dof = contact._bulk[i]
    vx = -0.5 + 7 * h_m                                          # master vertex at 0.7727
    mX = master.V.tabulate_dof_coordinates()[:, :d]
    mv = int(np.argmin(np.linalg.norm(mX - [vx, 0.0], axis=1)))
    x_vertex = vx + master.u.x.array[d * mv]

    def residual_with_node_at(s):
        slave.u.x.array[d * dof] = x_vertex + s * h_m - contact._X[i, 0]
        b, _ = problem.assemble()
        return b.getArray(readonly=True).copy()

    state = problem.state()
    r1 = residual_with_node_at(-0.02)
    u1 = slave.u.x.array.copy()
    residual_with_node_at(0.3)
    r2 = residual_with_node_at(-0.02)
    assert np.array_equal(r1, r2)
    problem.restore(state)
    slave.u.x.array[:] = u1
    r3, _ = problem.assemble()
    assert np.array_equal(r1, r3.getArray(readonly=True))
