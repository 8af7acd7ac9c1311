"""A problem with reduced unknowns: fields on a replicated mesh mapped linearly into the body.

Some unknowns are cheaper to carry on a smaller, *replicated* mesh (created on
``COMM_SELF`` on every rank) and to map into the distributed body by a fixed
linear operator: the quasi-steady wear groove of §5.3 keeps its shape mapping Ψ
on one cross-section and extrudes it along the sliding direction, w₃ = P w₂, so
the shape unknowns are a few per cent of all unknowns.  UFL cannot assemble
across two unrelated meshes, so this problem assembles its monolithic system
block by block:

* a *reduction* (image w₃, reduced unknown w₂, map P) keeps w₃ = P w₂ before every
  evaluation; a form that depends on w₃ gets the Jacobian block J_{· w₂} = J_{· w₃} P;
* an *algebraic row* adds s·Qᵀ r to the row of a reduced unknown, with r the
  assembled vector of a UFL form on the body (e.g. the nodal wear rate) and Q a
  map like P; its Jacobian is s·Qᵀ J_{r ·} (with the reduction product again);
* Dirichlet rows become identity rows with residual u − g.

Layout: distributed unknowns are owned as DOLFINx owns them; a replicated
unknown is owned by rank 0 (identical copies elsewhere; its Newton update is
broadcast).  The blocks are assembled by DOLFINx, multiplied by the maps
(PETSc MatMatMult) and merged into one (MPI)AIJ matrix by a COO sum.

A component declares, besides the protocol of :mod:`tribofx.problem`,
``bcs_by_unknown()`` ({unknown: [DirichletBC]}), and optionally
``reductions()`` (a list of :class:`Reduction`) and ``algebraic_rows()`` (a list
of :class:`AlgebraicRow`).  The map objects have ``apply(v2)`` (image values on
the local dofs, ghosts included), ``transpose(v3)`` (Qᵀ of the owned entries,
summed over ranks) and ``mat`` (PETSc MPIAIJ: owned image rows × reduced
columns owned by rank 0).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol, cast

import dolfinx.fem.petsc as fem_petsc
import numpy as np
import numpy.typing as npt
import ufl
from dolfinx import fem, la
from mpi4py import MPI
from petsc4py import PETSc

from .lifetimes import weak_callback
from .problem import Problem, _block

if TYPE_CHECKING:
    class LinearMap(Protocol):
        """A fixed linear map of a reduced unknown into the body (see the module docstring)."""

        #: PETSc MPIAIJ: owned image rows × reduced columns owned by rank 0
        mat: PETSc.Mat

        def apply(self, v2: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
            """Image values on the local dofs (ghosts included) of the reduced values ``v2``."""

        def transpose(self, v3: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
            """Qᵀ of the owned entries of ``v3``, summed over ranks."""

__all__ = ["AlgebraicRow", "ReducedProblem", "Reduction"]


@dataclass
class Reduction:
    """image = P · reduced: ``image`` a Function on the body, ``reduced`` a replicated unknown."""

    image: fem.Function
    reduced: fem.Function
    P: LinearMap


@dataclass
class AlgebraicRow:
    """Row of ``row`` += scale() · Qᵀ r, r the assembled vector of the linear ``form``.

    ``fixed``: None, or a callable returning None (r is live, with its Jacobian) or a
    vector used instead of r (frozen data, no Jacobian).
    """

    row: fem.Function
    form: ufl.Form
    Q: LinearMap
    scale: Callable[[], float]
    fixed: Callable[[], npt.NDArray[np.float64] | None] | None = None


class ReducedProblem(Problem):
    """A :class:`tribofx.problem.Problem` whose unknowns may live on replicated meshes.

    Arguments as for :class:`tribofx.problem.Problem`.
    """

    def _create_snes(self) -> None:
        self._red: list[Reduction] = [r for c in self.components for r in c.reductions()]
        # the communicator of the distributed body (of the unknowns or of the images of
        # the reduced ones); a problem whose meshes are all on COMM_SELF runs serially
        comms = [f.function_space.mesh.comm for f in self.u + [r.image for r in self._red]]
        comm = max(comms, key=lambda c: c.size)
        self.comm = comm
        self._replicated = {id(ui): ui.function_space.mesh.comm.size == 1 and comm.size > 1
                            for ui in self.u}
        self._alg: list[AlgebraicRow] = [r for c in self.components for r in c.algebraic_rows()]
        by_image = {id(r.reduced): r for r in self._red}
        emaps = self._emaps()
        kw: dict[str, Any] = {"entity_maps": emaps} if emaps else {}
        self._F = [fem.form(f, **kw) for f in self.residual_forms]
        # {(row key, j, "direct"): form, (row key, j, "image"): (form, map)}
        self._J: dict[tuple[tuple[str, int], int, str], fem.Form | tuple[fem.Form, LinearMap]] = {}
        for i, Fi in enumerate(self.residual_forms):
            for j, uj in enumerate(self.u):
                self._add_jacobian(("F", i), j, Fi, uj, by_image, kw)
        self._Falg = [fem.form(a.form, **kw) for a in self._alg]
        for k, a in enumerate(self._alg):
            for j, uj in enumerate(self.u):
                self._add_jacobian(("A", k), j, a.form, uj, by_image, kw)
        self._bc_rows = self._collect_bcs()
        sizes = [self.owned_size(ui) for ui in self.u]
        self._sizes: list[list[int]] = comm.allgather(sizes)
        self._starts: list[list[int]] = comm.allgather(
            [0 if self._replicated[id(ui)] else
             ui.function_space.dofmap.index_map.local_range[0]
             * ui.function_space.dofmap.index_map_bs for ui in self.u])
        nloc = sum(sizes)
        self._row0 = int(np.sum([sum(s) for s in self._sizes[:comm.rank]]))
        self._N = int(np.sum([sum(s) for s in self._sizes]))
        self._x = PETSc.Vec().createMPI((nloc, self._N), comm=comm)
        b = self._x.duplicate()
        self._set_maps()
        self._get_unknowns(self._x)
        # the COO pattern the Jacobian is preallocated with
        self._coo: tuple[npt.NDArray[np.integer], npt.NDArray[np.integer]] | None = None
        self._A = self._jacobian_matrix()
        self.snes = PETSc.SNES().create(comm)
        self.snes.setFunction(weak_callback(self._residual), b)
        self.snes.setJacobian(weak_callback(self._jacobian), self._A)

    def _add_jacobian(self, key: tuple[str, int], j: int, F: ufl.Form, uj: fem.Function,
                      by_image: dict[int, Reduction], kw: dict[str, Any]) -> None:
        """Jacobian block of form F in unknown j: direct, and through uj's image."""
        direct = _block(F, uj)
        red = by_image.get(id(uj))
        via = None
        if red is not None:
            img = red.image
            via = _block(F, img)
        if direct is not None:
            self._J[key, j, "direct"] = fem.form(direct, **kw)
        if via is not None:
            self._J[key, j, "image"] = (fem.form(via, **kw), cast(Reduction, red).P)  # via: red

    def _collect_bcs(self) -> dict[int, list[fem.DirichletBC]]:
        rows: dict[int, list[fem.DirichletBC]] = {}
        for c in self.components:
            for ui, bcs in c.bcs_by_unknown().items():
                if any(ui is v for v in self.u):
                    rows.setdefault(id(ui), []).extend(bcs)
        return rows

    # -- layout ------------------------------------------------------------------
    def owned_size(self, ui: fem.Function) -> int:
        """Rows of ``ui`` owned by this rank (a replicated unknown's all on rank 0)."""
        V = ui.function_space
        if V.mesh.comm.size == 1 and self.comm.size > 1:  # replicated: owned by rank 0
            return len(ui.x.array) if self.comm.rank == 0 else 0
        return V.dofmap.index_map.size_local * V.dofmap.index_map_bs

    def _owned(self, vec: la.Vector, ui: fem.Function) -> npt.NDArray[np.float64]:
        return vec.array[:self.owned_size(ui)]

    def block_start(self, k: int) -> int:
        """Global row of the first owned dof of unknown ``k`` on this rank."""
        return self._row0 + int(self._offsets()[1][self.comm.rank][k])

    def _offsets(self) -> tuple[npt.NDArray[np.int64], list[npt.NDArray[np.int64]]]:
        """Local offset of each unknown's rows on every rank, and each rank's first row."""
        boff = [np.concatenate([[0], np.cumsum(s)])[:-1] for s in self._sizes]
        roff = np.concatenate([[0], np.cumsum([sum(s) for s in self._sizes])])
        return roff, boff

    def _global_index(self, j: int, g: npt.NDArray[np.int64]) -> npt.NDArray[np.int64]:
        """Monolithic global index of unknown j's global dof indices ``g``."""
        roff, boff = self._offsets()
        if self._replicated[id(self.u[j])]:
            return roff[0] + boff[0][j] + g
        starts = np.array([s[j] for s in self._starts])
        sizes = np.array([s[j] for s in self._sizes])
        owner = np.searchsorted(starts + sizes, g, side="right")
        ob = np.array([b[j] for b in boff])
        return roff[owner] + ob[owner] + g - starts[owner]

    def refresh(self) -> None:
        """Images ← maps of the reduced unknowns, then every component's refresh."""
        self._set_maps()
        super().refresh()

    def _set_maps(self) -> None:
        for r in self._red:
            r.image.x.array[:] = r.P.apply(r.reduced.x.array)

    # -- unknowns <-> vector -------------------------------------------------------
    def set_unknowns(self, x: PETSc.Vec) -> None:
        """Copy the block vector ``x`` into the unknowns (reduced blocks mapped, ghosts updated)."""
        arr = x.getArray(readonly=True)
        i = 0
        for ui in self.u:
            n = self.owned_size(ui)
            if self._replicated[id(ui)]:
                vals = arr[i:i + n].copy() if self.comm.rank == 0 else None
                ui.x.array[:] = self.comm.bcast(vals, root=0)
            else:
                ui.x.array[:n] = arr[i:i + n]
                ui.x.scatter_forward()
            i += n
        self._set_maps()

    def _get_unknowns(self, x: PETSc.Vec) -> None:
        # (petsc4py's stubs type arrays Sequence; they take NumPy arrays)
        x.setArray(np.concatenate([ui.x.array[:self.owned_size(ui)] for ui in self.u]))  # type: ignore[arg-type]

    # -- assembly --------------------------------------------------------------------
    def _vector(self, form: fem.Form, ui: fem.Function | None = None,
                n: int | None = None) -> npt.NDArray[np.float64]:
        vec = fem.assemble_vector(form)
        vec.scatter_reverse(la.InsertMode.add)
        return vec.array[:n].copy() if n is not None else self._owned(
            vec, cast(fem.Function, ui)).copy()     # (n None: ui is given)

    def _alg_vector(self, k: int) -> npt.NDArray[np.float64]:
        a = self._alg[k]
        frozen = a.fixed() if a.fixed is not None else None
        if frozen is not None:
            return frozen
        Vr = a.form.arguments()[0].ufl_function_space()
        n = Vr.dofmap.index_map.size_local * Vr.dofmap.index_map_bs
        return self._vector(self._Falg[k], n=n)

    def algebraic_vector(self, k: int) -> npt.NDArray[np.float64]:
        """Assembled vector r (owned rows) of algebraic row ``k`` at the current state."""
        return self._alg_vector(k)

    def _evaluate(self, snes: PETSc.SNES, x: PETSc.Vec, b: PETSc.Vec) -> None:
        self.set_unknowns(x)
        self.refresh()
        parts = []
        for i, ui in enumerate(self.u):
            r = self._vector(self._F[i], ui)
            for k, a in enumerate(self._alg):
                if a.row is ui:
                    r = r + float(a.scale()) * a.Q.transpose(self._alg_vector(k))[:len(r)]
            for bc in self._bc_rows.get(id(ui), []):
                full = np.zeros_like(ui.x.array)
                full[:len(r)] = r
                bc.set(full, x0=ui.x.array, alpha=-1.0)
                r = full[:len(r)]
            parts.append(r)
        b.setArray(np.concatenate(parts) if parts else np.zeros(0))  # type: ignore[arg-type]  # petsc4py stub: Sequence, not ndarray
        self._shift_by_homotopy(b)

    def _matrices(self, key: tuple[str, int], j: int) -> tuple[list[PETSc.Mat], list[PETSc.Mat]]:
        """Assembled Jacobian blocks (PETSc) of row ``key`` in unknown j (direct, image·P)."""
        out, made = [], []
        d = cast("fem.Form | None", self._J.get((key, j, "direct")))
        if d is not None:
            A = fem_petsc.assemble_matrix(d)
            A.assemble()
            out.append(A)
        v = cast("tuple[fem.Form, LinearMap] | None", self._J.get((key, j, "image")))
        if v is not None:
            A = fem_petsc.assemble_matrix(v[0])
            A.assemble()
            made.append(A)
            out.append(A.matMult(v[1].mat))
        return out, made

    def _jacobian_coo(self) -> tuple[npt.NDArray[np.integer], npt.NDArray[np.integer],
                                     npt.NDArray[np.float64]]:
        """Return the Jacobian as COO triplets (global rows, columns, values).

        Duplicates are summed by PETSc; the Dirichlet rows are identity rows.
        """
        rank = self.comm.rank
        roff, boff = self._offsets()
        my0 = roff[rank]
        ri: list[npt.NDArray[np.int64]] | npt.NDArray[np.int64]     # per block, then joined
        ci: list[npt.NDArray[np.int64]] | npt.NDArray[np.int64]
        vals: list[npt.NDArray[np.float64]] | npt.NDArray[np.float64]
        made: list[PETSc.Mat]
        ri, ci, vals, made = [], [], [], []

        def add(i: int, j: int, A: PETSc.Mat, replicated_rows: bool) -> None:
            if replicated_rows and rank != 0:
                return
            ip, ind, val = A.getValuesCSR()
            nrow = len(ip) - 1
            if nrow == 0 or len(val) == 0:
                return
            # (the lists of per-block arrays, joined after the loop)
            cast(list, ri).append(my0 + boff[rank][i] + np.repeat(np.arange(nrow), np.diff(ip)))
            cast(list, ci).append(self._global_index(j, np.asarray(ind, dtype=np.int64)))
            cast(list, vals).append(val)

        for i, ui in enumerate(self.u):
            rep = self._replicated[id(ui)]
            for j in range(len(self.u)):
                mats, tmp = self._matrices(("F", i), j)
                made += mats + tmp
                for A in mats:
                    add(i, j, A, rep)
            for k, a in enumerate(self._alg):
                if a.row is not ui or (a.fixed is not None and a.fixed() is not None):
                    continue
                for j in range(len(self.u)):
                    mats, tmp = self._matrices(("A", k), j)
                    made += mats + tmp
                    for A in mats:
                        B = a.Q.mat.transposeMatMult(A)
                        B.scale(float(a.scale()))
                        made.append(B)
                        add(i, j, B, False)
        for m in made:
            m.destroy()
        ri = np.concatenate(ri) if ri else np.zeros(0, np.int64)
        ci = np.concatenate(ci) if ci else np.zeros(0, np.int64)
        vals = np.concatenate(vals) if vals else np.zeros(0)
        nloc = sum(self._sizes[rank])
        bc = np.zeros(nloc, dtype=bool)
        for i, ui in enumerate(self.u):
            for d in self._bc_rows.get(id(ui), []):
                idx = d.dof_indices()[0]
                idx = idx[idx < self._sizes[rank][i]]
                bc[boff[rank][i] + idx] = True
        keep = ~bc[ri - my0]
        rbc = my0 + np.flatnonzero(bc)
        ri = np.concatenate([ri[keep], rbc]).astype(PETSc.IntType)
        ci = np.concatenate([ci[keep], rbc]).astype(PETSc.IntType)
        vals = np.concatenate([vals[keep], np.ones(len(rbc))])
        return ri, ci, vals

    def _jacobian_matrix(self, A: PETSc.Mat | None = None) -> PETSc.Mat:
        """Assemble the Jacobian into ``A`` (None: a new MPIAIJ matrix); returns it.

        The matrix is preallocated from the COO pattern (PETSc sums duplicate
        entries); while the pattern is the one of the last call, only the values
        are set, so the matrix keeps its nonzero state (an LU keeps its analysis).
        """
        ri, ci, vals = self._jacobian_coo()
        pattern = self._coo
        same = (A is not None and pattern is not None and len(pattern[0]) == len(ri)
                and np.array_equal(pattern[0], ri) and np.array_equal(pattern[1], ci))
        same = self.comm.allreduce(same, op=MPI.LAND)   # the preallocation is collective
        if A is None:
            nloc = sum(self._sizes[self.comm.rank])
            A = PETSc.Mat().create(comm=self.comm)
            A.setSizes(((nloc, self._N), (nloc, self._N)))
            A.setType(PETSc.Mat.Type.AIJ)
        # (petsc4py's stubs: arrays are not Sequence, the insert mode is an int)
        if not same:
            A.setPreallocationCOO(ri, ci)  # type: ignore[arg-type]
            self._coo = (ri, ci)
        A.setValuesCOO(vals, addv=PETSc.InsertMode.INSERT_VALUES)  # type: ignore[arg-type]
        A.assemble()
        return A

    def _jacobian(self, snes: PETSc.SNES, x: PETSc.Vec, A: PETSc.Mat, P: PETSc.Mat) -> None:
        self.set_unknowns(x)
        self.refresh()
        self._jacobian_matrix(A)
