"""Block Newton solver for (possibly mixed-dimensional) residuals, with exact UFL tangents.

The residual blocks F_i(u_0, …, u_m) are compiled once; the Jacobian blocks are
their ``ufl.derivative``.  Every iteration assembles a monolithic PETSc matrix
(MPI AIJ over all blocks) and solves with MUMPS LU.  A ``pre_evaluate`` hook runs
after each update of the unknowns and before assembly, so that data computed
outside UFL (closest-point projections by the C++ kernel) follow the iterate.
"""

import dolfinx.fem.petsc as fem_petsc
import numpy as np
import ufl
from dolfinx import fem
from dolfinx.la.petsc import _ghost_update
from petsc4py import PETSc
from ufl.algorithms import expand_derivatives

from .problem import NewtonDivergence, NewtonReport, convergence_orders

__all__ = ["BlockNewton", "NewtonDivergence", "NewtonReport", "convergence_orders"]


class BlockNewton:
    """Newton's method for the block residual ``F`` in the unknowns ``u``.

    Args:
        F: list of UFL residual forms (one per unknown) or a single form.
        u: list of ``dolfinx.fem.Function`` (or a single one).
        bcs: Dirichlet conditions (on any block).
        entity_maps: entity maps for mixed-dimensional forms.
        pre_evaluate: callable run before every assembly (after ``u`` is updated).
        rtol, atol: relative/absolute tolerance on the residual 2-norm.
        max_it: maximum number of iterations.
        max_backtracks: maximum step halvings of the backtracking line search (0: off).
    """

    _count = 0

    def __init__(
        self,
        F,
        u,
        bcs=(),
        entity_maps=None,
        pre_evaluate=None,
        rtol=1e-10,
        atol=1e-10,
        max_it=30,
        max_backtracks=6,
        petsc_prefix=None,
    ):
        self.single = not isinstance(u, (list, tuple))
        self.u = [u] if self.single else list(u)
        F = [F] if self.single else list(F)
        J = [[ufl.derivative(Fi, uj, ufl.TrialFunction(uj.function_space)) for uj in self.u]
             for Fi in F]
        J = [[_nonzero_or_none(a) for a in row] for row in J]
        kw = {"entity_maps": entity_maps} if entity_maps else {}
        self.F = fem.form(F, **kw)
        self.J = fem.form(J, **kw)
        self.bcs = list(bcs)
        self.pre_evaluate = pre_evaluate
        self.rtol, self.atol, self.max_it = rtol, atol, max_it
        self.max_backtracks = max_backtracks
        spaces = [ui.function_space for ui in self.u]
        self.A = fem_petsc.create_matrix(self.J, kind="mpi")
        self.b = fem_petsc.create_vector(spaces, kind="mpi")
        self.x = fem_petsc.create_vector(spaces, kind="mpi")
        self.dx = self.x.duplicate()
        self._blocks = self.b.getAttr("_blocks")
        BlockNewton._count += 1
        petsc_prefix = petsc_prefix or f"tribofx_newton{BlockNewton._count}_"
        self.ksp = PETSc.KSP().create(self.A.comm)
        self.ksp.setOptionsPrefix(petsc_prefix)
        self.ksp.setOperators(self.A)
        self.ksp.setType("preonly")
        pc = self.ksp.getPC()
        pc.setType("lu")
        pc.setFactorSolverType("mumps")
        self.ksp.setFromOptions()

    @property
    def num_dofs(self):
        """Global number of unknowns of the block system."""
        return self.x.getSize()

    def _residual(self):
        _ghost_update(self.x, PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
        fem_petsc.assign(self.x, self.u)
        if self.pre_evaluate is not None:
            self.pre_evaluate()
        fem_petsc.assemble_residual(
            None, self.x, self.b, self.u, self.F, self.J, self.bcs, _blocks=self._blocks
        )
        return self.b.norm()

    def _jacobian(self):
        fem_petsc.assemble_jacobian(None, self.x, self.A, None, self.u, self.J, None, self.bcs)

    def assemble(self):
        """Assemble residual ``b`` and Jacobian ``A`` at the current values of ``u``.

        Dirichlet rows are treated as in :meth:`solve`; returns ``(b, A)``.
        """
        fem_petsc.assign(self.u, self.x)
        self._residual()
        self._jacobian()
        return self.b, self.A

    def solve(self, verbose=False):
        """Run Newton from the current values of ``u``; return a :class:`NewtonReport`.

        Raises :class:`NewtonDivergence` (leaving ``u`` at the entry values) on failure.
        """
        backup = [ui.x.array.copy() for ui in self.u]
        fem_petsc.assign(self.u, self.x)
        _ghost_update(self.x, PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
        report = NewtonReport()
        r0 = None
        for it in range(self.max_it + 1):
            r = self._residual()
            report.residuals.append(r)
            if verbose and self.x.comm.rank == 0:
                print(f"  newton {it:2d}: |R| = {r:.3e}")
            if not np.isfinite(r):
                break
            r0 = r if r0 is None else r0
            if r <= self.atol + self.rtol * max(r0, 1.0) and it > 0 or r <= self.atol:
                report.iterations = it
                fem_petsc.assign(self.x, self.u)
                for ui in self.u:
                    ui.x.scatter_forward()
                return report
            if it == self.max_it:
                break
            self._jacobian()
            self.ksp.solve(self.b, self.dx)
            if self.ksp.getConvergedReason() < 0:
                break
            report.increments.append(self.dx.norm())
            self._line_search(r)
        for ui, b in zip(self.u, backup):
            ui.x.array[:] = b
        raise NewtonDivergence(
            f"Newton did not converge in {self.max_it} iterations "
            f"(residual history {['%.2e' % v for v in report.residuals]})"
        )

    def _line_search(self, r):
        """Full Newton step unless it raises the residual norm; then backtrack.

        Semismooth Newton on contact and friction can cycle between active sets;
        halving the step while ‖R‖ does not decrease (Armijo, c = 1e-4) breaks the
        cycle.  Near the solution the full step is always accepted, which keeps
        the local quadratic rate.  If no trial decreases ‖R‖ the full step is taken.
        """
        x0 = self.x.copy()
        alpha = 1.0
        for _ in range(self.max_backtracks + 1):
            self.x.waxpy(-alpha, self.dx, x0)
            _ghost_update(self.x, PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
            if self.max_backtracks == 0 or self._residual() < (1 - 1e-4 * alpha) * r:
                x0.destroy()
                return
            alpha *= 0.5
        self.x.waxpy(-1.0, self.dx, x0)
        _ghost_update(self.x, PETSc.InsertMode.INSERT, PETSc.ScatterMode.FORWARD)
        x0.destroy()


def _nonzero_or_none(a):
    a = expand_derivatives(a)
    return None if a.empty() else a
