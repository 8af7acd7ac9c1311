"""Linear-solver strategies of a :class:`tribofx.problem.Problem`.

A strategy gives the PETSc options of the Newton system's KSP/PC (set under the
problem's prefix unless the command line sets them) and may configure the KSP
after SNES is set up (fieldsplit index sets, near-nullspaces).

* :class:`DirectSolver` — MUMPS LU.  PETSc redoes only the numeric factorisation
  while the matrix keeps its nonzero pattern (its ``nonzerostate``), so the
  symbolic analysis is reused across Newton iterations and load/time steps; a
  pattern that grows (new contact couplings) triggers one new analysis.  Block
  low-rank compression (MUMPS ICNTL(35), dropping tolerance CNTL(7)) is an option.
* :class:`LaggedSolver` — GMRES preconditioned by the MUMPS LU (block low-rank,
  dropping 1e-5, with BLR-compressed contribution blocks) of an earlier Newton
  matrix, refactorised when a solve needs more than 30 GMRES iterations: the
  Newton iteration stays exact (GMRES to 1e-10), the factorisations drop from
  one per Newton iteration to a few per run.
* :class:`IterativeSolver` — GMRES preconditioned by a PETSc fieldsplit.  The
  *bulk* field (vector unknowns on a mesh of full dimension: displacements,
  shape mappings) is solved by one V-cycle of algebraic multigrid (GAMG with the
  rigid-body near-nullspace of each bulk unknown); the
  *interface* field (everything else: contact multipliers, Reynolds pressure,
  void fraction, load and shape multipliers) enters by the Schur complement
  S = A₁₁ − A₁₀ A₀₀⁻¹ A₀₁, preconditioned by LU of its "selfp" approximation
  A₁₁ − A₁₀ diag(A₀₀)⁻¹ A₀₁, in the upper-triangular factorisation (one
  V-cycle per GMRES iteration).  The saddle-point rows of an active contact node
  (zero diagonal in A₁₁) are regular in S, so the split holds through
  active-set changes.
* ``auto`` — for 3D problems from :data:`AUTO_THRESHOLD` unknowns: iterative on
  tetrahedra, lagged on hexahedral tensor grids (whose graded cells of aspect
  ratio up to ~24 make the AMG iteration counts double per refinement); direct
  otherwise (2D, where LU fill is mild, and small problems).  Measured by
  ``benchmarks/bench_solvers.py`` (one run, serial, iterative against direct, the
  fieldsplit with the ``full`` Schur factorisation; the ``upper`` one used here takes
  22–31 % less time per Newton step): frictional Hertz ball on tetrahedra,
  cost per Newton iteration iterative/direct 1.86 (5.7k unknowns), 1.34 (24.5k),
  0.86 (142k; memory 731 MB against 3.1 GB), 21–26 GMRES iterations per Newton
  step at every size; the §5.3 groove on hexahedra 2.0 (14k), 2.1 (50k; 59 → 110
  GMRES iterations per Newton step).

Memory per rank on 2 ranks against one (both paths, measured by phase):
``docs/solvers.md``, "Memory per rank".

A run chooses its strategy and extra PETSc options with :func:`run_settings`
(``tribofx run CASE --set solver=iterative --petsc-option KEY=VALUE``).  A key
without the ``tribofx_`` prefix applies under every problem's prefix; a key
with it is set as given.
"""

from __future__ import annotations

from collections.abc import Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, TypeAlias, cast

import numpy as np
import numpy.typing as npt
from dolfinx.mesh import CellType
from mpi4py import MPI
from petsc4py import PETSc

from .krylov_guard import KrylovGuard
from .near_nullspace import near_nullspace
from .snes_lag import lag_preconditioner

if TYPE_CHECKING:
    from .problem import Problem

    #: the value of a PETSc option (None: a flag without value)
    OptionValue: TypeAlias = str | int | float | None
    #: PETSc options {key: value} without the problem's prefix
    OptionsDict: TypeAlias = dict[str, OptionValue]

