"""Newton's stopping test in physical units, and its backtracking line search.

:class:`NewtonControl` is the part of :class:`tribofx.problem.Problem` that
decides when a Newton iteration stops and how far a step goes.

Stopping test (per block, physical units): block ``i`` is converged when
``max_k |r_k / w_k| ≤ atol_i``, with ``w`` the block's lumped row measure (or 1):
nodal forces in N (N/mm in plane strain) for momentum rows, a gap in mm for
contact-constraint rows, a flux for Reynolds rows.  The iteration stops when
every block is converged, never on one 2-norm over mixed units.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, TypeAlias, cast

import numpy as np
import numpy.typing as npt
import ufl
from dolfinx import fem, la
from mpi4py import MPI
from petsc4py import PETSc

if TYPE_CHECKING:
    from dolfinx.mesh import EntityMap

    from .bordered import Border
    from .problem import ProblemComponent
    from .reports import BlockTolerance, NewtonReport

    #: one block of rows: (unknown's name, slice of its owned rows, its stopping
    #: tolerance, the lumped row weights w or None)
    BlockRows: TypeAlias = tuple[str, slice, BlockTolerance, npt.NDArray[np.float64] | None]

__all__ = ["NewtonControl"]


class NewtonControl:
    """Stopping test per block and line search of a :class:`tribofx.problem.Problem`.

    It reads the problem's ``components``, unknowns ``u``, ``snes``, ``max_it``,
    ``max_backtracks``, ``line_search``, ``stall_window``, ``_verbose`` and the
    report being filled (``_report``); row weights are assembled with
    ``_emaps()`` and cut by ``_owned``/``owned_size``; trial residuals go
    through ``_residual`` and its cache ``_cache``.

    ``border`` (a :class:`tribofx.bordered.Border`, or None): a scalar unknown
    and its equation beside the system; its correction of each Newton step runs
    before the line search, its equation joins the stopping test.
    """

    border: Border | None = None

    if TYPE_CHECKING:   # what it reads of its tribofx.problem.Problem
        components: list[ProblemComponent]
        u: list[fem.Function]
        snes: PETSc.SNES
        name: str
        max_it: int
        max_backtracks: int
        line_search: str
        stall_window: int | None
        _verbose: bool
        _report: NewtonReport | None
        _tolerances: list[BlockRows]
        _cache: tuple[npt.NDArray[Any], PETSc.Vec] | None

        def owned_size(self, ui: fem.Function) -> int:
            """Rows of ``ui`` owned by this rank."""

        def set_unknowns(self, x: PETSc.Vec) -> None:
            """Copy the block vector ``x`` into the unknowns."""

        def refresh(self) -> None:
            """Run every component's ``refresh`` at the current unknowns."""

        def _owned(self, vec: la.Vector, ui: fem.Function) -> npt.NDArray[np.float64]: ...

        def _emaps(self) -> list[EntityMap] | None: ...

        def _residual(self, snes: PETSc.SNES, x: PETSc.Vec, b: PETSc.Vec) -> None: ...

        def _evaluate(self, snes: PETSc.SNES, x: PETSc.Vec, b: PETSc.Vec) -> None: ...

    def _collect_tolerances(
            self, overrides: Mapping[fem.Function, BlockTolerance]) -> list[BlockRows]:
        """Per block: (name, slice of owned rows, BlockTolerance, row weights or None)."""
        tol: dict[int, BlockTolerance] = {}
        for c in self.components:
            for ui, t in c.tolerances().items():
                tol.setdefault(id(ui), t)
        for ui, t in overrides.items():
            tol[id(ui)] = t
        blocks, start = [], 0
        for ui in self.u:
            n = self.owned_size(ui)
            t = tol.get(id(ui))
            if t is None:
                raise ValueError(f"no stopping tolerance for unknown {ui.name!r}")
            w = None
            if t.weight is not None:
                vec = fem.assemble_vector(fem.form(cast(ufl.Form, t.weight),  # a UFL form
                                                   entity_maps=self._emaps()))
                vec.scatter_reverse(la.InsertMode.add)
                w = self._owned(vec, ui).copy()
                w[w <= 0] = 1.0
            blocks.append((ui.name, slice(start, start + n), t, w))
            start += n
        return blocks

    def _block_norms(self, b: PETSc.Vec) -> list[float]:
        arr = b.getArray(readonly=True)
        comm = b.comm.tompi4py()
        out = []
        for _, sl, _, w in self._tolerances:
            r = arr[sl] if w is None else arr[sl] / w
            out.append(comm.allreduce(float(np.max(np.abs(r), initial=0.0)), op=MPI.MAX))
        return out

    def _accept_iterate(self, snes: PETSc.SNES) -> float | None:
        """Let components with a Newton-iterate history accept the current iterate.

        (The two-body pairing's hysteresis reference.)  If one moved on, the
        residual is evaluated again; returns its 2-norm, or None if nothing changed.
        """
        movers = [c for c in self.components if c.iterates]
        if not movers:
            return None
        x = snes.getSolution()
        self.set_unknowns(x)
        changed = [c.accept_iterate() for c in movers]
        if not any(changed):
            return None
        b = snes.getFunction()[0]  # type: ignore[index]  # petsc4py stub: it is (Vec, ...)
        self._cache = None
        self._evaluate(snes, x, b)
        fnorm = b.norm()
        snes.setFunctionNorm(fnorm)
        return fnorm

    def _converged(self, snes: PETSc.SNES, it: int, norms: tuple[float, float, float]) -> int:
        assert self._report is not None     # SNES runs the test inside solve(), which sets it
        fnorm = norms[2]
        if it > 0:
            moved = self._accept_iterate(snes)
            fnorm = fnorm if moved is None else moved
        self._report.linear_iterations = snes.getLinearSolveIterations()
        b = snes.getFunction()[0]  # type: ignore[index]  # petsc4py stub: it is (Vec, ...)
        blocks = self._block_norms(b)
        self._report.residuals.append(fnorm)
        self._report.blocks.append(blocks)
        if it > 0:
            dx = snes.getSolutionUpdate().getArray(readonly=True)
            comm = b.comm.tompi4py()
            self._report.increments.append(
                [comm.allreduce(float(np.max(np.abs(dx[sl]), initial=0.0)), op=MPI.MAX)
                 for _, sl, _, _ in self._tolerances])
        if self._verbose and snes.comm.rank == 0:
            parts = "  ".join(f"{n} {v:.2e} {t.unit}" for (n, _, t, _), v in
                              zip(self._tolerances, blocks))
            print(f"  {self.name} newton {it:2d}: |R| = {fnorm:.3e}   {parts}")
        if not np.isfinite(fnorm):
            # (petsc4py's stub omits this reason)
            return PETSc.SNES.ConvergedReason.DIVERGED_FNORM_NAN  # type: ignore[attr-defined]
        held = self.border is None or self.border.converged()
        if self._verbose and self.border is not None and snes.comm.rank == 0:
            print(f"  {self.name} newton {it:2d}: |G - G*|/|G*| = {self.border.history[-1]:.2e}"
                  f"  δ = {self.border.parameter.get():.10g}")
        if held and all(v <= t.atol for v, (_, _, t, _) in zip(blocks, self._tolerances)):
            return PETSc.SNES.ConvergedReason.CONVERGED_FNORM_ABS
        if it >= self.max_it:
            return PETSc.SNES.ConvergedReason.DIVERGED_MAX_IT
        if self._stalled(self._report.residuals):
            return PETSc.SNES.ConvergedReason.DIVERGED_DTOL
        return PETSc.SNES.ConvergedReason.ITERATING

    def _stalled(self, residuals: Sequence[float]) -> bool:
        """Whether the best residual has not halved over the last ``stall_window`` iterations."""
        w = self.stall_window
        if w is None or len(residuals) <= 2 * w:
            return False
        return min(residuals[-w:]) > 0.5 * min(residuals[:-w])

    def _backtrack(self, x: PETSc.Vec, y: PETSc.Vec) -> None:
        """Line search: the full Newton step unless it raises ‖R‖₂ (and :meth:`_merit`); then halve.

        Semismooth Newton on contact and friction can cycle between active sets;
        halving the step while ‖R‖ does not decrease (Armijo, c = 1e-4) breaks
        the cycle.  Near the solution the full step is accepted, which keeps the
        local quadratic rate.  If no trial decreases ‖R‖ the full step is taken, or,
        when a component does not admit it (a film without fluid at a node: its
        Newton matrix is singular), the largest trial step every component admits.
        With ``line_search="admissible"`` a trial is accepted when every
        component's ``admissible()`` holds and R is finite; if none is, the
        smallest trial is taken.  The accepted trial's residual is cached, so SNES
        does not assemble it again.  With a :attr:`border` the step is bordered
        first and each trial moves its scalar unknown by the same fraction.
        """
        border = self.border
        if border is not None:
            border.correct(x, y)
            border.trial(1.0)
        if self.max_backtracks == 0:
            return
        b0 = self.snes.getFunction()[0]  # type: ignore[index]  # petsc4py stub: (Vec, ...)
        done = [v <= t.atol for v, (_, _, t, _) in zip(self._block_norms(b0), self._tolerances)]
        r0, r0_all = self._merit(b0, done), self.snes.getFunctionNorm()
        xt, bt = x.duplicate(), x.duplicate()
        alpha = 1.0
        largest_admissible = None    # the largest trial step the components admit
        for _ in range(self.max_backtracks + 1):
            if border is not None:
                border.trial(alpha)
            xt.waxpy(-alpha, y, x)
            self._cache = None
            self._residual(self.snes, xt, bt)
            self._cache = (xt.getArray(readonly=True).copy(), bt)
            if self._accept(cast(float, bt.norm()), r0_all, alpha) or (
                    any(done) and self._kept(bt, done)
                    and self._accept(self._merit(bt, done), r0, alpha)):
                if alpha != 1.0:
                    y.scale(alpha)
                xt.destroy()
                return
            if largest_admissible is None and all(c.admissible() for c in self.components):
                largest_admissible = alpha
            alpha *= 0.5
        if self.line_search == "admissible":  # the last (smallest) trial step
            y.scale(2 * alpha)
            if border is not None:
                border.trial(2 * alpha)
        else:  # Armijo found no decrease: the full step, or the largest admissible one
            if largest_admissible is None:
                # no trial is admitted: halve on, testing only the components (no assembly)
                for _ in range(40):
                    if self._admits(x, y, alpha, xt):
                        largest_admissible = alpha
                        break
                    alpha *= 0.5
            step = 1.0 if largest_admissible is None else largest_admissible
            if step != 1.0:
                y.scale(step)
            if border is not None:
                border.trial(step)
            self._cache = None
            bt.destroy()
        xt.destroy()

    def _admits(self, x: PETSc.Vec, y: PETSc.Vec, alpha: float, xt: PETSc.Vec) -> bool:
        """Whether every component admits the trial x − α y (the unknowns left there)."""
        xt.waxpy(-alpha, y, x)
        self.set_unknowns(xt)
        self.refresh()
        return all(c.admissible() for c in self.components)

    def _kept(self, b: PETSc.Vec, done: Sequence[bool]) -> bool:
        """Whether the blocks converged at the iterate (``done``) are still converged in ``b``."""
        return all(v <= t.atol for v, (_, _, t, _), d in
                   zip(self._block_norms(b), self._tolerances, done) if d)

    def _merit(self, b: PETSc.Vec, done: Sequence[bool]) -> float:
        """‖R‖₂ over the blocks not converged at the iterate (``done`` False), all ranks.

        A converged block sits at its round-off, which a full step stirs at
        random: in ‖R‖₂ over mixed units (a stiff body's nodal forces beside a
        film's fluxes) that noise can outweigh the blocks still converging and
        halve every step.  A trial that does not decrease ‖R‖₂ is therefore
        still accepted when it decreases this merit and keeps the converged
        blocks converged.
        """
        if all(done):
            return cast(float, b.norm())     # (NORM_2: a float)
        arr = b.getArray(readonly=True)
        sq = sum(float(np.dot(arr[sl], arr[sl]))
                 for (_, sl, _, _), d in zip(self._tolerances, done) if not d)
        return float(np.sqrt(b.comm.tompi4py().allreduce(sq, op=MPI.SUM)))

    def _accept(self, r: float, r0: float, alpha: float) -> bool:
        """Line-search test of a trial with residual 2-norm ``r`` (``r0`` at the iterate)."""
        ok = all(c.admissible() for c in self.components)
        if self.line_search == "admissible":
            return ok and np.isfinite(r)
        return ok and r < (1 - 1e-4 * alpha) * r0
