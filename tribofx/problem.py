"""One monolithic problem: the unknowns and residual blocks of bodies and interfaces.

A *component* (a :class:`tribofx.body.Body` or an interface of
:mod:`tribofx.interfaces`) declares

* ``unknowns()``: its ``dolfinx.fem.Function`` unknowns, in order;
* ``contributions()``: a list of ``(unknown, form)`` pairs, the residual terms it
  adds to the row of ``unknown`` (the form is linear in the test function of
  ``unknown``'s space; every term is built by :mod:`tribofx.forms`);
* ``bcs()``: Dirichlet conditions on any of its own or other unknowns, and
  ``bcs_by_unknown()``: the same as ``{unknown: [DirichletBC]}`` (which rows they fix);
* ``entity_maps()``: entity maps of its mixed-dimensional forms;
* ``refresh()``: data computed outside UFL (C++ kernel projections, traces),
  run before *every* residual and Jacobian evaluation, line-search trials
  included;
* ``tolerances()``: ``{unknown: BlockTolerance}``, the stopping test of its rows
  in physical units;
* ``state_fields()``: Functions and Constants that make up its state (unknowns,
  histories, positions) for :meth:`Problem.state` / :meth:`Problem.restore`;
* ``commit()``: accept a converged step (histories move on).

:class:`Problem` sums the contributions row by row, takes the exact tangent by
``ufl.derivative`` of each block, and solves with PETSc SNES through the public
DOLFINx 0.11 :class:`dolfinx.fem.petsc.NonlinearProblem`.  Every PETSc object has
the options prefix ``tribofx_<name>_``; the defaults (``newtonls``, the
backtracking of :meth:`Problem._backtrack`, the linear-solver strategy of
:mod:`tribofx.solvers`) are set only where the options database has no value,
so ``-tribofx_<name>_snes_monitor`` or ``-tribofx_<name>_pc_type`` on the
command line override them.

The stopping test per block in physical units and the backtracking line search
are :class:`tribofx.newton_control.NewtonControl`'s, which :class:`Problem` extends.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Mapping, Sequence
from typing import TYPE_CHECKING, Any, TypeAlias, cast

import dolfinx.fem.petsc as fem_petsc
import numpy as np
import numpy.typing as npt
import ufl
from dolfinx import fem
from mpi4py import MPI
from petsc4py import PETSc

from . import pattern, solvers
from .checkpoint import assign_fields, field_arrays
from .krylov_guard import reason_name
from .lifetimes import LIFETIMES, weak_callback
from .newton_control import NewtonControl
from .protocols import ComponentBase
from .reports import BlockTolerance, NewtonDivergence, NewtonReport, convergence_orders

if TYPE_CHECKING:
    from dolfinx import la
    from dolfinx.mesh import EntityMap

    from .bordered import Border
    from .newton_control import BlockRows
    from .protocols import Component
    from .solvers import DirectSolver, IterativeSolver, OptionValue

    class ProblemComponent(ComponentBase, Component):
        """A component as a Problem sees it: the hooks of ComponentBase, the Component protocol.

        (Every component derives ComponentBase and answers the protocol; a type
        checker has no intersection of the two, hence this class, for types only.)
        """

    #: a DOLFINx assembly function with its arguments: (function, args, keyword args)
    Assembly: TypeAlias = tuple[Callable[..., None], tuple[Any, ...], dict[str, Any]]

__all__ = [
    "BlockTolerance",
    "NewtonDivergence",
    "NewtonReport",
    "Problem",
    "convergence_orders",
    "options_name",
]


def options_name(base: str, variant: str = "") -> str:
    """Problem name of ``variant`` (e.g. "no-shear") of a case: ``base_no_shear``.

    The name is the options prefix ``tribofx_<name>_`` of the problem's SNES, KSP
    and PC; characters other than letters, digits and '_' become '_'.
    """
    name = f"{base}_{variant}" if variant else base
    return re.sub(r"[^A-Za-z0-9_]", "_", name)


def _block_layout(u: Sequence[fem.Function]) -> tuple[tuple[int, ...], tuple[int, ...]]:
    """Local offsets of each unknown's owned and ghost entries in a blocked vector.

    The layout :func:`dolfinx.la.petsc.create_vector` documents for the ``mpi``
    kind: ((0, n₀, n₀ + n₁, …), (N, N + g₀, …)), n the owned and g the ghost
    entries of each unknown, N = Σ n.  DOLFINx's blocked residual assembly takes it.
    """
    own = [f.function_space.dofmap.index_map.size_local * f.function_space.dofmap.index_map_bs
           for f in u]
    ghost = [f.function_space.dofmap.index_map.num_ghosts * f.function_space.dofmap.index_map_bs
             for f in u]
    owned = tuple(int(x) for x in np.cumsum([0, *own]))
    return owned, tuple(int(owned[-1] + x) for x in np.cumsum([0, *ghost]))


def _block(F: ufl.Form, u: fem.Function) -> ufl.Form | None:
    """Return the Jacobian block dF/du, or None where F does not contain u.

    Left unexpanded: DOLFINx expands the derivative when it compiles the form (on a
    JIT cache miss); expanding it here as well cost a second traversal of every
    block of the (large) residual forms at each Problem's creation.
    """
    if u not in F.coefficients():
        return None
    return ufl.derivative(F, u, ufl.TrialFunction(u.function_space))


def _unique[T](items: Iterable[T]) -> list[T]:
    out: list[T] = []
    for it in items:
        if not any(it is o for o in out):
            out.append(it)
    return out


class Problem(NewtonControl):
    """Monolithic Newton problem of ``components`` (bodies and interfaces).

    Args:
        components: bodies and interfaces (see the module docstring).
        unknowns: the subset of the components' unknowns to solve for (default:
            all, in component order); the others enter as data.  A staggered
            scheme builds one Problem per subset.
        name: options prefix ``tribofx_<name>_`` of the SNES, KSP and PC; a second
            problem of the same name in one process gets ``<name>2``, a third
            ``<name>3`` (the cases give each variant its own name,
            :func:`options_name`, so that a command-line option reaches the one meant).
        solver: linear-solver strategy (default: the run's, :func:`tribofx.solvers.choose`).
        max_it: maximum Newton iterations.
        max_backtracks: step halvings of the backtracking line search (0: full steps).
        petsc_options: further defaults under the prefix (the command line wins).
        tolerances: ``{unknown: BlockTolerance}`` overriding the components'.
        stall_window: stop (DIVERGED_DTOL) when the best residual has not halved
            over this many iterations, so that a controller cuts an over-long step
            instead of iterating to ``max_it``; None (default): never (a
            semismooth active-set search, e.g. JFO, may plateau and then converge).
        line_search: "armijo" (halve while ‖R‖₂ does not decrease) or "admissible"
            (halve only while a component's ``admissible()`` is False or R is not
            finite — for residuals whose 2-norm is a poor merit function, e.g. a
            film with thick flanks, where a step must only keep the film open).
    """

    _names: dict[str, int] = {}
    # components with add_residual/add_jacobian (see _create_snes)
    _assemblers: Sequence[ProblemComponent] = ()

    def __init__(self, components: Iterable[ComponentBase],
                 unknowns: Iterable[fem.Function] | None = None, name: str = "problem",
                 solver: DirectSolver | IterativeSolver | None = None, max_it: int = 30,
                 max_backtracks: int = 6, petsc_options: Mapping[str, OptionValue] | None = None,
                 tolerances: Mapping[fem.Function, BlockTolerance] | None = None,
                 line_search: str = "armijo", stall_window: int | None = None) -> None:
        if line_search not in ("armijo", "admissible"):
            raise ValueError(f"unknown line search {line_search!r}")
        self.line_search = line_search
        self.stall_window = stall_window
        # (ComponentBase is checked below; the Component protocol is the contract)
        self.components = cast("list[ProblemComponent]", list(components))
        for c in self.components:
            if not isinstance(c, ComponentBase):
                raise TypeError(f"{type(c).__name__} is not a component: derive "
                                "tribofx.protocols.ComponentBase (the optional hooks' defaults)")
        every = _unique([u for c in self.components for u in c.unknowns()])
        self.u = every if unknowns is None else list(unknowns)
        for ui in self.u:
            if not any(ui is e for e in every):
                raise ValueError(f"unknown {ui.name!r} is not owned by any component")
        rows: dict[int, ufl.Form | int] = {id(ui): 0 for ui in self.u}
        for c in self.components:
            for ui, form in c.contributions():
                if id(ui) in rows:
                    rows[id(ui)] = rows[id(ui)] + form
        for ui in self.u:
            if rows[id(ui)] == 0:
                raise ValueError(f"no residual contribution for unknown {ui.name!r}")
        self.residual_forms = [cast(ufl.Form, rows[id(ui)]) for ui in self.u]   # all nonzero
        count = Problem._names.get(name, 0)
        Problem._names[name] = count + 1
        self.name = name if count == 0 else f"{name}{count}"
        self.prefix = f"tribofx_{self.name}_"
        self.max_it, self.max_backtracks = int(max_it), int(max_backtracks)
        # DOLFINx sorts the conditions into blocks by space; those on unknowns that
        # are not solved for here are ignored
        self.bcs: list[fem.DirichletBC] = [bc for c in self.components for bc in c.bcs()]
        self._create_snes()
        self.solver = solver if solver is not None else solvers.choose(self)
        defaults = {"snes_type": "newtonls", "snes_linesearch_type": "basic",
                    "snes_max_it": self.max_it, "snes_max_fail": 1,
                    **self.solver.options(self), **(petsc_options or {}),
                    **solvers.run_options()}
        opts = PETSc.Options()
        for key, value in defaults.items():
            if not opts.hasName(self.prefix + key):
                opts[self.prefix + key] = value  # type: ignore[index]  # petsc4py stub: no __setitem__
        self.snes.setOptionsPrefix(self.prefix)
        self.snes.setFromOptions()
        self.solver.configure(self)
        # (petsc4py's stubs type the converged reasons as a class; they are its int values)
        self.snes.setConvergenceTest(weak_callback(self._converged))  # type: ignore[arg-type]
        # the backtracking of _backtrack (and a border's step) rides on the "basic"
        # line search; another type chosen on the command line (e.g. bt) replaces it
        if self.snes.getLineSearch().getType() == "basic":
            self.snes.setLineSearchPreCheck(weak_callback(self._backtrack))
        self._tolerances = self._collect_tolerances(tolerances or {})
        self._cache = None
        self._report = None
        self.report: NewtonReport | None = None
        # (s, R(u₀)) of solve_by_homotopy, None outside it
        self._homotopy: tuple[float, PETSc.Vec] | None = None

    def _create_snes(self) -> None:
        """SNES of the blocked UFL system (public NonlinearProblem), residual wrapped."""
        J = [[_block(Fi, uj) for uj in self.u] for Fi in self.residual_forms]
        # (DOLFINx's annotation omits the None of a zero block, which it takes)
        nlp = fem_petsc.NonlinearProblem(
            self.residual_forms, self.u, J=J, bcs=self.bcs, kind="mpi",  # type: ignore[arg-type]
            petsc_options_prefix=self.prefix, entity_maps=self._emaps())
        self.snes = nlp.solver
        self._x, self._A = nlp.x, nlp.A
        self._nlp_matrix = nlp.A
        comm = self.snes.comm.tompi4py()
        if comm.size > 1:
            LIFETIMES.release(comm)
        self._nlp = LIFETIMES.keep(self, nlp, comm)
        # wrap the residual callback: refresh the components' data at every iterate, then
        # DOLFINx's public blocked assembly with the problem's compiled forms
        self._assemble_residual: Assembly = (
            fem_petsc.assemble_residual,
            (nlp.u, nlp.F, nlp.J, self.bcs, _block_layout(self.u)), {})
        self.snes.setFunction(weak_callback(self._residual), nlp.b)
        # components that add assembled terms outside UFL (the two-body contact kernel)
        self._assemblers = [c for c in self.components if c.assembles]
        self._global: dict[int, tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]] = {}
        if self._assemblers:
            A, P = nlp.A, nlp.P_mat
            self._assemble_jacobian: Assembly = (fem_petsc.assemble_jacobian, (), {
                "u": nlp.u, "jacobian": nlp.J, "preconditioner": nlp.preconditioner,
                "bcs": self.bcs})
            # their couplings (slave-master pairs) may change: the pattern grows as needed
            # (petsc4py's stub types the option as its enumeration class; it is an int)
            A.setOption(PETSc.Mat.Option.NEW_NONZERO_ALLOCATION_ERR, False)  # type: ignore[arg-type]
            self._jacobian_cb = weak_callback(self._jacobian)
            self.snes.setJacobian(self._jacobian_cb, A, P)

    def owned_size(self, ui: fem.Function) -> int:
        """Return the number of rows of ``ui`` owned by this rank."""
        V = ui.function_space
        return V.dofmap.index_map.size_local * V.dofmap.index_map_bs

    def block_start(self, k: int) -> int:
        """Global row of the first owned dof of unknown ``k`` on this rank."""
        return self._x.getOwnershipRange()[0] + sum(
            self.owned_size(uj) for uj in self.u[:k])

    @property
    def block_tolerances(self) -> list[BlockRows]:
        """Per unknown: (name, slice of its owned rows, BlockTolerance, row weights or None)."""
        return list(self._tolerances)

    def block_slice(self, ui: fem.Function) -> slice:
        """Slice of the owned rows of unknown ``ui`` in this rank's part of the block vector."""
        k = next(i for i, uj in enumerate(self.u) if uj is ui)
        return self._tolerances[k][1]

    def record_linear_fallback(self, event: dict[str, Any]) -> None:
        """Record a linear solve's LU fallback (:mod:`tribofx.krylov_guard`) in the report."""
        if self._report is not None:
            self._report.linear_fallbacks.append(event)

    def _owned(self, vec: la.Vector, ui: fem.Function) -> npt.NDArray[np.float64]:
        """Owned part of an assembled, reverse-scattered DOLFINx vector of ``ui``'s space."""
        return vec.array[:self.owned_size(ui)]

    def _emaps(self) -> list[EntityMap] | None:
        return _unique([m for c in self.components for m in c.entity_maps()]) or None

    @property
    def entity_maps(self) -> list[EntityMap]:
        """Entity maps of the components' mixed-dimensional forms (a list)."""
        return self._emaps() or []

    @property
    def assembles_outside_ufl(self) -> bool:
        """Whether a component adds terms assembled outside UFL (the two-body kernels)."""
        return bool(self._assemblers)

    @property
    def num_dofs(self) -> int:
        """Global number of unknowns of the block system."""
        return self._x.getSize()

    @property
    def A(self) -> PETSc.Mat:
        """The PETSc Jacobian matrix."""
        return self._A

    # -- callbacks -----------------------------------------------------------
    def refresh(self) -> None:
        """Run every component's ``refresh`` at the current values of the unknowns."""
        for c in self.components:
            c.refresh()

    def _residual(self, snes: PETSc.SNES, x: PETSc.Vec, b: PETSc.Vec) -> None:
        key = x.getArray(readonly=True)
        if self._cache is not None:
            same = self._cache[0].shape == key.shape and np.array_equal(self._cache[0], key)
            if x.comm.tompi4py().allreduce(same, op=MPI.LAND):
                self._cache[1].copy(b)
                return
        self._evaluate(snes, x, b)

    def _jacobian(self, snes: PETSc.SNES, x: PETSc.Vec, A: PETSc.Mat, P: PETSc.Mat) -> None:
        """Jacobian at ``x``: blocked UFL assembly, then the components' assembled terms."""
        fn, args, kargs = self._assemble_jacobian
        fn(snes, x, A, P, *args, **kargs)
        for c in self._assemblers:
            c.add_jacobian(A, self)
        A.assemblyBegin()
        A.assemblyEnd()

    def _grow_pattern(self) -> None:
        """Preallocate the couplings the assemblers may add in this solve (:mod:`.pattern`)."""
        blocks = [b for b in (c.couplings(self) for c in self._assemblers) if b is not None]
        if not blocks:
            return
        A = self._A
        if not A.isAssembled():      # the UFL pattern only (it is read, not used)
            fn, args, kargs = self._assemble_jacobian
            fn(self.snes, self._x, A, A, *args, **kargs)
        for rows, cols in blocks:
            M = pattern.grow(A, rows, cols)
            if M is not None:
                if A is not self._nlp_matrix:
                    A.destroy()
                A = M
        if A is not self._A:
            self._A = A
            self.snes.setJacobian(self._jacobian_cb, A, A)

    def global_rows(self, ui: fem.Function) -> tuple[npt.NDArray[np.int64], npt.NDArray[np.int64]]:
        """Global rows of the block system of every local dof of ``ui`` (owned, then ghosts).

        Blocked spaces are unrolled (dof k of block j at ``bs·j + k``); rows of
        Dirichlet dofs are −1, so that PETSc ignores values added to them (their
        columns are kept: the correction of a prescribed dof is known from its
        own row, and coupling it in is the exact Newton system).  Returns
        (rows of the unknowns, -1 for ``ui`` not solved for here; columns).
        """
        key = id(ui)
        if key not in self._global:
            k = next((i for i, uj in enumerate(self.u) if uj is ui), None)
            V = ui.function_space
            n = len(ui.x.array)
            if k is None:
                cols = np.full(n, -1, dtype=np.int64)
                self._global[key] = (cols, cols)
                return self._global[key]
            start = self.block_start(k)
            f = fem.Function(V)
            n_own = self.owned_size(ui)
            f.x.array[:n_own] = start + np.arange(n_own)
            f.x.scatter_forward()
            cols = np.rint(f.x.array).astype(np.int64)
            rows = cols.copy()
            for c in self.components:
                for bc in next((b for v, b in c.bcs_by_unknown().items() if v is ui), []):
                    rows[bc.dof_indices()[0]] = -1
            self._global[key] = (rows, cols)
        return self._global[key]

    def set_unknowns(self, x: PETSc.Vec) -> None:
        """Copy the block vector ``x`` into the unknowns (ghosts updated)."""
        # (petsc4py's stubs: the modes are ints; DOLFINx's: assign's (Vec, Functions) overload)
        x.ghostUpdate(addv=PETSc.InsertMode.INSERT,  # type: ignore[arg-type]
                      mode=PETSc.ScatterMode.FORWARD)  # type: ignore[arg-type]
        fem_petsc.assign(x, self.u)  # type: ignore[arg-type]

    def _get_unknowns(self, x: PETSc.Vec) -> None:
        """Copy the unknowns into the block vector ``x``."""
        fem_petsc.assign(self.u, x)

    def _evaluate(self, snes: PETSc.SNES, x: PETSc.Vec, b: PETSc.Vec) -> None:
        """Residual at ``x`` into ``b``: unknowns ← x, refresh, blocked UFL assembly."""
        self.set_unknowns(x)
        self.refresh()
        fn, args, kargs = self._assemble_residual
        fn(snes, x, b, *args, **kargs)
        if self._assemblers:
            for c in self._assemblers:
                c.add_residual(b, self)
            b.assemblyBegin()
            b.assemblyEnd()
        self._shift_by_homotopy(b)

    def _shift_by_homotopy(self, b: PETSc.Vec) -> None:
        """Inside :meth:`solve_by_homotopy`: b ← b − (1 − s) R(u₀) (nothing at s = 1)."""
        if self._homotopy is not None and self._homotopy[0] != 1.0:
            s, r0 = self._homotopy
            b.axpy(-(1.0 - s), r0)

    # -- solve ---------------------------------------------------------------
    def solve(self, verbose: bool = False, border: Border | None = None) -> NewtonReport:
        """Newton from the current values of the unknowns; returns a :class:`NewtonReport`.

        Raises :class:`NewtonDivergence` (the unknowns back at their entry
        values, the report of the failed solve as its ``report``) when SNES
        does not converge.  ``border``: a :class:`tribofx.bordered.Border`, a
        scalar unknown and its equation solved with this Newton iteration (a
        response held by :class:`tribofx.hold.Hold`).
        """
        if self.snes.comm.size > 1:
            LIFETIMES.release(self.snes.comm.tompi4py())
        backup = [ui.x.array.copy() for ui in self.u]
        self._report = NewtonReport(names=[n for n, _, _, _ in self._tolerances])
        self._verbose = verbose
        self._cache = None
        self.border = border
        if border is not None:
            border.history = []
        failure = None
        self._reset_iterates()
        try:
            self._get_unknowns(self._x)
            self._grow_pattern()
            self.solver.prepare(self)
            self.snes.solve(None, self._x)
            self.set_unknowns(self._x)
        except PETSc.Error as err:  # e.g. a MUMPS factorisation failure: cut the step
            code = err.ierr  # type: ignore[attr-defined]  # petsc4py's stubs omit it
            failure = f"PETSc error {code}{self._linear_state()}"
        finally:
            if self._cache is not None:
                self._cache[1].destroy()
            self._cache = None
            self.border = None
        reason = -1 if failure else cast(int, self.snes.getConvergedReason())
        if reason == PETSc.SNES.ConvergedReason.DIVERGED_LINEAR_SOLVE:
            failure = f"DIVERGED_LINEAR_SOLVE{self._linear_state()}"
        report = self._report
        report.reason = int(reason)
        report.iterations = self.snes.getIterationNumber()
        self.report = report
        if reason <= 0:
            for ui, a in zip(self.u, backup):
                ui.x.array[:] = a
            self.refresh()
            why = failure or reason_name(reason, PETSc.SNES.ConvergedReason)
            raise NewtonDivergence(
                f"Newton did not converge ({why}) in "
                f"{report.iterations} iterations (residual history "
                f"{['%.2e' % v for v in report.residuals]})", report=report)
        for ui in self.u:
            ui.x.scatter_forward()
        self.refresh()
        return report

    def solve_by_homotopy(self, verbose: bool = False, min_step: float = 2.0**-8,
                          direct: bool = True) -> NewtonReport:
        """Newton from the current state; if it fails, the Newton homotopy with step cuts.

        The first trial is :meth:`solve` itself (a solve that converges is
        unchanged).  If it fails, the state at entry u₀ is the solution at s = 0 of

            H(u, s) = R(u) − (1 − s) R(u₀) = 0,

        (on a Dirichlet row R = x − g: the prescribed value moves from x₀ to g),
        and s is marched to 1: a converged step doubles the increment (up to
        the rest), a failed one restores the last converged s and halves it.
        The tangent of H is that of R, so every step is an exact Newton solve;
        no intermediate state is committed (histories do not move).  This is
        the cut-and-retry of a solve that has no physical parameter to cut: a
        first coupled solve from a decoupled start, a step's solve of a
        prescribed history.  Raises :class:`NewtonDivergence` (state at entry)
        when the increment falls below ``min_step``.  Returns the report of the
        last solve, with ``iterations`` the total over the trials.  ``direct``
        False: march s from the start, without the first trial.
        """
        entry = self.state()
        first, spent = "started at s = 0", 0
        if direct:
            try:
                return self.solve(verbose=verbose)
            except NewtonDivergence as err:
                first = str(err)
            spent = cast(NewtonReport, self.report).iterations   # solve() has set it
        x0 = self._x
        self._get_unknowns(x0)
        r0 = x0.duplicate()
        self._cache = None
        self._evaluate(self.snes, x0, r0)
        s, ds, last = 0.0, 0.5, None
        try:
            while s < 1.0:
                trial = min(1.0, s + ds)
                saved = self.state()
                self._homotopy = (trial, r0)
                try:
                    last = self.solve(verbose=verbose)
                except NewtonDivergence:
                    spent += cast(NewtonReport, self.report).iterations
                    self.restore(saved)
                    ds *= 0.5
                    if ds < min_step:
                        self.restore(entry)
                        raise NewtonDivergence(
                            f"{first}; the Newton homotopy stalled at s = {s:.4g} "
                            f"(increment {ds:.1e})") from None
                    continue
                spent += last.iterations
                s = trial
                ds = min(2 * ds, 1.0 - s) if s < 1.0 else ds
        finally:
            self._homotopy = None
            self._cache = None
            r0.destroy()
        assert last is not None      # s reached 1 through a converged solve
        last.iterations = spent
        self.report = last
        return last

    def _linear_state(self) -> str:
        """Describe the last linear solve's failure for an error message ('' if it converged).

        ``: KSP <type> <reason> after <n> iterations``, and whether its LU
        fallback (:mod:`tribofx.krylov_guard`) failed too.
        """
        ksp = self.snes.getKSP()
        reason = cast(int, ksp.getConvergedReason())
        events = self._report.linear_fallbacks if self._report is not None else []
        failed = [e for e in events if e["direct"] == "failed"]
        if failed:
            e = failed[-1]
            return (f": KSP {e['krylov']} {e['reason']} after {e['iterations']} iterations, "
                    f"LU fallback failed")
        if reason >= 0:
            return ""
        its = ksp.getIterationNumber()
        return f": KSP {ksp.getType()} {reason_name(reason)} after {its} iterations"

    def _reset_iterates(self) -> None:
        """Components with a Newton-iterate history start from their committed one."""
        for c in self.components:
            c.reset_iterate()

    def assemble(self) -> tuple[PETSc.Vec, PETSc.Mat]:
        """Residual ``b`` and Jacobian ``A`` at the current unknowns (Taylor tests)."""
        x = self._x
        self._get_unknowns(x)
        self._cache = None
        b = self.snes.getFunction()[0]  # type: ignore[index]  # petsc4py stub: it is (Vec, ...)
        self._residual(self.snes, x, b)
        self.snes.computeJacobian(x, self._A)
        return b, self._A

    def residual_at(self, x: PETSc.Vec) -> PETSc.Vec:
        """Residual at the block vector ``x`` (a copy; the unknowns end at ``x``)."""
        b = x.duplicate()
        self._cache = None
        self._residual(self.snes, x, b)
        return b

    # -- state ---------------------------------------------------------------
    def state_fields(self) -> list[fem.Function | fem.Constant]:
        """Functions and Constants making up the state of every component."""
        return _unique([f for c in self.components for f in c.state_fields()])

    def state(self) -> list:
        """Copy of the full state (unknowns, histories, positions, parameters)."""
        return field_arrays(self.state_fields())

    def restore(self, state: list) -> None:
        """Restore a state from :meth:`state` and refresh the kernel data."""
        assign_fields(self.state_fields(), state)
        self._reset_iterates()
        self.refresh()

    def commit(self) -> None:
        """Accept the converged step in every component."""
        self.refresh()
        for c in self.components:
            c.commit()
