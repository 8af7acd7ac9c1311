"""The bordered Newton system: one scalar unknown and its equation beside a Problem.

Force control inside the Newton iteration: the position δ of a rigid
countersurface (a parameter held by a ``dolfinx.fem.Constant``) is an unknown
of the deformation problem's Newton iteration, with the equation
g = G(x, δ) − G* = 0 (G the contact force, a UFL functional), instead of a
secant of complete Newton solves around it.  The Newton system is bordered,

    [ K   b ] [Δx]     [ R ]      b = ∂R/∂δ,  c = ∂G/∂x,  d = ∂G/∂δ,
    [ cᵀ  d ] [Δδ] = − [ g ],

and solved by block elimination with the preconditioner of K that the
problem's SNES has just set up (with a direct solver one more back-substitution
per iteration, else one more Krylov solve; :func:`solve_like`, a KSP of its own
that shares the PC, so the SNES's linear-solve counters and fallbacks see only
their own solves):
y = K⁻¹R (the SNES step), z = K⁻¹b, Δδ = (c·y − g)/(d − c·z),
Δx = −(y + Δδ z).  The correction of y rides on the problem's line-search
pre-check (:meth:`tribofx.newton_control.NewtonControl._backtrack`), the test
|g| ≤ rtol |G*| on its stopping test; a backtracked step scales Δδ with Δx.

b, c and d are exact: UFL derivatives of the residual forms and of G, with
the Constant replaced by Constant + s·e (s a DG0 field at 0, differentiated
along s = 1).  δ must therefore enter the residual only through UFL (a
closed-form countersurface, :class:`tribofx.obstacles.AnalyticObstacle`), not
through data a component's ``refresh`` computes outside UFL.

Dirichlet rows of b are zero (δ moves no prescribed dof); c keeps them, so
that c·Δx is the exact linearization also while prescribed values are being
reached.  Units: those of the parameter (mm) and of G (N).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, cast

import numpy as np
import numpy.typing as npt
import ufl
from dolfinx import fem, la
from mpi4py import MPI
from petsc4py import PETSc
from ufl.algorithms import expand_derivatives

if TYPE_CHECKING:
    from dolfinx.mesh import EntityMap, Mesh

    from .continuation import ConstantParameter
    from .problem import Problem

__all__ = ["Border", "solve_like"]


def solve_like(ksp: PETSc.KSP, b: PETSc.Vec, x: PETSc.Vec) -> bool:
    """Solve K x = b as ``ksp`` does (its operators, type, tolerances and set-up PC).

    A second KSP that shares ``ksp``'s PC: no new factorization, and ``ksp``'s
    iteration counts and reasons stay those of the SNES's own solves.  Returns
    whether the solve converged.
    """
    other = PETSc.KSP().create(ksp.comm)
    other.setOperators(*ksp.getOperators())
    other.setType(ksp.getType())
    other.setTolerances(*ksp.getTolerances())
    other.setPC(ksp.getPC())
    try:
        other.solve(b, x)
        return cast(int, other.getConvergedReason()) > 0   # (petsc4py stub: the reason class)
    finally:
        other.destroy()


def _compiled(form: ufl.Form, emaps: Sequence[EntityMap] | None) -> fem.Form | None:
    """Compiled ``form`` (None if its derivative expanded to nothing)."""
    form = expand_derivatives(form)
    return None if form.empty() else fem.form(form, entity_maps=emaps)


class Border:
    """The scalar unknown δ (``parameter``) and its equation G(x, δ) = ``target``.

    Args:
        problem: the :class:`tribofx.problem.Problem` whose Newton iteration is bordered.
        parameter: :class:`tribofx.continuation.ConstantParameter` holding δ.
        functional: G, a rank-0 UFL form of the problem's unknowns and of the
            parameter's Constant (e.g. the contact force, N).
        target: G* (same units).
        mesh: a mesh of the forms (the DG0 field s lives on it; the Constant's mesh).
        rtol: the equation is solved when |G − G*| ≤ rtol |G*|.
    """

    def __init__(self, problem: Problem, parameter: ConstantParameter, functional: ufl.Form,
                 target: float, mesh: Mesh, rtol: float = 1e-8) -> None:
        if problem.assembles_outside_ufl:
            raise ValueError("a border needs a residual in UFL alone (no assembled terms)")
        self.problem, self.parameter = problem, parameter
        self.target, self.rtol = float(target), float(rtol)
        const = parameter.constant
        s = fem.Function(fem.functionspace(mesh, ("DG", 0)), name="border_s")
        if parameter.index is None:
            moved = const + parameter.scale * s
        else:
            e = np.zeros(const.value.shape)
            e[parameter.index] = parameter.scale
            moved = const + s * ufl.as_vector(e.tolist())
        one = ufl.as_ufl(1.0)
        emaps = problem.entity_maps or None
        self._G = fem.form(functional, entity_maps=emaps)
        self._d = _compiled(ufl.derivative(ufl.replace(functional, {const: moved}), s, one),
                            emaps)
        self._b = [_compiled(ufl.derivative(ufl.replace(F, {const: moved}), s, one), emaps)
                   for F in problem.residual_forms]
        self._c = [_compiled(ufl.derivative(functional, u, ufl.TestFunction(u.function_space)),
                             emaps) for u in problem.u]
        # owned Dirichlet dofs of each unknown (zero rows of b)
        self._fixed: list[npt.NDArray[np.int32]] = []
        for u in problem.u:
            n_own = problem.owned_size(u)
            dofs: list[npt.NDArray[np.int32]] | npt.NDArray[np.int32]
            dofs = [bc.dof_indices()[0] for c in problem.components
                    for v, bcs in c.bcs_by_unknown().items() if v is u for bc in bcs]
            dofs = np.concatenate(dofs) if dofs else np.zeros(0, dtype=np.int32)
            self._fixed.append(dofs[dofs < n_own])
        self.step = (0.0, 0.0)       # (δ at the iterate, Δδ of its Newton step)
        self.history: list[float] = []   # |g|/|G*| at each iterate of the last solve

    # -- the functional and its derivatives --------------------------------------------
    def _scalar(self, form: fem.Form | None) -> float:
        comm = self.problem.snes.comm.tompi4py()
        return 0.0 if form is None else comm.allreduce(fem.assemble_scalar(form), op=MPI.SUM)

    def value(self) -> float:
        """G at the current unknowns and δ."""
        return self._scalar(self._G)

    def derivative(self) -> float:
        """Return d = ∂G/∂δ at the current unknowns and δ."""
        return self._scalar(self._d)

    def _block_vector(self, forms: Sequence[fem.Form | None], zero_fixed: bool) -> PETSc.Vec:
        """PETSc vector of the problem's layout assembled from one form per unknown."""
        P = self.problem
        out = P.snes.getFunction()[0].duplicate()  # type: ignore[index]  # stub: (Vec, ...)
        parts = []
        for u, form, fixed in zip(P.u, forms, self._fixed):
            n_own = P.owned_size(u)
            if form is None:
                parts.append(np.zeros(n_own))
                continue
            vec = fem.assemble_vector(form)
            vec.scatter_reverse(la.InsertMode.add)
            a = vec.array[:n_own].copy()
            if zero_fixed:
                a[fixed] = 0.0
            parts.append(a)
        out.setArray(np.concatenate(parts))
        return out

    def vectors(self) -> tuple[PETSc.Vec, PETSc.Vec]:
        """(b, c): ∂R/∂δ (Dirichlet rows zero) and ∂G/∂x at the current unknowns (PETSc)."""
        return self._block_vector(self._b, True), self._block_vector(self._c, False)

    # -- the Newton step (called by NewtonControl) -------------------------------------
    def correct(self, x: PETSc.Vec, y: PETSc.Vec) -> None:
        """Border the SNES step ``y`` (K y = R at ``x``): y ← y + Δδ z; remember Δδ.

        An iterate without contact (d − c·z = 0: G does not depend on δ), or a
        failed solve for z, leaves δ and y as they are (the force equation then
        stays unsolved and Newton fails at ``max_it``: the caller's fallback).
        """
        P = self.problem
        P.set_unknowns(x)
        P.refresh()
        step = self.condense(y, self.value() - self.target)
        self.step = (self.parameter.get(), step or 0.0)

    def condense(self, y: PETSc.Vec, g: float = 0.0) -> float | None:
        """Eliminate δ from a solve ``y`` = K⁻¹r at the current state: y ← y + Δδ z.

        Δδ = (c·y − g)/(d − c·z), z = K⁻¹b: with r = R the bordered Newton step
        (−Δx = y), with r a right side f and g = 0 the solution Δx = y of
        [K b; cᵀ d][Δx; −Δδ] = [f; 0] (the response with G held).  Returns Δδ, or
        None (y unchanged) when the solve for z fails or d − c·z = 0.
        """
        b, c = self.vectors()
        z = b.duplicate()
        try:
            if not solve_like(self.problem.snes.getKSP(), b, z):
                return None
            schur = self.derivative() - c.dot(z)
            if schur == 0 or not np.isfinite(schur):
                return None
            step = cast(float, (c.dot(y) - g) / schur)     # (real PETSc scalars)
            y.axpy(step, z)
            return step
        finally:
            for v in (b, c, z):
                v.destroy()

    def trial(self, alpha: float) -> None:
        """Set δ to that of the trial x − α y of the line search."""
        delta, step = self.step
        self.parameter.set(delta + alpha * step)

    def converged(self) -> bool:
        """Whether |g| ≤ rtol |G*| at the current unknowns and δ (recorded in :attr:`history`)."""
        r = abs(self.value() - self.target) / max(abs(self.target), 1e-300)
        self.history.append(r)
        return r <= self.rtol