__all__ = [
    "AUTO_THRESHOLD",
    "STRATEGIES",
    "DirectSolver",
    "IterativeSolver",
    "LaggedSolver",
    "PRODUCT_CLEAR",
    "WORKSPACE_ERRORS",
    "SolverRun",
    "choose",
    "current_run",
    "grow_workspace",
    "run_options",
    "run_settings",
]

#: global PETSc option set by :class:`IterativeSolver`: matrix products free their
#: intermediate data after the numeric product (``MatProductClear``)
PRODUCT_CLEAR = "mat_product_clear"
#: unknowns from which ``auto`` leaves LU on 3D problems (iterative on tetrahedra, else lagged)
AUTO_THRESHOLD = 50_000
STRATEGIES = ("direct", "lagged", "iterative", "auto")

@dataclass
class SolverRun:
    """What one run asks of its linear solvers and what they did.

    ``strategy`` ("direct", "lagged", "iterative" or "auto") and ``options`` (extra
    PETSc options without prefix) apply to the problems built inside
    :func:`run_settings`; ``used`` ``{problem name: strategy description}`` and
    ``fallbacks`` ``{problem name: [event, ...]}`` (Krylov solves that failed and
    were solved by LU, :class:`tribofx.krylov_guard.KrylovGuard`; shared lists)
    record them.
    """

    strategy: str = "auto"
    options: dict = field(default_factory=dict)
    used: dict = field(default_factory=dict)
    fallbacks: dict = field(default_factory=dict)

    def failed_krylov(self) -> dict:
        """Return ``{problem name: [event, ...]}`` of the problems with a fallback."""
        return {k: list(v) for k, v in self.fallbacks.items() if v}


# the runs in progress, innermost last; outside every run, a default one
_runs = [SolverRun()]


def current_run() -> SolverRun:
    """Return the innermost run in progress (outside :func:`run_settings`: the default)."""
    return _runs[-1]


@contextmanager
def run_settings(strategy: str = "auto",
                 petsc_options: Mapping[str, OptionValue] | None = None) -> Iterator[SolverRun]:
    """Strategy and extra PETSc options of the problems built inside the block.

    Yields the block's :class:`SolverRun`, which records the linear solver of
    every problem built inside it and their Krylov fallbacks.

    Args:
        strategy: "direct", "iterative" or "auto".
        petsc_options: {key: value}; keys with the ``tribofx_`` prefix are put
            into the options database as given, others under every problem's
            prefix (as defaults the command line still overrides).
    """
    if strategy not in STRATEGIES:
        raise ValueError(f"unknown solver strategy {strategy!r}")
    opts = PETSc.Options()
    options = dict(petsc_options or {})
    verbatim = {k: v for k, v in options.items() if k.startswith("tribofx_")}
    run = SolverRun(strategy, {k: v for k, v in options.items() if k not in verbatim})
    for k, v in verbatim.items():
        opts[k] = v  # type: ignore[index]  # petsc4py stub: no __setitem__
    _runs.append(run)
    try:
        yield run
    finally:
        _runs.remove(run)
        for k in verbatim:
            opts.delValue(k)


def run_options() -> OptionsDict:
    """Extra PETSc options of the current run (without prefix)."""
    return dict(current_run().options)


def choose(problem: Problem) -> DirectSolver | IterativeSolver:
    """Return the run's strategy for ``problem`` (``auto``: by dimension and size)."""
    run = current_run()
    strategy = run.strategy
    if strategy == "auto":
        bulk = bulk_fields(problem)[0]
        tets = bool(bulk) and all(
            problem.u[k].function_space.mesh.topology.cell_type == CellType.tetrahedron
            for k in bulk)
        solid = bool(bulk) and problem.u[bulk[0]].function_space.mesh.topology.dim == 3
        strategy = ("direct" if problem.num_dofs < AUTO_THRESHOLD or not solid
                    else "iterative" if tets else "lagged")
    if strategy == "iterative" and not bulk_fields(problem)[0]:
        solver = DirectSolver()       # nothing for AMG (a film or cross-section alone)
        run.used[problem.name] = solver.describe(problem) + "; iterative asked, no bulk field"
        return solver
    solver = {"iterative": IterativeSolver, "lagged": LaggedSolver}.get(strategy, DirectSolver)()
    run.used[problem.name] = solver.describe(problem)
    if hasattr(solver, "guard"):
        run.fallbacks[problem.name] = solver.guard.fallbacks
    return solver


