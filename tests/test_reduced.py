"""Checks of :class:`tribofx.reduced.ReducedProblem` on a tiny problem with a known answer.

A distributed box Ω = [0, L_x] × [0, 1]² (Q1 hexahedra) is the extrusion along x
of the replicated square S = [0, 1]² (Q1 quadrilaterals, ``COMM_SELF``).  The
unknowns are u on Ω and s on S; s enters Ω through its extrusion s₃ = P s
(a :class:`Reduction`), and the row of s gets the algebraic term (1/L_x) Pᵀ r
with r_i = ∫_Ω u s₃² φ_i dV (an :class:`AlgebraicRow`):

    ∫_Ω [∇(u − s₃)·∇v + (1 + u² + s₃²)(u − s₃) v] dV = 0,
    ∫_S (∇s·∇q − f q) dA + (1/L_x) Pᵀ r = 0,      s = 0 on y = 0.

The first equation gives u = s₃ (the discrete problem is uniquely solvable in
u for given s₃, and u = s₃ solves it); then Pᵀ r is, since the x hats of the
extruded basis sum to the 2D hat, ∫_Ω s₃³ φ_j(y, z) dV = L_x ∫_S s³ φ_j dA (the
tensor Gauss rule integrates the x direction of a product with x-independent
factors exactly).  So s solves the 2D problem ∫_S (∇s·∇q + s³ q − f q) dA = 0,
solved here independently by DOLFINx's own Newton solver on S.  This cannot
hold by construction: a wrong extrusion, transpose, block layout, Jacobian
product J P / Pᵀ J, Dirichlet row or rank-0 ownership of the replicated rows
breaks it (or the Newton rate).
"""

import dolfinx.fem.petsc as fem_petsc
import numpy as np
import pytest
import ufl
from dolfinx import fem, mesh
from mpi4py import MPI
from tribofx.meshes.halfspace import prolongation

from tribofx.interfaces.steady_wear import Extrusion
from tribofx.problem import BlockTolerance
from tribofx.protocols import ComponentBase
from tribofx.reduced import AlgebraicRow, ReducedProblem, Reduction
from tribofx.testing import block_taylor_orders, exact_tangent

LX, N, NX, F = 2.0, 4, 3, 20.0


class _Bulk(ComponentBase):
    """u on Ω: ∫ ∇(u − s₃)·∇v + (1 + u² + s₃²)(u − s₃) v dV."""

    def __init__(self, box, s3):
        self.u = fem.Function(s3.function_space.clone(), name="u")
        v = ufl.TestFunction(self.u.function_space)
        e = self.u - s3
        self.form = (ufl.inner(ufl.grad(e), ufl.grad(v)) + (1 + self.u**2 + s3**2) * e * v) * ufl.dx

    def unknowns(self):
        return [self.u]

    def contributions(self):
        return [(self.u, self.form)]

    def tolerances(self):
        return {self.u: BlockTolerance(1e-13)}

    def state_fields(self):
        return [self.u]



class _Section(ComponentBase):
    """s on S: ∫ ∇s·∇q − f q dA + (1/L_x) Pᵀ r, r = ∫_Ω u s₃² φ dV; the reduction s₃ = P s."""

    def __init__(self, square, s3, bulk, P):
        V2 = fem.functionspace(square, ("Lagrange", 1))
        self.s, self.s3, self.P = fem.Function(V2, name="s"), s3, P
        q = ufl.TestFunction(V2)
        self.form = (ufl.inner(ufl.grad(self.s), ufl.grad(q)) - F * q) * ufl.dx
        self.rate = bulk.u * s3**2 * ufl.TestFunction(s3.function_space) * ufl.dx
        facets = mesh.locate_entities_boundary(square, 1, lambda x: np.isclose(x[0], 0.0))
        dofs = fem.locate_dofs_topological(V2, 1, facets)
        self.bc = fem.dirichletbc(fem.Constant(square, 0.0), dofs, V2)

    def unknowns(self):
        return [self.s]

    def contributions(self):
        return [(self.s, self.form)]

    def reductions(self):
        return [Reduction(self.s3, self.s, self.P)]

    def algebraic_rows(self):
        return [AlgebraicRow(self.s, self.rate, self.P, lambda: 1.0 / LX)]

    def bcs(self):
        return [self.bc]

    def bcs_by_unknown(self):
        return {self.s: [self.bc]}

    def tolerances(self):
        return {self.s: BlockTolerance(1e-13)}

    def state_fields(self):
        return [self.s]



def _build(comm):
    box = mesh.create_box(comm, [[0.0, 0.0, 0.0], [LX, 1.0, 1.0]], [NX, N, N],
                          mesh.CellType.hexahedron)
    square = mesh.create_rectangle(MPI.COMM_SELF, [[0.0, 0.0], [1.0, 1.0]], [N, N],
                                   mesh.CellType.quadrilateral)
    V3 = fem.functionspace(box, ("Lagrange", 1))
    s3 = fem.Function(V3, name="s3")
    V2 = fem.functionspace(square, ("Lagrange", 1))
    im = V3.dofmap.index_map
    P = Extrusion(*prolongation(V3.tabulate_dof_coordinates(),
                                V2.tabulate_dof_coordinates()[:, :2]),
                  comm, im.size_local, im.size_global)
    bulk = _Bulk(box, s3)
    section = _Section(square, s3, bulk, P)
    return bulk, section, ReducedProblem([bulk, section], name="reduced_test")


