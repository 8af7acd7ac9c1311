"""Safeguards of a Krylov solve inside Newton: a floor in the Newton test's units, an LU fallback.

The floor stops GMRES once its true residual is below a fraction of the Newton
stopping test of every block; the fallback solves the same system by LU when a
Krylov solve fails.

**Why a floor.** GMRES stops at ``‖r‖₂ ≤ rtol·‖b‖₂``.  When ``b`` lies in rows of a
small unit while the solution moves rows of a large one, that bound can sit below
the round-off of any solver.  Measured on the first Newton system of an implicit
§5.3 groove step (``tests/test_solvers.py``, 3450 unknowns): ``b`` is the wear
rate in the shape-multiplier rows, ‖b‖ = 2.9·10⁻⁵ mm, so rtol 10⁻¹⁰ asks for
‖r‖ ≤ 2.9·10⁻¹⁵, while MUMPS's LU of the same system leaves 1.4·10⁻¹² in the
displacement rows (row sums 1.6·10⁷ N/mm, ‖x‖ = 0.016 mm: ε‖A‖‖x‖ ≈ 5·10⁻¹¹).
GMRES's recurrence residual goes below what its true residual can reach; it
stagnates (996 iterations) or breaks down at its restart, depending on the CPU's
round-off.  The preconditioner is not the cause: asked for rtol 10⁻⁹ the same
solve takes 64 iterations.

The floor is the Newton test's own: block ``i`` of the Newton residual is
converged at ``max |r_k / w_k| ≤ atol_i`` (:mod:`tribofx.newton_control`).  A
linear residual ``r`` with ``|r_k| ≤ η·atol_i·w_k`` in every row changes the next
Newton residual by at most η of every block's tolerance, so the stopping
decision and the quadratic rate down to the tolerance are those of an exact
solve.  GMRES stops at rtol, or when the true residual passes this row test
(η = 0.1); the true residual (one extra preconditioner application and product)
is formed only once the recurrence residual is below the floor's 2-norm, a
necessary condition, so in the last few iterations of a solve.

**Fallback.** A Krylov solve that still fails (breakdown, iteration cap, NaN) is
not the end of a Newton step: the same system is solved by MUMPS LU, the KSP is
marked converged, and the event (Krylov reason, iterations, Newton iteration) is
kept in :attr:`KrylovGuard.fallbacks`, in the Newton report, on stderr, and in
``summary.json`` (``linear_fallbacks``).  A run that LU finishes is finished.
With ``switch_after`` = n (the iterative strategy: 2), the n-th failed Krylov
solve of a problem switches its KSP to that LU for good (the event says so): a
preconditioner that failed twice on a problem's Newton systems fails on later
ones too (measured: the soft-EHL ball at 40 N, 64k unknowns, GMRES at its
3000-iteration cap, or broken down, in the first Newton iteration of every load
step), and each failed solve costs the iteration cap before the LU.
"""

from __future__ import annotations

import sys
import weakref
from typing import TYPE_CHECKING, Any, cast

import numpy as np
import numpy.typing as npt
from mpi4py import MPI
from petsc4py import PETSc

if TYPE_CHECKING:
    from .problem import Problem

__all__ = ["KrylovGuard", "reason_name"]


def reason_name(reason: int, kind: type = PETSc.KSP.ConvergedReason) -> str:
    """Name of a PETSc converged reason: ``DIVERGED_BREAKDOWN`` for KSP's -5.

    ``kind``: the reason enumeration, KSP's (default) or ``PETSc.SNES.ConvergedReason``.
    """
    names = {v: k for k, v in vars(kind).items() if isinstance(v, int)}
    return names.get(int(reason), str(int(reason)))