def bulk_fields(problem: Problem) -> tuple[list[int], list[int]]:
    """Return the indices of the bulk unknowns, and of the rest.

    Bulk: vector fields on a distributed mesh of the problem's full dimension
    (displacements, shape mappings of a body); a field on a facet submesh, a
    scalar, or a field on a smaller replicated mesh (a cross-section) is not.
    """
    gdim = max(ui.function_space.mesh.geometry.dim for ui in problem.u)
    size = max(ui.function_space.mesh.comm.size for ui in problem.u)
    bulk: list[int]
    rest: list[int]
    bulk, rest = [], []
    for k, ui in enumerate(problem.u):
        V = ui.function_space
        msh = V.mesh
        full = msh.topology.dim == msh.geometry.dim == gdim and msh.comm.size == size
        vector = V.dofmap.index_map_bs == gdim and len(V.value_shape) == 1
        (bulk if full and vector else rest).append(k)
    return bulk, rest


class DirectSolver:
    """Sparse LU by MUMPS (``preonly`` + ``lu``), the default for small problems.

    Args:
        package: factorisation package (``mumps``).
        blr: MUMPS block low-rank factorisation with dropping tolerance ``blr``
            (None: full-rank), the contribution blocks compressed too
            (ICNTL(37) = 1: less memory, ``docs/solvers.md``).  A
            compressed LU is inexact: Newton then converges linearly at a rate
            ~``blr`` · cond; 1e-10 keeps it quadratic to the stopping
            tolerances here.
    """

    name = "direct"

    def __init__(self, package: str = "mumps", blr: float | None = None) -> None:
        self.package = package
        self.blr = blr

    def options(self, problem: Problem | None = None) -> OptionsDict:
        """PETSc options of the KSP and PC (without the problem's prefix)."""
        out: OptionsDict = {"ksp_type": "preonly", "pc_type": "lu",
                            "pc_factor_mat_solver_type": self.package}
        if self.blr is not None:   # BLR factors, and BLR-compressed contribution blocks
            out.update({"mat_mumps_icntl_35": 1, "mat_mumps_cntl_7": self.blr,
                        "mat_mumps_icntl_37": 1})
        return out

    def configure(self, problem: Problem) -> None:
        """Nothing beyond the options for a direct solve."""

    def prepare(self, problem: Problem) -> None:
        """Grow MUMPS's workspace if the last factorisation ran out of it."""
        grow_workspace(problem.snes.getKSP().getPC())

    def describe(self, problem: Problem) -> str:
        """One line naming the strategy (recorded in ``summary.json``)."""
        blr = f", BLR {self.blr:g}" if self.blr is not None else ""
        return f"direct ({self.package} LU{blr}, {problem.num_dofs} unknowns)"


#: MUMPS INFOG(1) of a factorisation that ran out of its estimated workspace
WORKSPACE_ERRORS = (-8, -9, -11, -12, -14, -15, -17, -20)