def _reference_2d():
    """The 2D problem ∫ ∇s·∇q + s³ q − f q dA = 0 (s = 0 on y = 0) by DOLFINx's Newton."""
    square = mesh.create_rectangle(MPI.COMM_SELF, [[0.0, 0.0], [1.0, 1.0]], [N, N],
                                   mesh.CellType.quadrilateral)
    V = fem.functionspace(square, ("Lagrange", 1))
    s, q = fem.Function(V), ufl.TestFunction(V)
    R = (ufl.inner(ufl.grad(s), ufl.grad(q)) + s**3 * q - F * q) * ufl.dx
    facets = mesh.locate_entities_boundary(square, 1, lambda x: np.isclose(x[0], 0.0))
    bc = fem.dirichletbc(fem.Constant(square, 0.0), fem.locate_dofs_topological(V, 1, facets), V)
    opts = {"snes_type": "newtonls", "snes_linesearch_type": "basic", "snes_rtol": 0.0,
            "snes_atol": 1e-13, "ksp_type": "preonly", "pc_type": "lu"}
    fem_petsc.NonlinearProblem(R, s, bcs=[bc], petsc_options=opts,
                               petsc_options_prefix="reduced_ref_").solve()
    return s.x.array.copy()


def _solve(comm):
    bulk, section, prob = _build(comm)
    rep = prob.solve()
    u_max = comm.allreduce(float(np.max(np.abs(bulk.u.x.array - section.s3.x.array))),
                           op=MPI.MAX)
    return section.s.x.array.copy(), rep, u_max


@pytest.mark.mpi
def test_reduced_solution_equals_the_2d_problem():
    s, rep, du = _solve(MPI.COMM_WORLD)
    ref = _reference_2d()
    print("iterations", rep.iterations, "residuals", rep.residuals, "|u - s3|", du,
          "|s - s_2d|", np.abs(s - ref).max(), "max s", ref.max())
    # both Newton solves stop at residual rows ≤ 1e-13 on an O(1)-conditioned 25-dof
    # (O(100) 3D) system: 1e-10 relative leaves three decades for the condition number
    assert np.abs(s - ref).max() <= 1e-10 * np.abs(ref).max()
    assert du <= 1e-10 * np.abs(ref).max()  # u = P s
    assert ref.max() > 0.5  # the s³ term matters (s = O(1))
    # exact Jacobian of the reduced system: quadratic convergence
    orders = rep.rates()
    print("orders", orders)
    assert orders[-1] > 1.8


@pytest.mark.mpi
def test_reduced_jacobian_taylor():
    """Taylor test of the assembled (block-merged) Jacobian at a random state.

    Every coupling path is exercised: J_{u s} = J_{u s₃} P, the algebraic row
    (1/L_x) Pᵀ (J_{r u}, J_{r s₃} P), and the Dirichlet row of s.
    """
    bulk, section, prob = _build(MPI.COMM_WORLD)
    rng = np.random.default_rng(7 + MPI.COMM_WORLD.rank)
    bulk.u.x.array[:] = rng.uniform(0.5, 1.5, len(bulk.u.x.array))
    bulk.u.x.scatter_forward()
    section.s.x.array[:] = np.random.default_rng(3).uniform(0.5, 1.5, len(section.s.x.array))
    prob.refresh()
    d_u = rng.standard_normal(len(bulk.u.x.array))
    d_s = np.random.default_rng(5).standard_normal(len(section.s.x.array))
    n_u = bulk.u.function_space.dofmap.index_map.size_local
    d_s = d_s if (MPI.COMM_WORLD.size == 1 or MPI.COMM_WORLD.rank == 0) else d_s[:0]
    # per block (u's columns alone, s's alone): the residual is a polynomial (degree 3)
    # in the unknowns, non-linear along each: the remainder of an exact Jacobian is
    # O(ε²) (orders 2 to O(ε) relative), of an inexact block O(ε)
    blocks = block_taylor_orders(prob, [d_u[:n_u], d_s], eps0=1e-2)
    for name, (orders, rel, floor) in blocks.items():
        print(name, "orders", orders, "relative remainders", rel)
        assert exact_tangent(orders, rel, floor, min_order=1.9), (name, orders, rel, floor)


@pytest.mark.mpi
def test_reduced_two_ranks_match_serial():
    if MPI.COMM_WORLD.size != 2:
        pytest.skip("needs mpiexec -n 2")
    s, rep, _ = _solve(MPI.COMM_WORLD)
    bulk, _, prob = _build(MPI.COMM_WORLD)
    assert min(MPI.COMM_WORLD.allgather(bulk.u.function_space.dofmap.index_map.size_local)) > 0
    ref = _solve(MPI.COMM_SELF) if MPI.COMM_WORLD.rank == 0 else None
    ref = MPI.COMM_WORLD.bcast(None if ref is None else (ref[0], ref[1].iterations), root=0)
    # same discrete problem, another partition: round-off of the LU solves only
    assert np.abs(s - ref[0]).max() <= 1e-12 * np.abs(ref[0]).max()
    assert rep.iterations == ref[1]