class KrylovGuard:
    """The floor test and the direct fallback of one problem's Krylov solve.

    Args:
        eta: fraction of each block's Newton tolerance the linear residual must reach
            (rows ``|r_k| ≤ eta·atol_i·w_k``) for GMRES to stop before rtol.
        package: factorisation package of the fallback LU.
        switch_after: number of Krylov failures of the problem after which the KSP
            becomes that LU for the rest of the run (None: never).
    """

    def __init__(self, eta: float = 0.1, package: str = "mumps",
                 switch_after: int | None = None) -> None:
        self.eta, self.package = float(eta), package
        self.switch_after = switch_after
        self._failed = 0
        self.fallbacks: list[dict[str, Any]] = []
        self._direct: PETSc.KSP | None = None
        self._bound: tuple[npt.NDArray[np.float64], float] | None = None

    def install(self, problem: Problem) -> None:
        """Add the floor test and the fallback to ``problem``'s KSP (weakly referenced)."""
        ref = weakref.ref(problem)
        ksp = problem.snes.getKSP()

        def floor(ksp: PETSc.KSP, its: int, rnorm: float) -> int:
            p = ref()
            return 0 if p is None else self._floor_test(p, ksp, its, rnorm)

        def post(ksp: PETSc.KSP, b: PETSc.Vec, x: PETSc.Vec) -> None:
            p = ref()
            if p is not None:
                self._fallback(p, ksp, b, x)

        # (petsc4py's stub wants the reason class from the test; the reasons are ints)
        ksp.addConvergenceTest(floor)  # type: ignore[arg-type]
        ksp.setPostSolve(post)

    # -- the floor -----------------------------------------------------------------------
    def bound(self, problem: Problem) -> tuple[npt.NDArray[np.float64], float]:
        """Owned rows' bound η·atol_i·w_k, and its global 2-norm (computed once)."""
        if self._bound is None:
            n = sum(problem.owned_size(ui) for ui in problem.u)
            rows = np.empty(n)
            for _, sl, tol, w in problem.block_tolerances:
                rows[sl] = self.eta * tol.atol * (1.0 if w is None else w)
            comm = problem.snes.comm.tompi4py()
            self._bound = (rows, np.sqrt(comm.allreduce(float(rows @ rows), op=MPI.SUM)))
        return self._bound

    def _floor_test(self, problem: Problem, ksp: PETSc.KSP, its: int, rnorm: float) -> int:
        if its == 0 or ksp.getPCSide() != PETSc.PC.Side.RIGHT:
            return 0     # rnorm is the true residual's 2-norm only under right preconditioning
        rows, norm = self.bound(problem)
        if not rnorm <= norm:
            return 0
        r = ksp.buildResidual()
        ok = bool(np.all(np.abs(r.getArray(readonly=True)) <= rows))
        r.destroy()
        ok = ksp.getComm().tompi4py().allreduce(ok, op=MPI.LAND)
        return PETSc.KSP.ConvergedReason.CONVERGED_ATOL if ok else 0

    # -- the fallback --------------------------------------------------------------------
    def _fallback(self, problem: Problem, ksp: PETSc.KSP, b: PETSc.Vec, x: PETSc.Vec) -> None:
        # (petsc4py's stubs type the reasons as their enumeration class: they are ints)
        reason = cast(int, ksp.getConvergedReason())
        if reason >= 0:
            return
        self._failed += 1
        its = ksp.getIterationNumber()
        A, _ = ksp.getOperators()
        if self._direct is None:
            d = PETSc.KSP().create(ksp.getComm())
            d.setOptionsPrefix((problem.prefix or "") + "fallback_")
            d.setType("preonly")
            d.getPC().setType("lu")
            d.getPC().setFactorSolverType(self.package)
            d.setFromOptions()
            self._direct = d
        d = self._direct
        d.setOperators(A)
        d.solve(b, x)
        ok = cast(int, d.getConvergedReason()) > 0 and np.isfinite(x.norm())
        d.reset()                    # the factor is freed: a fallback is the exception
        newton = problem.snes.getIterationNumber()
        event = {"newton_iteration": int(newton), "krylov": ksp.getType(),
                 "reason": reason_name(reason), "iterations": int(its),
                 "direct": "converged" if ok else "failed"}
        self.fallbacks.append(event)
        problem.record_linear_fallback(event)
        if ksp.getComm().getRank() == 0:
            sys.stderr.write(
                f"tribofx: {problem.name}: {ksp.getType().upper()} {event['reason']} after "
                f"{its} iterations in Newton iteration {newton}; solved by "
                f"{self.package.upper()} LU instead ({event['direct']})\n")
        if ok:   # (petsc4py's stub wants the reason class; the reason is an int)
            ksp.setConvergedReason(PETSc.KSP.ConvergedReason.CONVERGED_ITS)  # type: ignore[arg-type]
        if ok and self.switch_after and self._failed >= self.switch_after:
            self._switch(problem, ksp)

    def _switch(self, problem: Problem, ksp: PETSc.KSP) -> None:
        """Make ``ksp`` the direct solve for the rest of the run (the fallback's LU)."""
        ksp.setType("preonly")
        pc = ksp.getPC()
        pc.setType("lu")
        pc.setFactorSolverType(self.package)
        self.fallbacks[-1]["switched"] = f"{self.package} LU from here on"
        if ksp.getComm().getRank() == 0:
            sys.stderr.write(f"tribofx: {problem.name}: {self._failed} Krylov failures: "
                             f"{self.package.upper()} LU from here on\n")