def grow_workspace(pc: PETSc.PC, cap: int = 10_000) -> int | None:
    """Double MUMPS's extra workspace ICNTL(14) after a factorisation that ran out of it.

    MUMPS sizes its workspace from the analysis, plus ICNTL(14) per cent (20 by
    default) for the pivots delayed at factorisation; a matrix needing more
    delayed pivots (near-singular diagonal blocks, e.g. the small-strain ball at
    40 N) fails with INFOG(1) = −9, and PETSc then skips every later numeric
    factorisation of that factor.  Called before each solve: when the last
    factorisation of ``pc`` failed so (INFOG(1) in :data:`WORKSPACE_ERRORS`, the
    same on all ranks), ICNTL(14) is doubled (up to ``cap``) in the options under
    the PC's prefix and the PC is reset, so that the next solve analyses and
    factorises anew.  Any other failed MUMPS factorisation resets the PC too.  Returns
    the (new) ICNTL(14), or None (no failed MUMPS factor).
    """
    # a factor is queried only after a failed set-up (before the first factorisation
    # MUMPS's data is not allocated); the failure is collective, the reason maybe not
    # (petsc4py's stub types the reason as its enumeration class; it is an int)
    if pc.getComm().tompi4py().allreduce(int(pc.getFailedReason()),  # type: ignore[call-overload]
                                         op=MPI.MAX) == 0:
        return None
    try:
        F = pc.getFactorMatrix()
        if F.getType() != "mumps" or F.getMumpsInfog(1) >= 0:
            return None
        info, percent = F.getMumpsInfog(1), F.getMumpsIcntl(14)
    except PETSc.Error:   # not a factorisation PC
        return None
    if info in WORKSPACE_ERRORS:
        percent = min(cap, 2 * max(percent, 10))
        # (petsc4py's stub has no Options.__setitem__)
        PETSc.Options()[(pc.getOptionsPrefix() or "") + "mat_mumps_icntl_14"] = percent  # type: ignore[index]
    # PETSc skips every numeric factorisation after a failed one (it takes the
    # failure for the analysis's), whatever the failure (workspace, a singular or
    # non-finite matrix of a wild Newton trial): reset the PC, so that the next
    # set-up analyses and factorises anew and reads ICNTL(14) from the options (the
    # next Newton iteration sets the operators again)
    pc.reset()
    return percent


class LaggedSolver(DirectSolver):
    """GMRES preconditioned by the MUMPS LU of an earlier Newton matrix.

    The Newton systems are solved to GMRES relative residual ``rtol`` (right
    preconditioning: the true residual), so the Newton iteration is the exact one
    and keeps its quadratic rate; only the preconditioner lags.  The matrix is
    factorised at the first Newton iteration of a run, and again at the next
    iteration after a linear solve that needed more than ``refactor_its`` GMRES
    iterations (an active-set change, a large shape update), a failed solve or
    factorisation, or on a new matrix; otherwise the factor is kept across Newton
    iterations and steps.  A numeric LU costs ~N² on a 3D mesh and its two
    triangular solves ~N^(4/3), so the trade grows with N (measurements:
    ``docs/solvers.md``).

    The factor is a MUMPS block low-rank (BLR) LU with dropping tolerance ``blr``
    (default 1e-5): as a preconditioner it need not be exact, and the compressed
    factorisation and its triangular solves are cheaper; GMRES still solves to
    ``rtol``.  Compressing the contribution blocks as well cuts the peak memory
    (the §5.3 groove at 230k: by 17 % serially, 26 % on 2 ranks) at no cost in
    time.  Measured on 2 ranks (the §5.3 groove, initial contact and one
    implicit step, 14 Newton iterations each): 50k unknowns 51 s against 60–63 s
    full-rank; to T at 230k: ``docs/solvers.md``.

    Args:
        blr: BLR dropping tolerance of the factor (None: full-rank LU).
        refactor_its: GMRES iterations of one solve above which the next Newton
            iteration refactorises.
        rtol, restart, max_it: GMRES relative tolerance, restart length, iteration cap.
    """

    name = "lagged"
    _lag: int       # the preconditioner lag after the last Newton iteration (set in configure)
    _seen: int      # Krylov fallbacks seen by the monitor (set in configure)

    def __init__(self, package: str = "mumps", blr: float | None = 1e-5, refactor_its: int = 30,
                 rtol: float = 1e-10, restart: int = 200, max_it: int = 1000) -> None:
        super().__init__(package, blr)
        self.refactor_its, self.rtol, self.restart, self.max_it = (refactor_its, rtol,
                                                                   restart, max_it)
        self.factorisations = 0
        self._pattern: PETSc.Mat | None = None
        self.guard = KrylovGuard(package=package)

    def options(self, problem: Problem | None = None) -> OptionsDict:
        """PETSc options of the KSP and PC (without the problem's prefix)."""
        out = super().options(problem)
        out.update({"ksp_type": "gmres", "ksp_gmres_restart": self.restart,
                    "ksp_pc_side": "right", "ksp_rtol": self.rtol, "ksp_atol": 0.0,
                    "ksp_max_it": self.max_it, "ksp_gmres_modifiedgramschmidt": None,
                    # the lag (set in configure) holds across Newton solves
                    "snes_lag_preconditioner_persists": True})
        return out

    def configure(self, problem: Problem) -> None:
        """Keep the factor across Newton solves; a monitor decides when to refactorise."""
        snes = problem.snes
        lag_preconditioner(snes, -2)       # factorise at the next Jacobian, then keep it
        self.guard.install(problem)

        def monitor(snes: PETSc.SNES, it: int, fnorm: float) -> None:
            # SNES turns a lag of -2 into -1 when it factorises at its next Jacobian
            if self._lag == -2 and lag_preconditioner(snes) == -1:
                self.factorisations += 1
            fell_back = len(self.guard.fallbacks) > self._seen
            self._seen = len(self.guard.fallbacks)
            if it > 0 and (fell_back or snes.getKSP().getIterationNumber() > self.refactor_its):
                lag_preconditioner(snes, -2)
            self._lag = lag_preconditioner(snes)

        self._seen = 0

        self._lag = -2
        snes.setMonitor(monitor)

    def prepare(self, problem: Problem) -> None:
        """Refactorise after a failed solve or factorisation, or on a new matrix."""
        snes = problem.snes
        ksp = snes.getKSP()
        if (grow_workspace(ksp.getPC()) is not None or problem.A is not self._pattern
                or cast(int, ksp.getConvergedReason()) < 0):
            self._pattern = problem.A
            lag_preconditioner(snes, -2)
        self._lag = lag_preconditioner(snes)

    def describe(self, problem: Problem) -> str:
        """One line naming the strategy (recorded in ``summary.json``)."""
        blr = f", BLR {self.blr:g}" if self.blr is not None else ""
        return (f"lagged (GMRES rtol {self.rtol:g}, {self.package} LU{blr} of an earlier "
                f"matrix, refactorised after {self.refactor_its} GMRES iterations; "
                f"{problem.num_dofs} unknowns)")


