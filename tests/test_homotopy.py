"""The Newton homotopy of :meth:`tribofx.problem.Problem.solve_by_homotopy`.

A field with its own component: the reaction–diffusion rows

    ∫ (ε ∇u·∇v + arctan(u − g) v) dx = 0   on the unit square, natural boundaries,

whose exact solution is u ≡ g (P1 represents it exactly; the discrete solution is
g to the solver's tolerance).  Newton without a line search on arctan(x) = 0
diverges from |x₀| > 1.3917 (the root of 2x = (1 + x²) arctan x): from u₀ = 0 and
g = 3 every iterate overshoots further (|x| 3 → 9.5 → 124 → …).  The homotopy
R(u) − (1 − s) R(u₀) = 0 must reach u = g by cutting s, and a solve that
converges directly must be untouched (the same iterations and state).
"""

import numpy as np
import pytest
import ufl
from dolfinx import fem, mesh
from mpi4py import MPI

from tribofx.problem import BlockTolerance, NewtonDivergence, Problem
from tribofx.protocols import ComponentBase

ATOL = 1e-10          # the rows' stopping test (max |r_i / w_i|, w_i the lumped row area)


class Reaction(ComponentBase):
    """The rows ∫ (ε ∇u·∇v + arctan(u − g) v) dx of one P1 unknown u."""

    def __init__(self, g, eps=0.1):
        msh = mesh.create_unit_square(MPI.COMM_WORLD, 6, 6)
        V = fem.functionspace(msh, ("Lagrange", 1))
        self.u = fem.Function(V, name="u")
        self.g = fem.Constant(msh, float(g))
        v = ufl.TestFunction(V)
        self.form = (eps * ufl.inner(ufl.grad(self.u), ufl.grad(v))
                     + ufl.atan(self.u - self.g) * v) * ufl.dx
        self.weight = v * ufl.dx

    def unknowns(self):
        return [self.u]

    def contributions(self):
        return [(self.u, self.form)]

    def tolerances(self):
        return {self.u: BlockTolerance(ATOL, "-", self.weight)}

    def state_fields(self):
        return [self.u]



def _max_error(c, g):
    return MPI.COMM_WORLD.allreduce(float(np.max(np.abs(c.u.x.array - g))), op=MPI.MAX)


@pytest.mark.mpi
def test_plain_newton_diverges_and_the_homotopy_reaches_the_exact_solution():
    g = 3.0
    c = Reaction(g)
    problem = Problem([c], name="homotopy_arctan", max_backtracks=0, max_it=25)
    with pytest.raises(NewtonDivergence):
        problem.solve()
    assert _max_error(c, g) == g                # a failed solve leaves the entry state
    report = problem.solve_by_homotopy()
    # |u − g| ≤ |arctan(u − g)|/(1 − …) ≈ the row residual over the row area: ATOL
    assert _max_error(c, g) <= 10 * ATOL
    assert report.iterations > 25                # the failed direct trial is counted


@pytest.mark.mpi
def test_a_solve_that_converges_directly_is_unchanged():
    """From |u₀ − g| = 1 < 1.39 Newton converges: the homotopy's first trial is that solve."""
    a, b = Reaction(1.0), Reaction(1.0)
    ra = Problem([a], name="homotopy_direct_a", max_backtracks=0).solve()
    rb = Problem([b], name="homotopy_direct_b", max_backtracks=0).solve_by_homotopy()
    assert ra.iterations == rb.iterations
    assert np.array_equal(a.u.x.array, b.u.x.array)


@pytest.mark.mpi
def test_the_homotopy_gives_up_with_the_entry_state():
    """A problem with no solution (arctan(u − g) = 2 > π/2 has none): the homotopy
    stalls where arctan saturates, then raises with the entry state restored."""
    c = Reaction(0.0)
    c.form = c.form - 2.0 * ufl.TestFunction(c.u.function_space) * ufl.dx
    c.u.x.array[:] = 0.25
    problem = Problem([c], name="homotopy_none", max_backtracks=0, max_it=15)
    with pytest.raises(NewtonDivergence, match="homotopy stalled"):
        problem.solve_by_homotopy(min_step=2.0**-5)
    assert np.all(c.u.x.array == 0.25)