class IterativeSolver:
    """GMRES with a bulk-AMG / interface-Schur fieldsplit (see the module docstring).

    The AMG is GAMG (smoothed aggregation with the rigid-body near-nullspace; the
    PETSc of the DOLFINx wheel has no hypre).

    Args:
        rtol: relative tolerance of GMRES (the Newton corrections are exact to it).
        restart: GMRES restart length.
    """

    name = "iterative"

    amg = "gamg"

    def __init__(self, rtol: float = 1e-10, restart: int = 300, max_it: int = 3000) -> None:
        self.rtol, self.restart, self.max_it = rtol, restart, max_it
        # (bulk IS, interface IS, near-nullspace); the index sets None without an interface
        self._split: tuple[PETSc.IS | None, PETSc.IS | None, PETSc.NullSpace] | None = None
        self.guard = KrylovGuard(switch_after=2)

    def _amg_options(self, pre: str) -> OptionsDict:
        # Chebyshev on SOR sweeps: on the graded tensor grid of the groove (cell aspect
        # ratios to ~24) it takes the GAMG-CG iterations of the elastic block from 118
        # (Jacobi) to 37; on a uniform cube 18 -> 13 (benchmarks/bench_solvers.py notes)
        return {f"{pre}pc_type": "gamg", f"{pre}pc_gamg_type": "agg",
                f"{pre}pc_gamg_threshold": 0.01,
                f"{pre}mg_levels_ksp_type": "chebyshev",
                f"{pre}mg_levels_pc_type": "sor",
                f"{pre}mg_levels_ksp_max_it": 2}

    def options(self, problem: Problem | None = None) -> OptionsDict:
        """PETSc options of the KSP and PC (without the problem's prefix).

        With ``problem`` and no interface field: AMG on the whole matrix.
        """
        if problem is not None and not bulk_fields(problem)[1]:
            return self.single_field_options()
        # right preconditioning: rtol bounds the true residual of the Newton system
        out: OptionsDict = {"ksp_type": "gmres", "ksp_gmres_restart": self.restart,
                            "ksp_pc_side": "right", "ksp_rtol": self.rtol, "ksp_atol": 0.0,
                            "ksp_max_it": self.max_it, "ksp_gmres_modifiedgramschmidt": None}
        out.update({"pc_type": "fieldsplit", "pc_fieldsplit_type": "schur",
                    # upper: S solve, then one bulk V-cycle per GMRES iteration ("full"
                    # applies the V-cycle twice): ball 24.5k 22 % and groove 14k 31 %
                    # less time per Newton step, GMRES iterations +6 % and +4 %
                    "pc_fieldsplit_schur_fact_type": "upper",
                    "pc_fieldsplit_schur_precondition": "selfp",
                    "fieldsplit_bulk_ksp_type": "preonly",
                    "fieldsplit_interface_ksp_type": "preonly",
                    "fieldsplit_interface_pc_type": "lu",
                    "fieldsplit_interface_pc_factor_mat_solver_type": "mumps"})
        out.update(self._amg_options("fieldsplit_bulk_"))
        return out

    def single_field_options(self) -> OptionsDict:
        """Options when there is no interface field: AMG on the whole matrix."""
        out = {k: v for k, v in self.options().items() if k.startswith("ksp_")}
        out.update(self._amg_options(""))
        return out

    def configure(self, problem: Problem) -> None:
        """Index sets of the two fields and the near-nullspace of the bulk one."""
        bulk, rest = bulk_fields(problem)
        if not bulk:
            raise ValueError(f"problem {problem.name!r} has no bulk field for AMG")
        comm = problem.snes.comm
        ksp = problem.snes.getKSP()
        pc = ksp.getPC()
        # GAMG's Galerkin products A_c = PᵀAP carry no options prefix, so this one
        # option is global: without it each product keeps its intermediate data
        # for a reuse that never comes (the hierarchy is rebuilt at every set-up);
        # with it the ball at 142k on 2 ranks peaks 8-12 % lower, in the same time
        # within this machine's noise
        # (docs/solvers.md, "Memory per rank")
        opts = PETSc.Options()
        if not opts.hasName(PRODUCT_CLEAR):
            opts[PRODUCT_CLEAR] = None  # type: ignore[index]  # petsc4py stub: no __setitem__

        def index_set(ks: Sequence[int], bs: int = 1) -> PETSc.IS:
            idx: list[npt.NDArray[np.integer]] | npt.NDArray[np.integer]
            idx = [problem.block_start(k) + np.arange(problem.owned_size(problem.u[k]))
                   for k in ks]
            idx = np.concatenate(idx) if idx else np.zeros(0, dtype=np.int64)
            # (petsc4py's stub types the indices Sequence; it takes an array)
            iset = PETSc.IS().createGeneral(idx.astype(PETSc.IntType), comm=comm)  # type: ignore[arg-type]
            iset.setBlockSize(bs)    # AMG aggregates nodes (blocks of gdim), not dofs
            return iset

        nsp = near_nullspace([problem.u[k].function_space for k in bulk],
                             [problem.owned_size(problem.u[k]) for k in bulk], comm)
        if rest:
            gdim = problem.u[bulk[0]].function_space.mesh.geometry.dim
            is0, is1 = index_set(bulk, gdim), index_set(rest)
            is0.compose("nearnullspace", nsp)
            pc.setType("fieldsplit")
            pc.setFieldSplitIS(("bulk", is0), ("interface", is1))
            self._split = (is0, is1, nsp)
        else:     # the options (Problem) already made the PC an AMG on the whole matrix
            self._split = (None, None, nsp)
        ksp.setFromOptions()
        self.guard.install(problem)

    def prepare(self, problem: Problem) -> None:
        """Near-nullspace on the current matrix (a grown pattern is a new matrix)."""
        if self._split is not None and self._split[0] is None:
            problem.A.setNearNullSpace(self._split[2])

    def describe(self, problem: Problem) -> str:
        """One line naming the strategy and its fields (recorded in ``summary.json``)."""
        bulk, rest = bulk_fields(problem)
        names = lambda ks: "+".join(problem.u[k].name for k in ks) or "-"  # noqa: E731
        return (f"iterative (GMRES rtol {self.rtol:g}; bulk {names(bulk)}: {self.amg}; "
                f"interface {names(rest)}: Schur selfp LU; {problem.num_dofs} unknowns)")
